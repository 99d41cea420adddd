"""`canspec import SOURCE... -o DIR`: a spec bundle from a DBC, ARXML, KCD or SYM file (or several)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from canspec.importer import yamlout
from canspec.importer.dbctext import DbcError
from canspec.importer.run import import_sources
from canspec.render import writer


def _where(source: str, line: int | None) -> str:
    return f"{source}:{line}" if line is not None else source


def run(args: argparse.Namespace) -> int:
    try:
        spec, report = import_sources(args.source)
    except DbcError as exc:
        print(f"canspec import: {exc}", file=sys.stderr)
        return 1
    for source, line, text in report.warnings:
        print(f"{_where(source, line)}: {'error' if args.strict else 'warning'}: {text}", file=sys.stderr)
    if args.strict and report.warnings:
        print(f"canspec import: {len(report.warnings)} warning(s) are errors under --strict; nothing written", file=sys.stderr)
        return 1
    name = spec["protocol"]["name"]
    header = [f"Imported by `canspec import` from {', '.join(Path(s).name for s in args.source)}.",
              "Edit this file (it is the source of truth now); `canspec check` says what is wrong."]
    bundle = f"# canspec bundle written by `canspec import`\nschema_version: 1\nkind: bundle\nname: {name}\nfiles:\n  - {name}.yaml\n"
    out = Path(args.output)
    writer.apply(out, writer.Plan(write={f"{name}.yaml": yamlout.dump(spec, header).encode(), "canspec.yaml": bundle.encode()}))
    print(f"canspec import: {len(spec['messages'])} messages into {out}/{name}.yaml ({len(report.warnings)} warning(s))", file=sys.stderr)
    return 0


def register(sub) -> None:  # type: ignore[no-untyped-def]
    p = sub.add_parser("import", help="write a spec from a DBC, ARXML, KCD or SYM file (several are merged into one spec)")
    p.add_argument("source", nargs="+", help="the files to import (.dbc, .arxml, .kcd, .sym)")
    p.add_argument("-o", "--output", required=True, help="directory to write the spec bundle to (canspec.yaml and <name>.yaml)")
    p.add_argument("--strict", action="store_true", help="treat every warning as an error (nothing is written)")
    p.set_defaults(func=run)
