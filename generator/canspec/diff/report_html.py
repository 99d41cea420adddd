"""`canspec diff OLD NEW --format html`: the revision report a new protocol version is published
with — one self-contained page: the computed changes classed strictest first with the suggested
version bump, and, when the new revision is a spec with a change record, each declared item beside
the computed changes it accounts for (release.py). Meaning is decided here; the page's shape is
templates/diff/report.html.j2 (styled by report.css, embedded)."""

from __future__ import annotations

from dataclasses import dataclass
from itertools import groupby

from canspec import resources
from canspec.diff.classes import LADDER, TITLES
from canspec.diff.compare import Change
from canspec.diff.model import ProtocolModel
from canspec.diff.release import Release, release
from canspec.diff.report import summarize
from canspec.render.environment import environment

CLASS_ZH = {"wire": "线上不兼容", "source": "源码不兼容", "compatible": "兼容", "docs": "仅文档"}


@dataclass(frozen=True)
class Row:
    """One computed change."""

    cls: str
    frame_id: str
    message: str
    signal: str
    kind: str
    detail: str
    declared_in: str  # "V2.0.5 #2", "" when no item declares it
    needs_item: bool  # a change the record must declare (not docs) and does not


@dataclass(frozen=True)
class ItemRow:
    """One declared item of the change record and what the diff shows for it."""

    version: str
    number: int
    zh: str
    en: str
    ids: str
    changes: tuple[Row, ...]
    missing: tuple[str, ...]
    unreconstructed: tuple[str, ...]


def _rows(changes: list[Change], rel: Release | None) -> list[Row]:
    out = []
    for i, ch in enumerate(changes):
        declared = ", ".join(rel.declared_in(i)) if rel is not None else ""
        out.append(Row(ch.cls, ch.subject, ch.message, ch.signal or "", ch.kind, ch.detail, declared,
                       rel is not None and i in rel.undeclared))
    return out


def _items(rel: Release, rows: list[Row]) -> list[ItemRow]:
    return [ItemRow(f"V{c.version.version}", c.item.number, c.item.zh, c.item.en, ", ".join(f"0x{i:08X}" for i in c.item.ids),
                    tuple(rows[i] for i in c.changes), c.missing, c.unreconstructed) for c in rel.items]


def html(old: ProtocolModel, new: ProtocolModel, changes: list[Change]) -> str:
    s = summarize(old, new, changes)
    rel = release(new.changelog, old.version, new.version, changes)
    rows = _rows(changes, rel)
    groups = [(key, list(items)) for key, items in groupby(rows, key=lambda r: (r.frame_id, r.message))]
    css = (resources.templates_dir() / "diff" / "report.css").read_text(encoding="utf-8")
    return environment("diff").get_template("diff/report.html.j2").render(
        old=old, new=new, summary=s, ladder=LADDER, titles=TITLES, class_zh=CLASS_ZH, groups=groups, css=css,
        release=rel, items=_items(rel, rows) if rel is not None else [], undeclared=[r for r in rows if r.needs_item],
    )
