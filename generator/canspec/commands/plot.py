"""`canspec plot LOG... SIGNAL...`: signals over time from any supported log, with matplotlib.

Signals are names or shell patterns (`accel_*`, `vehicle_state_1.*`) matched against `signal`
and `message.signal`. Time is in seconds from the first decoded frame; `--start/--stop` cut it.
Signals of one unit share an axis (`--stack`: one axis per signal); value-table signals are drawn
as steps on an axis of their own with their labels as ticks; the legend names message, signal and
unit. `-o FILE` writes PNG/SVG/PDF (by extension); without it a window opens."""

from __future__ import annotations

import argparse
import fnmatch
import os
import sys
from dataclasses import dataclass
from typing import Any

from canspec import ir
from canspec.commands import outfile
from canspec.commands.common import number_in
from canspec.commands.logrun import EXTRA_HINT, LOG_FORMATS, each_chunk, load_protocol, summarize

MAX_DPI = 600  # a print resolution; the image at it is bounded by MAX_PIXELS too
MAX_PIXELS = 50_000_000  # 200 MB of RGBA: beyond it the renderer's allocation fails (std::bad_alloc)


@dataclass
class Series:
    msg: ir.Message
    sig: ir.Signal
    time: Any  # numpy float64 seconds from the start
    value: Any  # numpy float64 physical values

    @property
    def label(self) -> str:
        return f"{self.msg.name}.{self.sig.name}" + (f" [{self.sig.unit}]" if self.sig.unit else "")


def select(can: ir.CanProtocol, patterns: list[str]) -> tuple[list[tuple[ir.Message, ir.Signal]], list[str]]:
    """The (message, signal) pairs the patterns name, in spec order; and patterns matching nothing."""
    chosen, unmatched = [], []
    for pattern in patterns:
        hits = [
            (m, s) for m in can.messages for s in m.data_signals if fnmatch.fnmatchcase(s.name, pattern) or fnmatch.fnmatchcase(f"{m.name}.{s.name}", pattern)
        ]
        if not hits:
            unmatched.append(pattern)
        chosen += [h for h in hits if h not in chosen]
    return chosen, unmatched


def collect(tables: dict[str, list[Any]], chosen: list[tuple[ir.Message, ir.Signal]], start: float | None, stop: float | None) -> list[Series]:
    """The chosen signals' values from the decoded tables, time from the first decoded frame."""
    import numpy as np
    import pyarrow as pa

    merged = {name: pa.concat_tables(parts) for name, parts in tables.items()}
    t0 = min((float(np.nanmin(t.column(0).to_numpy())) for t in merged.values() if t.num_rows), default=0.0)
    series = []
    for msg, sig in chosen:
        table = merged.get(msg.name)
        if table is None:
            continue
        time = table.column(0).to_numpy() - t0  # column 0 is the time stamp (bulk.Layout)
        value = table.column(sig.name).to_numpy()
        keep = np.ones(len(time), bool)
        if start is not None:
            keep &= time >= start
        if stop is not None:
            keep &= time <= stop
        series.append(Series(msg, sig, time[keep], value[keep]))
    return series


def panels(series: list[Series], stack: bool) -> list[list[Series]]:
    """The axes: one per signal with --stack; otherwise signals of one unit share an axis and a
    value-table signal gets its own (its labels are the axis ticks)."""
    groups: dict[object, list[Series]] = {}
    for s in series:
        key = (s.msg.name, s.sig.name) if stack or s.sig.labels else ("unit", s.sig.unit)
        groups.setdefault(key, []).append(s)
    return list(groups.values())


def figure(series: list[Series], stack: bool, title: str):  # type: ignore[no-untyped-def]
    """A matplotlib figure, one row of axes per panel, time shared."""
    import matplotlib.pyplot as plt

    rows = panels(series, stack)
    fig, axes = plt.subplots(len(rows), 1, sharex=True, squeeze=False, figsize=(10, 2.2 * len(rows) + 1.6), layout="constrained")
    for (ax,), group in zip(axes, rows):
        for s in group:
            if s.sig.labels:
                ax.step(s.time, s.value, where="post", label=s.label)
                ticks = sorted({lb.raw for lb in s.sig.labels})
                ax.set_yticks([float(s.sig.physical(r)) for r in ticks], [s.sig.label_of(r).name for r in ticks])  # type: ignore[union-attr]
            else:
                ax.plot(s.time, s.value, label=s.label, linewidth=1)
        ax.grid(True, alpha=0.3)
        ax.legend(loc="upper right", fontsize="small")
    axes[-1][0].set_xlabel("time [s] from the first frame")
    fig.suptitle(title)
    return fig


def _stop_text(stop: float | None) -> str:
    return "the end of the logs" if stop is None else f"{stop:g} s"


def _too_large(fig: Any, dpi: int) -> str | None:
    """Why the image at `dpi` is too large to render (its size grows with dpi and the panels)."""
    width, height = (round(inches * dpi) for inches in fig.get_size_inches())
    if width * height <= MAX_PIXELS:
        return None
    return f"a {width} x {height} pixel image at --dpi {dpi} is more than {MAX_PIXELS:,} pixels (hint: a lower --dpi, or fewer signals)"


