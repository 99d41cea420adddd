"""The doc comments of the generated crate. Spec text becomes Markdown that rustdoc and clippy
read as plain prose: no links, HTML, code blocks (indented or fenced: rustdoc would run them
as doctests), list items or bidirectional-text controls (rustc rejects those in comments).
An English-only spec shows no empty Chinese; a bilingual one shows both.
"""

from __future__ import annotations

import re
import textwrap
from fractions import Fraction

from canspec import ir
from canspec.ir.bits import describe
from canspec.ir.names import humanize
from canspec.render.literals import RUST, num

BIDI_CONTROLS = re.compile("[\u202a-\u202e\u2066-\u2069]")
LIST_MARKER = re.compile(r"^([-*+]|\d+[.)])(\s|$)")
NONE = "—"
DOC_WIDTH = 96  # a wrapped doc paragraph's text, `//! ` or `/// ` before it


def doc_text(text: str) -> str:
    """One line of prose, safe inside a `///` comment."""
    text = " ".join(text.split())
    text = BIDI_CONTROLS.sub(lambda m: f"U+{ord(m.group()):04X}", text)
    for ch, escaped in (("\\", "\\\\"), ("[", "\\["), ("]", "\\]"), ("<", "&lt;"), (">", "&gt;"), ("`", "'"), ("~", "\\~"), ("|", "\\|")):
        text = text.replace(ch, escaped)
    if LIST_MARKER.match(text) or text.startswith("#"):
        # Markdown would read the line as a list item or a heading: escape its marker.
        return re.sub(r"^(\d+)([.)])", r"\1\\\2", text) if text[0].isdigit() else "\\" + text
    return text


def doc_lines(text: str) -> list[str]:
    """Multi-line prose: each line as `doc_text`, blank lines kept as paragraph breaks."""
    lines = [doc_text(line) for line in text.splitlines()]
    while lines and not lines[-1]:
        lines.pop()
    return lines


def both(zh: str, en: str) -> str:
    """`中文 — English`, or whichever of the two the spec gives."""
    return " — ".join(t for t in (zh, en) if t)


def labelled(zh: str, en: str) -> str:
    """`中文 (English)`, or whichever of the two the spec gives."""
    return f"{zh} ({en})" if zh and en else zh or en


def _range_text(lo: Fraction | None, hi: Fraction | None) -> str:
    return NONE if lo is None else f"{num(lo)} … {num(hi)}"


def _unit(sig: ir.Signal) -> str:
    return doc_text(sig.unit) or NONE


def field_doc(sig: ir.Signal) -> tuple[str, ...]:
    first = both(sig.zh, sig.desc.splitlines()[0] if sig.desc else "") or humanize(sig.name)
    lines = doc_lines(first)
    rest = sig.desc.splitlines()[1:] if sig.desc else []
    if rest:
        lines += doc_lines("\n".join(rest))
    if sig.desc_zh:
        lines += ["", *doc_lines(sig.desc_zh)]
    lines += [
        "",
        "| start bit | length | factor | offset | unit | range | raw |",
        "|---|---|---|---|---|---|---|",
        (f"| {sig.start} | {sig.length} | {num(sig.factor)} | {num(sig.offset)} | {_unit(sig)} "
         f"| {_range_text(sig.check_min, sig.check_max)} | {RUST.integer(sig.raw_min)} … {RUST.integer(sig.raw_max)} |"),
    ]
    if sig.is_big_endian:
        lines += ["", doc_text(f"Motorola (big-endian; the start bit is the most significant): {describe(sig.start, sig.length, sig.byte_order)}.")]
    if sig.is_float:
        lines += ["", doc_text(f"IEEE 754 float{sig.length}: the raw value is its bit pattern; NaN and ±infinity are "
                               f"{'refused (a range is documented)' if sig.doc_min is not None else 'allowed'}; NaN is sent as the quiet NaN.")]
    for s in sig.specials:
        lines += ["", doc_text(f"Special raw value {RUST.integer(s.raw)}: {labelled(s.label_zh, s.label)}")]
    if sig.errata:
        lines += ["", doc_text(f"Errata: {', '.join(sig.errata)} (see spec/ERRATA.md)")]
    return tuple(lines)


def short_doc(sig: ir.Signal, type_name: str, getter: str) -> str:
    """One line: name, range and unit, and where the getter is (rustdoc links no raw identifier)."""
    where = f"`{type_name}::{getter}`" if getter.startswith("r#") else f"[`{type_name}::{getter}`]"
    return doc_text(f"{sig.zh or humanize(sig.name)}: {_range_text(sig.check_min, sig.check_max)} {sig.unit}".rstrip()) + f" (see {where})."


