"""`make bench-decode`: canspec decode on N frames (every message of the shipped spec) in every
log format, against its peers, in one run. Prints wall and CPU time (user + system of the
process; CPU is the fair measure on a shared machine) and peak memory (max RSS) per run:

  text     canspec decode LOG > /dev/null           vs  python -m cantools decode --single-line  (target ≥5×)
  parquet  canspec decode --format parquet -o DIR   vs  bench/reference_parquet.py (cantools
                                                        decode_message per frame → pandas → Parquet,
                                                        + the checksum check per frame)  (target ≥20×)
  mf4      canspec decode --format parquet bus.mf4  vs  asammdf MDF.extract_bus_logging with the generated DBC
                                                        + saving, + the checksum check a user adds (vectorised)
  every format: canspec decode --format parquet (candump, .gz, screen forms, ASC, BLF, TRC, MF4)
  memory   --memory-frames M: peak memory of the Parquet run on an M-frame candump log (streaming: bounded)

    python3 bench/bench_decode.py [--frames N] [--memory-frames M] [--cache DIR] [--only text,parquet,mf4,formats]

canspec's tables flag each checksum frame (`checksum_ok`); neither Parquet peer checks checksums, so
each one's script does that work too, as its user would write it (said in the output). canspec runs
with its compiled-spec cache warm (a folder of the run's own), as in a user's every run after the
first; the MF4 comparison shows a first run too. The logs are written once per N into --cache
(python-can's writers take a while)."""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path[:0] = [str(ROOT / "tests" / "logs"), str(ROOT / "generator")]
from canspec.pipeline import compile_spec
from logsynth import FORMATS, STEP, T0, frames_from_cases, vector_cases, write

DBC = ROOT / "generated" / "dbc" / "kaiwo_gateway.dbc"
ENV = dict(os.environ, PYTHONPATH=str(ROOT / "generator"))
CANSPEC = [sys.executable, "-m", "canspec", "decode"]
PROBE = """
import resource, subprocess, sys, time
t = time.perf_counter()
rc = subprocess.call(sys.argv[1:], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, stdin=sys.stdin)
u = resource.getrusage(resource.RUSAGE_CHILDREN)
print(time.perf_counter() - t, u.ru_utime + u.ru_stime, u.ru_maxrss / 1024, rc)
"""
ASAMMDF = """
import json, sys
import numpy as np
from asammdf import MDF
mdf = MDF(sys.argv[1])
mdf.extract_bus_logging({"CAN": [(sys.argv[2], 0)]}).save(sys.argv[3], overwrite=True)
# asammdf does not check checksums: the user's XOR check of each checksum frame, whole columns at once
ids = mdf.get("CAN_DataFrame.ID").samples & 0x1FFFFFFF
data = mdf.get("CAN_DataFrame.DataBytes").samples
bad = 0
for c in json.loads(sys.argv[4]):
    frames = data[ids == c["frame_id"]]
    bad += int(np.count_nonzero(np.bitwise_xor.reduce(frames[:, c["covers"]], axis=1) != frames[:, c["byte"]]))
print(bad, "checksum mismatches")
"""
SECTIONS = ("text", "parquet", "mf4", "formats")


def measure(cmd: list[str], stdin: Path | None = None) -> tuple[float, float, float]:
    """(wall s, CPU s, peak RSS MiB) of a command, measured by a parent process of its own."""
    probe = [sys.executable, "-c", PROBE, *cmd]
    with (stdin.open("rb") if stdin else open(os.devnull, "rb")) as inp:
        out = subprocess.run(probe, stdin=inp, capture_output=True, text=True, env=ENV, check=True).stdout.split()
    wall, cpu, rss, rc = float(out[0]), float(out[1]), float(out[2]), int(out[3])
    if rc != 0:
        raise SystemExit(f"failed ({rc}): {' '.join(cmd)}")
    return wall, cpu, rss


def logs(cache: Path, frames: int) -> dict[str, Path]:
    folder = cache / str(frames)
    done = folder / "done.json"
    if done.exists():
        return {k: Path(v) for k, v in json.loads(done.read_text()).items()}
    folder.mkdir(parents=True, exist_ok=True)
    vectors = json.loads((ROOT / "generated" / "vectors" / "can.json").read_text(encoding="utf-8"))
    data = frames_from_cases(vector_cases(vectors), frames)
    paths = {}
    for fmt, name in FORMATS.items():
        print(f"  writing {frames:,} frames as {fmt} …", file=sys.stderr, flush=True)
        with contextlib.redirect_stdout(sys.stderr):  # the MF4 writer reports progress on stdout
            paths[fmt] = str(write(fmt, folder / name, data))
    done.write_text(json.dumps(paths))
    return {k: Path(v) for k, v in paths.items()}


def big_candump(path: Path, frames: int) -> None:
    vectors = json.loads((ROOT / "generated" / "vectors" / "can.json").read_text(encoding="utf-8"))
    lines = [f" can0 {fid:08X}#{data.hex().upper()}\n" for fid, _, data in vector_cases(vectors)]
    with path.open("w", encoding="ascii", buffering=1 << 20) as out:
        for start in range(0, frames, 100000):
            out.write("".join(f"({T0 + i * STEP:.6f}){lines[i % len(lines)]}" for i in range(start, min(frames, start + 100000))))


