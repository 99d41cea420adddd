"""Round trips of a generated DBC through SYM, KCD and ARXML with canmatrix and cantools, and a
model of exactly what each converter loses (the README's DBC section states the same list).

A snapshot is what cantools reads from a DBC: the nodes with their comments, and per message
(frame ID, 11/29 bit) its name, DLC, cycle time, senders and comment, and per signal its start,
length, byte order, sign, factor, offset, minimum, maximum, unit, value table, receivers and
comment. `expected()` turns the original's snapshot into what the converter is known to give
back; the round trip must give exactly that (numbers the converter rewrites are compared as
doubles, everything else exactly). DBC attributes (Vector's, SpecSignalName) have no place in
SYM, KCD or ARXML and are not compared.
"""

from __future__ import annotations

import copy
from decimal import Decimal, localcontext
from fractions import Fraction
from pathlib import Path
from typing import Any

import canmatrix.formats
from canspec.importer.dbctext import written_numbers
from canspec.targets.dbc.naming import SPEC_NAME_ATTRIBUTE
from dbc_support import ENCODINGS, attribute, load_cantools

# The canmatrix minor version: its ARXML writer changed between 1.2 and 1.3 (see _canmatrix_arxml).
CANMATRIX = tuple(int(part) for part in canmatrix.__version__.split(".")[:2])
# (tool, format) → whether the converter rewrites numbers (then compared as exact decimals in, doubles out)
PATHS = [("canmatrix", "sym"), ("canmatrix", "kcd"), ("canmatrix", "arxml"), ("cantools", "sym"), ("cantools", "kcd")]
REWRITTEN = ("scale", "offset", "min", "max")  # numbers canmatrix's KCD and ARXML writers recompute or round


def snapshot(path: Path, exact: bool = False) -> dict[str, Any]:
    """`exact`: factor, offset and range as Decimals of the SG_ lines' text (cantools reads doubles),
    for the converters that compute with the written decimals."""
    db = load_cantools(path, strict=False)
    written = written_numbers(path.read_text(encoding="utf-8")) if exact else {}
    messages = {}
    for m in db.messages:
        dbc_id = m.frame_id | 0x80000000 if m.is_extended_frame else m.frame_id
        signals = {s.name: {
            "start": s.start, "length": s.length, "order": s.byte_order, "signed": s.is_signed, "float": s.is_float, "scale": s.scale,
            "offset": s.offset, "min": s.minimum, "max": s.maximum, "unit": s.unit or "",
            "choices": {int(k): str(v) for k, v in (s.choices or {}).items()}, "receivers": sorted(s.receivers),
            "comment": s.comment, "spec_name": attribute(s, SPEC_NAME_ATTRIBUTE), "attributes": _texts(s),
        } for s in m.signals}
        for (frame, name), numbers in written.items():
            if frame == dbc_id:
                signals[name].update(zip(REWRITTEN, map(_decimal, numbers)))
        messages[(m.frame_id, m.is_extended_frame)] = {
            "name": m.name, "dlc": m.length, "fd": m.is_fd, "brs": attribute(m, "CANFD_BRS") if m.is_fd else None, "cycle": m.cycle_time,
            "senders": list(m.senders), "comment": m.comment, "signals": signals,
        }
    bus = {"type": attribute(db, "BusType"), "data_bitrate": attribute(db, "BaudrateCANFD")}
    return {"bus": bus, "nodes": {n.name: n.comment for n in db.nodes}, "messages": messages}


def _texts(sig: Any) -> dict[str, str]:
    """A signal's attributes other than canspec's own, but ENUMs, as text: canmatrix's KCD writer appends
    these to the notes (its attempt to append an ENUM's text fails, and it skips it)."""
    attributes = sig.dbc.attributes if sig.dbc else {}
    return {name: str(a.value) for name, a in attributes.items()
            if a.definition.type_name != "ENUM" and name not in ("SigType", SPEC_NAME_ATTRIBUTE)}


def _decimal(value: Fraction) -> Decimal:
    with localcontext() as ctx:
        ctx.prec = 80  # more than any DBC number's digits: the quotient is the written decimal
        return Decimal(value.numerator) / Decimal(value.denominator)


def round_trip(tool: str, fmt: str, dbc: Path, work: Path) -> Path:
    """DBC → `fmt` → DBC through one tool; returns the DBC written at the end."""
    middle, back = work / f"{tool}.{fmt}", work / f"{tool}_{fmt}.dbc"
    if tool == "canmatrix":
        canmatrix.formats.dumpp(canmatrix.formats.loadp(str(dbc), **ENCODINGS), str(middle), **ENCODINGS)
        (matrix,) = canmatrix.formats.loadp(str(middle), **ENCODINGS).values()
        canmatrix.formats.dumpp({"": matrix}, str(back), **ENCODINGS)
    else:
        middle.write_text(getattr(load_cantools(dbc), f"as_{fmt}_string")(), encoding="utf-8")
        back.write_text(load_cantools(middle, strict=False).as_dbc_string(), encoding="utf-8")
    return back


