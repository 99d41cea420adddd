"""What `canspec decode` and `canspec plot` share: the input options, the loop over log files
chunk by chunk (bulk decode of each chunk), problems at FILE:LINE with a limit, the progress
bar and the closing summary. Needs the `logs` extra (NumPy, pyarrow, python-can, ...)."""

from __future__ import annotations

import argparse
import sys
import time
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import IO, Any

from canspec import ir
from canspec.commands.common import compile_or_report, number_in
from canspec.commands.extras import install_hint

PROBLEM_KINDS = ("malformed", "unknown_id", "wrong_length", "checksum")
LOG_FORMATS = ("candump", "asc", "blf", "trc", "mf4")
EXTRA_HINT = install_hint("logs")


def add_input_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("logs", nargs="+", metavar="LOG", help="log files (.log candump, .asc, .blf, .trc, .mf4; .gz too); - reads a text log from stdin")
    p.add_argument("--input-format", choices=LOG_FORMATS, default=None, help="the logs' format (default: from the extension; stdin: candump)")
    p.add_argument("--spec", default=None, help="spec bundle, directory or file (default: the shipped spec)")
    p.add_argument("--max-problems", type=number_in(int, 0, 10**9), default=1000,
                   metavar="N", help="print at most N problems per input (all are counted; default 1000)")


def load_protocol(command: str, spec: str | None) -> ir.CanProtocol | None:
    compiled = compile_or_report(spec, quiet_warnings=True, targets=[], cached=True)  # decoding needs no target's refusals
    if compiled.spec is None:
        print(f"canspec {command}: the spec has errors (see above)", file=sys.stderr)
        return None
    if compiled.spec.can is None:
        print(f"canspec {command}: the spec has no CAN protocol", file=sys.stderr)
        return None
    return compiled.spec.can


class Problems:
    """Problems of one input: printed as FILE:LINE up to a limit, all counted."""

    def __init__(self, source: str, limit: int, write: Callable[[str], None]) -> None:
        self.source, self.limit, self.write = source, limit, write
        self.counts: Counter[str] = Counter()

    def report(self, items: list[tuple[int, str, str]]) -> None:
        for line, kind, text in sorted(items):
            self.counts[kind] += 1
            shown = sum(self.counts.values())
            if shown <= self.limit:
                self.write(f"{self.source}:{line}: {'warning' if kind == 'checksum' else 'error'}: {text}")
            elif shown == self.limit + 1:
                self.write(f"{self.source}: more problems not shown (--max-problems {self.limit}); they are counted in the summary")


class Progress:
    """A tqdm bar on stderr for one input, only when stderr is a terminal."""

    def __init__(self, source: str, total: int | None, stream: IO[str]) -> None:
        self.bar = None
        if stream.isatty():
            from tqdm import tqdm

            self.bar = tqdm(total=total, desc=source, unit="B", unit_scale=True, file=stream, leave=False, dynamic_ncols=True)

    def update(self, position: int | None, frames: int) -> None:
        if self.bar is not None:
            if position is not None and self.bar.total:
                self.bar.update(position - self.bar.n)
            self.bar.set_postfix_str(f"{frames:,} frames", refresh=False)

    def write(self, text: str) -> None:
        if self.bar is not None:
            self.bar.write(text, file=sys.stderr)
        else:
            print(text, file=sys.stderr)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


@dataclass
class InputStats:
    source: str
    counts: Counter[str] = field(default_factory=Counter)
    problems: Counter[str] = field(default_factory=Counter)
    failed: str | None = None  # why the input could not be read


def message_problems(msg_of: Callable[[int], ir.Message], batch: Any, decoded: Any) -> list[tuple[int, str, str]]:
    """The undecodable frames of a decoded chunk as (line, kind, text)."""
    items = []
    line, fid, ext, dlc = batch.line, batch.frame_id, batch.extended, batch.dlc
    for i in decoded.unknown.tolist():
        items.append((int(line[i]), "unknown_id", f"unknown frame ID {int(fid[i]):0{8 if ext[i] else 3}X}"))
    for i in decoded.wrong_length.tolist():
        m = msg_of(int(decoded.key[i]))
        items.append((int(line[i]), "wrong_length", f"{m.name} ({m.id_text}): {int(dlc[i])} data bytes, expected {m.dlc} (truncated or padded frame)"))
    for i in decoded.bad_checksum.tolist():
        m = msg_of(int(decoded.key[i]))
        assert m.checksum is not None
        items.append((
            int(line[i]), "checksum",
            f"{m.name} ({m.id_text}): checksum mismatch (byte {m.checksum.byte} is 0x{batch.frame_bytes(i)[m.checksum.byte]:02X})"))
    return items


