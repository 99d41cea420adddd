"""What the CAN pages' table cells say: Python decides every number and word, in the spec's
languages (lang.py); the templates only place the cells."""

from __future__ import annotations

from fractions import Fraction

from canspec import ir
from canspec.ir import bits
from canspec.ir.encoding import round_half_away
from canspec.ir.fd import CLASSIC_MAX, dlc_code
from canspec.ir.mux import ranges_text
from canspec.render.literals import hex_text, num
from canspec.targets.docs.lang import Lang


def cell(text: object) -> str:
    """Text made safe for a Markdown table cell."""
    return str(text).replace("|", "\\|").replace("\n", "<br>")


def hex_id(value: int) -> str:
    """A frame ID from the change record, which does not say whether it is 11 or 29 bits."""
    return hex_text(value, 8)


def pct(value: Fraction, places: int = 2) -> str:
    """A share (0..1) as a percentage, rounded half up at `places` decimals: 0.34944 → 34.94 %."""
    scaled = value * 100 * 10**places
    n = round_half_away(scaled)
    text = f"{abs(n) // 10**places}.{abs(n) % 10**places:0{places}d}" if places else str(abs(n))
    return ("-" if n < 0 else "") + text + " %"


def decimal(value: Fraction, places: int = 1) -> str:
    """A rate rounded half up to `places` decimals, trailing zeros kept: 1600 → 1600.0."""
    return pct(value / 100, places)[:-2]


def titled(zh: str, en: str) -> str:
    """A page or section title from a Chinese and an English name, either of which may be missing."""
    return " — ".join(t for t in (zh, en) if t)


def id_kind(msg: ir.Message, lang: Lang) -> str:
    return lang.en_zh("29-bit extended", "扩展帧") if msg.is_extended else lang.en_zh("11-bit standard", "标准帧")


def cycle_text(msg: ir.Message, lang: Lang) -> str:
    return f"{msg.cycle_ms} ms" if msg.cycle_ms is not None else lang.en_zh("event-driven", "事件触发")


def doc_range(sig: ir.Signal) -> str:
    if sig.doc_min is None or sig.doc_max is None:
        return "—"
    return f"{num(sig.doc_min)} … {num(sig.doc_max)}"


def enc_range(sig: ir.Signal) -> str:
    """What a physical encode can produce: the documented range cut to what the bits carry. A float
    field carries its value's IEEE 754 bit pattern: any float of its width, NaN and ±Inf too, unless
    a range is documented (then that range, which a float always reaches)."""
    if sig.is_float:
        shown = doc_range(sig) if sig.doc_min is not None else f"any float{sig.length}, NaN, ±Inf"
        return f"{shown}<br><small>raw: the IEEE 754 bit pattern</small>"
    return f"{num(sig.phys_min)} … {num(sig.phys_max)}<br><small>raw {sig.raw_min} … {sig.raw_max}</small>"


def range_note(sig: ir.Signal, lang: Lang) -> str:
    if sig.doc_min is None or sig.doc_max is None or sig.is_float:
        return ""
    if (sig.doc_min, sig.doc_max) != (sig.phys_min, sig.phys_max):
        return "⚠ " + lang.en_zh("differs from the documented range", "与文档范围不同")
    return ""


def label_text(lb: ir.Label, lang: Lang) -> str:
    return " ".join(t for t in (lang.only_zh(lb.label_zh), lb.label) if t)


def vt_anchor(name: str) -> str:
    return f"vt-{name.replace('_', '-')}"


def value_cell(sig: ir.Signal, prefix: str, lang: Lang) -> str:
    """The signal's value table (linked) and its entries: the labels that are not special values."""
    if sig.value_table is None:
        return ""
    parts = [f"[`{sig.value_table.name}`]({prefix}value_tables.md#{vt_anchor(sig.value_table.name)})"]
    parts += [f"{lb.raw} = {label_text(lb, lang)}" for lb in sig.labels if not lb.is_special]
    return "<br>".join(cell(p) for p in parts)


def special_cell(sig: ir.Signal, lang: Lang) -> str:
    """Special values, as decoders name them (a value the table names keeps the table's name)."""
    return "<br>".join(cell(f"{hex_text(lb.raw)} = {label_text(lb, lang)}") for lb in sig.labels if lb.is_special)


def role_cell(sig: ir.Signal, msg: ir.Message, lang: Lang) -> str:
    if sig.role == "counter" and msg.counter is not None:
        return lang.zh_en("心跳", f"rolling counter, mod {msg.counter.modulo}")
    if sig.role == "checksum" and msg.checksum is not None:
        return lang.zh_en("异或校验", f"{msg.checksum.algorithm.upper()} of bytes {byte_list(msg.checksum.covers)} → byte {msg.checksum.byte}")
    if sig.role == "reserved":
        return lang.zh_en("保留", lang.en_zh("reserved, sent as 0", "发送 0"))
    if msg.multiframe is not None and sig.name == msg.multiframe.index_signal:
        return lang.zh_en("多帧序号", "frame index")
    if msg.multiframe is not None and sig.name == msg.multiframe.payload_signal:
        return lang.zh_en("VIN 片段", f"text chunk ({msg.multiframe.bytes_per_frame} × {msg.multiframe.encoding.upper()})")
    return ""


