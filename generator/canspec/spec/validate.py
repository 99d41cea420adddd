"""Semantic rules over a resolved spec. Each rule has an ID (shown as `[rule]` after the
message) and an invalid fixture under tests/fixtures/invalid/ that triggers it."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from fractions import Fraction
from typing import Any

from canspec.ir import j1939
from canspec.ir.bits import BIG, describe, fits, positions
from canspec.ir.encoding import raw_type_range
from canspec.ir.fd import FD_LENGTHS
from canspec.ir.ids import max_id
from canspec.spec.finite import finite
from canspec.spec.problems import Problem, error, warning
from canspec.spec.resolve import Resolved, ResolvedCan, label_pair
from canspec.spec.validate_dbc import dbc_rules
from canspec.spec.validate_json import check_changelog, json_rules
from canspec.spec.validate_mux import coexist, mux_rules
from canspec.spec.validate_ranges import range_rules
from canspec.spec.yamlsource import LocDict, LocList

MAX_CYCLE_MS = 600_000
Rule = Callable[[ResolvedCan], Iterator[Problem]]
CAN_RULES: list[Rule] = []


def rule(fn: Rule) -> Rule:
    CAN_RULES.append(fn)
    return fn


def _signals(msg: LocDict) -> LocList:
    return msg["signals"]


@rule
def unique_names_and_ids(can: ResolvedCan) -> Iterator[Problem]:
    names: dict[str, Any] = {}
    ids: dict[int, Any] = {}
    for msg in can.messages:
        if msg["name"] in names:
            yield error(
                f"message name {msg['name']!r} is used twice (first at {names[msg['name']]})", msg.loc_of("name"), "give each message its own name",
                "duplicate-message-name")
        names.setdefault(msg["name"], msg.loc_of("name"))
        if msg["id"] in ids:
            yield error(
                f"frame ID 0x{msg['id']:08X} is used twice (first at {ids[msg['id']]})", msg.loc_of("id"), "each message needs its own frame ID",
                "duplicate-frame-id")
        ids.setdefault(msg["id"], msg.loc_of("id"))
        seen: dict[str, Any] = {}
        for sig in _signals(msg):
            if sig["name"] in seen:
                yield error(
                    f"signal name {sig['name']!r} is used twice in message {msg['name']!r} (first at {seen[sig['name']]})", sig.loc_of("name"),
                    "rename one of the signals", "duplicate-signal-name")
            seen.setdefault(sig["name"], sig.loc_of("name"))


@rule
def nodes(can: ResolvedCan) -> Iterator[Problem]:
    nodes = can.doc.data["nodes"]
    names: dict[str, Any] = {}
    sas: dict[int, str] = {}
    j1939_bus = can.doc.data["bus"]["addressing"] == "j1939"
    for node in nodes:
        if node["name"] in names:
            yield error(f"node {node['name']!r} is defined twice", node.loc_of("name"), None, "duplicate-node")
        if "sa" not in node:
            if j1939_bus:
                yield error(
                    f"node {node['name']!r} has no source address, which J1939 addressing needs", node.loc, "add `sa: 0x..` (its J1939 source address)",
                    "node-sa")
        elif node["sa"] in sas:
            yield error(
                f"source address 0x{node['sa']:02X} of {node['name']!r} is already {sas[node['sa']]!r}'s", node.loc_of("sa"),
                "each node needs its own source address", "duplicate-node")
        names[node["name"]] = node
        if "sa" in node:
            sas.setdefault(node["sa"], node["name"])
    aliases = {a: n["name"] for n in nodes for a in n.get("aliases", [])}
    for msg in can.messages:
        refs = [("sender", msg["sender"], msg.loc_of("sender"))]
        receivers = msg["receivers"]
        if isinstance(receivers, list):
            refs += [("receiver", r, receivers.loc_of(i)) for i, r in enumerate(receivers)]
        for what, ref, where in refs:
            if ref == "ALL" or ref in names:
                continue
            hint = f"{ref!r} is an alias of {aliases[ref]!r}; use the node name" if ref in aliases else f"known nodes: {', '.join(names)} (or ALL)"
            yield error(f"{what} {ref!r} of message {msg['name']!r} is not a node", where, hint, "unknown-node")
        sender = names.get(msg["sender"])
        if sender is not None and j1939_bus and "sa" in sender and (msg["id"] & 0xFF) != sender["sa"]:
            yield error(
                f"message {msg['name']!r} is sent by {sender['name']!r} (SA 0x{sender['sa']:02X}) "
                f"but its ID 0x{msg['id']:08X} carries SA 0x{msg['id'] & 0xFF:02X}",
                msg.loc_of("id"), "fix the ID's last byte or the sender", "sender-sa")


@rule
def frame_ids(can: ResolvedCan) -> Iterator[Problem]:
    bus = can.doc.data["bus"]
    extended, j1939_bus = bus["id_format"] == "extended", bus["addressing"] == "j1939"
    for msg in can.messages:
        is_extended = msg.get("extended", extended)
        if not 0 <= msg["id"] <= max_id(is_extended):
            yield error(f"frame ID 0x{msg['id']:X} of {msg['name']!r} does not fit {29 if is_extended else 11} bits", msg.loc_of("id"), None, "id-range")
            continue
        if j1939_bus and not is_extended:
            where = msg.loc_of("extended") if "extended" in msg else bus.loc_of("id_format")
            yield error(
                f"message {msg['name']!r} has an 11-bit ID, but J1939 addressing needs 29-bit IDs", where,
                "use `id_format: extended`, or `addressing: none` for a bus without J1939", "j1939-addressing")
            continue
        declared = msg.get("j1939")
        if declared is None:
            continue  # derived from the ID
        if not j1939_bus:
            yield error(
                f"message {msg['name']!r} declares J1939 fields on a bus without J1939 addressing", msg.loc_of("j1939"),
                "remove `j1939:`, or set the bus's `addressing: j1939`", "j1939-addressing")
            continue
        actual = j1939.decompose(msg["id"])
        for key in ("priority", "edp", "dp", "pf", "ps", "sa"):
            if key in declared and declared[key] != getattr(actual, key):
                yield error(
                    f"message {msg['name']!r}: declared J1939 {key} 0x{declared[key]:02X} but ID 0x{msg['id']:08X} has 0x{getattr(actual, key):02X}",
                    declared.loc_of(key), "the ID is authoritative on the wire: correct the declared field (and record the erratum)", "j1939-mismatch")


@rule
def cycle_and_dlc(can: ResolvedCan) -> Iterator[Problem]:
    for msg in can.messages:
        if not 0 <= msg.get("cycle_ms", 0) <= MAX_CYCLE_MS:
            yield error(
                f"cycle time {msg['cycle_ms']} ms of {msg['name']!r} is not in 0..{MAX_CYCLE_MS}", msg.loc_of("cycle_ms"),
                "give the period in milliseconds (0, or no `cycle_ms`, for an event-driven message)", "cycle-time")
        yield from _frame_format(msg, can.doc.data["bus"])
        if msg.get("layout_undefined") and len(_signals(msg)):
            yield error(f"message {msg['name']!r} says `layout_undefined` but lists signals", msg.loc_of("layout_undefined"), None, "empty-message")
        if not msg.get("layout_undefined") and not len(_signals(msg)) and msg.get("dlc", 8) != 0:
            yield error(
                f"message {msg['name']!r} has no signals", msg.loc,
                "list its signals, or set `layout_undefined: true` if the document defines none (a DLC-0 frame needs none)", "empty-message")


def _frame_format(msg: LocDict, bus: LocDict) -> Iterator[Problem]:
    """DLC and the CAN FD flags: classic frames carry 0..8 bytes, FD frames also 12..64 in steps."""
    dlc, fd = msg.get("dlc", 8), msg.get("fd", False)
    if dlc not in FD_LENGTHS:
        yield error(f"DLC {dlc} of {msg['name']!r} is not a CAN frame length", msg.loc_of("dlc"),
                    f"classic CAN frames carry 0 to 8 bytes, CAN FD frames also {', '.join(map(str, FD_LENGTHS[9:]))}", "dlc-range")
    elif dlc > 8 and not fd:
        yield error(f"DLC {dlc} of {msg['name']!r} needs a CAN FD frame", msg.loc_of("dlc"), "add `fd: true` to the message, or use 0..8 bytes", "dlc-range")
    if msg.get("brs") and not fd:
        yield error(f"message {msg['name']!r} sets `brs` but is not a CAN FD frame", msg.loc_of("brs"), "add `fd: true`, or remove `brs`", "fd-brs")
    elif fd and msg.get("brs", bus.get("data_bitrate") is not None) and bus.get("data_bitrate") is None:
        yield error(f"message {msg['name']!r} switches bit rate, but the bus gives no data-phase bit rate", msg.loc_of("brs"),
                    "add `data_bitrate:` (bit/s) to `bus`, or `brs: false` to the message", "fd-brs")


def _where(sig: LocDict) -> str:
    """Where a field lies, in words: its order and bytes (both orders use the DBC's bit numbers)."""
    order = "Motorola" if sig["byte_order"] == BIG else "Intel"
    return f"{order}, start {sig['start']}, {sig['len']} bits: {describe(sig['start'], sig['len'], sig['byte_order'])}"


@rule
def signal_shapes(can: ResolvedCan) -> Iterator[Problem]:
    for msg in can.messages:
        dlc = msg.get("dlc", 8)
        frame_bytes = dlc if dlc in FD_LENGTHS else 64  # a bad DLC is reported by dlc-range
        owners: dict[int, str] = {}
        together = coexist(_signals(msg))  # fields of different pages may overlap
        placed: list[tuple[LocDict, frozenset[int]]] = []
        for sig in _signals(msg):
            start, length = sig["start"], sig["len"]
            if not 1 <= length <= 64 or start < 0:
                yield error(
                    f"signal {sig['name']!r}: start {start} / length {length} is not a valid bit field", sig.loc_of("len"),
                    "length is 1..64 bits, start is >= 0", "signal-length")
                continue
            if not fits(start, length, sig["byte_order"], frame_bytes):
                hint = "check start and length against the DLC" + (
                    "; a Motorola field's start is its most significant bit, and it runs down to bit 0, then on from bit 7 of the next byte"
                    if sig["byte_order"] == BIG else "")
                yield error(f"signal {sig['name']!r} ({_where(sig)}) extends beyond the {frame_bytes}-byte frame of {msg['name']!r}",
                            sig.loc_of("start"), hint, "signal-beyond-dlc")
                continue
            bits = positions(start, length, sig["byte_order"])
            if together is None:
                clash = {owners[b] for b in bits if b in owners}
            else:
                clash = {other["name"] for other, taken in placed if together(sig, other) and not taken.isdisjoint(bits)}
                placed.append((sig, frozenset(bits)))
            if clash:
                yield error(
                    f"signal {sig['name']!r} ({_where(sig)}) overlaps {', '.join(sorted(clash))} in {msg['name']!r}",
                    sig.loc_of("start"), "check the start bits, lengths and byte orders in the document's table", "signal-overlap")
            for b in bits:
                owners.setdefault(b, sig["name"])
            yield from _float_shape(sig)
            for key in ("factor", "offset"):
                if not finite(sig[key]):
                    yield error(f"signal {sig['name']!r}: {key} must be a finite number within the range of a double", sig.loc_of(key), None, "nonfinite")
            if finite(sig["factor"]) and sig["factor"] == 0:
                yield error(
                    f"signal {sig['name']!r} has factor 0", sig.loc_of("factor"), "physical = raw * factor + offset needs a non-zero factor", "factor-zero"
                )


def _float_shape(sig: LocDict) -> Iterator[Problem]:
    """An IEEE float field: 32 or 64 bits holding the physical value itself (ir.Signal.is_float)."""
    if not sig["float"]:
        return
    if sig["len"] not in (32, 64):
        yield error(f"float signal {sig['name']!r} has {sig['len']} bits", sig.loc_of("len"), "IEEE floats are 32 (float32) or 64 (float64) bits",
                    "float-field")
    for key, bad in (("signed", sig["signed"]), ("factor", sig["factor"] != 1), ("offset", sig["offset"] != 0), ("values", "values" in sig),
                     ("special", "special" in sig), ("role", sig["role"] != "data")):
        if bad:
            yield error(f"float signal {sig['name']!r} gives `{key}`", sig.loc_of(key),
                        "a float field holds its physical value itself: no sign flag, factor 1, offset 0, no value table or specials, role data",
                        "float-field")


rule(mux_rules)
rule(dbc_rules)


rule(range_rules)


@rule
def value_fit(can: ResolvedCan) -> Iterator[Problem]:
    for msg in can.messages:
        for sig in _signals(msg):
            if not 1 <= sig["len"] <= 64:
                continue
            tmin, tmax = raw_type_range(sig["len"], sig["signed"])
            tname = sig.get("values")
            if tname is not None and tname not in can.value_tables:
                yield error(
                    f"signal {sig['name']!r} uses unknown value table {tname!r}", sig.loc_of("values"), "define it under value_tables", "unknown-value-table"
                )
            tables = [("value", tname, can.value_tables.get(tname))] if tname else []
            if "special" in sig:
                tables.append(("special value", None, sig["special"]))
            for what, _, table in tables:
                if table is None:
                    continue
                for raw in table:
                    if not tmin <= raw <= tmax:
                        hex_raw = f"{'-' if raw < 0 else ''}0x{abs(raw):X}"
                        yield error(
                            f"{what} {raw} ({hex_raw}) does not fit the {sig['len']}-bit field {sig['name']!r} of {msg['name']!r} ({tmin}..{tmax})",
                            sig.loc_of("values" if what == "value" else "special"), "widen the field or drop the value", "value-out-of-field")
            if sig["role"] == "reserved" and any(k in sig for k in ("values", "special", "range")):
                yield warning(f"reserved field {sig['name']!r} has values or a range", sig.loc, "reserved bits carry no meaning", "reserved-with-meaning")


@rule
def value_table_identifiers(can: ResolvedCan) -> Iterator[Problem]:
    for tname, table in can.value_tables.items():
        seen: dict[str, int] = {}
        for raw, value in table.items():
            ident = label_pair(value)[0]
            if ident in seen:
                yield error(
                    f"value table {tname!r}: identifier {ident!r} names both {seen[ident]} and {raw}", table.loc_of(raw),
                    "identifiers become enum members and must be unique", "duplicate-value-name")
            seen.setdefault(ident, raw)


@rule
def counters_and_checksums(can: ResolvedCan) -> Iterator[Problem]:
    for msg in can.messages:
        dlc = msg.get("dlc", 8)
        for role in ("counter", "checksum"):
            found = [s for s in _signals(msg) if s["role"] == role]
            for extra in found[1:]:
                yield error(f"message {msg['name']!r} has more than one {role}", extra.loc_of("role"), None, f"{role}-shape")
        for sig in _signals(msg):
            if sig["role"] not in ("counter", "checksum"):
                continue
            role = sig["role"]
            if sig["signed"] or sig["factor"] != 1 or sig["offset"] != 0:
                yield error(f"{role} {sig['name']!r} must be unsigned with factor 1 and offset 0", sig.loc_of("role"), None, f"{role}-shape")
            full = [0, (1 << sig["len"]) - 1] if 1 <= sig["len"] <= 64 else None
            rng = sig.get("range")
            if rng is not None and full is not None and all(finite(v) for v in rng) and [Fraction(rng[0]), Fraction(rng[1])] != full:
                yield error(
                    f"{role} {sig['name']!r} claims range [{rng[0]}, {rng[1]}] but its {sig['len']} bits count {full[0]}..{full[1]}", sig.loc_of("range"),
                    f"a rolling {role} covers its whole field: use [0, {full[1]}]" if role == "counter" else "a checksum byte covers 0..255", f"{role}-shape")
            if role == "checksum":
                if sig["len"] != 8 or sig["start"] % 8 != (7 if sig["byte_order"] == BIG else 0):
                    yield error(
                        f"checksum {sig['name']!r} must be one whole byte (8 bits from bit 0 of a byte, or from bit 7 in Motorola order), "
                        f"not {sig['len']} bits at bit {sig['start']}",
                        sig.loc_of("start"), "the XOR checksum is byte 7 = XOR of bytes 0..6", "checksum-shape")
                elif dlc < 2:
                    yield error(
                        f"checksum {sig['name']!r} in a {dlc}-byte frame has no byte to cover", sig.loc_of("start"),
                        "the XOR checksum needs a frame of at least 2 bytes", "checksum-shape")
                elif sig["start"] // 8 != dlc - 1:
                    yield error(
                        f"checksum {sig['name']!r} in byte {sig['start'] // 8} would not cover the bytes after it; "
                        "the XOR checksum is the last byte of the frame", sig.loc_of("start"), f"put it at start bit {8 * (dlc - 1)}", "checksum-shape")
            if role == "counter" and sig["len"] > 8:
                yield error(f"counter {sig['name']!r} is {sig['len']} bits; rolling counters are 1..8 bits", sig.loc_of("len"), None, "counter-shape")


@rule
def multiframes(can: ResolvedCan) -> Iterator[Problem]:
    for msg in can.messages:
        mf = msg.get("multiframe")
        if mf is None:
            continue
        sigs = {s["name"]: s for s in _signals(msg)}
        index, payload = sigs.get(mf["index"]), sigs.get(mf["payload"])
        for key, sig in (("index", index), ("payload", payload)):
            if sig is None:
                yield error(f"multiframe {key} {mf[key]!r} is not a signal of {msg['name']!r}", mf.loc_of(key), None, "multiframe")
        if index is None or payload is None or not (1 <= index["len"] <= 64 and 1 <= payload["len"] <= 64):
            continue  # a bad length is reported by signal-length
        if payload["start"] % 8 or payload["len"] % 8 or payload["factor"] != 1 or payload["offset"] != 0:
            yield error(f"multiframe payload {payload['name']!r} must be whole bytes with factor 1, offset 0", mf.loc_of("payload"), None, "multiframe")
            continue
        per_frame = payload["len"] // 8
        if mf["frames"] * per_frame < mf["text_length"]:
            yield error(
                f"{mf['frames']} frames × {per_frame} bytes cannot carry {mf['text_length']} characters", mf.loc_of("frames"),
                "raise `frames` or shorten the text", "multiframe")
        if mf["frames"] > (1 << index["len"]):
            yield error(
                f"{mf['frames']} frames need more than the {index['len']}-bit index {index['name']!r} can count", mf.loc_of("frames"), None, "multiframe"
            )


def validate(res: Resolved) -> list[Problem]:
    problems = list(res.problems)
    if res.can is not None and not any(p.severity == "error" for p in problems):
        for fn in CAN_RULES:
            problems.extend(fn(res.can))
    for doc in res.json:
        problems.extend(json_rules(doc))
    problems.extend(check_changelog(res))
    unique: dict[tuple[object, str], Problem] = {}
    for p in problems:  # a shared layout reports once, not once per variant
        unique.setdefault((p.loc, p.message), p)
    return list(unique.values())