def special_doc(sig: ir.Signal, special: ir.SpecialValue, field: str) -> str:
    return doc_text(f"{sig.zh or humanize(sig.name)}: {labelled(special.label_zh, special.label)}") + f", raw value of `{field}`"


def table_row(sig: ir.Signal, field: str, bilingual: bool) -> str:
    zh = f" {doc_text(sig.zh) or NONE} |" if bilingual else ""
    return f"| `{field}` |{zh} {sig.start} | {sig.length} | {num(sig.factor)} | {num(sig.offset)} | {_unit(sig)} |"


def table_head(bilingual: bool) -> tuple[str, str]:
    return ("| signal | 名称 | start bit | length | factor | offset | unit |", "|---|---|---|---|---|---|---|") if bilingual else \
        ("| signal | start bit | length | factor | offset | unit |", "|---|---|---|---|---|---|")


def variant_doc(entry: ir.ValueEntry) -> str:
    return doc_text(f"{entry.raw}: {both(entry.label_zh, entry.label)}")


def message_doc(msg: ir.Message) -> tuple[str, ...]:
    lines = [*doc_lines(both(msg.zh, msg.title)), ""]
    if msg.desc:
        lines += [*doc_lines(msg.desc), ""]
    width = "29-bit" if msg.is_extended else "11-bit"
    timing = f"every {msg.cycle_ms} ms" if msg.cycle_ms is not None else "event-driven (no cycle time)"
    section = f", section {doc_text(msg.section)} of the document" if msg.section else ""
    lines.append(f"ID `{msg.id_text}` ({width}), DLC {msg.dlc}, {timing}{section}.")
    j = msg.j1939
    if j is not None:
        destination = f", destination {RUST.hex(j.da, 2)}." if j.da is not None else " (broadcast)."
        lines.append(f"J1939: priority {j.priority}, PGN {j.pgn_text}, source address {RUST.hex(j.sa, 2)}{destination}")
    receivers = f"; receivers {', '.join(msg.receivers)}" if msg.receivers else ""
    lines.append(doc_text(f"Sender {msg.sender}{receivers}."))
    if msg.layout_undefined:
        lines += ["", "The document lists this message but defines no layout: it carries no signals."]
    if msg.checksum:
        lines += ["", f"Byte {msg.checksum.byte} is the XOR of bytes {', '.join(map(str, msg.checksum.covers))}: `encode` fills it, decoding checks it."]
    if msg.counter:
        lines += ["", f"`{msg.counter.signal}` is a rolling counter modulo {msg.counter.modulo}."]
    if msg.errata:
        lines += ["", doc_text(f"Errata: {', '.join(msg.errata)} (see spec/ERRATA.md)")]
    return tuple(lines)


def crate_title(can: ir.CanProtocol) -> tuple[str, ...]:
    """The crate doc's first paragraph: `中文标题 1.2.3 — English title.`"""
    zh = f"{' '.join(can.title_zh.split())} {can.version}" if can.title_zh else ""
    en = f"{' '.join(can.title.split())}" if zh else f"{' '.join(can.title.split())} {can.version}"
    return (doc_text(both(zh, en)) + ".",)


def crate_summary(can: ir.CanProtocol, has_enums: bool) -> tuple[str, ...]:
    """The crate doc's second paragraph: what the crate offers for this protocol."""
    offers = [name for name, present in (("value tables as enums", has_enums), ("J1939 identifier helpers", can.bus.is_j1939),
                                          ("rolling counters", can.has_counters), ("XOR checksums", can.has_checksums),
                                          ("multi-frame text", can.has_multiframe)) if present]
    text = ("Generated by canspec from the protocol spec: one type per message with range-checked physical setters, raw accessors, "
            f"`encode` into a frame and `decode` out of one{''.join(f'; {o}' for o in offers)}. `no_std`, no allocation. Features: `std` "
            f"(the `std::error::Error` impl), `serde` (`Serialize`/`Deserialize` on the physical-value structs{' and the enums' if has_enums else ''}).")
    return tuple(textwrap.wrap(text, DOC_WIDTH))


def message_row(msg: ir.Message, type_name: str, bilingual: bool) -> str:
    zh = f" {doc_text(msg.zh) or NONE} |" if bilingual else ""
    cycle = msg.cycle_ms if msg.cycle_ms is not None else "event"
    return f"| [`{type_name}`] |{zh} `{msg.id_text}` | {msg.dlc} | {cycle} |"


def message_table_head(bilingual: bool) -> tuple[str, str]:
    return (
        ("| message | 名称 | ID | DLC | cycle (ms) |", "|---|---|---|---|---|") if bilingual else ("| message | ID | DLC | cycle (ms) |", "|---|---|---|---|")
    )
