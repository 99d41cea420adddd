"""`canspec changelog [SPEC] [--lang both|zh|en] [--newest-first] [-o FILE]`: the spec's change
record as Markdown in the document's own style (version, numbered items with message IDs,
authors and date), bilingual by default."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from canspec.commands.common import compile_or_report
from canspec.diff.changelog import LANGUAGES, rows
from canspec.render.environment import render

_TEXT = {  # (zh, en)
    "heading": ("变更记录表", "Change record"),
    "version": ("版本号", "Version"),
    "changes": ("变更描述", "Changes"),
    "signature": ("签名/日期", "Signature / date"),
    "errata_note": ("[H..] / [E..]: 勘误，见 spec/ERRATA.md", "[H..] / [E..]: errata, see spec/ERRATA.md"),
}


def _labels(lang: str, title: str, title_zh: str, version: str, has_errata: bool) -> dict[str, str]:
    def pick(zh: str, en: str, sep: str) -> str:
        return {"zh": zh, "en": en}.get(lang) or (f"{zh}{sep}{en}" if zh else en)

    labels = {key: pick(zh, en, "<br>" if key in ("version", "changes", "signature") else " · ") for key, (zh, en) in _TEXT.items()}
    labels["subtitle"] = f"{pick(title_zh, title, ' · ')} V{version}"
    if not has_errata:
        labels["errata_note"] = ""
    return labels


def run(args: argparse.Namespace) -> int:
    compiled = compile_or_report(args.spec, quiet_warnings=True, cached=True)
    if compiled.spec is None:
        print("canspec changelog: the spec has errors (see above)", file=sys.stderr)
        return 1
    spec = compiled.spec
    if spec.changelog is None:
        print("canspec changelog: the spec has no changelog (a file of kind `changelog`)", file=sys.stderr)
        return 1
    can = spec.can
    title, title_zh = (can.title, can.title_zh) if can else (spec.name, "")
    has_errata = any(r.errata or any(i.errata for i in r.items) for r in rows(spec.changelog))
    text = render(
        "changelog/changelog.md.j2", spec, "changelog", rows=rows(spec.changelog, args.newest_first), lang=args.lang,
        labels=_labels(args.lang, title, title_zh, spec.version, has_errata),
    )
    if args.output:
        try:
            Path(args.output).write_text(text, encoding="utf-8")
        except OSError as exc:
            print(f"canspec changelog: cannot write {args.output}: {exc.strerror}", file=sys.stderr)
            return 1
    else:
        sys.stdout.write(text)
    return 0


def register(sub) -> None:  # type: ignore[no-untyped-def]
    p = sub.add_parser("changelog", help="render the spec's change record as Markdown (bilingual, in the document's style)")
    p.add_argument("spec", nargs="?", default=None, help="spec bundle, directory or file (default: the shipped spec)")
    p.add_argument("--lang", choices=LANGUAGES, default="both", help="both (default), zh or en")
    p.add_argument("--newest-first", action="store_true", help="list the newest version first (the document lists oldest first)")
    p.add_argument("-o", "--output", help="write to this file instead of standard output")
    p.set_defaults(func=run)
