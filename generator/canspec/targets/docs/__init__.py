"""The protocol handbook: bilingual Markdown pages (plus one bit-layout SVG per message) that
MkDocs turns into the static site (`make docs`, config in the top-level `mkdocs.yml`).

Python decides every number and every cell's content here; the templates in
`templates/docs/` only lay the pages out. Links between pages are relative and every anchor
that is linked to is given explicitly (`{#id}`), so `mkdocs build --strict` can check them.
"""

from __future__ import annotations

import json
import re
from fractions import Fraction
from typing import Any

import yaml

from canspec import ir
from canspec.reference import busload
from canspec.render.environment import header_lines, render
from canspec.render.literals import num
from canspec.targets import Target
from canspec.targets.docs import svg

OUT = "docs/"
NAV_FILE = "mkdocs.nav.yml"  # merged into the top-level mkdocs.yml by `INHERIT`


# --- small text helpers (filters for the templates) ----------------------------------------


def cell(text: object) -> str:
    """Text made safe for a Markdown table cell."""
    return str(text).replace("|", "\\|").replace("\n", "<br>")


def hex_id(value: int) -> str:
    return f"0x{value:08X}"


def pct(value: Fraction, places: int = 2) -> str:
    """A share (0..1) as a percentage, rounded half up at `places` decimals: 0.34944 → 34.94 %."""
    scaled = value * 100 * 10**places
    n = int(scaled + Fraction(1, 2)) if scaled >= 0 else -int(-scaled + Fraction(1, 2))
    text = f"{abs(n) // 10**places}.{abs(n) % 10**places:0{places}d}" if places else str(abs(n))
    return ("-" if n < 0 else "") + text + " %"


def decimal(value: Fraction, places: int = 1) -> str:
    """A rate rounded half up to `places` decimals, trailing zeros kept: 1600 → 1600.0."""
    return pct(value / 100, places)[:-2]


# --- pages and anchors ----------------------------------------------------------------------


def message_page(msg: ir.Message) -> str:
    return f"messages/{msg.name}.md"


def message_svg(msg: ir.Message) -> str:
    return f"messages/{msg.name}.svg"


def json_page(proto: ir.JsonProtocol) -> str:
    return f"json/{proto.name}.md"


def anchor(ident: str) -> str:
    """Markdown attribute list giving a heading an explicit id (Jinja reads `{#` as a comment)."""
    return "{#" + ident + "}"


def json_anchor(name: str) -> str:
    return f"msg-{name.replace('_', '-')}"


def version_anchor(version: str) -> str:
    return "v" + version.replace(".", "-")


def vt_anchor(name: str) -> str:
    return f"vt-{name.replace('_', '-')}"


def erratum_anchor(eid: str) -> str:
    return eid.lower()


def errata_links(ids: tuple[str, ...], prefix: str) -> str:
    return ", ".join(f"[{e}]({prefix}errata.md#{erratum_anchor(e)})" for e in ids)


# --- meaning shown in the signal tables ----------------------------------------------------


def doc_range(sig: ir.Signal) -> str:
    if sig.doc_min is None or sig.doc_max is None:
        return "—"
    return f"{num(sig.doc_min)} … {num(sig.doc_max)}"


def enc_range(sig: ir.Signal) -> str:
    """What a physical encode can produce: the documented range cut to what the bits carry."""
    return f"{num(sig.phys_min)} … {num(sig.phys_max)}<br><small>raw {sig.raw_min} … {sig.raw_max}</small>"


def range_note(sig: ir.Signal) -> str:
    if sig.doc_min is None or sig.doc_max is None:
        return ""
    if (sig.doc_min, sig.doc_max) != (sig.phys_min, sig.phys_max):
        return "⚠ differs from the documented range 与文档范围不同"
    return ""


def value_cell(sig: ir.Signal, prefix: str) -> str:
    parts = []
    if sig.value_table is not None:
        vt = sig.value_table
        parts.append(f"[`{vt.name}`]({prefix}value_tables.md#{vt_anchor(vt.name)})")
        parts += [f"{e.raw} = {e.label_zh} {e.label}" for e in vt.entries]
    return "<br>".join(cell(p) for p in parts)


