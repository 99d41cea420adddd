"""DBC → comparison model, through cantools. Names and choices map onto the same model as a
spec; what a DBC cannot say (Chinese names, descriptions, value labels) stays None and is not
compared. Vector J1939 attributes are read when present: GenMsgCycleTime, SigType
(MessageCounter / MessageChecksum roles), and SpecSignalName: the spec's name of a signal the DBC
renamed (targets/dbc/naming.py), so a spec and its own DBC compare equal. Special values are read
back from the comments canspec writes ("0x3FF = no_obstacle (无障碍物)", "-0x4 = no_limit" for a
negative raw value or a special without a Chinese label). Factors, offsets and ranges are taken
as written in the SG_ lines: cantools reads them as doubles, which cannot hold 0.1 or a 64-bit
field's 18446744073709551615 exactly. Byte order (`@0` Motorola, `@1` Intel: the start bit means
what it means in the spec), IEEE floats (SIG_VALTYPE_ 1/2; a float's [0|0] is "no range": every
finite value), CAN FD frames (VFrameFormat 14/15, which cantools reads as is_fd) and their
bit-rate switching (CANFD_BRS, else its BA_DEF_DEF_ default, else unknown: not compared) are read.
Multiplexing (M/mN, SG_MUL_VAL_) is read as each field's multiplexer and values. What the model
cannot hold is refused (an InputError naming it): ignored, a change of it would read as "no
differences"."""

from __future__ import annotations

import re
from fractions import Fraction
from pathlib import Path

from canspec.commands.extras import install_hint
from canspec.diff.model import Entry, MessageModel, ProtocolModel, SignalModel
from canspec.ir.encoding import FLOAT_MAX, raw_type_range
from canspec.ir.model import to_physical
from canspec.ir.mux import ranges_of
from canspec.targets.dbc.naming import SPEC_NAME_ATTRIBUTE


class InputError(Exception):
    """A diff input that cannot be read: the message says what and how to fix it."""


_SIG_TYPE_ROLES = {"MessageCounter": "counter", "MessageChecksum": "checksum"}
_SPECIAL = re.compile(r"(-?)0x([0-9A-Fa-f]+) = ([A-Za-z_][A-Za-z0-9_]*)(?: \(([^)]*)\))?")
_NO_NODE = "Vector__XXX"
_BO = re.compile(r"^\s*BO_\s+(\d+)\s")
# SG_ name [multiplexing] : start|length@order sign (factor,offset) [minimum|maximum]
_SG = re.compile(r"^\s*SG_\s+(\w+)[^:]*:\s*\d+\|\d+@[01][+-]\s*\(([^,()]+),([^,()]+)\)\s*\[([^|\]]+)\|([^\]]+)\]")

Numbers = tuple[Fraction, Fraction, Fraction, Fraction]  # factor, offset, minimum, maximum


def _frac(value: object) -> Fraction:
    return Fraction(str(value)) if value is not None else Fraction(0)


def written_numbers(text: str) -> dict[tuple[int, str], Numbers]:
    """(BO_ id as written, signal name) → the SG_ line's numbers, exactly."""
    out: dict[tuple[int, str], Numbers] = {}
    frame = None
    for line in text.splitlines():
        if (bo := _BO.match(line)) is not None:
            frame = int(bo.group(1))
        elif frame is not None and (sg := _SG.match(line)) is not None:
            try:
                f, o, lo, hi = (Fraction(g.strip()) for g in sg.groups()[1:])
            except (ValueError, ZeroDivisionError):
                continue  # cantools' reading stands
            out[(frame, sg.group(1))] = (f, o, lo, hi)
    return out


def _attr(obj: object, name: str) -> object:
    dbc = getattr(obj, "dbc", None)
    attrs = getattr(dbc, "attributes", None) or {}
    attr = attrs.get(name)
    return getattr(attr, "value", None) if attr is not None else None


def _role(sig: object, attribute_definitions: dict) -> str:  # type: ignore[type-arg]
    value = _attr(sig, "SigType")
    if isinstance(value, int):
        definition = attribute_definitions.get("SigType")
        choices = getattr(definition, "choices", None)
        if choices and 0 <= value < len(choices):
            value = choices[value]
    return _SIG_TYPE_ROLES.get(str(value), "data")


def _range(sig, written: Numbers | None, definitions) -> tuple[Fraction, Fraction, Fraction, Fraction]:  # type: ignore[no-untyped-def]
    """factor, offset and the range, exactly as written; a missing range is what the bits can carry."""
    if written is not None:
        factor, offset, lo, hi = written
        # [0|0] says "no range" in a DBC, but a range of exactly 0 … 0 in one canspec wrote (not for a float: it writes [0|0] for none).
        no_range = lo == hi == 0 and (sig.is_float or SPEC_NAME_ATTRIBUTE not in definitions)
    else:
        factor, offset, lo, hi = _frac(sig.scale), _frac(sig.offset), _frac(sig.minimum), _frac(sig.maximum)
        no_range = sig.minimum is None or sig.maximum is None
    if no_range and sig.is_float:
        if sig.length not in FLOAT_MAX:
            raise InputError(f"signal {sig.name!r} is an IEEE float of {sig.length} bits (SIG_VALTYPE_ needs 32 or 64)")
        return factor, offset, -FLOAT_MAX[sig.length], FLOAT_MAX[sig.length]
    if no_range:
        a, b = (to_physical(raw, factor, offset) for raw in raw_type_range(sig.length, bool(sig.is_signed)))
        lo, hi = min(a, b), max(a, b)
    return factor, offset, lo, hi


