"""The communication matrix (通信矩阵): one row per signal in the column layout OEM matrices use —
the message's attributes repeated on each of its signal rows (so a filter on any column keeps whole
rows), the signal's coding, and one column per node saying S (sends) or R (receives).

Reserved bits are not signals and get no row. A message without signals (DLC 0, or a layout the
document leaves undefined) gets one row with its message columns only. Numbers are cells Excel
holds exactly, else exact text (render.literals.sheet_number); raw values are the field's bits
in hex, negative ones followed by their value: 0x200 (-512) for a 10-bit signed field. Byte order is
the signal's own (Intel / Motorola), its start bit and start byte the DBC's (a Motorola field starts
at its most significant bit); an IEEE float field says so in the data-type column, its range is the
documented one (else every finite value) and its raw limits are those values' bit patterns. A CAN FD
frame says FD in its frame format, and the BRS column (only on a bus with FD frames) whether its data
phase switches to the data bitrate."""

from __future__ import annotations

from fractions import Fraction

from canspec import ir
from canspec.ir.encoding import float_inside
from canspec.ir.mux import ranges_text
from canspec.render.literals import hex_byte, hex_text, num, sheet_number
from canspec.targets.xlsx.model import Cell, Column, Sheet, joined, sheet

NAME = "通信矩阵 Matrix"
BYTE_ORDER = {"little_endian": "Intel", "big_endian": "Motorola"}
S, R = "S", "R"

MESSAGE_COLUMNS = (
    Column("message", "报文名称", "Message name", 26),
    Column("message_zh", "报文中文名称", "Message name (Chinese)", 24, optional=True),
    Column("id", "报文标识符", "Message ID", 12),
    Column("pgn", "参数组编号", "PGN", 9, optional=True),
    Column("frame_format", "帧格式", "Frame format", 10),
    Column("brs", "比特率切换", "BRS", 7, optional=True),
    Column("send_type", "发送类型", "Send type", 9),
    Column("cycle_ms", "周期时间 (ms)", "Cycle time (ms)", 10),
    Column("dlc", "报文长度 (字节)", "DLC (bytes)", 9),
    Column("sender", "发送节点", "Sender", 13),
)
SIGNAL_COLUMNS = (
    Column("signal", "信号名称", "Signal name", 26),
    Column("signal_zh", "信号中文名称", "Signal name (Chinese)", 20, optional=True),
    Column("description", "信号描述", "Description", 36, wrap=True),
    Column("byte_order", "排列格式", "Byte order", 8),
    Column("multiplexing", "多路复用", "Multiplexing", 22, wrap=True, optional=True),
    Column("start_byte", "起始字节", "Start byte", 7),
    Column("start_bit", "起始位", "Start bit", 7),
    Column("length", "信号长度 (位)", "Length (bits)", 8),
    Column("signedness", "数据类型", "Signedness", 10),
    Column("factor", "精度", "Factor", 9),
    Column("offset", "偏移量", "Offset", 9),
    Column("phys_min", "物理最小值", "Physical min", 11),
    Column("phys_max", "物理最大值", "Physical max", 11),
    Column("raw_min", "总线最小值 (十六进制)", "Raw min (hex)", 12),
    Column("raw_max", "总线最大值 (十六进制)", "Raw max (hex)", 12),
    Column("initial", "初始值 (十六进制)", "Initial value (hex)", 18, wrap=True),
    Column("special", "无效值/特殊值", "Invalid / special values", 26, wrap=True),
    Column("unit", "单位", "Unit", 8),
    Column("values", "值描述", "Value table", 30, wrap=True),
    Column("notes", "备注", "Notes", 30, wrap=True),
)


def raw_hex(sig: ir.Signal, raw: int) -> str:
    """The field's bits in hex (two's complement for signed fields), plus the value when negative."""
    text = hex_text(raw & sig.mask)
    return text if raw >= 0 else f"{text} ({raw})"


def label_lines(sig: ir.Signal, special: bool) -> str:
    """`0x3FF: No obstacle 无障碍物`, one line per value-table entry (or per special value)."""
    return "\n".join(f"{raw_hex(sig, lb.raw)}: {joined(lb.label, lb.label_zh)}" for lb in sig.labels if lb.is_special == special)


def initial_value(sig: ir.Signal) -> str:
    """The protocol defines no initial values: raw 0, what an all-zero message packs to (the
    generated codecs' zero-initialised structs), with what it means, so a reviewer sees it."""
    label = sig.label_of(0)
    meaning = joined(label.label, label.label_zh) if label else joined(num(sig.physical(0)), sig.unit)
    return f"0x0 ({meaning})"


def _byte_span(covers: tuple[int, ...]) -> str:
    contiguous = len(covers) > 1 and list(covers) == list(range(covers[0], covers[-1] + 1))
    return f"{covers[0]}–{covers[-1]}" if contiguous else ", ".join(map(str, covers))


