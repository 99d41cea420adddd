"""`canspec import SOURCE... -o DIR`: a spec bundle from a DBC, ARXML, KCD or SYM file (or several)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from canspec.commands.common import add_encoding_argument
from canspec.importer import outdir, yamlout
from canspec.importer.clashes import RoundCompile, compile_in_temp
from canspec.importer.dbctext import DbcError
from canspec.importer.run import import_sources
from canspec.pipeline import Compiled
from canspec.render import writer
from canspec.spec_cache import compile_cached


def _where(source: str, line: int | None) -> str:
    return f"{source}:{line}" if line is not None else source


class _Refused(Exception):
    """The -o directory holds files import must not replace (outdir.refusal says which)."""


def _files(spec: dict[str, Any], sources: list[str]) -> tuple[dict[str, bytes], str, dict[int, tuple[int, ...]]]:
    """The bundle and spec file import writes, the spec file's name, and its line map."""
    header = [f"Imported by `canspec import` from {', '.join(Path(s).name for s in sources)}.",
              "Edit this file (it is the source of truth now); `canspec check` says what is wrong."]
    text, where = yamlout.dump_with_lines(spec, header)
    name = spec["protocol"]["name"]
    file = outdir.spec_file(name)
    data = text.encode()
    return {file: data, outdir.BUNDLE: outdir.bundle(name, file, data)}, file, where


def _write(out: Path, files: dict[str, bytes], force: bool) -> None:
    if (why := outdir.refusal(out, files, force)) is not None:
        raise _Refused(why)
    writer.apply(out, writer.Plan(write=files))


def _written_round(out: Path, args: argparse.Namespace) -> RoundCompile:
    """A clash-resolution round that writes the spec to -o and compiles it there through the
    compiled-spec cache: the last round's entry is what a following `canspec gen DIR` reads
    instead of compiling the spec again."""

    def compile_round(spec: dict[str, Any]) -> tuple[Compiled, str, dict[int, tuple[int, ...]]]:
        files, file, where = _files(spec, args.source)
        _write(out, files, args.force)
        return compile_cached(out), file, where

    return compile_round


def run(args: argparse.Namespace) -> int:
    out = Path(args.output)
    if (why := outdir.refusal(out, {}, args.force)) is not None:  # before the import's work: -o names a file
        print(f"canspec import: {why}", file=sys.stderr)
        return 1
    try:
        # --strict writes nothing when a warning comes up, renames included: its rounds compile privately
        spec, report, compiled = import_sources(args.source, args.encoding, compile_in_temp if args.strict else _written_round(out, args))
        for source, line, text in report.warnings:
            print(f"{_where(source, line)}: {'error' if args.strict else 'warning'}: {text}", file=sys.stderr)
        if args.strict and report.warnings:
            print(f"canspec import: {len(report.warnings)} warning(s) are errors under --strict; nothing written", file=sys.stderr)
            return 1
        if args.strict:
            _write(out, _files(spec, args.source)[0], args.force)
    except DbcError as exc:
        print(f"canspec import: {exc}", file=sys.stderr)
        return 1
    except _Refused as exc:
        print(f"canspec import: {exc}", file=sys.stderr)
        return 1
    except OSError as exc:
        print(f"canspec import: cannot write {out}: {exc.strerror or exc}; nothing written", file=sys.stderr)
        return 1
    print(f"canspec import: {len(spec['messages'])} messages into {out / outdir.spec_file(spec['protocol']['name'])} "
          f"({len(report.warnings)} warning(s))", file=sys.stderr)
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