def byte_list(covers: tuple[int, ...]) -> str:
    """0, 1, 2, 3 → "0–3"; anything not contiguous is listed."""
    if len(covers) > 1 and list(covers) == list(range(covers[0], covers[-1] + 1)):
        return f"{covers[0]}–{covers[-1]}"
    return ", ".join(map(str, covers))


def bytes_cell(sig: ir.Signal) -> str:
    """The bytes the field touches, in frame order (a Motorola field's least significant bits lie in its last byte)."""
    touched = sorted(seg.byte for seg in sig.segments)
    first, last = touched[0], touched[-1]
    return str(first) if first == last else f"{first}–{last}"


def order_cell(sig: ir.Signal, lang: Lang) -> str:
    return "Motorola" + lang.only_zh(" 大端") if sig.is_big_endian else "Intel" + lang.only_zh(" 小端")


def type_cell(sig: ir.Signal) -> str:
    if sig.is_float:
        return f"float{sig.length}"
    return "signed" if sig.signed else "unsigned"


def kbit(bitrate: int) -> str:
    return num(Fraction(bitrate, 1000)) + " kbit/s"


def frame_cell(msg: ir.Message, bus: ir.Bus, lang: Lang) -> str:
    """The frame format: classic CAN, or CAN FD with or without bit-rate switching."""
    if not msg.is_fd:
        return lang.en_zh("classic CAN", "经典 CAN")
    if not msg.brs:
        return lang.en_zh("CAN FD, no bit-rate switch: the data phase at the nominal bit rate", "CAN FD，不切换波特率")
    phase = f": the data phase at {kbit(bus.data_bitrate)}" if bus.data_bitrate else ""
    return lang.en_zh(f"CAN FD with bit-rate switch (BRS){phase}", "CAN FD，数据段切换波特率")


def length_cell(msg: ir.Message) -> str:
    """The data length; an FD length beyond 8 bytes with the DLC code that announces it."""
    if msg.dlc <= CLASSIC_MAX:
        return f"{msg.dlc} bytes"
    return f"{msg.dlc} bytes (DLC code {dlc_code(msg.dlc)})"


def dlc_column(msg: ir.Message) -> str:
    """The overview's DLC column: the length, marked FD for an FD frame."""
    return f"{msg.dlc} FD" + (" BRS" if msg.brs else "") if msg.is_fd else str(msg.dlc)


def node_label(can: ir.CanProtocol, name: str, lang: Lang) -> str:
    node = next((n for n in can.nodes if n.name == name), None)
    if node is not None:
        return f"{node.label} ({node.zh})" if lang.zh and node.zh else node.label
    return f"ALL ({lang.zh_en('任意', 'any')})" if name == "ALL" else name


def receivers_text(can: ir.CanProtocol, msg: ir.Message) -> str:
    return ", ".join(next((n.label for n in can.nodes if n.name == r), r) for r in msg.receivers) or "—"


def siblings(can: ir.CanProtocol, msg: ir.Message) -> tuple[ir.Message, ...]:
    """The other messages built from the same shared layout."""
    if msg.layout is None:
        return ()
    return tuple(m for m in can.messages if m.layout == msg.layout and m.name != msg.name)


def checksum_rule(can: ir.CanProtocol) -> str:
    """The checksum rule for the overview: the bytes themselves when every checksum has the same."""
    shapes = {(m.checksum.byte, m.checksum.covers) for m in can.messages if m.checksum is not None}
    if len(shapes) == 1:
        ((byte, covers),) = shapes
        return f"byte {byte} = XOR of bytes {byte_list(covers)}"
    return "the last byte = XOR of every other byte of the frame"


# The handbook's worked example of the two byte orders: a 12-bit field at start bit 3.
EXAMPLE_START, EXAMPLE_LENGTH = 3, 12


def order_example(byte_order: str) -> list[tuple[int, list[str]]]:
    """Per byte the field touches, its cells bit 7 … 0: the value bit held there (11 = MSB), or "·"."""
    pos = bits.positions(EXAMPLE_START, EXAMPLE_LENGTH, byte_order)
    return [(byte, [str(pos.index(8 * byte + k)) if 8 * byte + k in pos else "·" for k in range(7, -1, -1)])
            for byte in sorted({p // 8 for p in pos})]


def order_where(byte_order: str) -> str:
    return bits.describe(EXAMPLE_START, EXAMPLE_LENGTH, byte_order)


# --- multiplexing ----------------------------------------------------------------------------


def page_caption(msg: ir.Message, values: dict[str, int]) -> str:
    """What selects a page: each multiplexer with the values of its page holding `values`."""
    parts = []
    for name, value in values.items():
        group = next((g for g in msg.mux_groups if g.multiplexer == name and any(lo <= value <= hi for lo, hi in g.ranges)), None)
        parts.append(f"{name} = {ranges_text(group.ranges) if group else value}")
    return ", ".join(parts)


def presence_cell(msg: ir.Message, sig: ir.Signal, lang: Lang) -> str:
    """When a field is in the frame: always, or while its multiplexers (the whole chain) hold these values."""
    chain = msg.mux_chain(sig)
    when = " and ".join(f"`{c.by}` = {ranges_text(c.ranges)}" for c in chain) if chain else lang.en_zh("every frame", "每帧")
    return f"{lang.en_zh('multiplexer', '多路复用器')}; {when}" if sig.is_multiplexer else when