def special_cell(sig: ir.Signal) -> str:
    return "<br>".join(cell(f"0x{s.raw:X} = {s.label_zh} {s.label}") for s in sig.specials)


def role_cell(sig: ir.Signal, msg: ir.Message) -> str:
    if sig.role == "counter" and msg.counter is not None:
        return f"心跳 rolling counter, mod {msg.counter.modulo}"
    if sig.role == "checksum" and msg.checksum is not None:
        return f"异或校验 {msg.checksum.algorithm.upper()} of bytes {byte_list(msg.checksum.covers)} → byte {msg.checksum.byte}"
    if sig.role == "reserved":
        return "保留 reserved, sent as 0 发送 0"
    if msg.multiframe is not None and sig.name == msg.multiframe.index_signal:
        return "多帧序号 frame index"
    if msg.multiframe is not None and sig.name == msg.multiframe.payload_signal:
        return f"VIN 片段 text chunk ({msg.multiframe.bytes_per_frame} × {msg.multiframe.encoding.upper()})"
    return ""


def byte_list(covers: tuple[int, ...]) -> str:
    """0, 1, 2, 3 → "0–3"; anything not contiguous is listed."""
    if len(covers) > 1 and list(covers) == list(range(covers[0], covers[-1] + 1)):
        return f"{covers[0]}–{covers[-1]}"
    return ", ".join(map(str, covers))


def bytes_cell(sig: ir.Signal) -> str:
    first, last = sig.segments[0].byte, sig.segments[-1].byte
    return str(first) if first == last else f"{first}–{last}"


def node_label(can: ir.CanProtocol, name: str) -> str:
    node = next((n for n in can.nodes if n.name == name), None)
    return f"{node.label} ({node.zh})" if node else ("ALL (任意 any)" if name == "ALL" else name)


def receivers_text(can: ir.CanProtocol, msg: ir.Message) -> str:
    return ", ".join(next((n.label for n in can.nodes if n.name == r), r) for r in msg.receivers)


def siblings(can: ir.CanProtocol, msg: ir.Message) -> tuple[ir.Message, ...]:
    """The other messages built from the same shared layout."""
    if msg.layout is None:
        return ()
    return tuple(m for m in can.messages if m.layout == msg.layout and m.name != msg.name)


# --- JSON protocol -------------------------------------------------------------------------


def json_range(field: ir.JsonField) -> str:
    if field.json_type == "string":
        if field.min_length is not None or field.max_length is not None:
            lo, hi = field.min_length, field.max_length
            return f"length {lo if lo is not None else 0} … {hi if hi is not None else '∞'}"
        return ""
    if field.min is not None or field.max is not None:
        lo = num(field.min) if field.min is not None else _type_bound(field.type_min)
        hi = num(field.max) if field.max is not None else _type_bound(field.type_max)
        return f"{lo} … {hi}"
    if field.type_min is not None and field.type_max is not None:
        return f"{_type_bound(field.type_min)} … {_type_bound(field.type_max)} (type)"
    return ""


def _type_bound(value: float | None) -> str:
    if value is None:
        return "—"
    return repr(value) if isinstance(value, float) else str(value)


def json_values(field: ir.JsonField) -> str:
    parts = [f"`{json.dumps(e.value, ensure_ascii=False)}` = {e.label_zh} {e.label}" for e in field.enum]
    parts += [f"`{json.dumps(e.value, ensure_ascii=False)}` = {e.label_zh} {e.label} (sentinel 哨兵值)" for e in field.sentinels]
    return "<br>".join(cell(p) for p in parts)


def json_example(example: dict[str, Any]) -> str:
    return json.dumps(example, ensure_ascii=False)


def json_pairs(proto: ir.JsonProtocol) -> list[tuple[ir.JsonMessage, ir.JsonMessage]]:
    return [(proto.message(m.reply_to), m) for m in proto.messages if m.reply_to is not None]


def party_label(proto: ir.JsonProtocol, name: str) -> str:
    party = next((p for p in proto.parties if p.name == name), None)
    return f"{party.zh} {name}" if party else name


# --- errata --------------------------------------------------------------------------------


