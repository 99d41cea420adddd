"""Bit-layout diagram of a CAN frame as SVG: one row per byte × 8 bit columns (bit 7 left, bit 0
right, as CAN matrices draw them), each signal a coloured span labelled with its name and the
value bits the span carries. The spans are the IR's segments, so either byte order is drawn as it
lies: an Intel field continues in the next byte row's low bits, a Motorola field in its high bits
(the label of each span says which value bits it holds). A long CAN FD frame is drawn in parts of
at most PART_ROWS bytes, each a diagram of its own, so that every part fits a printed page.

Built as text with integer coordinates, so the output is byte-for-byte reproducible."""

from __future__ import annotations

from dataclasses import dataclass
from xml.sax.saxutils import escape, quoteattr

from canspec import ir

# Colour-blind-friendly light fills (Okabe-Ito hues lightened) with a darker edge each.
PALETTE = (
    ("#cfe6f7", "#0072b2"), ("#fde2c0", "#e69f00"), ("#c9ecdf", "#009e73"), ("#f9d3e6", "#cc79a7"),
    ("#d6ecf9", "#56b4e9"), ("#f6e9a8", "#b59a00"), ("#f7cdb8", "#d55e00"), ("#e0dcf2", "#6a5acd"),
    ("#d9ead3", "#38761d"), ("#fff2cc", "#bf9000"), ("#ead1dc", "#a64d79"), ("#d0e0e3", "#45818e"),
)
RESERVED = ("#eeeeee", "#9e9e9e")
CELL_W = 104
CELL_H = 52
LEFT = 64  # room for the byte labels
TOP = 40  # room for the bit labels
FONT = "ui-monospace, 'DejaVu Sans Mono', Menlo, Consolas, monospace"
CHAR_W = 6.8  # advance of a 11.5px monospace glyph, to decide when a label must be squeezed
PART_ROWS = 16  # bytes per diagram: a 64-byte FD frame is drawn as 4 diagrams of 16 rows


@dataclass(frozen=True)
class Span:
    """One signal's share of one byte row."""

    signal: ir.Signal
    byte: int
    hi_bit: int  # leftmost bit (in the byte) of the span
    lo_bit: int
    value_lo: int  # value bits carried: [value_lo, value_hi]
    value_hi: int
    fill: str
    stroke: str


def colours(msg: ir.Message) -> dict[str, tuple[str, str]]:
    """Fill and edge colour per signal, stable for a given layout."""
    out = {}
    data = [s for s in msg.signals if not s.is_reserved]
    for i, sig in enumerate(data):
        out[sig.name] = PALETTE[i % len(PALETTE)]
    for sig in msg.reserved_signals:
        out[sig.name] = RESERVED
    return out


def spans(msg: ir.Message) -> list[Span]:
    cols = colours(msg)
    out = []
    for sig in msg.signals:
        for seg in sig.segments:
            fill, stroke = cols[sig.name]
            out.append(Span(sig, seg.byte, seg.byte_shift + seg.width - 1, seg.byte_shift, seg.value_shift,
                            seg.value_shift + seg.width - 1, fill, stroke))
    return out


def parts(msg: ir.Message) -> tuple[range, ...]:
    """The byte rows of each diagram of the message, in frame order."""
    return tuple(range(first, min(first + PART_ROWS, msg.dlc)) for first in range(0, msg.dlc, PART_ROWS))


def tooltip(sig: ir.Signal, zh: bool) -> str:
    name = f"{sig.name} {sig.zh}".strip() if zh else sig.name
    kind = f", float{sig.length}" if sig.is_float else ""
    if sig.is_big_endian:
        return f"{name}: start {sig.start} (MSB, Motorola), length {sig.length}{kind}"
    return f"{name}: start {sig.start}, length {sig.length}{kind}"


def _span_label(span: Span) -> str:
    sig = span.signal
    if sig.length == 1:
        return "1 bit"
    if span.value_lo == 0 and span.value_hi == sig.length - 1:
        return f"{sig.length} bits"
    return f"bits {span.value_lo}–{span.value_hi} of {sig.length}"


