"""`canspec decode LOG...`: bus logs (candump, Vector ASC/BLF, PEAK TRC, ASAM MF4) decoded with
the spec — frames as text / JSON lines / CSV, per-message Parquet tables, or a health report.

Every chunk of every log is decoded in bulk (logs/bulk.py); text, JSON and CSV are then
written frame by frame in log order. Unknown IDs, malformed lines, wrong lengths and checksum
mismatches go to stderr as `FILE:LINE: problem` and are counted; one summary line per input
ends the run. Exit status: 2 when an input cannot be read (or is not in its format), 1 when an
input has nothing decodable (or, with --strict, any problem), else 0. Nothing in a log makes it
crash; a closed stdout ends it quietly. `-o FILE` is replaced only by a run that exits 0 or 1
(commands/outfile.py): after exit 2 the old file is as it was."""

from __future__ import annotations

import argparse
import json
import os
import sys
from typing import IO

from canspec.commands import outfile
from canspec.commands.logrun import EXTRA_HINT, PROBLEM_KINDS, add_input_arguments, each_chunk, load_protocol, summarize

FORMATS = ("text", "json", "csv", "parquet")


def _sink(args: argparse.Namespace, decoder, out: IO[str]):  # type: ignore[no-untyped-def]
    from canspec.logs import logsinks

    if args.format == "parquet":
        return logsinks.ParquetSink(decoder, args.output)
    return {"text": logsinks.TextSink, "json": logsinks.JsonSink, "csv": logsinks.CsvSink}[args.format](decoder, out)


def _report(args: argparse.Namespace, can, decoder, out: IO[str]) -> int:  # type: ignore[no-untyped-def]
    """One health report per input (a recording each: monitor state starts afresh)."""
    from canspec.logs.fields import MessageFrames
    from canspec.logs.loghealth import HealthReport, backwards_warning, format_text

    reports: dict[str, HealthReport] = {}

    def feed(source: str, batch, decoded) -> None:  # type: ignore[no-untyped-def]
        health = reports.get(source) or reports.setdefault(source, HealthReport(can.messages))
        for name, rows in decoded.groups.items():
            msg = can.message(name)
            health.feed_message(msg, batch.timestamp[rows], MessageFrames.of(msg, batch, rows).payloads(), batch.line[rows])
        health.feed_unknown(batch.frame_id[decoded.unknown], batch.extended[decoded.unknown])

    results = each_chunk(args, decoder, "decode", False, feed)
    records = []
    for st in results:
        if st.failed is None:
            counts = {k: st.counts[k] for k in ("lines", "frames", "decoded", "remote", "error")} | {k: st.problems[k] for k in PROBLEM_KINDS}
            records.append({"source": st.source, **(reports.get(st.source) or HealthReport(can.messages)).result(counts)})
            if warning := backwards_warning(records[-1]):  # a warning, not a problem: the frames themselves are sound
                print(f"{st.source}:{warning}", file=sys.stderr)
    if args.format == "json":
        out.write(json.dumps({"inputs": records}, ensure_ascii=False, indent=1) + "\n")
    else:
        out.write("\n".join(f"{r['source']}:\n{format_text(r)}" for r in records))
    return summarize("decode", results, args.strict, quiet=True)


def run(args: argparse.Namespace) -> int:
    try:
        from canspec.logs.bulk import Decoder
    except ImportError as exc:
        print(f"canspec decode: {exc.name} is missing; {EXTRA_HINT}", file=sys.stderr)
        return 2
    can = load_protocol("decode", args.spec)
    if can is None:
        return 2
    if args.format == "parquet" and not args.output:
        print("canspec decode: --format parquet writes a directory of tables: give it with -o OUT", file=sys.stderr)
        return 2
    if args.report and args.format not in ("text", "json"):
        print("canspec decode: --report is text or json", file=sys.stderr)
        return 2
    if args.format == "parquet" and (problem := outfile.directory_problem(args.output)):
        print(f"canspec decode: cannot write {args.output}: {problem}", file=sys.stderr)
        return 2
    decoder = Decoder(can.messages, raw=args.raw)
    target = outfile.OutputFile(args.output) if args.output and args.format != "parquet" else None
    try:
        out: IO[str] = target.open() if target is not None else sys.stdout
    except OSError as exc:
        print(f"canspec decode: cannot write {args.output}: {exc.strerror}", file=sys.stderr)
        return 2
    status = 2  # an exception (an internal error, Ctrl-C) keeps the old output file
    try:
        status = _decode(args, can, decoder, out)
    finally:
        if target is not None:
            try:
                target.finish(out, keep=status < 2)  # exit 2: an input was unreadable, the output is not complete
            except OSError as exc:
                print(f"canspec decode: cannot write {args.output}: {exc.strerror or exc}", file=sys.stderr)
                status = 2
    return status


def _decode(args: argparse.Namespace, can, decoder, out: IO[str]) -> int:  # type: ignore[no-untyped-def]
    try:
        if args.report:
            return _report(args, can, decoder, out)
        sink = _sink(args, decoder, out)
        try:
            results = each_chunk(args, decoder, "decode", args.format == "parquet", sink)
        finally:
            sink.close()
        return summarize("decode", results, args.strict)
    except BrokenPipeError:  # `canspec decode big.log | head`: stop quietly
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0


def register(sub) -> None:  # type: ignore[no-untyped-def]
    p = sub.add_parser("decode", help="decode bus logs (candump, ASC, BLF, TRC, MF4) with the spec: text, JSON, CSV, Parquet tables or a health report",
                       description=__doc__.split("\n\n")[0])
    add_input_arguments(p)
    p.add_argument("--format", choices=FORMATS, default="text", help="text (default), json (one object per frame), csv (one row per signal value), "
                   "parquet (one table per message, needs -o DIR)")
    p.add_argument("-o", "--output", metavar="OUT", help="output file (a directory for parquet; default: stdout)")
    p.add_argument("--raw", action="store_true", help="parquet: add each signal's raw value as <signal>_raw (exact integers)")
    p.add_argument("--report", action="store_true", help="instead of frames, a health report per message (count, period vs spec, counter jumps/repeats, "
                   "checksum errors, gaps beyond the timeout; unknown IDs, bad lines) as text or --format json")
    p.add_argument("--strict", action="store_true", help="exit 1 when any line had a problem")
    p.set_defaults(func=run)
