"""The errata sheet: each erratum that ERRATA.md describes in a table row of its own (its cells,
Markdown marks removed, under the section heading it stands in) and where the spec cites it. An
erratum the spec cites but ERRATA.md does not describe still gets its row."""

from __future__ import annotations

import re
from dataclasses import dataclass

from canspec import ir
from canspec.targets.xlsx.model import Cell, Column, Sheet, sheet

_ROW = re.compile(r"^\|\s*([A-Z]+\d+)\s*\|")
_SEPARATOR = re.compile(r"^\|(\s*:?-+:?\s*\|)+\s*$")
_HEADING = re.compile(r"^#{2,6}\s+(.*?)\s*$")
_CELL_SPLIT = re.compile(r"(?<!\\)\|")
_MARKS = ((re.compile(r"\*\*(.+?)\*\*"), r"\1"), (re.compile(r"`([^`]*)`"), r"\1"), (re.compile(r"(?<!!)\[([^\]]+)\]\([^)\s]+\)"), r"\1"))
MAX_WIDTH = 50


@dataclass(frozen=True)
class Row:
    erratum: str
    section: str
    header: tuple[str, ...]  # the table's column names after the ID column
    cells: tuple[str, ...]


def plain(markdown: str) -> str:
    """Table-cell Markdown as text: `code`, **bold** and [links](x) lose their marks, <br> breaks the line."""
    text = markdown.replace("\\|", "|").replace("<br>", "\n")
    for pattern, repl in _MARKS:
        text = pattern.sub(repl, text)
    return text


def _cells(line: str) -> tuple[str, ...]:
    return tuple(plain(c.strip()) for c in _CELL_SPLIT.split(line.strip().strip("|")))


def described(errata_md: str | None) -> list[Row]:
    rows: list[Row] = []
    section, header = "", ()
    lines = (errata_md or "").splitlines()
    for n, line in enumerate(lines):
        if m := _HEADING.match(line):
            section = plain(m.group(1))
        elif n + 1 < len(lines) and line.startswith("|") and _SEPARATOR.match(lines[n + 1]):
            header = _cells(line)[1:]
        elif m := _ROW.match(line):
            rows.append(Row(m.group(1), section, header, _cells(line)[1:]))
    return rows


def citations(spec: ir.Spec) -> dict[str, list[str]]:
    """Erratum id → what cites it, in spec order."""
    out: dict[str, list[str]] = {}

    def add(ids: tuple[str, ...], what: str) -> None:
        for e in ids:
            out.setdefault(e, []).append(what)

    for msg in spec.can.messages if spec.can is not None else ():
        add(msg.errata, f"{msg.id_text} {msg.name}")
        for sig in msg.signals:
            add(sig.errata, f"{msg.id_text} {msg.name}.{sig.name}")
    for proto in spec.json:
        add(proto.errata, proto.name)
        for jm in proto.messages:
            for f in jm.fields:
                add(f.errata, f"{proto.name}: {jm.name}.{f.json_name}")
    for v in spec.changelog.versions if spec.changelog is not None else ():
        add(v.errata, f"V{v.version}")
        for item in v.items:
            add(item.errata, f"V{v.version} #{item.number}")
    return out


def _order(eid: str) -> tuple[str, int, str]:
    m = re.match(r"([A-Za-z]*)(\d*)(.*)", eid)
    assert m is not None
    return (m.group(1), int(m.group(2) or 0), m.group(3))


def _header(rows: list[Row], k: int) -> str:
    """Column k's name: the tables' own, each distinct name once ("Where in D / Where in J")."""
    names = dict.fromkeys(r.header[k] for r in rows if k < len(r.header) and r.header[k])
    return " / ".join(names) or f"Column {k + 2}"


def errata(spec: ir.Spec) -> Sheet | None:
    rows, cited = described(spec.errata_md), citations(spec)
    ids = [r.erratum for r in rows] + sorted(set(cited) - {r.erratum for r in rows}, key=_order)
    if not ids:
        return None
    width = max((len(r.cells) for r in rows), default=0)
    by_id = {r.erratum: r for r in rows}
    table: list[list[Cell]] = []
    for eid in ids:
        row = by_id.get(eid)
        cells = list(row.cells if row else ()) + [None] * (width - len(row.cells if row else ()))
        table.append([eid, row.section if row else None, *cells, "\n".join(cited.get(eid, ()))])
    columns = [Column("erratum", "勘误", "Erratum", 8), Column("section", "章节", "Section", 16, wrap=True, optional=True)]
    for k in range(width):
        longest = max(len(str(r[2 + k] or "")) for r in table)
        columns.append(Column(f"col{k + 2}", "", _header(rows, k), min(max(longest, 8) + 2, MAX_WIDTH), wrap=True))
    columns.append(Column("cited_by", "引用处", "Cited by", 40, wrap=True))
    return sheet("勘误 Errata", columns, table, freeze="erratum")