def errata_refs(spec: ir.Spec) -> dict[str, list[tuple[str, str]]]:
    """Every erratum id the spec cites → (page link, what cites it), in spec order."""
    refs: dict[str, list[tuple[str, str]]] = {}

    def add(ids: tuple[str, ...], link: str, what: str) -> None:
        for e in ids:
            refs.setdefault(e, []).append((link, what))

    if spec.can is not None:
        for msg in spec.can.messages:
            add(msg.errata, message_page(msg), f"{msg.name} ({msg.zh})")
            for sig in msg.signals:
                add(sig.errata, message_page(msg), f"{msg.name}.{sig.name} ({sig.zh})" if sig.zh else f"{msg.name}.{sig.name}")
    for proto in spec.json:
        add(proto.errata, json_page(proto), proto.name)
        for jm in proto.messages:
            for f in jm.fields:
                add(f.errata, json_page(proto), f"{jm.name}.{f.json_name} ({f.zh})")
    if spec.changelog is not None:
        for v in spec.changelog.versions:
            add(v.errata, "history.md", f"V{v.version}")
            for item in v.items:
                add(item.errata, "history.md", f"V{v.version} #{item.number}")
    return dict(sorted(refs.items(), key=lambda kv: _erratum_key(kv[0])))


def _erratum_key(eid: str) -> tuple[str, int, str]:
    m = re.match(r"([A-Za-z]*)(\d*)(.*)", eid)
    assert m is not None
    return (m.group(1), int(m.group(2) or 0), m.group(3))


_LINK = re.compile(r"(?<!!)\[([^\]]+)\]\(([^)\s]+)\)")
_FENCE = re.compile(r"^\s*(```|~~~)")
_ROW_ID = re.compile(r"^\|\s*([A-Z]+\d+)\s*\|")


def errata_row_ids(text: str | None) -> set[str]:
    """Ids of the errata that ERRATA.md describes in a table row of their own (`| E10 | ...`)."""
    return {m.group(1) for line in (text or "").splitlines() if (m := _ROW_ID.match(line))}


def embed_markdown(text: str) -> str:
    """ERRATA.md placed under our own page title: its title dropped, headings one level down,
    each erratum's table row given the anchor other pages link to (`errata.md#e10`), and links
    to files outside the site (e.g. `can/gateway.yaml`) turned into code text so the strict build holds."""
    lines = text.strip().splitlines()
    if lines and lines[0].startswith("# "):
        lines = lines[1:]
    out, fenced = [], False
    for line in lines:
        if _FENCE.match(line):
            fenced = not fenced
        elif not fenced:
            if line.startswith("#"):
                line = "#" + line if not line.startswith("######") else line
            line = _LINK.sub(_local_link, line)
            line = _ROW_ID.sub(lambda m: f'| <span id="{erratum_anchor(m.group(1))}"></span>{m.group(1)} |', line, count=1)
        out.append(line)
    return "\n".join(out).strip() + "\n"


def _local_link(m: re.Match[str]) -> str:
    text, target = m.group(1), m.group(2)
    if re.match(r"^(https?:|mailto:|#)", target):
        return m.group(0)
    return f"{text} (`spec/{target}`)"


# --- history -------------------------------------------------------------------------------


def id_link(can: ir.CanProtocol | None, frame_id: int, prefix: str = "") -> str:
    msg = can.by_id(frame_id) if can is not None else None
    return f"[`{hex_id(frame_id)}`]({prefix}{message_page(msg)})" if msg else f"`{hex_id(frame_id)}`"


# --- the site navigation ----------------------------------------------------------------------


def nav(spec: ir.Spec) -> dict[str, Any]:
    pages: list[Any] = [{"概览 Overview": "index.md"}]
    if spec.can is not None:
        pages.append({"报文 Messages": [{f"{hex_id(m.frame_id)} {m.zh}": message_page(m)} for m in spec.can.messages]})
        pages.append({"值表 Value tables": "value_tables.md"})
        pages.append({"总线负载 Bus load": "busload.md"})
    for proto in spec.json:
        pages.append({f"JSON: {proto.title_zh}": json_page(proto)})
    pages.append({"勘误 Errata": "errata.md"})
    if spec.changelog is not None:
        pages.append({"修订历史 Revision history": "history.md"})
    title = spec.can.title_zh if spec.can is not None else (spec.json[0].title_zh if spec.json else spec.name)
    return {"site_name": f"{title} V{spec.version}", "site_description": f"{spec.name} {spec.version}: protocol handbook generated by canspec", "nav": pages}