def warm_spec_cache(log: Path, folder: Path) -> None:
    """canspec's compiled-spec cache in a folder of this run's own, filled by a decode of a few lines."""
    ENV["CANSPEC_CACHE_DIR"] = str(folder)
    head = folder.parent / "head.log"
    with log.open("rb") as src:
        head.write_bytes(b"".join(src.readline() for _ in range(100)))
    measure([*CANSPEC, str(head)])


def checksums() -> str:
    """The shipped spec's checksum layouts as JSON, for the peers' checksum check."""
    can = compile_spec(None, targets=[]).spec.can
    return json.dumps([{"frame_id": m.frame_id, "byte": m.checksum.byte, "covers": list(m.checksum.covers)} for m in can.messages if m.checksum])


def row(label: str, ours: tuple[float, float, float], theirs: tuple[float, float, float] | None = None, target: float | None = None) -> None:
    text = f"  {label:44} {ours[0]:7.2f} s {ours[1]:7.2f} s {ours[2]:8.0f} MiB"
    if theirs:
        ratio = theirs[1] / ours[1]
        text += f"   vs {theirs[0]:7.2f} s {theirs[1]:7.2f} s {theirs[2]:8.0f} MiB   CPU {ratio:5.1f}× wall {theirs[0] / ours[0]:5.1f}×"
        if target:
            text += f"  ({'meets' if ratio >= target else 'BELOW'} the {target:g}× target)"
    print(text, flush=True)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--frames", type=int, default=1_000_000)
    ap.add_argument("--memory-frames", type=int, default=0, help="also the peak memory on a candump log of this many frames (e.g. 10000000)")
    ap.add_argument("--cache", type=Path, default=ROOT / "build" / "bench-logs")
    ap.add_argument("--only", type=sections, default=SECTIONS, metavar="SECTION,...", help=f"run only these comparisons ({', '.join(SECTIONS)})")
    args = ap.parse_args()
    paths = logs(args.cache, args.frames)
    layouts = checksums()
    print(f"{args.frames:,} frames, every message of the shipped spec; columns: wall, CPU (user+sys), peak RSS\n")
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp)
        log = paths["candump"]
        warm_spec_cache(log, out / "spec-cache")
        print("canspec's compiled-spec cache is warm, as in a user's every run after the first (MF4: the first run too)")
        if "text" in args.only:
            print("\ntext output (candump -L log → /dev/null)        canspec                               peer")
            row("canspec decode  vs  python -m cantools decode", measure([*CANSPEC, str(log)]),
                measure([sys.executable, "-m", "cantools", "decode", "--single-line", str(DBC)], stdin=log), 5)
        if "parquet" in args.only:
            print("\nparquet output (one table per message; the reference script also checks each checksum frame's XOR, as canspec does)")
            row("canspec decode --format parquet  vs  reference", measure([*CANSPEC, "--format", "parquet", "-o", str(out / "a"), str(log)]),
                measure([sys.executable, str(ROOT / "bench" / "reference_parquet.py"), str(DBC), str(log), str(out / "b"), layouts]), 20)
        if "mf4" in args.only:
            print("\nASAM MF4 (same frames; added to asammdf's side: the checksum check canspec does, vectorised over its columns)")
            asammdf = measure([sys.executable, "-c", ASAMMDF, str(paths["mf4"]), str(DBC), str(out / "d.mf4"), layouts])
            row("canspec decode --format parquet  vs  asammdf", measure([*CANSPEC, "--format", "parquet", "-o", str(out / "c"), str(paths["mf4"])]), asammdf)
            shutil.rmtree(out / "spec-cache")
            row("same, first run (spec compiled and cached)", measure([*CANSPEC, "--format", "parquet", "-o", str(out / "c1"), str(paths["mf4"])]), asammdf)
        if "formats" in args.only:
            every_format(paths, out)
        if args.memory_frames:
            memory(args, out, log)
    return 0


def sections(text: str) -> tuple[str, ...]:
    chosen = tuple(s.strip() for s in text.split(",") if s.strip())
    unknown = sorted(set(chosen) - set(SECTIONS))
    if unknown or not chosen:
        raise argparse.ArgumentTypeError(f"unknown section {', '.join(unknown) or '(none)'}; choose from {', '.join(SECTIONS)}")
    return chosen


def every_format(paths: dict[str, Path], out: Path) -> None:
    print("\nevery format, canspec decode --format parquet (text output in brackets)")
    for fmt, path in paths.items():
        shutil.rmtree(out / "e", ignore_errors=True)
        parquet = measure([*CANSPEC, "--format", "parquet", "-o", str(out / "e"), str(path)])
        text = measure([*CANSPEC, str(path)])
        row(f"{fmt:16} ({text[1]:.2f} s CPU as text)", parquet)


def memory(args: argparse.Namespace, out: Path, log: Path) -> None:
    big = out / "big.log"
    big_candump(big, args.memory_frames)
    print(f"\npeak memory, streaming ({args.memory_frames:,}-frame candump log, {big.stat().st_size / 2**20:,.0f} MiB)")
    row(f"parquet, {args.memory_frames:,} frames", measure([*CANSPEC, "--format", "parquet", "-o", str(out / "f"), str(big)]))
    row(f"text, {args.memory_frames:,} frames", measure([*CANSPEC, str(big)]))
    row(f"parquet, {args.frames:,} frames (for comparison)", measure([*CANSPEC, "--format", "parquet", "-o", str(out / "g"), str(log)]))


if __name__ == "__main__":
    sys.exit(main())
