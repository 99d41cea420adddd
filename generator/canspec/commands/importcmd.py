"""`canspec import SOURCE... -o DIR`: a spec bundle from a DBC, ARXML, KCD or SYM file (or several)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from canspec.commands.common import add_encoding_argument
from canspec.importer import outdir, yamlout
from canspec.importer.dbctext import DbcError
from canspec.importer.run import import_sources
from canspec.render import writer


def _where(source: str, line: int | None) -> str:
    return f"{source}:{line}" if line is not None else source


def run(args: argparse.Namespace) -> int:
    out = Path(args.output)
    if (why := outdir.refusal(out, {}, args.force)) is not None:  # before the import's work: -o names a file
        print(f"canspec import: {why}", file=sys.stderr)
        return 1
    try:
        spec, report, compiled = import_sources(args.source, args.encoding)
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
    text = yamlout.dump(spec, header).encode()
    file = outdir.spec_file(name)
    files = {file: text, outdir.BUNDLE: outdir.bundle(name, file, text)}
    if (why := outdir.refusal(out, files, args.force)) is not None:
        print(f"canspec import: {why}", file=sys.stderr)
        return 1
    try:
        writer.apply(out, writer.Plan(write=files))
    except OSError as exc:
        print(f"canspec import: cannot write {out}: {exc.strerror or exc}; nothing written", file=sys.stderr)
        return 1
    print(f"canspec import: {len(spec['messages'])} messages into {out / file} ({len(report.warnings)} warning(s))", file=sys.stderr)
    if compiled.errors:  # what the importer could not decide: the spec is written for the user to fix
        print(f"canspec import: `canspec check {out}` finds {len(compiled.errors)} error(s) to fix in the written spec, e.g. "
              f"{compiled.errors[0].message}", file=sys.stderr)
        return 1
    return 0


def register(sub) -> None:  # type: ignore[no-untyped-def]
    p = sub.add_parser("import", help="write a spec from a DBC, ARXML, KCD or SYM file (several are merged into one spec)")
    p.add_argument("source", nargs="+", help="the files to import (.dbc, .arxml, .kcd, .sym)")
    p.add_argument("-o", "--output", required=True, help="directory to write the spec bundle to (canspec.yaml and <name>.yaml)")
    p.add_argument("--force", action="store_true",
                   help="replace files in the -o directory that an earlier import did not write, or that were edited since")
    p.add_argument("--strict", action="store_true", help="treat every warning as an error (nothing is written)")
    add_encoding_argument(p)
    p.set_defaults(func=run)