def _format_problem(path: str) -> str | None:
    """Why `path` names no image format: matplotlib would append `.png` to a name without one."""
    from matplotlib.backend_bases import FigureCanvasBase

    known = FigureCanvasBase.get_supported_filetypes()
    if os.path.splitext(path)[1][1:].lower() in known:
        return None
    return f"{path}: name the image format by the file's extension ({', '.join('.' + k for k in sorted(known))})"


def _save(fig: Any, path: str, dpi: int) -> int:
    """Writes the image atomically (commands/outfile.py): a failed write leaves an old file as it was. 0, or 2."""
    target = outfile.OutputFile(path)
    try:
        out = target.open(binary=True)
    except OSError as exc:
        print(f"canspec plot: cannot write {path}: {exc.strerror or exc}", file=sys.stderr)
        return 2
    written = False
    try:
        fig.savefig(out, format=os.path.splitext(path)[1][1:].lower(), dpi=dpi)
        written = True
    except (OSError, ValueError) as exc:
        print(f"canspec plot: cannot write {path}: {exc}", file=sys.stderr)
    finally:
        target.finish(out, written)
    return 0 if written else 2


def run(args: argparse.Namespace) -> int:
    try:
        import matplotlib

        from canspec.logs.bulk import Decoder
    except ImportError as exc:
        print(f"canspec plot: {exc.name} is missing; {EXTRA_HINT}", file=sys.stderr)
        return 2
    if args.start is not None and args.stop is not None and args.start >= args.stop:
        print(f"canspec plot: --start {args.start:g} is not before --stop {args.stop:g}: nothing to plot", file=sys.stderr)
        return 2
    if args.output and (why := _format_problem(args.output)) is not None:
        print(f"canspec plot: {why}", file=sys.stderr)
        return 2
    logs = [a for a in args.items if a == "-" or os.path.exists(a)]
    patterns = args.items[len(logs):] if args.items[: len(logs)] == logs else None
    if not logs or not patterns:
        print("canspec plot: give LOG... then SIGNAL... (the logs must exist; signals are names or patterns)", file=sys.stderr)
        return 2
    can = load_protocol("plot", args.spec)
    if can is None:
        return 2
    chosen, unmatched = select(can, patterns)
    if unmatched:
        print(f"canspec plot: no signal matches {', '.join(map(repr, unmatched))} (signals are 'name' or 'message.name', with * and ?)", file=sys.stderr)
        return 2
    if args.output:
        matplotlib.use("Agg")
    tables: dict[str, list[Any]] = {}
    decoder = Decoder(can.messages)

    def keep(source: str, batch: Any, decoded: Any) -> None:
        for name, table in decoded.tables.items():
            tables.setdefault(name, []).append(table)

    args.logs, args.strict = logs, False
    status = summarize("plot", each_chunk(args, decoder, "plot", True, keep), False, quiet=True)
    series = collect(tables, chosen, args.start, args.stop)
    if not series:
        print("canspec plot: none of the chosen signals' messages is in the logs", file=sys.stderr)
        return max(status, 1)
    if not any(len(s.time) for s in series):  # --start/--stop cut every frame: an empty plot would look like a dead bus
        print(f"canspec plot: the chosen signals have no frame from {args.start or 0:g} s to {_stop_text(args.stop)}", file=sys.stderr)
        return max(status, 1)
    fig = figure(series, args.stack, ", ".join(os.path.basename(p) for p in logs))
    if args.output and (why := _too_large(fig, args.dpi)) is not None:
        print(f"canspec plot: {why}", file=sys.stderr)
        return 2
    if args.output:
        return _save(fig, args.output, args.dpi) or status
    else:
        import matplotlib.pyplot as plt

        plt.show()
    return status


def register(sub) -> None:  # type: ignore[no-untyped-def]
    p = sub.add_parser("plot", help="plot signals over time from bus logs (PNG/SVG/PDF or a window)", description=__doc__.split("\n\n")[0])
    p.add_argument("items", nargs="+", metavar="LOG... SIGNAL...", help="log files (or - for stdin), then signal names or patterns ('accel_*', 'eps_state.*')")
    p.add_argument("--input-format", choices=LOG_FORMATS, default=None, help="the logs' format (default: from the extension)")
    p.add_argument("--spec", default=None, help="spec bundle, directory or file (default: the shipped spec)")
    p.add_argument("-o", "--output", metavar="FILE", help="write the plot to FILE (.png, .svg, .pdf); default: open a window")
    p.add_argument("--stack", action="store_true", help="one subplot per signal (default: one per unit; value-table signals get their own)")
    p.add_argument("--start", type=number_in(float, 0, 1e9), default=None, metavar="S", help="from S seconds after the first frame")
    p.add_argument("--stop", type=number_in(float, 0, 1e9), default=None, metavar="S", help="up to S seconds after the first frame")
    p.add_argument("--dpi", type=number_in(int, 1, MAX_DPI), default=100, help=f"resolution of PNG output, 1..{MAX_DPI} (default 100)")
    p.add_argument("--max-problems", type=number_in(int, 0, 10**9), default=20, metavar="N", help="print at most N problems per input (default 20)")
    p.set_defaults(func=run)