def notes(msg: ir.Message, sig: ir.Signal) -> str:
    out = []
    if msg.counter is not None and sig.name == msg.counter.signal:
        out.append(f"Rolling counter 循环计数, modulo {msg.counter.modulo}")
    if msg.checksum is not None and sig.name == msg.checksum.signal:
        out.append(f"XOR checksum 异或校验 of bytes {_byte_span(msg.checksum.covers)}")
    mf = msg.multiframe
    if mf is not None and sig.name == mf.index_signal:
        out.append(f"Frame index 帧序号: {mf.text_length} {mf.encoding.upper()} characters over {mf.frames} frames")
    if mf is not None and sig.name == mf.payload_signal:
        out.append(f"Text chunk 文本片段: {mf.bytes_per_frame} characters per frame, padding {hex_byte(mf.padding)}")
    if sig.is_float:
        out.append(f"IEEE 754 binary{sig.length}: raw = the bit pattern" + ("" if sig.doc_min is not None else "; NaN and ±Inf allowed"))
    elif sig.doc_min is not None and sig.doc_max is not None and (sig.doc_min, sig.doc_max) != (sig.phys_min, sig.phys_max):
        out.append(f"Documented range 文档范围 {num(sig.doc_min)} … {num(sig.doc_max)}; encodable 可编码 {num(sig.phys_min)} … {num(sig.phys_max)}")
    if sig.since:
        out.append(f"Since 新增于 V{sig.since}")
    if sig.errata:
        out.append(f"Errata 勘误: {', '.join(sig.errata)}")
    return "\n".join(out)


def role(node: ir.Node, msg: ir.Message) -> str:
    sends, receives = node.name == msg.sender, node.name in msg.receivers
    return "/".join(flag for flag, on in ((S, sends), (R, receives)) if on)


def message_cells(can: ir.CanProtocol, msg: ir.Message) -> list[Cell]:
    labels = {n.name: n.label for n in can.nodes}
    return [
        msg.name, msg.zh, msg.id_text, msg.j1939.pgn_text if msg.j1939 is not None else None,
        ("Extended" if msg.is_extended else "Standard") + (" FD" if msg.is_fd else ""), ("Yes" if msg.brs else "No") if msg.is_fd else None,
        "Cycle" if msg.is_cyclic else "Event", msg.cycle_ms, msg.dlc, labels.get(msg.sender, msg.sender),
    ]


def data_type(sig: ir.Signal) -> str:
    if sig.is_float:
        return f"Float{sig.length} (IEEE 754)"
    return "Signed" if sig.signed else "Unsigned"


def limits(sig: ir.Signal) -> tuple[Fraction, Fraction, str, str]:
    """Physical min/max and their raw hex: a float's documented range (else its finite range) and those values' bit patterns."""
    if sig.is_float:
        lo, hi = sig.check_min, sig.check_max
        return lo, hi, hex_text(float_inside(lo, sig.length, up=True)), hex_text(float_inside(hi, sig.length, up=False))  # raw ends inside the range
    return sig.phys_min, sig.phys_max, raw_hex(sig, sig.raw_min), raw_hex(sig, sig.raw_max)


def limit_cell(sig: ir.Signal, value: Fraction) -> Cell:
    """A float's largest finite value as the shortest text naming that double (-3.4028234663852886e+38), not 39 digits."""
    return repr(float(value)) if sig.is_float and sig.doc_min is None else sheet_number(value)


def signal_cells(msg: ir.Message, sig: ir.Signal) -> list[Cell]:
    lo, hi, raw_lo, raw_hi = limits(sig)
    return [
        sig.name, sig.zh, "\n".join(t for t in (sig.desc, sig.desc_zh) if t), BYTE_ORDER[sig.byte_order], multiplexing(msg, sig),
        sig.start // 8, sig.start, sig.length, data_type(sig), sheet_number(sig.factor), sheet_number(sig.offset), limit_cell(sig, lo), limit_cell(sig, hi),
        raw_lo, raw_hi, initial_value(sig), label_lines(sig, True), sig.unit, label_lines(sig, False), notes(msg, sig),
    ]


def multiplexing(msg: ir.Message, sig: ir.Signal) -> str | None:
    """`Multiplexer` and/or the values that put the field in the frame (`mode = 1, 4…6`, the whole
    chain of multiplexers); none for a field of every frame of a message without multiplexing."""
    when = " and ".join(f"{c.by} = {ranges_text(c.ranges)}" for c in msg.mux_chain(sig))
    if sig.is_multiplexer:
        return "多路复用器 Multiplexer" + (f"; {when}" if when else "")
    return when or None


def no_signal_cells(msg: ir.Message) -> list[Cell]:
    undefined = "Layout not defined by the document 文档未定义信号布局" if msg.layout_undefined else None
    return [None] * (len(SIGNAL_COLUMNS) - 1) + [undefined]


def node_column(node: ir.Node) -> Column:
    """Wide enough for the node's name on one line, up to a limit (CJK characters count double)."""
    chars = max(len(node.label), 2 * len(node.zh))
    return Column(f"node:{node.name}", node.zh, node.label, min(max(chars + 2, 8), 18), center=True)


def matrix(can: ir.CanProtocol) -> Sheet:
    rows: list[list[Cell]] = []
    bands: list[int] = []
    for i, msg in enumerate(can.messages):
        head = message_cells(can, msg)
        roles: list[Cell] = [role(n, msg) for n in can.nodes]
        for sig in msg.data_signals:
            rows.append(head + signal_cells(msg, sig) + roles)
        if not msg.data_signals:
            rows.append(head + no_signal_cells(msg) + roles)
        bands += [i % 2] * (len(msg.data_signals) or 1)
    columns = [*MESSAGE_COLUMNS, *SIGNAL_COLUMNS, *(node_column(n) for n in can.nodes)]
    return sheet(NAME, columns, rows, freeze="message", bands=bands)
