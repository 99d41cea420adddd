"""Bilingual where the spec is, English-only where it is: the handbook shows Chinese only when the
spec gives Chinese text somewhere, so an English-only spec gets no Chinese headings, columns or
sentences (and no empty Chinese cells)."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

from canspec import ir


@dataclass(frozen=True)
class Lang:
    zh: bool  # the spec has Chinese text: headings and labels are bilingual

    def zh_en(self, zh: str, en: str) -> str:
        """A heading or label, Chinese first: "值表 Value tables" / "Value tables"."""
        return f"{zh} {en}" if self.zh and zh else en

    def en_zh(self, en: str, zh: str) -> str:
        """A sentence with its Chinese after it: "Sent as 0. 发送 0。" / "Sent as 0."."""
        return f"{en} {zh}" if self.zh and zh else en

    def only_zh(self, zh: str) -> str:
        """Chinese text on its own (a column, a page's Chinese line): empty in an English-only spec."""
        return zh if self.zh else ""


def _texts(spec: ir.Spec) -> Iterator[str]:
    """Every Chinese text the spec itself gives (not the placeholder "保留" of reserved bits)."""
    if spec.can is not None:
        can = spec.can
        yield can.title_zh
        yield from (n.zh for n in can.nodes)
        yield from (e.label_zh for vt in can.value_tables for e in vt.entries)
        for msg in can.messages:
            yield msg.zh
            for sig in msg.data_signals:
                yield from (sig.zh, sig.desc_zh, *(lb.label_zh for lb in sig.labels))
            yield from (s.desc_zh for s in msg.reserved_signals)
    for proto in spec.json:
        yield from (proto.title_zh, *(p.zh for p in proto.parties))
        for jm in proto.messages:
            yield jm.zh
            for f in jm.fields:
                yield from (f.zh, f.desc_zh, *(e.label_zh for e in (*f.enum, *f.sentinels)))
    if spec.changelog is not None:
        for v in spec.changelog.versions:
            yield from (v.label_zh, *(item.zh for item in v.items))


def lang(spec: ir.Spec) -> Lang:
    return Lang(zh=any(_texts(spec)))