class _NoPandas:
    """An import finder that says pandas is not installed."""

    def find_spec(self, name: str, path: object = None, target: object = None) -> None:
        if name == "pandas" or name.startswith("pandas."):
            raise ModuleNotFoundError("hidden from pyarrow", name=name)


def pyarrow_without_pandas() -> None:
    """pyarrow imports pandas (0.6 s) the first time it builds an array, only to learn whether it
    exists; the commands never hand it pandas objects, so it is told pandas is absent (it caches
    the answer). pandas itself stays importable (asammdf needs it). Only for the CLI's process."""
    if "pandas" in sys.modules:
        return
    import pyarrow as pa

    finder = _NoPandas()
    sys.meta_path.insert(0, finder)  # type: ignore[arg-type]
    try:
        pa.array([0.0])
    finally:
        sys.meta_path.remove(finder)  # type: ignore[arg-type]


def asammdf_without_extras(args: argparse.Namespace) -> None:
    """asammdf imports sympy (its fallback for formula conversions numexpr cannot evaluate), polars
    (DataFrame export) and, through canmatrix, openpyxl (Excel matrices) when they are installed:
    0.35 s of its 0.7 s import, for nothing the MF4 reader asks of it (raw columns). With an MF4
    input, asammdf is imported with them hidden, as if absent. Only for the CLI's process: a
    library user's asammdf keeps them."""
    from canspec.logs.logread import InputError, detect_format

    def is_mf4(path: str) -> bool:
        try:
            return detect_format(path, args.input_format) == "mf4"
        except InputError:
            return False

    if "asammdf" in sys.modules or not any(map(is_mf4, args.logs)):
        return
    hidden = [name for name in ("sympy", "polars", "openpyxl") if name not in sys.modules]
    sys.modules.update(dict.fromkeys(hidden))  # type: ignore[arg-type]  # an import of None fails fast, as if absent
    try:
        import asammdf  # noqa: F401
    except ImportError:
        pass  # the MF4 reader says what is missing
    finally:
        for name in hidden:
            del sys.modules[name]


def each_chunk(args: argparse.Namespace, decoder: Any, command: str, want_tables: bool,
               consume: Callable[[str, Any, Any], None]) -> list[InputStats]:
    """Reads every input chunk by chunk, decodes each chunk in bulk, reports its problems and
    hands (source, batch, decoded) to `consume`; returns per-input statistics."""
    from canspec.logs.logread import InputError, input_size, read_log

    if want_tables:
        pyarrow_without_pandas()
    asammdf_without_extras(args)
    results = []
    for path in args.logs:
        source = "<stdin>" if path == "-" else path
        stats = InputStats(source)
        results.append(stats)
        started = time.perf_counter()
        progress = Progress(source, input_size(path), sys.stderr)
        problems = Problems(source, args.max_problems, progress.write)
        try:
            for chunk in read_log(path, args.input_format):
                batch = chunk.batch
                decoded = decoder.decode(batch, tables=want_tables)
                items = [(line, "malformed", text) for line, text in chunk.problems]
                problems.report(items + message_problems(lambda k: decoder.layouts[k].msg, batch, decoded))
                stats.counts.update(lines=chunk.lines, frames=len(batch), decoded=int(decoded.fits.sum()), remote=decoded.remote, error=decoded.error)
                consume(source, batch, decoded)
                progress.update(chunk.position, stats.counts["frames"])
        except InputError as exc:
            stats.failed = str(exc)
        finally:
            progress.close()
        stats.problems = problems.counts
        stats.counts["seconds_x1000"] = int((time.perf_counter() - started) * 1000)
    return results


def summarize(command: str, results: list[InputStats], strict: bool, quiet: bool = False) -> int:
    """One closing line per input on stderr; the exit status: 2 when an input could not be read,
    1 when an input had nothing to decode (or, with --strict, any problem), else 0."""
    status = 0
    for st in results:
        if st.failed is not None:
            print(f"canspec {command}: {st.source}: {st.failed}", file=sys.stderr)
            status = 2
            continue
        c = st.counts
        problems = ", ".join(f"{st.problems[k]} {k.replace('_', ' ')}" for k in PROBLEM_KINDS)
        if not quiet or not c["decoded"]:
            print(f"canspec {command}: {st.source}: {c['lines']:,} lines, {c['frames']:,} frames, {c['decoded']:,} decoded, {c['remote']:,} remote, "
                  f"{c['error']:,} error frames; problems: {problems}; {c['seconds_x1000'] / 1000:.2f} s", file=sys.stderr)
        if not c["decoded"]:
            print(f"canspec {command}: {st.source}: nothing decodable in this input", file=sys.stderr)
            status = max(status, 1)
        elif strict and sum(st.problems.values()):
            status = max(status, 1)
    return status
