"""The matrix's companion sheets: value tables, nodes, the change history and a title sheet (说明
About) naming the spec, its version and hash and how to read the matrix. A sheet with nothing to
list (no value tables, no change record) is left out."""

from __future__ import annotations

from canspec import ir
from canspec.render.environment import header_lines
from canspec.render.literals import hex_byte, hex_text, sheet_number
from canspec.targets.xlsx.model import Cell, Column, Sheet, joined, sheet

INITIAL_VALUE_NOTE = (
    "The protocol document defines no initial values. The column shows raw 0x0 — what the generated codecs send for a "
    "zero-initialised message — and what it means; agree on real start-up values with the protocol owner."
)


def value_tables(can: ir.CanProtocol) -> Sheet | None:
    if not can.value_tables:
        return None
    users: dict[str, list[str]] = {}
    for msg in can.messages:
        for sig in msg.signals:
            if sig.value_table is not None:
                users.setdefault(sig.value_table.name, []).append(f"{msg.name}.{sig.name}")
    columns = [
        Column("table", "值表", "Value table", 24), Column("raw", "原始值", "Raw value", 10), Column("hex", "十六进制", "Hex", 10),
        Column("identifier", "标识符", "Identifier", 26), Column("label", "英文", "English", 26), Column("label_zh", "中文", "Chinese", 24, optional=True),
        Column("used_by", "使用信号", "Used by", 60, wrap=True),
    ]
    rows: list[list[Cell]] = []
    bands: list[int] = []
    for i, vt in enumerate(can.value_tables):
        for n, e in enumerate(vt.entries):
            used = "\n".join(users.get(vt.name, ())) if n == 0 else None
            rows.append([vt.name, sheet_number(e.raw), hex_text(e.raw), e.name, e.label, e.label_zh, used])
            bands.append(i % 2)
    return sheet("值表 Value tables", columns, rows, freeze="table", bands=bands)


def nodes(can: ir.CanProtocol) -> Sheet:
    columns = [
        Column("node", "节点", "Node", 16), Column("label", "显示名", "Label", 16), Column("zh", "中文名称", "Chinese name", 18, optional=True),
        Column("sa", "源地址", "Source address", 10, optional=True), Column("aliases", "别名", "Aliases", 12, optional=True),
        Column("desc", "说明", "Description", 36, wrap=True), Column("sends", "发送报文", "Sends", 34, wrap=True),
        Column("receives", "接收报文", "Receives", 34, wrap=True),
    ]
    rows: list[list[Cell]] = []
    for n in can.nodes:
        sends = [f"{m.id_text} {m.name}" for m in can.messages if m.sender == n.name]
        receives = [f"{m.id_text} {m.name}" for m in can.messages if n.name in m.receivers]
        rows.append([n.name, n.label, n.zh, hex_byte(n.sa) if n.sa is not None else None, ", ".join(n.aliases), n.desc, "\n".join(sends), "\n".join(receives)])
    return sheet("节点 Nodes", columns, rows, freeze="node")


def history(log: ir.Changelog | None) -> Sheet | None:
    if log is None:
        return None
    columns = [
        Column("version", "版本", "Version", 10), Column("date", "日期", "Date", 11), Column("authors", "作者", "Authors", 14),
        Column("label", "版本说明", "Label", 20, wrap=True, optional=True), Column("number", "序号", "Item", 6),
        Column("zh", "变更描述", "Change (Chinese)", 48, wrap=True, optional=True), Column("en", "英文", "Change (English)", 48, wrap=True, optional=True),
        Column("ids", "报文标识符", "Message IDs", 13, wrap=True), Column("errata", "勘误", "Errata", 10),
    ]
    rows: list[list[Cell]] = []
    bands: list[int] = []
    for i, v in enumerate(reversed(log.versions)):  # newest first, as the handbook shows it
        head: list[Cell] = [f"V{v.version}", v.date, ", ".join(v.authors), joined(v.label, v.label_zh)]
        for item in v.items:
            rows.append([*head, item.number, item.zh, item.en, "\n".join(hex_text(fid, 8) for fid in item.ids), ", ".join(item.errata)])
        if not v.items:
            rows.append([*head, None, None, None, None, ", ".join(v.errata)])
        bands += [i % 2] * (len(v.items) or 1)
    return sheet("修订历史 History", columns, rows, freeze="version", bands=bands)


def _dialect_facts(can: ir.CanProtocol) -> list[tuple[str, Cell]]:
    """How to read the byte-order, float and FD columns, on a bus that has them."""
    facts: list[tuple[str, Cell]] = []
    if can.has_big_endian:
        facts.append(("排列格式 Byte order", ("Per signal. Bits are numbered as in the DBC: 8 × byte + bit (bit 0 = least significant bit of the byte). "
                                            "Intel: the start bit is the field's least significant bit, the field runs upward. Motorola: the start bit "
                                            "is its most significant bit; the field runs down to bit 0 of the byte, then on from bit 7 of the next byte.")))
    if can.has_float:
        facts.append(("浮点 Float", "Float32/Float64 (IEEE 754): the raw value is the bit pattern; raw min/max are the patterns of the physical limits."))
    if can.has_fd:
        rate = f" ({can.bus.data_bitrate} bit/s)" if can.bus.data_bitrate else ""
        facts.append(("CAN FD", f"Frame format \"… FD\": a CAN FD frame. BRS Yes: its data phase runs at the data bitrate{rate}."))
    return facts


def about(spec: ir.Spec, can: ir.CanProtocol, sheet_names: list[str]) -> Sheet:
    bus = can.bus
    facts: list[tuple[str, Cell]] = [
        ("协议 Protocol", joined(can.title_zh, can.title)),
        ("版本 Version", f"V{can.version}" + (f" (document {can.document})" if can.document else "")),
        ("规范 Spec", f"{spec.name} {spec.version}"),
        ("规范哈希 Spec sha256", spec.sha256),
        ("生成器 Generator", header_lines(spec, "xlsx")[0]),
        ("总线 Bus", f"{bus.kbit} kbit/s, {bus.id_format} identifiers, addressing {bus.addressing}, byte order {bus.byte_order}"),
        ("报文 Messages", len(can.messages)),
        ("信号 Signals", sum(len(m.data_signals) for m in can.messages)),
        ("工作表 Sheets", "\n".join(sheet_names)),
        ("S / R", "S: the node sends the message 发送; R: the node receives it 接收. Sender ALL: any node (no node column is S)."),
        ("原始值 Raw values", "Hex of the field's bits (two's complement for signed fields); a negative value follows in parentheses."),
        (
            "物理范围 Physical range",
            "What a sender may encode: the documented range cut to what the bits carry; Notes show the documented range where it differs."),
        ("初始值 Initial value", INITIAL_VALUE_NOTE),
        *_dialect_facts(can),
    ]
    columns = [Column("item", "项目", "Item", 24), Column("value", "内容", "Value", 110, wrap=True)]
    return sheet("说明 About", columns, [[k, v] for k, v in facts])
