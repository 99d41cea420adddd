"""Turn a diff argument into a comparison model: a spec (bundle, directory or file), or a database
file — DBC, ARXML, KCD or SYM — read the way `canspec import` reads it (one reading of a source,
not two: its repairs, its names, multiplexing, FD, floats and exact SG_ numbers) and compiled like
any spec. What the import leaves out or reinterprets, diff could not compare: it refuses the file
and names what."""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

from canspec.commands.extras import install_hint
from canspec.diff.fromdb import from_database
from canspec.diff.model import ProtocolModel, from_spec
from canspec.nomf4 import import_without_mf4
from canspec.pipeline import compile_spec

DATABASES = (".dbc", ".arxml", ".kcd", ".sym")
# Import warnings that lose or reinterpret what diff compares: a message or signal left out, a float's
# scaling, a page's counter or checksum role, a long frame's missing FD flag (a change of that flag
# would go unseen).
_UNCOMPARABLE = ("left out", "scaling dropped", "role dropped", "taken as CAN FD")


class InputError(Exception):
    """A diff input that cannot be read: the message says what and how to fix it."""


def is_database(arg: str) -> bool:
    return Path(arg).is_file() and Path(arg).suffix.lower() in DATABASES


def load_model(arg: str, comments: bool = False, encoding: str | None = None) -> ProtocolModel:
    """`comments`: a database's comments are compared (both inputs are databases); `encoding`: a
    DBC's or SYM's text encoding (None: UTF-8, else a guess with a warning)."""
    path = Path(arg)
    if not path.exists():
        raise InputError(f"{arg}: no such file or directory (pass a spec bundle, spec directory or a {', '.join(DATABASES)} file)")
    if is_database(arg):
        return _database(path, arg, comments, encoding)
    if path.is_file() and path.suffix.lower() not in (".yaml", ".yml"):
        raise InputError(f"{arg}: not a spec (.yaml) or database ({', '.join(DATABASES)}) file")
    return from_spec(_compiled(path, arg, f"run `canspec check {arg}`"), arg)


def _compiled(path: Path, arg: str, hint: str):  # type: ignore[no-untyped-def]
    compiled = compile_spec(path, targets=[])  # a revision is compared as the spec rules read it: what a target refuses is that target's concern
    if compiled.spec is None:
        shown = "\n".join(p.format() for p in compiled.errors[:10])
        more = f"\n  ... and {len(compiled.errors) - 10} more" if len(compiled.errors) > 10 else ""
        raise InputError(f"{arg}: the spec has errors ({hint}):\n{shown}{more}")
    if compiled.spec.can is None:
        raise InputError(f"{arg}: the spec has no CAN protocol to compare")
    return compiled.spec


def _database(path: Path, arg: str, comments: bool, encoding: str | None) -> ProtocolModel:
    try:
        import_without_mf4("cantools")  # the import extra: reading databases needs it
    except ImportError as exc:
        raise InputError(f"{arg}: reading {path.suffix} files needs cantools; {install_hint('import')}") from exc
    from canspec.importer import tospec
    from canspec.importer.dbctext import DbcError
    from canspec.importer.load import load
    from canspec.importer.yamlout import dump_with_lines

    try:
        loaded = load(path, arg, encoding)
    except DbcError as exc:
        raise InputError(str(exc)) from None
    report = tospec.Report([(arg, line, text) for line, text in loaded.warnings])
    spec = tospec.build_spec(loaded, report)
    lost = [_where(w) for w in report.warnings if any(words in w[2] for words in _UNCOMPARABLE)]
    if lost:
        shown = "\n  ".join(lost[:10]) + (f"\n  ... and {len(lost) - 10} more" if len(lost) > 10 else "")
        raise InputError(f"{arg}: canspec diff cannot compare what reading it leaves out or changes (see `canspec import {arg}`):\n  {shown}")
    for warning in report.warnings:  # decisions diff compares as taken (an assumed bit rate, a 29-bit ID): said, not fatal
        print(f"canspec diff: warning: {_where(warning)}", file=sys.stderr)
    with tempfile.TemporaryDirectory() as tmp:
        yaml_path = Path(tmp) / "spec.yaml"
        yaml_path.write_text(dump_with_lines(spec, [])[0], encoding="utf-8")
        ir_spec = _compiled(yaml_path, arg, f"run `canspec import {arg}` and `canspec check` on the result")
    return from_database(ir_spec, loaded, arg, comments)


def _where(warning: tuple[str, int | None, str]) -> str:
    source, line, text = warning
    return f"{source}:{line}: {text}" if line else f"{source}: {text}"
