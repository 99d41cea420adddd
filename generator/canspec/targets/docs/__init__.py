"""The protocol handbook: Markdown pages (plus each message's bit-layout SVG: one, or one per 16
bytes of a long CAN FD frame) that MkDocs turns into the static site (`make docs`, config in the
top-level `mkdocs.yml`), bilingual where the spec is and English-only where it is (lang.py).

Python decides every number and every cell's content (cells.py, jsonpage.py, errata.py); the
templates in `templates/docs/` only lay the pages out. Links between pages are relative and every
anchor that is linked to is given explicitly (`{#id}`), so `mkdocs build --strict` can check them.
"""

from __future__ import annotations

from typing import Any

import yaml

from canspec import ir
from canspec.ir import busload, nodeview
from canspec.render.environment import header_lines, render
from canspec.render.literals import hex_text
from canspec.targets import Target
from canspec.targets.c.names import CNames
from canspec.targets.docs import cells, jsonpage, svg
from canspec.targets.docs.errata import embed_markdown, errata_links, errata_refs, errata_row_ids, erratum_anchor, json_page, message_page
from canspec.targets.docs.lang import Lang, lang

__all__ = ["TARGET", "errata_row_ids", "render_docs", "svg"]

OUT = "docs/"
NAV_FILE = "mkdocs.nav.yml"  # merged into the top-level mkdocs.yml by `INHERIT`


def svg_parts(msg: ir.Message) -> list[tuple[str, range, str]]:
    """The message's bit diagrams (file name beside its page, byte rows, the page they show): one,
    or one per svg.PART_ROWS bytes of a long FD frame; the first keeps the message's name. A
    multiplexed message has them for each page layout (ir.Message.page_layouts), `.page-N` named."""
    if not msg.is_multiplexed:
        return [(f"{msg.name}.svg" if not rows[0] else f"{msg.name}.bytes-{rows[0]}-{rows[-1]}.svg", rows, "") for rows in svg.parts(msg)]
    out = []
    for n, values in enumerate(msg.page_layouts, 1):
        caption = cells.page_caption(msg, values)
        out += [(f"{msg.name}.page-{n}.svg" if not rows[0] else f"{msg.name}.page-{n}.bytes-{rows[0]}-{rows[-1]}.svg", rows, caption)
                for rows in svg.parts(msg)]
    return out


def drawn(msg: ir.Message, file: str) -> ir.Message:
    """The message a diagram file shows: a page of a multiplexed one (svg_parts' naming)."""
    if not msg.is_multiplexed:
        return msg
    n = int(file.split(".page-")[1].split(".")[0])
    return msg.page(msg.page_layouts[n - 1])


def anchor(ident: str) -> str:
    """Markdown attribute list giving a heading an explicit id (Jinja reads `{#` as a comment)."""
    return "{#" + ident + "}"


def json_anchor(name: str) -> str:
    return f"msg-{name.replace('_', '-')}"


def version_anchor(version: str) -> str:
    return "v" + version.replace(".", "-")


def id_link(can: ir.CanProtocol | None, frame_id: int, prefix: str = "") -> str:
    """A frame ID of the change record, linked to its message's page where the spec has one."""
    msg = can.by_id(frame_id) if can is not None else None
    return f"[`{msg.id_text}`]({prefix}{message_page(msg)})" if msg else f"`{cells.hex_id(frame_id)}`"


# --- facts the overview and bus-load pages state -------------------------------------------


def id_format_text(can: ir.CanProtocol, lg: Lang) -> str:
    """The bus's identifier format, and how many messages differ from it."""
    extended = can.bus.id_format == "extended"
    text = f"extended ({lg.en_zh('29-bit identifier', '29 位扩展帧')})" if extended else f"standard ({lg.en_zh('11-bit identifier', '11 位标准帧')})"
    others = sum(1 for m in can.messages if m.is_extended != extended)
    if others:
        text += f"; {others} message{'s' if others > 1 else ''} with {'11' if extended else '29'}-bit identifiers"
    return text