def _signal(sig, definitions, written: Numbers | None, names: dict[str, str]) -> SignalModel:  # type: ignore[no-untyped-def]
    """`names`: the message's DBC signal names → the spec's (a multiplexer is named by its spec name)."""
    specials = {}
    for m in _SPECIAL.finditer(sig.comment or ""):
        specials[int(m.group(1) + m.group(2), 16)] = Entry(m.group(3), m.group(4))
    # canspec lists special values in VAL_ too (so tools show them); they are not enum entries.
    choices = {int(raw): str(getattr(v, "name", v)) for raw, v in (sig.choices or {}).items()}
    values = {raw: Entry(name, None) for raw, name in choices.items() if not (raw in specials and specials[raw].name == name)} or None
    factor, offset, lo, hi = _range(sig, written, definitions)
    return SignalModel(
        name=str(_attr(sig, SPEC_NAME_ATTRIBUTE) or sig.name), start=sig.start, length=sig.length, signed=bool(sig.is_signed), factor=factor, offset=offset,
        unit=sig.unit or "", minimum=lo, maximum=hi, role=_role(sig, definitions), values=values, values_table=None,
        specials=specials, zh=None, desc=None, byte_order=sig.byte_order, is_float=bool(sig.is_float),
        mux=(names.get(sig.multiplexer_signal, sig.multiplexer_signal), ranges_of(sig.multiplexer_ids)) if sig.multiplexer_ids else None,
        is_multiplexer=bool(sig.is_multiplexer),
    )


def _brs(msg, definitions) -> bool | None:  # type: ignore[no-untyped-def]
    """Bit-rate switching of an FD frame: its CANFD_BRS, else the attribute's default, else unknown."""
    if not msg.is_fd:
        return False
    value = _attr(msg, "CANFD_BRS")
    if value is None:
        value = getattr(definitions.get("CANFD_BRS"), "default_value", None)
    return None if value is None else str(value) == "1"


def _read_text(path: Path, source: str) -> str:
    data = path.read_bytes()
    for encoding in ("utf-8", "cp1252"):  # canspec writes UTF-8; Vector tools often write cp1252
        try:
            return data.decode(encoding)
        except UnicodeDecodeError:
            continue
    raise InputError(f"{source}: not a readable DBC file (neither UTF-8 nor cp1252 text)")


def load_dbc(path: Path, source: str) -> ProtocolModel:
    try:
        import cantools  # optional: only DBC inputs need it
    except ImportError as exc:
        raise InputError(f"{source}: reading DBC files needs cantools; {install_hint('import')}") from exc
    text = _read_text(path, source)
    try:
        db = cantools.database.load_string(text, database_format="dbc", strict=False)
    except Exception as exc:  # cantools raises many kinds; all mean "not a DBC"
        first = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise InputError(f"{source}: not a readable DBC file: {first}") from exc
    if not isinstance(db, cantools.database.can.Database):
        raise InputError(f"{source}: not a CAN database")
    definitions = getattr(getattr(db, "dbc", None), "attribute_definitions", None) or {}
    written = written_numbers(text)
    messages = []
    for msg in db.messages:
        dbc_id = msg.frame_id | 0x80000000 if msg.is_extended_frame else msg.frame_id
        try:
            names = {s.name: str(_attr(s, SPEC_NAME_ATTRIBUTE) or s.name) for s in msg.signals}
            signals = tuple(sorted((_signal(s, definitions, written.get((dbc_id, s.name)), names) for s in msg.signals), key=lambda s: (s.start, s.length)))
        except InputError as exc:
            raise InputError(f"{source}: message {msg.name!r}: {exc}") from exc
        senders = [s for s in msg.senders if s != _NO_NODE]
        receivers = sorted({r for s in msg.signals for r in s.receivers if r != _NO_NODE})
        messages.append(
            MessageModel(
                frame_id=msg.frame_id, extended=bool(msg.is_extended_frame), name=msg.name, title=None, zh=None,
                dlc=msg.length, cycle_ms=msg.cycle_time, sender=senders[0] if senders else "ALL",
                receivers=tuple(receivers) if receivers else None, signals=signals, checksum=None, multiframe=None,
                fd=bool(msg.is_fd), brs=_brs(msg, definitions),
            )
        )
    version = (getattr(db, "version", None) or "").strip() or None
    name = path.stem
    if version and " " in version:  # canspec writes VERSION "<protocol> <version>"
        name, version = version.rsplit(" ", 1)
    return ProtocolModel(source, "dbc", name, version, tuple(messages))
