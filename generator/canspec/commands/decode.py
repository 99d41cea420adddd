"""`canspec decode [--spec SPEC] LOGFILE|-`: decode a candump log with the spec.

One line per frame on stdout (text, or --format json|csv); unknown IDs, malformed lines,
wrong lengths and checksum mismatches go to stderr as `FILE:LINE: problem` and are
counted; a summary ends the run. Nothing in the log makes it crash."""

from __future__ import annotations

import argparse
import csv
import json
import os
import sys
import time
from collections import Counter
from collections.abc import Callable
from typing import IO, Any

from canspec import ir
from canspec.commands.common import compile_or_report
from canspec.reference import codec
from canspec.reference.candump import LineError, parse_line

PROGRESS_EVERY = 65536  # lines between progress-bar updates
PROBLEM_KINDS = ("malformed", "unknown_id", "wrong_length", "checksum")


class Progress:
    """A progress bar on stderr (only when stderr is a terminal and the input's size is known)."""

    def __init__(self, total: int | None, stream: IO[str]) -> None:
        self.total = total if total and stream.isatty() else None
        self.stream = stream
        self.done = 0

    def advance(self, nbytes: int, lines: int) -> None:
        self.done += nbytes
        if self.total and lines % PROGRESS_EVERY == 0:
            frac = min(1.0, self.done / self.total)
            bar = "#" * int(frac * 30)
            self.stream.write(f"\r[{bar:<30}] {frac:6.1%} {lines:,} lines")
            self.stream.flush()

    def close(self) -> None:
        if self.total:
            self.stream.write("\r" + " " * 60 + "\r")
            self.stream.flush()


class Output:
    def __init__(self, fmt: str, out: IO[str]) -> None:
        self.fmt = fmt
        self.out = out
        self.csv = csv.writer(out, lineterminator="\n") if fmt == "csv" else None
        self._formatters: dict[int, Callable[[int], str]] = {}
        if self.csv is not None:
            self.csv.writerow(["timestamp", "channel", "frame_id", "message", "signal", "raw", "value", "unit", "checksum_ok"])

    def formatter(self, msg: ir.Message) -> Callable[[int], str]:
        fmt = self._formatters.get(msg.frame_id)
        if fmt is None:
            fmt = self._formatters[msg.frame_id] = codec.text_decoder(msg)
        return fmt

    def frame(self, frame: Any, msg: ir.Message, v: int, checksum_ok: bool) -> None:
        fid = f"{frame.frame_id:08X}" if msg.is_extended else f"{frame.frame_id:03X}"
        if self.fmt == "text":
            fields = self.formatter(msg)(v)
            head = f"({frame.timestamp}) {frame.channel} " if frame.timestamp is not None else (f"{frame.channel} " if frame.channel else "")
            flag = "" if checksum_ok else "  [checksum mismatch]"
            self.out.write(f"{head}{fid} {msg.name}: {fields}{flag}\n")
            return
        values = [(s, codec.raw_value(s, v)) for s in msg.data_signals]
        if self.fmt == "json":
            record = {
                "timestamp": float(frame.timestamp) if _is_number(frame.timestamp) else frame.timestamp,
                "channel": frame.channel,
                "frame_id": fid,
                "message": msg.name,
                "signals": {s.name: _json_value(s, raw) for s, raw in values},
                "checksum_ok": checksum_ok,
            }
            self.out.write(json.dumps(record, ensure_ascii=False) + "\n")
        else:
            assert self.csv is not None
            for s, raw in values:
                self.csv.writerow([frame.timestamp or "", frame.channel or "", fid, msg.name, s.name, raw, codec.value_text(s, raw), s.unit, int(checksum_ok)])


def _json_value(sig: ir.Signal, raw: int) -> str | float | int:
    label = sig.label_of(raw)
    if label is not None:
        return label.name
    phys = codec.physical_number(sig, raw)
    return round(phys, sig.decimals) if sig.decimals else phys


def _is_number(text: str | None) -> bool:
    try:
        float(text)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        return False
    return True


class Reporter:
    def __init__(self, source: str, limit: int, stream: IO[str]) -> None:
        self.source = source
        self.limit = limit
        self.stream = stream
        self.counts: Counter[str] = Counter()

    def __call__(self, kind: str, lineno: int, text: str) -> None:
        self.counts[kind] += 1
        shown = sum(self.counts.values())
        if shown <= self.limit:
            self.stream.write(f"{self.source}:{lineno}: {'warning' if kind == 'checksum' else 'error'}: {text}\n")
        elif shown == self.limit + 1:
            self.stream.write(f"{self.source}: more problems not shown (--max-problems {self.limit}); they are counted in the summary\n")


