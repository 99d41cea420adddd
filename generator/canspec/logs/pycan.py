"""Vector ASC and PEAK TRC through python-can's readers: batches of its messages turned into frame
columns. The readers see a line-counting file, so frames and problems carry their line numbers.

python-can reads leniently: it drops a record it cannot parse with a message on its `can` loggers
(printed raw on stderr, no file or line) and skips, without a word, every ASC line its pattern does
not match (a time stamp like `0.0x2000`, `-5.0` or `nan`). Here nothing is dropped silently: the
loggers' warnings become malformed-line problems at the line being read (the record is dropped,
as for a bad candump line), and an ASC line that looks like a frame record but whose time stamp the
reader would not take is one too."""

from __future__ import annotations

import io
import logging
import math
import re
from collections.abc import Iterator
from typing import IO, Any

from canspec.ir.ids import max_id
from canspec.logs import frames as fr
from canspec.logs.candump import DATA, ERROR, REMOTE, Frame
from canspec.nomf4 import import_without_mf4

CHUNK_FRAMES = 1 << 18  # frames per batch
TRC_VERSIONS = ("1.0", "1.1", "1.3", "2.0", "2.1")  # what python-can's TRCReader parses (no version line: 1.0)
# ASC: a frame record (CHANNEL ID DIR, CHANNEL ErrorFrame, CANFD ...) after a time stamp of any form
ASC_RECORD = re.compile(r"(?P<time>\S+)\s+(\d+\s+(\w+\s+(Tx|Rx)|ErrorFrame)|CANFD)\b", re.ASCII | re.IGNORECASE)
ASC_UNTIMED = re.compile(r"(CANFD\s+\d+|\d+\s+\w+)\s+(Tx|Rx)\b", re.ASCII | re.IGNORECASE)
ASC_TIME = re.compile(r"\d+\.\d+", re.ASCII)  # the only time stamp form python-can's ASCReader takes


class Unreadable(Exception):
    """The file's header cannot be parsed: the file is not readable."""


def trc_version_problem(head: bytes) -> str | None:
    """Why python-can would misread this TRC header's version (None: it reads it). An unknown
    version is parsed as 1.0, so every record would be malformed with a misleading reason."""
    for raw in head.splitlines():
        line = raw.decode("utf-8", errors="replace").strip()
        if not line.startswith(";"):
            return None
        if line.startswith(";$FILEVERSION"):
            version = line.partition("=")[2]
            if version not in TRC_VERSIONS:
                return f"unsupported TRC version {version or '(none)'} (supported: {', '.join(TRC_VERSIONS)})"
    return None


def read_text(stream: IO[bytes], fmt: str) -> Iterator[tuple[fr.Batch, list[tuple[int, str]], int]]:
    """(batch, problems as (line, text), lines read) per CHUNK_FRAMES frames. A record the reader
    cannot parse, or whose ID does not fit, is one malformed problem at its line and reading goes
    on with the next line; a header it cannot parse raises Unreadable."""
    can = import_without_mf4("can")
    counter = _LineCounter(stream, _asc_skipped if fmt == "asc" else None)
    kwargs: dict[str, Any] = {"relative_timestamp": False} if fmt == "asc" else {}
    reader = {"asc": can.ASCReader, "trc": can.TRCReader}[fmt](counter, **kwargs)
    header = _HeaderOnce(reader, counter if fmt == "asc" else None)
    frames: list[Frame] = []
    lines: list[int] = []
    problems: list[tuple[int, str]] = []
    done, failed_at = 0, -1
    with _LibraryLog(counter):
        while True:
            try:
                for msg in reader:  # after a bad record: a new pass over the same reader, from the next line
                    frame = _frame(msg)
                    flagged = counter.take()
                    problems += flagged
                    if isinstance(frame, str):
                        problems.append((counter.line, f"malformed line: {frame}: {counter.text}"))
                    elif all(line != counter.line for line, _ in flagged):  # a warning on the record's line: it is malformed
                        frames.append(frame)
                        lines.append(counter.line)
                    if len(frames) == CHUNK_FRAMES:
                        yield fr.from_frames(frames, lines), problems, counter.line - done
                        done, frames, lines, problems = counter.line, [], [], []
                break
            except Exception as exc:  # noqa: BLE001 - the reader's parse error on one record (or the header)
                what = f"{type(exc).__name__}: {str(exc).strip()}"
                if not header.done:
                    raise Unreadable(f"not a readable {fmt.upper()} file ({what})") from None
                problems += [p for p in counter.take() if p[0] != counter.line]  # the error says more than a warning on its line
                if counter.line == failed_at:  # failed again without reading a line: nothing left to resume
                    problems.append((counter.line, f"unreadable {fmt.upper()} file ({what}); the rest of the file is not read"))
                    break
                failed_at = counter.line
                problems.append((counter.line, f"malformed line: unreadable {fmt.upper()} record ({what}): {counter.text}"))
        problems += counter.take()
    yield fr.from_frames(frames, lines), problems, counter.line - done