def shared_layout_senders(can: ir.CanProtocol) -> list[str]:
    """Senders whose messages share layouts with another sender's (alternative controllers)."""
    by_layout: dict[str, set[str]] = {}
    for m in can.messages:
        if m.layout is not None:
            by_layout.setdefault(m.layout, set()).add(m.sender)
    names = {s for senders in by_layout.values() if len(senders) > 1 for s in senders}
    out = []
    for node in can.nodes:
        if node.name in names:
            out.append(node.label + (f" ({', '.join(node.aliases)})" if node.aliases else ""))
    return out


def and_list(items: list[str]) -> str:
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]


# --- the site navigation ----------------------------------------------------------------------


def nav(spec: ir.Spec, lg: Lang) -> dict[str, Any]:
    pages: list[Any] = [{lg.zh_en("概览", "Overview"): "index.md"}]
    if spec.can is not None:
        pages.append({lg.zh_en("报文", "Messages"): [{f"{m.id_text} {m.zh if lg.zh and m.zh else m.title}": message_page(m)} for m in spec.can.messages]})
        pages.append({lg.zh_en("值表", "Value tables"): "value_tables.md"})
        pages.append({lg.zh_en("总线负载", "Bus load"): "busload.md"})
        pages.append({lg.zh_en("在固件中使用", "Use it in your firmware"): "firmware.md"})
    for proto in spec.json:
        pages.append({f"JSON: {proto.title_zh if lg.zh and proto.title_zh else proto.title}": json_page(proto)})
    pages.append({lg.zh_en("勘误", "Errata"): "errata.md"})
    if spec.changelog is not None:
        pages.append({lg.zh_en("修订历史", "Revision history"): "history.md"})
    if spec.can is not None:
        title = spec.can.title_zh if lg.zh and spec.can.title_zh else spec.can.title
    else:
        title = next((p.title_zh if lg.zh and p.title_zh else p.title for p in spec.json), spec.name)
    return {"site_name": f"{title} V{spec.version}", "site_description": f"{spec.name} {spec.version}: protocol handbook generated by canspec", "nav": pages}


def nav_yaml(spec: ir.Spec, lg: Lang) -> str:
    head = "".join(f"# {line}\n" for line in header_lines(spec, "docs"))
    head += "# Site navigation, merged into the top-level mkdocs.yml with `INHERIT`.\n"
    return head + str(yaml.safe_dump(nav(spec, lg), allow_unicode=True, sort_keys=False, width=200))


# --- rendering -------------------------------------------------------------------------------

HELPERS: dict[str, Any] = {
    "cell": cells.cell, "raw_hex": hex_text, "pct": cells.pct, "decimal": cells.decimal, "titled": cells.titled,
    "id_kind": cells.id_kind, "cycle_text": cells.cycle_text, "doc_range": cells.doc_range, "enc_range": cells.enc_range,
    "range_note": cells.range_note, "value_cell": cells.value_cell, "special_cell": cells.special_cell, "role_cell": cells.role_cell,
    "bytes_cell": cells.bytes_cell, "byte_list": cells.byte_list, "node_label": cells.node_label, "receivers_text": cells.receivers_text,
    "siblings": cells.siblings, "checksum_rule": cells.checksum_rule, "order_cell": cells.order_cell, "type_cell": cells.type_cell,
    "presence_cell": cells.presence_cell,
    "kbit": cells.kbit, "frame_cell": cells.frame_cell, "length_cell": cells.length_cell, "dlc_column": cells.dlc_column, "svg_parts": svg_parts,
    "order_example": cells.order_example, "order_where": cells.order_where, "example_start": cells.EXAMPLE_START, "example_length": cells.EXAMPLE_LENGTH,
    "message_page": message_page, "anchor": anchor, "json_anchor": json_anchor, "version_anchor": version_anchor,
    "json_page": json_page, "vt_anchor": cells.vt_anchor, "erratum_anchor": erratum_anchor, "errata_links": errata_links, "id_link": id_link,
    "json_range": jsonpage.json_range, "json_values": jsonpage.json_values, "json_example": jsonpage.json_example,
    "json_pairs": jsonpage.json_pairs, "party_label": jsonpage.party_label, "id_format_text": id_format_text,
    "shared_layout_senders": shared_layout_senders, "and_list": and_list, "tie_epsilon": ir.TIE_EPSILON_TEXT,
}