def decode_stream(lines: IO[str], source: str, by_id: dict[tuple[int, bool], ir.Message], output: Output, report: Reporter, progress: Progress) -> Counter[str]:
    stats: Counter[str] = Counter()
    frames = decoded = lineno = 0
    for lineno, line in enumerate(lines, 1):
        progress.advance(len(line), lineno)
        try:
            frame = parse_line(line)
        except LineError as exc:
            report("malformed", lineno, f"malformed line: {exc}: {line.strip()[:80]!r}")
            continue
        if frame is None:
            continue
        frames += 1
        msg = by_id.get((frame.frame_id, frame.extended))
        if msg is None:
            report("unknown_id", lineno, f"unknown frame ID {frame.frame_id:0{8 if frame.extended else 3}X}")
            continue
        if len(frame.data) != msg.dlc:
            report("wrong_length", lineno, f"{msg.name} ({msg.id_text}): {len(frame.data)} data bytes, expected {msg.dlc} (truncated or padded frame)")
            continue
        ok = codec.checksum_ok(msg, frame.data)
        if not ok:
            assert msg.checksum is not None
            report("checksum", lineno, f"{msg.name} ({msg.id_text}): checksum mismatch (byte {msg.checksum.byte} is 0x{frame.data[msg.checksum.byte]:02X})")
        output.frame(frame, msg, codec.frame_word(frame.data), ok)
        decoded += 1
    stats.update(lines=lineno, frames=frames, decoded=decoded)
    return stats


def run(args: argparse.Namespace) -> int:
    compiled = compile_or_report(args.spec, quiet_warnings=True)
    if compiled.spec is None:
        print("canspec decode: the spec has errors (see above)", file=sys.stderr)
        return 2
    if compiled.spec.can is None:
        print("canspec decode: the spec has no CAN protocol", file=sys.stderr)
        return 2
    by_id = {(m.frame_id, m.is_extended): m for m in compiled.spec.can.messages}
    if args.logfile == "-":
        stream: IO[str] = sys.stdin
        source, size = "<stdin>", None
    else:
        try:
            stream = open(args.logfile, encoding="utf-8", errors="replace")  # noqa: SIM115
            size = os.fstat(stream.fileno()).st_size
        except OSError as exc:
            print(f"canspec decode: cannot read {args.logfile}: {exc.strerror}", file=sys.stderr)
            return 2
        source = args.logfile
    report = Reporter(source, args.max_problems, sys.stderr)
    progress = Progress(size, sys.stderr)
    started = time.perf_counter()
    try:
        stats = decode_stream(stream, source, by_id, Output(args.format, sys.stdout), report, progress)
    except OSError as exc:
        print(f"canspec decode: cannot read {source}: {exc.strerror}", file=sys.stderr)
        return 2
    finally:
        progress.close()
        if stream is not sys.stdin:
            stream.close()
    sys.stdout.flush()
    elapsed = time.perf_counter() - started
    problems = sum(report.counts[k] for k in PROBLEM_KINDS)
    counts = ", ".join(f"{report.counts[k]} {k.replace('_', ' ')}" for k in PROBLEM_KINDS)
    print(f"canspec decode: {stats['lines']:,} lines, {stats['frames']:,} frames, {stats['decoded']:,} decoded; problems: {counts}; {elapsed:.2f} s", file=sys.stderr)
    return 1 if args.strict and problems else 0


def register(sub) -> None:  # type: ignore[no-untyped-def]
    p = sub.add_parser("decode", help="decode a candump log (file or - for stdin) with the spec")
    p.add_argument("logfile", help="candump log: '(TS) CHANNEL ID#DATA' or 'ID#DATA' lines; - reads stdin")
    p.add_argument("--spec", default=None, help="spec bundle, directory or file (default: the shipped spec)")
    p.add_argument("--format", choices=("text", "json", "csv"), default="text", help="output format (default: text)")
    p.add_argument("--max-problems", type=int, default=1000, metavar="N", help="print at most N problems (all are counted; default 1000)")
    p.add_argument("--strict", action="store_true", help="exit 1 when any line had a problem")
    p.set_defaults(func=run)
