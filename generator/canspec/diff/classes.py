"""The breaking-change ladder, strictest first, and the version bump each class suggests.

wire       an old receiver would decode different values, or could not take part (the bus's bit
           rates; layout, byte order, integer ↔ IEEE
           float, factor, offset, signedness, unit, ID, DLC, classic ↔ CAN FD frame, enum meaning,
           checksum/counter roles, removed message or signal, the page a field is in)
source     the wire is the same but generated identifiers change (renames)
compatible old code keeps working (new message, new signal in formerly free bits, new enum
           value, widened range, cycle time, sender/receivers, a DBC's own attributes (send type,
           start value: tools act on them, the bits decode as before), bit-rate switching of an FD frame:
           the data phase's speed changes, not its bits — an FD controller follows the frame's BRS
           bit on receive, so only timing and bus load change)
docs       names as printed, descriptions
"""

from __future__ import annotations

LADDER = ("wire", "source", "compatible", "docs")
TITLES = {"wire": "wire-breaking", "source": "source-breaking", "compatible": "compatible", "docs": "docs"}

# Every change kind and its class; kinds whose class depends on the change are listed with the
# strictest class and decided in compare.py (signal_added, signal_range_changed).
KINDS: dict[str, str] = {
    "bus_bitrate_changed": "wire",  # every node must run at the bus's rates: old ones could not take part
    # a source DBC's own attributes (diff/attributes.py): tools act on them, the bits decode as before
    "network_attribute_changed": "compatible",
    "message_attribute_changed": "compatible",
    "signal_attribute_changed": "compatible",
    # a node's frames are its messages' (their senders and receivers): a node alone changes no frame
    "node_added": "compatible",
    "node_removed": "compatible",
    "node_description_changed": "docs",
    "message_added": "compatible",
    "message_removed": "wire",
    "message_id_changed": "wire",
    "message_renamed": "source",
    "message_dlc_changed": "wire",
    "message_cycle_changed": "compatible",
    "message_sender_changed": "compatible",
    "message_receivers_changed": "compatible",
    "message_checksum_changed": "wire",
    "message_multiframe_changed": "wire",
    "message_fd_changed": "wire",  # a classic controller cannot receive an FD frame (nor sends one where FD is expected)
    "message_brs_changed": "compatible",  # timing only: see the ladder above
    "message_title_changed": "docs",
    "message_description_changed": "docs",
    "signal_added": "wire",  # compatible when its bits were free (reserved or unused) before
    "signal_removed": "wire",
    "signal_renamed": "source",
    "signal_moved": "wire",
    "signal_resized": "wire",
    "signal_rescaled": "wire",
    "signal_signedness_changed": "wire",
    "signal_byte_order_changed": "wire",
    "signal_float_changed": "wire",  # integer ↔ IEEE float: the same bits, another value
    "signal_mux_changed": "wire",  # another multiplexer, other values, or a multiplexer no more: frames mean other fields
    "signal_unit_changed": "wire",
    "signal_range_changed": "wire",  # compatible when only widened
    "signal_role_changed": "wire",
    "signal_receivers_changed": "compatible",  # who reads a field, as sender/receivers of a message
    "signal_values_table_renamed": "source",
    "signal_label_changed": "docs",
    "signal_description_changed": "docs",
    "value_added": "compatible",
    "value_removed": "wire",
    "value_relabelled": "wire",
    "value_renamed": "source",
    "special_added": "compatible",
    "special_removed": "wire",
    "special_relabelled": "wire",
    "special_renamed": "source",
}

# --fail-on LEVEL fails on changes of these classes.
FAIL_ON = {
    "wire": ("wire",),
    "source": ("wire", "source"),
    "compatible": ("wire", "source", "compatible"),
    "any": LADDER,
}


def strictest(classes: list[str] | tuple[str, ...] | set[str]) -> str | None:
    return next((c for c in LADDER if c in classes), None)


def suggest_bump(old_version: str | None, classes: set[str]) -> tuple[str, str | None, str]:
    """(bump, suggested new version or None, why)."""
    top = strictest(classes)
    if top is None:
        return "none", old_version, "no changes"
    bump, why = {
        "wire": ("major", "old receivers would decode different values"),
        "source": ("major", "generated identifiers change; old and new ECUs still interoperate on the wire"),
        "compatible": ("minor", "only additions and relaxations"),
        "docs": ("patch", "names and descriptions only"),
    }[top]
    parts = (old_version or "").split(".")
    if len(parts) != 3 or not all(p.isdigit() for p in parts):
        return bump, None, why
    major, minor, patch = map(int, parts)
    new = {"major": f"{major + 1}.0.0", "minor": f"{major}.{minor + 1}.0", "patch": f"{major}.{minor}.{patch + 1}"}[bump]
    return bump, new, why


def actual_bump(old_version: str | None, new_version: str | None) -> str | None:
    """major / minor / patch / none for two A.B.C versions ("none": not above); None if not semver."""
    try:
        a = tuple(int(p) for p in (old_version or "").split("."))
        b = tuple(int(p) for p in (new_version or "").split("."))
    except ValueError:
        return None
    if len(a) != 3 or len(b) != 3:
        return None
    if b <= a:
        return "none"
    return "major" if b[0] != a[0] else ("minor" if b[1] != a[1] else "patch")


BUMP_ORDER = ("none", "patch", "minor", "major")


def bump_note(old_version: str | None, new_version: str | None, suggested_bump: str) -> str | None:
    """A remark when the new revision's version says less than its changes do."""
    actual = actual_bump(old_version, new_version)
    if actual is None or BUMP_ORDER.index(actual) >= BUMP_ORDER.index(suggested_bump):
        return None
    if actual == "none":
        return f"the new revision's version ({new_version}) is not above the old one ({old_version})"
    return f"{old_version} → {new_version} is a {actual} bump; the changes suggest {suggested_bump}"