def nav_yaml(spec: ir.Spec) -> str:
    head = "".join(f"# {line}\n" for line in header_lines(spec, "docs"))
    head += "# Site navigation, merged into the top-level mkdocs.yml with `INHERIT`.\n"
    return head + yaml.safe_dump(nav(spec), allow_unicode=True, sort_keys=False, width=200)


# --- rendering -------------------------------------------------------------------------------


def _page(template: str, spec: ir.Spec, **ctx: Any) -> bytes:
    text = render(f"docs/{template}", spec, "docs", **HELPERS, **ctx)
    return (text.rstrip("\n") + "\n").encode("utf-8")


HELPERS: dict[str, Any] = {
    "cell": cell, "hex_id": hex_id, "pct": pct, "decimal": decimal, "message_page": message_page,
    "message_svg": message_svg, "anchor": anchor, "json_anchor": json_anchor, "version_anchor": version_anchor, "json_page": json_page, "vt_anchor": vt_anchor, "erratum_anchor": erratum_anchor,
    "errata_links": errata_links, "doc_range": doc_range, "enc_range": enc_range, "range_note": range_note,
    "value_cell": value_cell, "special_cell": special_cell, "role_cell": role_cell, "bytes_cell": bytes_cell, "byte_list": byte_list,
    "node_label": node_label, "receivers_text": receivers_text, "siblings": siblings, "json_range": json_range,
    "json_values": json_values, "json_example": json_example, "json_pairs": json_pairs, "party_label": party_label,
    "id_link": id_link, "tie_epsilon": ir.TIE_EPSILON_TEXT,
}


def value_table_users(can: ir.CanProtocol) -> dict[str, list[tuple[ir.Message, ir.Signal]]]:
    users: dict[str, list[tuple[ir.Message, ir.Signal]]] = {vt.name: [] for vt in can.value_tables}
    for msg in can.messages:
        for sig in msg.signals:
            if sig.value_table is not None:
                users.setdefault(sig.value_table.name, []).append((msg, sig))
    return users


def render_docs(spec: ir.Spec) -> dict[str, bytes]:
    files: dict[str, bytes] = {}
    can = spec.can
    load = busload.bus_load(can) if can is not None else None
    files["index.md"] = _page("index.md.j2", spec, can=can, load=load)
    if can is not None:
        svg_head = "".join(f"<!-- {line.replace('--', '—')} -->\n" for line in header_lines(spec, "docs"))
        for msg in can.messages:
            files[message_page(msg)] = _page("message.md.j2", spec, can=can, msg=msg)
            files[message_svg(msg)] = (svg_head + svg.bit_layout(msg)).encode("utf-8")
        files["value_tables.md"] = _page("value_tables.md.j2", spec, can=can, users=value_table_users(can))
        g = busload.STUFFED_CONTROL_BITS[True]
        files["busload.md"] = _page("busload.md.j2", spec, can=can, load=load, frame_bits=busload.frame_bits,
                                    g=g, g_minus_1=g - 1, trailer=busload.UNSTUFFED_TRAILER_BITS, fixed_bits=g + busload.UNSTUFFED_TRAILER_BITS)
    for proto in spec.json:
        files[json_page(proto)] = _page("json_protocol.md.j2", spec, proto=proto)
    in_table = errata_row_ids(spec.errata_md)
    files["errata.md"] = _page("errata.md.j2", spec, refs=errata_refs(spec), in_table=in_table,
                               errata_md=embed_markdown(spec.errata_md) if spec.errata_md else None)
    if spec.changelog is not None:
        files["history.md"] = _page("history.md.j2", spec, can=can, changelog=spec.changelog)
    files["assets/handbook.css"] = _page("handbook.css.j2", spec)
    files[NAV_FILE] = nav_yaml(spec).encode("utf-8")
    return {OUT + rel: data for rel, data in files.items()}


TARGET = Target("docs", "protocol handbook: bilingual Markdown + SVG bit diagrams for MkDocs", OUT, render_docs, order=80, cost=2)
