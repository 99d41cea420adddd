"""DBC for the CAN protocol, with Vector's J1939 attributes. Encoding: UTF-8 (see the README):
identifiers are ASCII, Chinese text appears only in CM_ comments."""

from __future__ import annotations

from canspec import ir
from canspec.render.environment import render
from canspec.targets import Target

# Vector J1939 SigType enum (index = value written in BA_).
SIG_TYPES = ("Default", "Range", "RangeSigned", "ASCII", "Discrete", "Control", "ReferencePGN", "DTC",
             "StringDelimiter", "StringLength", "StringLengthControl", "MessageCounter", "MessageChecksum")
VFRAME_FORMATS = ("StandardCAN", "ExtendedCAN", "reserved", "J1939PG")
UNKNOWN_NODE = "Vector__XXX"


def sig_type(sig: ir.Signal) -> int:
    if sig.role == "counter":
        return SIG_TYPES.index("MessageCounter")
    if sig.role == "checksum":
        return SIG_TYPES.index("MessageChecksum")
    if sig.value_table is not None:
        return SIG_TYPES.index("Discrete")
    return SIG_TYPES.index("Range")


def dbc_id(msg: ir.Message) -> int:
    return msg.frame_id | 0x80000000 if msg.is_extended else msg.frame_id


def sender(msg: ir.Message) -> str:
    return UNKNOWN_NODE if msg.sender == "ALL" else msg.sender


def signal_comment(sig: ir.Signal) -> str:
    parts = [sig.zh]
    if sig.desc:
        parts.append(sig.desc)
    if sig.desc_zh:
        parts.append(sig.desc_zh)
    if sig.doc_min is not None and (sig.doc_min != sig.phys_min or sig.doc_max != sig.phys_max):
        parts.append(f"Documented range [{ir_num(sig.doc_min)}, {ir_num(sig.doc_max)}]")
    for s in sig.specials:
        parts.append(f"0x{s.raw:X} = {s.name} ({s.label_zh})")
    if sig.value_table is not None:
        parts.append("; ".join(f"{e.raw}: {e.label_zh}" for e in sig.value_table.entries))
    return " | ".join(p for p in parts if p)


def ir_num(value: object) -> str:
    from canspec.render.literals import num

    return num(value)  # type: ignore[arg-type]


def render_dbc(spec: ir.Spec) -> dict[str, bytes]:
    if spec.can is None:
        return {}
    text = render(
        "dbc/protocol.dbc.j2", spec, "dbc", can=spec.can, sig_type=sig_type, dbc_id=dbc_id, sender=sender,
        signal_comment=signal_comment, sig_types=SIG_TYPES, vframe_formats=VFRAME_FORMATS,
        vframe_j1939=VFRAME_FORMATS.index("J1939PG"),
    )
    return {f"dbc/{spec.can.name}.dbc": text.encode("utf-8")}


TARGET = Target("dbc", "DBC database (Vector J1939 attributes, UTF-8)", "dbc/", render_dbc, order=10)
