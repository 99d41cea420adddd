"""The change record as rows in the document's own style (版本号 | 变更描述 | 签名/日期):
numbered items "1、… 0x1804A0B0" with their English line, authors and a dotted date. The text
is shaped by templates/changelog/changelog.md.j2; meaning (numbering, IDs, dates) is here."""

from __future__ import annotations

from dataclasses import dataclass

from canspec import ir


@dataclass(frozen=True)
class ItemRow:
    number: int
    zh: str  # as printed, with the message IDs the item names appended when the text lacks them
    en: str
    errata: tuple[str, ...]


@dataclass(frozen=True)
class VersionRow:
    version: str  # "V2.0.0 (矿卡起始版)"
    version_en: str
    signature: str  # "李朗 华凤玲 2020.05.06"
    numbered: bool
    items: tuple[ItemRow, ...]
    errata: tuple[str, ...]


LANGUAGES = ("both", "zh", "en")


def _ids(ids: tuple[int, ...]) -> list[str]:
    return [f"0x{i:08X}" for i in ids]


def _zh(item: ir.ChangeItem) -> str:
    missing = [t for t in _ids(item.ids) if t.lower() not in item.zh.lower()]
    return f"{item.zh} {'、'.join(missing)}" if missing else item.zh


def _en(item: ir.ChangeItem) -> str:
    ids = _ids(item.ids)
    return f"{item.en} ({', '.join(ids)})" if ids and item.en else item.en


def rows(log: ir.Changelog, newest_first: bool = False) -> list[VersionRow]:
    out = []
    for v in log.versions:
        date = (v.date or "").replace("-", ".")
        out.append(
            VersionRow(
                version=f"V{v.version}" + (f" ({v.label_zh})" if v.label_zh else ""),
                version_en=f"V{v.version}" + (f" ({v.label})" if v.label else ""),
                signature=" ".join([*v.authors, date]).strip(),
                numbered=len(v.items) > 1,
                items=tuple(ItemRow(it.number, _zh(it), _en(it), it.errata) for it in v.items),
                errata=v.errata,
            )
        )
    return out[::-1] if newest_first else out
