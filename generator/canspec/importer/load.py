"""Load one import source through cantools: a DBC (repaired where dbctext.py knows a sensible
reading), or ARXML, KCD and SYM by cantools' own readers. cantools is the reader because it is the
one the corpus measures (it reads 81 of opendbc's 115 DBCs strictly, 94 after the repairs) and it
keeps what the spec needs — byte order, floats, FD, multiplexing, attributes, comments — while
canmatrix 1.2 reads every file but silently drops messages."""

from __future__ import annotations

import logging
import re
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from canspec.importer.dbctext import BO_LINE, MAX_REPAIRS, DbcError, Repairs, clip, prepass, repair_step
from canspec.importer.encoding import TextError, decode
from canspec.nomf4 import import_without_mf4

FORMATS = {".dbc": "dbc", ".arxml": "arxml", ".kcd": "kcd", ".sym": "sym"}


@dataclass
class Loaded:
    source: str  # as the user named it
    format: str
    db: Any  # cantools.database.can.Database
    text: str | None  # the DBC text cantools read (repaired), for line numbers
    warnings: list[tuple[int | None, str]]
    renamed: dict[str, str]  # placeholder → the DBC's own name (digit-first names)


def read_text(path: Path, source: str, encoding: str | None = None) -> tuple[str, list[tuple[int, str]]]:
    """The text (\r\n as \n), and a warning at its line when its encoding was a guess."""
    try:
        text, guess = decode(path.read_bytes(), encoding)
    except TextError as exc:
        raise DbcError(f"{_where(source, exc.line)}: {exc}") from None
    return text.replace("\r\n", "\n"), [guess] if guess else []


class _Records(logging.Handler):
    def __init__(self) -> None:
        super().__init__(logging.WARNING)
        self.records: list[logging.LogRecord] = []

    def emit(self, record: logging.LogRecord) -> None:
        self.records.append(record)


@contextmanager
def _cantools_log() -> Iterator[_Records]:
    """cantools logs what it decides (a message that replaces another in its lookup tables) as bare
    text on stderr: kept here instead, to be said as canspec warnings at their lines."""
    logger, handler = logging.getLogger("cantools"), _Records()
    propagate, logger.propagate = logger.propagate, False
    logger.addHandler(handler)
    try:
        yield handler
    finally:
        logger.removeHandler(handler)
        logger.propagate = propagate


def _cantools() -> Any:
    return import_without_mf4("cantools")  # the [import] extra; the CLI names it when missing


def load_dbc(path: Path, source: str, encoding: str | None = None) -> Loaded:
    cantools = _cantools()
    text, guessed = read_text(path, source, encoding)
    rep = Repairs(source, text.split("\n"), list(guessed))
    prepass(rep)
    last = ""
    with _cantools_log() as log:
        for _ in range(MAX_REPAIRS):
            log.records.clear()  # what the parse that succeeds logged, not the attempts before a repair
            try:
                db = cantools.database.load_string(rep.text, database_format="dbc", strict=False)
                break
            except Exception as exc:  # noqa: BLE001 - cantools raises many kinds; each is read for a repair
                last = clip(str(exc).splitlines()[0] if str(exc) else type(exc).__name__)
                before = list(rep.lines)
                if not repair_step(rep, str(exc)) or rep.lines == before:  # no repair, or one that changed nothing
                    raise DbcError(f"{_where(source, _line_of(last, rep.lines))}: not a readable DBC: {last}"
                                   " (hint: fix the line; canspec import repairs only what has one sensible reading)") from None
        else:
            raise DbcError(f"{source}: too many repairs needed ({MAX_REPAIRS}); last: {last}")
    for record in log.records:
        rep.warnings.append(_logged(record.getMessage(), rep))
    warnings: list[tuple[int | None, str]] = sorted(rep.warnings, key=lambda w: (w[0] or 0, w[1]))
    return Loaded(source, "dbc", db, rep.text, warnings, rep.renamed)


def _where(source: str, line: int | None) -> str:
    return f"{source}:{line}" if line is not None else source


def _line_of(error: str, lines: list[str]) -> int | None:
    """The line cantools' error is about: the one it names, or the first holding a value it quotes
    (`could not convert string to float: 'fast'` names no line); None when neither is found."""
    if (m := re.search(r"line (\d+)", error)) is not None:
        return int(m.group(1))
    for value in re.findall(r"'([^'\n]+)'", error):
        quoted = f'"{value}"'
        word = re.compile(rf"(?<![\w]){re.escape(value)}(?![\w])")
        found = next((i for i, line in enumerate(lines, 1) if quoted in line), None) or \
            next((i for i, line in enumerate(lines, 1) if word.search(line)), None)
        if found is not None:
            return found
    return None


_NAME_TWICE = re.compile(r"Overwriting message '(\w+)' with '(\w+)' in the name to message dictionary")


def _logged(text: str, rep: Repairs) -> tuple[int | None, str]:
    """A cantools log line as a canspec warning at its line. Two BO_ lines of one name: cantools keeps
    both messages (its lookup by name finds the second), so does the spec, the second under a spec
    name of its own; a repeated frame ID is refused before cantools reads the file (dbctext)."""
    if (m := _NAME_TWICE.search(text)) is not None:
        at = [i for i, line in enumerate(rep.lines, 1) if (bo := BO_LINE.match(line)) is not None and bo.group(4) == m.group(2)]
        name = rep.renamed.get(m.group(2), m.group(2))
        shown = f"lines {', '.join(map(str, at))}" if at else "two BO_ lines"
        return (at[-1] if at else None), (f"message name {name} is given to two messages ({shown}): both kept, the later one "
                                          f"under a spec name of its own (its dbc_name stays {name})")
    return _line_of(text, rep.lines), f"cantools: {clip(text)}"


def load(path: Path, source: str, encoding: str | None = None) -> Loaded:
    """`encoding`: the text's (DBC and SYM), None to read UTF-8 or guess (encoding.py)."""
    _cantools()  # the reader first: without it, the command names the extra to install
    kind = FORMATS.get(path.suffix.lower())
    if kind is None:
        raise DbcError(f"{source}: unknown format {path.suffix!r} (canspec import reads {', '.join(sorted(FORMATS))})")
    if not path.is_file():
        raise DbcError(f"{source}: no such file")
    if kind == "dbc":
        return load_dbc(path, source, encoding)
    guessed: list[tuple[int, str]] = []
    with _cantools_log() as log:
        try:
            if kind == "sym":  # text like a DBC's, in the same encodings; ARXML and KCD are XML, which declares its own
                text, guessed = read_text(path, source, encoding)
                db = _cantools().database.load_string(text, database_format=kind, strict=False)
            else:
                db = _cantools().database.load_file(str(path), database_format=kind, strict=False)
        except DbcError:
            raise
        except Exception as exc:  # noqa: BLE001 - cantools raises many kinds; all mean unreadable
            first = clip(str(exc).splitlines()[0] if str(exc) else type(exc).__name__)
            raise DbcError(f"{source}: not a readable {kind.upper()} file: {first}") from None
    # a frame ID twice in KCD or ARXML (several buses) is tospec's warning, with what it decided
    logged = [r.getMessage() for r in log.records if "in the frame id to message dictionary" not in r.getMessage()]
    warnings = [*guessed, *((None, f"cantools: {clip(text)}") for text in logged)]
    return Loaded(source, kind, db, None, warnings, {})