def _text(x: int, y: int, text: str, size: float, room: int, weight: str = "normal", colour: str = "#1a1a1a") -> str:
    attrs = f'x="{x}" y="{y}" font-size="{size}" text-anchor="middle" font-weight="{weight}" fill="{colour}"'
    if len(text) * CHAR_W * size / 11.5 > room:
        attrs += f' textLength="{room}" lengthAdjust="spacingAndGlyphs"'
    return f"<text {attrs}>{escape(text)}</text>"


def bit_layout(msg: ir.Message, zh: bool, rows: range | None = None) -> str:
    """The diagram of the byte `rows` (default: the whole frame). `zh`: the handbook is bilingual,
    so a signal's tooltip gives its Chinese name too."""
    rows = range(msg.dlc) if rows is None else rows
    width = LEFT + 8 * CELL_W + 8
    height = TOP + len(rows) * CELL_H + 8
    title = f"{msg.name} ({msg.id_text}) bit layout" + (f", bytes {rows[0]}–{rows[-1]}" if len(rows) < msg.dlc else "")
    out = [
        (f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" '
         f'font-family="{FONT}" role="img" aria-label={quoteattr(title)}>'),
        f"<title>{escape(title)}</title>",
        f'<rect x="0" y="0" width="{width}" height="{height}" fill="#ffffff"/>',
        f'<text x="{LEFT // 2}" y="{TOP - 14}" font-size="11" text-anchor="middle" fill="#555555">byte</text>',
    ]
    for col in range(8):
        bit = 7 - col
        out.append(f'<text x="{LEFT + col * CELL_W + CELL_W // 2}" y="{TOP - 14}" font-size="12" text-anchor="middle" fill="#555555">bit {bit}</text>')
    for row, byte in enumerate(rows):
        y = TOP + row * CELL_H
        out.append(f'<text x="{LEFT // 2}" y="{y + CELL_H // 2 + 5}" font-size="14" text-anchor="middle" font-weight="bold" fill="#333333">{byte}</text>')
        for col in range(8):  # empty cells first: bits no signal covers stay white
            out.append(f'<rect x="{LEFT + col * CELL_W}" y="{y}" width="{CELL_W}" height="{CELL_H}" fill="#ffffff" stroke="#d0d0d0"/>')
    out += _span_shapes(msg, zh, rows)
    for row, byte in enumerate(rows):  # absolute bit numbers (8 × byte + bit, a start bit's numbering) in each cell's corner
        for col in range(8):
            bit = byte * 8 + 7 - col
            out.append(
                f'<text x="{LEFT + col * CELL_W + CELL_W - 5}" y="{TOP + row * CELL_H + 11}" font-size="8" text-anchor="end" fill="#777777">{bit}</text>'
            )
    out.append(f'<rect x="{LEFT}" y="{TOP}" width="{8 * CELL_W}" height="{len(rows) * CELL_H}" fill="none" stroke="#555555" stroke-width="1.5"/>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


def _span_shapes(msg: ir.Message, zh: bool, rows: range) -> list[str]:
    out = []
    for span in spans(msg):
        if span.byte not in rows:
            continue
        x = LEFT + (7 - span.hi_bit) * CELL_W
        y = TOP + (span.byte - rows[0]) * CELL_H
        w = (span.hi_bit - span.lo_bit + 1) * CELL_W
        sig = span.signal
        out.append(f'<g class="signal" data-signal={quoteattr(sig.name)}>')
        out.append(f"<title>{escape(tooltip(sig, zh))}</title>")
        out.append(f'<rect x="{x + 2}" y="{y + 2}" width="{w - 4}" height="{CELL_H - 4}" rx="5" fill="{span.fill}" stroke="{span.stroke}" stroke-width="1.5"/>')
        out.append(_text(x + w // 2, y + 28, "reserved" if sig.is_reserved else sig.name, 11.5, w - 12, "bold"))
        out.append(_text(x + w // 2, y + 43, _span_label(span), 10, w - 12, colour="#444444"))
        out.append("</g>")
    return out
