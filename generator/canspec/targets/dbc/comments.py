"""The DBC's CM_ comments: what a DBC has no field for (Chinese names, descriptions, the documented
range, special values, Chinese value labels), parts joined by " | ". A part the spec leaves out is
left out, never written empty, so an English-only spec gives English-only comments.

Special values are written `0x3FF = no_obstacle (无障碍物)` (`-0x4` for a negative raw value, the
label only where the spec gives one): `canspec import` (and `canspec diff`
through it) reads them back from there (importer/signals.py)."""

from __future__ import annotations

from canspec import ir
from canspec.render.literals import hex_byte, hex_text, num

SEPARATOR = " | "


def joined(parts: list[str]) -> str:
    return SEPARATOR.join(p for p in parts if p)


def special_text(s: ir.SpecialValue) -> str:
    return f"{hex_text(s.raw)} = {s.name}" + (f" ({s.label_zh})" if s.label_zh else "")


def signal_comment(sig: ir.Signal, spec_name: str | None, as_imported: bool = False) -> str:
    """`spec_name`: the spec's name of a signal the DBC renamed (see naming.py), else None. A DBC as
    imported writes the documented range as its [min|max] itself (model.DbcSignal.bounds)."""
    parts = [sig.zh, sig.desc, sig.desc_zh]
    if not as_imported and sig.doc_min is not None and sig.doc_max is not None and (sig.doc_min, sig.doc_max) != (sig.phys_min, sig.phys_max):
        parts.append(f"Documented range [{num(sig.doc_min)}, {num(sig.doc_max)}]")
    parts += [special_text(s) for s in sig.specials]
    parts.append("; ".join(f"{lb.raw}: {lb.label_zh}" for lb in sig.labels if not lb.is_special and lb.label_zh))
    if spec_name is not None:
        parts.append(f"spec name: {spec_name}")
    return joined(parts)


def message_comment(msg: ir.Message, as_imported: bool = False) -> str:
    """A title that is only the message's name (the default) says nothing the BO_ line does not. A
    source DBC's message without signals said nothing of its layout: as imported, it still says nothing."""
    return joined([msg.zh, msg.title if msg.title != msg.name else "", msg.desc, f"§{msg.section}" if msg.section else "",
                   "layout not defined by the document" if msg.layout_undefined and not as_imported else ""])


def node_comment(node: ir.Node) -> str:
    return joined([node.zh, node.desc, f"SA {hex_byte(node.sa)}" if node.sa is not None else ""])