def _bits_range(sig: dict[str, Any]) -> tuple[Any, Any]:
    """What canmatrix puts where a range is missing: raw type limits × factor + offset."""
    n = sig["length"]
    lo, hi = (-(1 << (n - 1)), (1 << (n - 1)) - 1) if sig["signed"] else (0, (1 << n) - 1)
    return sig["offset"] + lo * sig["scale"], sig["offset"] + hi * sig["scale"]


def _no_nodes(snap: dict[str, Any]) -> None:
    """SYM has no nodes: no node list, senders or receivers (the senders read back are the SYM
    sections a frame was listed in: not compared)."""
    snap["nodes"] = {}
    for m in snap["messages"].values():
        del m["senders"]
        for s in m["signals"].values():
            s["receivers"] = []


def _one_line_comments(snap: dict[str, Any]) -> None:
    for m in snap["messages"].values():
        for item in (m, *m["signals"].values()):
            if item["comment"]:
                item["comment"] = item["comment"].replace("\n", " ")


def _six_digit_scaling(sig: dict[str, Any]) -> None:
    """canmatrix writes factor and offset to KCD and ARXML with "%g": 6 significant digits."""
    # "%g" % a Decimal goes through a double, as canmatrix's writer does (Decimal's own :g would not)
    sig["scale"], sig["offset"] = Decimal("%g" % sig["scale"]), Decimal("%g" % sig["offset"])  # noqa: UP031


def _canmatrix_kcd(snap: dict[str, Any]) -> None:
    """canmatrix writes slope and intercept with 6 significant digits ("%g"), min and max with 16,
    leaves out a minimum of 0 and a maximum of 0 or 1 (reading back the bits' range instead), and
    appends the signal's attributes but ENUMs to its notes (by name); KCD nodes have no comments."""
    snap["nodes"] = dict.fromkeys(snap["nodes"])
    for m in snap["messages"].values():
        for s in m["signals"].values():
            _six_digit_scaling(s)
            bits_lo, bits_hi = _bits_range(s)
            s["min"] = bits_lo if s["min"] == 0 else Decimal(f"{s['min']:.16g}")
            s["max"] = bits_hi if s["max"] in (0, 1) else Decimal(f"{s['max']:.16g}")
            notes = s["attributes"] | ({SPEC_NAME_ATTRIBUTE: s["spec_name"]} if s["spec_name"] else {})
            if notes:
                s["comment"] = (s["comment"] or "") + "\n" + "".join(f"\n{name}: {text}" for name, text in sorted(notes.items()))


class _Lost:
    """A field the converter gives wrongly: not compared."""

    def __repr__(self) -> str:
        return "LOST"


LOST = _Lost()


def _canmatrix_arxml(snap: dict[str, Any]) -> None:
    """canmatrix's ARXML: frames come back named after their FRAME element (`FRAME_<name>`), no
    cycle times, factor and offset to 6 significant digits, signal ranges as the bits' range (it
    writes none), only the BO_ line's sender (not BO_TX_BU_'s further ones), and only the nodes that send a message or receive a signal. A message named like
    a signal, and such a signal, get their sender and receivers wrongly (an ECU's frame and signal ports share names)."""
    used = set()
    signal_names = {name for m in snap["messages"].values() for name in m["signals"]}
    message_names = {m["name"] for m in snap["messages"].values()}
    for m in snap["messages"].values():
        if m["name"] in signal_names:
            m["senders"] = LOST
        for name, s in m["signals"].items():
            if m["name"] in signal_names or name in message_names:
                s["receivers"] = LOST
        m["name"], m["cycle"] = f"FRAME_{m['name']}", None
        m["senders"] = m["senders"][:1] if m["senders"] is not LOST else LOST  # the BO_ line's; BO_TX_BU_'s are lost
        used.update(m["senders"] if m["senders"] is not LOST else ())
        for s in m["signals"].values():
            if CANMATRIX < (1, 3):
                _six_digit_scaling(s)
            else:
                _one_decimal_scaling(s)
            s["min"], s["max"] = _bits_range(s)
            used.update(s["receivers"] if s["receivers"] is not LOST else ())
    snap["nodes"] = {n: c for n, c in snap["nodes"].items() if n in used}