def _page(template: str, spec: ir.Spec, lg: Lang, **ctx: Any) -> bytes:
    text = render(f"docs/{template}", spec, "docs", lang=lg, **HELPERS, **ctx)
    return (text.rstrip("\n") + "\n").encode("utf-8")


def value_table_users(can: ir.CanProtocol) -> dict[str, list[tuple[ir.Message, ir.Signal]]]:
    users: dict[str, list[tuple[ir.Message, ir.Signal]]] = {vt.name: [] for vt in can.value_tables}
    for msg in can.messages:
        for sig in msg.signals:
            if sig.value_table is not None:
                users.setdefault(sig.value_table.name, []).append((msg, sig))
    return users


def _can_pages(spec: ir.Spec, can: ir.CanProtocol, lg: Lang, load: busload.BusLoad) -> dict[str, bytes]:
    files: dict[str, bytes] = {}
    svg_head = "".join(f"<!-- {line.replace('--', '—')} -->\n" for line in header_lines(spec, "docs"))
    for msg in can.messages:
        files[message_page(msg)] = _page("message.md.j2", spec, lg, can=can, msg=msg)
        for name, rows, _ in svg_parts(msg):  # a DLC-0 frame has no bits to draw
            files[f"messages/{name}"] = (svg_head + svg.bit_layout(drawn(msg, name), lg.zh, rows)).encode("utf-8")
    files["value_tables.md"] = _page("value_tables.md.j2", spec, lg, can=can, users=value_table_users(can))
    g = busload.STUFFED_CONTROL_BITS[True]
    files["busload.md"] = _page("busload.md.j2", spec, lg, can=can, load=load, frame_bits=busload.frame_bits, g=g, g_minus_1=g - 1,
                                g_standard=busload.STUFFED_CONTROL_BITS[False], trailer=busload.UNSTUFFED_TRAILER_BITS,
                                fixed_bits=g + busload.UNSTUFFED_TRAILER_BITS, message_bits=busload.message_bits, fd=busload.fd_formula_facts())
    files["firmware.md"] = _page("firmware.md.j2", spec, lg, can=can, c=CNames.plain(can), example_node=_example_node(can),
                                 node_traffic=[(n.name, *nodeview.traffic(can, n.name)) for n in can.nodes])
    return files


def _example_node(can: ir.CanProtocol) -> str | None:
    """The node the firmware page's commands name: the one receiving most, as an ECU under command does."""
    if not can.nodes:
        return None
    return max(can.nodes, key=lambda n: nodeview.traffic(can, n.name)[2]).name


def render_docs(spec: ir.Spec) -> dict[str, bytes]:
    lg = lang(spec)
    can = spec.can
    load = busload.bus_load(can) if can is not None else None
    files = {"index.md": _page("index.md.j2", spec, lg, can=can, load=load)}
    if can is not None and load is not None:
        files.update(_can_pages(spec, can, lg, load))
    for proto in spec.json:
        files[json_page(proto)] = _page("json_protocol.md.j2", spec, lg, proto=proto)
    files["errata.md"] = _page("errata.md.j2", spec, lg, refs=errata_refs(spec), in_table=errata_row_ids(spec.errata_md),
                               errata_md=embed_markdown(spec.errata_md) if spec.errata_md else None)
    if spec.changelog is not None:
        files["history.md"] = _page("history.md.j2", spec, lg, can=can, changelog=spec.changelog)
    files["assets/handbook.css"] = _page("handbook.css.j2", spec, lg)
    files[NAV_FILE] = nav_yaml(spec, lg).encode("utf-8")
    return {OUT + rel: data for rel, data in files.items()}


TARGET = Target("docs", "protocol handbook: Markdown + SVG bit diagrams for MkDocs, bilingual where the spec is", OUT, render_docs,
                order=80, cost=2)
