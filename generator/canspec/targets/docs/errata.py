"""The errata page: spec/ERRATA.md placed in the handbook, and an index of where the spec cites
each erratum (anchored, so every page can link to an erratum)."""

from __future__ import annotations

import re

from canspec import ir


def erratum_anchor(eid: str) -> str:
    return eid.lower()


def errata_links(ids: tuple[str, ...], prefix: str) -> str:
    return ", ".join(f"[{e}]({prefix}errata.md#{erratum_anchor(e)})" for e in ids)


def message_page(msg: ir.Message) -> str:
    return f"messages/{msg.name}.md"


def json_page(proto: ir.JsonProtocol) -> str:
    return f"json/{proto.name}.md"


def errata_refs(spec: ir.Spec) -> dict[str, list[tuple[str, str]]]:
    """Every erratum id the spec cites → (page link, what cites it), in spec order."""
    refs: dict[str, list[tuple[str, str]]] = {}

    def add(ids: tuple[str, ...], link: str, what: str) -> None:
        for e in ids:
            refs.setdefault(e, []).append((link, what))

    if spec.can is not None:
        for msg in spec.can.messages:
            add(msg.errata, message_page(msg), _what(msg.name, msg.zh))
            for sig in msg.signals:
                add(sig.errata, message_page(msg), _what(f"{msg.name}.{sig.name}", sig.zh))
    for proto in spec.json:
        add(proto.errata, json_page(proto), proto.name)
        for jm in proto.messages:
            for f in jm.fields:
                add(f.errata, json_page(proto), _what(f"{jm.name}.{f.json_name}", f.zh))
    if spec.changelog is not None:
        for v in spec.changelog.versions:
            add(v.errata, "history.md", f"V{v.version}")
            for item in v.items:
                add(item.errata, "history.md", f"V{v.version} #{item.number}")
    return dict(sorted(refs.items(), key=lambda kv: _erratum_key(kv[0])))


def _what(name: str, zh: str) -> str:
    return f"{name} ({zh})" if zh else name


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