def _asc_skipped(line: str) -> str | None:
    """Why python-can's ASCReader skips this line as not a frame when it is one (None: it is not
    one, or the reader takes it)."""
    text = line.strip()
    found = ASC_RECORD.match(text)
    if found is None:
        return "a frame record without a time stamp" if ASC_UNTIMED.match(text) else None
    stamp = found["time"]
    if ASC_TIME.fullmatch(stamp):
        return None
    try:
        value = float(stamp)
    except ValueError:
        return f"time stamp {stamp!r} is not a number"
    if not math.isfinite(value):
        return f"time stamp {stamp} is not a finite number"
    if value < 0:
        return f"time stamp {stamp} is negative (refused)"
    return f"time stamp {stamp} is not in the ASC form SECONDS.FRACTION"


def _library_text(record: logging.LogRecord) -> str:
    """A python-can reader's warning as a problem: the known ones said plainly, others marked as its."""
    if record.msg.startswith("DLC vs Data Length mismatch") and len(record.args or ()) == 3:
        dlc, expected, length = record.args  # type: ignore[misc]
        return f"DLC {dlc:X} means {expected} data bytes, but the data length is {length}"
    if record.msg.startswith("TRCReader: Failed to parse message"):
        return "a TRC record with too few columns (fewer data bytes than its length, or a column missing)"
    return "python-can: " + record.getMessage().split(": ", 1)[-1]


class _LibraryLog(logging.Handler):
    """For the duration of a read, python-can's warnings are collected with the line being read
    (see the module doc) instead of reaching the user raw, without file and line."""

    def __init__(self, counter: _LineCounter) -> None:
        super().__init__(logging.WARNING)
        self.counter, self.logger = counter, logging.getLogger("can")

    def emit(self, record: logging.LogRecord) -> None:
        self.counter.problems.append((self.counter.line, f"malformed line: {_library_text(record)}: {self.counter.text}"))

    def __enter__(self) -> _LibraryLog:
        self.saved = self.logger.level, self.logger.propagate
        self.logger.addHandler(self)
        self.logger.setLevel(logging.WARNING)  # whatever the root logger's level, warnings reach this handler
        self.logger.propagate = False  # ... and only it
        return self

    def __exit__(self, *exc: object) -> None:
        self.logger.removeHandler(self)
        self.logger.setLevel(self.saved[0])
        self.logger.propagate = self.saved[1]


class _HeaderOnce:
    """Makes a python-can text reader parse its header only on its first pass, so a second pass
    (after a bad record ended the first) resumes at the next record with the header's settings.
    ASC (`counter`): the header parse ends by consuming the line after the header, `Begin
    Triggerblock` in a file that has one; a frame record there is handed out again, not lost."""

    def __init__(self, reader: Any, counter: _LineCounter | None = None) -> None:
        self.reader, self.parse, self.done, self.counter = reader, reader._extract_header, False, counter
        reader._extract_header = self

    def __call__(self) -> Any:
        if self.done:
            return None  # TRC: no first line to parse again
        first = self.parse()
        self.done = True
        if self.counter is not None and (ASC_RECORD.match(self.counter.last.strip()) or ASC_UNTIMED.match(self.counter.last.strip())):
            self.counter.unread()
        return first


def _frame(msg: Any) -> Frame | str:
    """A python-can message as a Frame; what is wrong with it when it cannot be one."""
    if msg.arbitration_id > max_id(msg.is_extended_id) or msg.arbitration_id < 0:  # python-can does not check
        return f"frame ID {msg.arbitration_id:X} does not fit {29 if msg.is_extended_id else 11} bits"
    if not math.isfinite(msg.timestamp):  # TRC: python-can reads `nan` as a time offset
        return f"time stamp {msg.timestamp} is not a finite number"
    kind = ERROR if msg.is_error_frame else REMOTE if msg.is_remote_frame else DATA
    channel = None if msg.channel is None else str(msg.channel)
    flags = (fr.FD | fr.BRS * msg.bitrate_switch | fr.ESI * msg.error_state_indicator) if msg.is_fd else 0
    data = bytes(msg.data) if kind == DATA else b""
    return Frame(msg.timestamp, channel, msg.arbitration_id, msg.is_extended_id, data, kind, flags)


class _LineCounter(io.TextIOBase):
    """A text view of a byte stream that counts the lines handed out, and collects problems with
    them (`check`: what is wrong with a line the reader will skip)."""

    def __init__(self, stream: IO[bytes], check: Any = None) -> None:
        self.stream, self.line, self.last, self.check, self.again = stream, 0, "", check, False
        self.problems: list[tuple[int, str]] = []

    def unread(self) -> None:
        """The next line handed out is the last one again (its number and problems stay as they were)."""
        self.again = True

    @property
    def text(self) -> str:
        """The last line handed out, as a problem quotes it (like a malformed candump line)."""
        return repr(self.last.strip()[:80])

    def take(self) -> list[tuple[int, str]]:
        taken, self.problems = self.problems, []
        return taken

    def __iter__(self) -> _LineCounter:
        return self

    def __next__(self) -> str:
        if self.again:
            self.again = False
            return self.last
        raw = self.stream.readline()
        if not raw:
            raise StopIteration
        self.line += 1
        self.last = raw.decode("utf-8", errors="replace")
        if self.check is not None and (problem := self.check(self.last)):
            self.problems.append((self.line, f"malformed line: {problem}: {self.text}"))
        return self.last

    def readline(self, size: int = -1) -> str:  # type: ignore[override]
        try:
            return next(self)
        except StopIteration:
            return ""
