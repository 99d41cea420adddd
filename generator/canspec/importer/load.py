"""Load one import source through cantools: a DBC (repaired where dbctext.py knows a sensible
reading), or ARXML, KCD and SYM by cantools' own readers. cantools is the reader because it is the
one the corpus measures (it reads 81 of opendbc's 115 DBCs strictly, 94 after the repairs) and it
keeps what the spec needs — byte order, floats, FD, multiplexing, attributes, comments — while
canmatrix 1.2 reads every file but silently drops messages."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from canspec.importer.dbctext import MAX_REPAIRS, DbcError, Repairs, prepass, repair_step

FORMATS = {".dbc": "dbc", ".arxml": "arxml", ".kcd": "kcd", ".sym": "sym"}


@dataclass
class Loaded:
    source: str  # as the user named it
    format: str
    db: Any  # cantools.database.can.Database
    text: str | None  # the DBC text cantools read (repaired), for line numbers
    warnings: list[tuple[int | None, str]]
    renamed: dict[str, str]  # placeholder → the DBC's own name (digit-first names)


def read_text(path: Path, source: str) -> str:
    data = path.read_bytes()
    for encoding in ("utf-8-sig", "cp1252"):  # Vector tools often write cp1252
        try:
            return data.decode(encoding)
        except UnicodeDecodeError:
            continue
    raise DbcError(f"{source}: not a readable text file (neither UTF-8 nor cp1252)")


def _cantools() -> Any:
    import cantools  # the [import] extra; the CLI names it when missing

    return cantools


def load_dbc(path: Path, source: str) -> Loaded:
    cantools = _cantools()
    rep = Repairs(source, read_text(path, source).replace("\r\n", "\n").split("\n"))
    prepass(rep)
    last = ""
    for _ in range(MAX_REPAIRS):
        try:
            db = cantools.database.load_string(rep.text, database_format="dbc", strict=False)
            break
        except Exception as exc:  # noqa: BLE001 - cantools raises many kinds; each is read for a repair
            last = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
            before = list(rep.lines)
            if not repair_step(rep, str(exc)) or rep.lines == before:  # no repair, or one that changed nothing
                raise DbcError(f"{source}:{_line_of(last)}: not a readable DBC: {last}"
                               " (hint: fix the line; canspec import repairs only what has one sensible reading)") from None
    else:
        raise DbcError(f"{source}: too many repairs needed ({MAX_REPAIRS}); last: {last}")
    warnings: list[tuple[int | None, str]] = sorted(rep.warnings)
    return Loaded(source, "dbc", db, rep.text, warnings, rep.renamed)


def _line_of(error: str) -> str:
    import re

    m = re.search(r"line (\d+)", error)
    return m.group(1) if m else "1"


def load(path: Path, source: str) -> Loaded:
    _cantools()  # the reader first: without it, the command names the extra to install
    kind = FORMATS.get(path.suffix.lower())
    if kind is None:
        raise DbcError(f"{source}: unknown format {path.suffix!r} (canspec import reads {', '.join(sorted(FORMATS))})")
    if not path.is_file():
        raise DbcError(f"{source}: no such file")
    if kind == "dbc":
        return load_dbc(path, source)
    try:
        db = _cantools().database.load_file(str(path), database_format=kind, strict=False)
    except Exception as exc:  # noqa: BLE001 - cantools raises many kinds; all mean unreadable
        first = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        raise DbcError(f"{source}: not a readable {kind.upper()} file: {first}") from None
    return Loaded(source, kind, db, None, [], {})