def _one_decimal_scaling(sig: dict[str, Any]) -> None:
    """canmatrix 1.3's ARXML: every signal comes back unsigned; factor and offset are written with one
    decimal place (a factor that rounds to 0 comes back as 1: 0.02 → 1, 0.05 → 0.1); a signal with
    value descriptions gets a text table only and comes back unscaled (factor 1, offset 0)."""
    sig["signed"] = False
    if sig["choices"]:
        sig["scale"], sig["offset"] = Decimal(1), Decimal(0)
        return
    sig["scale"] = Decimal(repr(round(float(sig["scale"]), 1))) or Decimal(1)
    sig["offset"] = Decimal(repr(round(float(sig["offset"]), 1)))


def _classic_frames(snap: dict[str, Any]) -> None:
    """SYM and KCD (both tools) have no CAN FD frame format: an FD frame comes back a classic frame of
    the same length, without bit-rate switching; the bus type and the data-phase bitrate (DBC
    attributes) are not written. Byte order and IEEE float types come back."""
    snap["bus"] = {"type": None, "data_bitrate": None}
    for m in snap["messages"].values():
        m["fd"], m["brs"] = False, None


def _canmatrix_arxml_fd(snap: dict[str, Any]) -> None:
    """canmatrix's ARXML keeps the FD frame format (VFrameFormat comes back) and writes BusType "CAN FD"
    for a matrix with an FD frame (none for a classic one), but not bit-rate switching (no CANFD_BRS
    comes back) nor the data-phase bitrate; a float signal comes back signed (1.2; 1.3 makes every
    signal unsigned, see _one_decimal_scaling)."""
    snap["bus"] = {"type": "CAN FD" if any(m["fd"] for m in snap["messages"].values()) else None, "data_bitrate": None}
    for m in snap["messages"].values():
        m["brs"] = None
        for s in m["signals"].values():
            s["signed"] = s["signed"] or s["float"]


def _unindented_comments(snap: dict[str, Any]) -> None:
    """canmatrix strips the indentation of a comment's lines (a multi-line description's list)."""
    for m in snap["messages"].values():
        for item in (m, *m["signals"].values()):
            if item["comment"]:
                item["comment"] = "\n".join(line.lstrip() for line in item["comment"].split("\n"))


def expected(tool: str, fmt: str, original: dict[str, Any]) -> dict[str, Any]:
    snap = copy.deepcopy(original)
    if tool == "canmatrix":
        _unindented_comments(snap)
    if fmt != "arxml":
        _classic_frames(snap)
    else:
        _canmatrix_arxml_fd(snap)
    if fmt == "sym":
        _no_nodes(snap)
        _one_line_comments(snap)
        if tool == "canmatrix":  # its SYM writer keeps 16 characters of a unit
            for m in snap["messages"].values():
                for s in m["signals"].values():
                    s["unit"] = s["unit"][:16]
    elif (tool, fmt) == ("cantools", "kcd"):
        snap["nodes"] = dict.fromkeys(snap["nodes"])  # KCD nodes have no comments
    elif (tool, fmt) == ("canmatrix", "kcd"):
        _canmatrix_kcd(snap)
    else:
        _canmatrix_arxml(snap)
    return snap


def _double(value: Any) -> float | None:
    return None if value is None else float(value)


def differences(want: dict[str, Any], got: dict[str, Any], as_doubles: bool) -> list[str]:
    """Every field of `want` that differs in `got` (spec names and other attributes are DBC attributes: not compared)."""
    out = [f"{part}: {want[part]} != {got[part]}" for part in ("bus", "nodes") if want[part] != got[part]]
    if set(want["messages"]) != set(got["messages"]):
        return out + [f"messages: {sorted(want['messages'])} != {sorted(got['messages'])}"]
    for key, wm in want["messages"].items():
        gm = got["messages"][key]
        out += [f"{key} {f}: {wm[f]!r} != {gm[f]!r}" for f in wm if f != "signals" and wm[f] is not LOST and wm[f] != gm[f]]
        if set(wm["signals"]) != set(gm["signals"]):
            out.append(f"{key} signals: {sorted(wm['signals'])} != {sorted(gm['signals'])}")
            continue
        for name, ws in wm["signals"].items():
            gs = gm["signals"][name]
            for f in ws:
                if f in ("spec_name", "attributes") or ws[f] is LOST:
                    continue
                same = _double(ws[f]) == _double(gs[f]) if as_doubles and f in REWRITTEN else (ws[f] == gs[f] and type(ws[f]) is type(gs[f]))
                if not same:
                    out.append(f"{key} {name}.{f}: {ws[f]!r} != {gs[f]!r}")
    return out
