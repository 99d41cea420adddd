"""Benchmark of the generated Python package against cantools on the generated DBC, and of
`canspec decode` against `python -m cantools decode` on a generated candump log.

    python3 tests/targets/python/bench.py [--log-frames N] [--vectors PATH]

Same frames for both sides: every physical-encodable vector case (all messages). Prints
µs per frame per message and overall, with ratios (cantools time / canspec time)."""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from collections import defaultdict
from collections.abc import Callable
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(1, str(Path(__file__).resolve().parents[2]))  # tests/: dbc_names
import cantools
from dbc_names import load_with_spec_names
import pkgpath
from vector_runner import PHYSICAL_KINDS, attr_names, shipped_package

gw = shipped_package()


def pair_us(ours: Callable[..., Any], theirs: Callable[..., Any], our_items: list[tuple[Any, ...]], their_items: list[tuple[Any, ...]],
            loops: int, rounds: int = 7) -> tuple[float, float]:
    """µs per call of ours(*item) and theirs(*item): the same bare loop for both, alternated over
    several rounds so that load on a shared machine hits both sides alike; best round of each."""
    best = [float("inf"), float("inf")]
    for _ in range(rounds):
        for side, (fn, items) in enumerate(((ours, our_items), (theirs, their_items))):
            batch = items * loops
            t = time.perf_counter()
            for item in batch:
                fn(*item)
            best[side] = min(best[side], (time.perf_counter() - t) / len(batch) * 1e6)
    return best[0], best[1]


def codec_table(vectors: dict[str, Any], db: Any, loops: int) -> tuple[float, float, float, float]:
    by_msg: dict[str, list[dict[str, Any]]] = defaultdict(list)
    for case in vectors["cases"]:
        if case["kind"] in PHYSICAL_KINDS:
            by_msg[case["message"]].append(case)
    header = f"{'message':28} {'decode µs':>10} {'cantools':>9} {'ratio':>6}   {'encode µs':>10} {'cantools':>9} {'ratio':>6}"
    print(header)
    print("-" * len(header))
    totals = [0.0, 0.0, 0.0, 0.0]
    n = 0
    for name, cases in by_msg.items():
        frames = [(c["frame_id"], bytes.fromhex(c["data"])) for c in cases]
        cls = gw.BY_ID[cases[0]["frame_id"]]
        names = attr_names(cls)
        messages = [cls(**{names[s]: v for s, v in c["physical"].items()}) for c in cases]
        cmsg = db.get_message_by_frame_id(cases[0]["frame_id"])
        # cantools' strict encode refuses special values outside the DBC range: compare on what it accepts
        ok_pairs = []
        for c, m in zip(cases, messages):
            try:
                cmsg.encode(c["physical"])
            except cantools.database.EncodeError:
                pass
            else:
                ok_pairs.append((c["physical"], m))
        dec, cdec = pair_us(gw.decode, db.decode_message, frames, frames, loops)
        enc, cenc = pair_us(gw.encode, cmsg.encode, [(m,) for _, m in ok_pairs], [(p,) for p, _ in ok_pairs], loops)
        print(f"{name:28} {dec:10.2f} {cdec:9.2f} {cdec / dec:5.1f}x   {enc:10.2f} {cenc:9.2f} {cenc / enc:5.1f}x")
        for i, value in enumerate((dec, cdec, enc, cenc)):
            totals[i] += value
        n += 1
    dec, cdec, enc, cenc = (t / n for t in totals)
    print("-" * len(header))
    print(f"{'mean over messages':28} {dec:10.2f} {cdec:9.2f} {cdec / dec:5.1f}x   {enc:10.2f} {cenc:9.2f} {cenc / enc:5.1f}x")
    return dec, cdec, enc, cenc


def write_log(path: Path, vectors: dict[str, Any], frames: int) -> None:
    cases = [c for c in vectors["cases"] if c["kind"] in PHYSICAL_KINDS]
    lines = [f"{c['frame_id']:08X}#{c['data']}" for c in cases]
    with path.open("w", encoding="ascii") as out:
        for i in range(frames):
            out.write(f"({1700000000 + i * 0.0005:.6f}) can0 {lines[i % len(lines)]}\n")


def timed(cmd: list[str], log: Path, env: dict[str, str]) -> tuple[float, float]:
    """Wall time and CPU time (user + system) of a command reading the log on stdin."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    with log.open("rb") as stdin:
        proc = subprocess.run(cmd, stdin=stdin, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env, check=False)
    elapsed = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed: {proc.stderr.decode()[-500:]}")
    return elapsed, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def log_table(vectors: dict[str, Any], frames: int) -> None:
    env = dict(os.environ, PYTHONPATH=str(pkgpath.ROOT / "generator"))
    with tempfile.TemporaryDirectory() as tmp:
        log = Path(tmp) / "bench.log"
        write_log(log, vectors, frames)
        ours, ours_cpu = timed([sys.executable, "-m", "canspec", "decode", "-"], log, env)
        theirs, theirs_cpu = timed([sys.executable, "-m", "cantools", "decode", "--single-line", str(pkgpath.DBC)], log, env)
    print(f"\ncandump log of {frames:,} frames (text output to /dev/null):      wall            CPU")
    print(f"  canspec decode            {ours:8.2f} s {frames / ours:>10,.0f} frames/s   {ours_cpu:7.2f} s")
    print(f"  python -m cantools decode {theirs:8.2f} s {frames / theirs:>10,.0f} frames/s   {theirs_cpu:7.2f} s")
    print(f"  ratio (cantools / canspec): wall {theirs / ours:.1f}x, CPU {theirs_cpu / ours_cpu:.1f}x")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--vectors", type=Path, default=pkgpath.DEFAULT_VECTORS)
    ap.add_argument("--loops", type=int, default=20, help="passes over the frames per timing (best of 5)")
    ap.add_argument("--log-frames", type=int, default=1_000_000, help="frames in the generated candump log (0: skip)")
    args = ap.parse_args()
    vectors = json.loads(args.vectors.read_text(encoding="utf-8"))
    db = load_with_spec_names(pkgpath.DBC)  # the DBC-unique signal names read back as the spec's
    print(f"python {sys.version.split()[0]}, cantools {cantools.__version__}; generated {gw.PROTOCOL} {gw.VERSION}\n")
    dec, cdec, enc, cenc = codec_table(vectors, db, args.loops)
    print(f"\ndecode: {cdec / dec:.1f}x faster than cantools (target 5x); encode: {cenc / enc:.1f}x faster (target 10x)")
    if args.log_frames:
        log_table(vectors, args.log_frames)
    return 0


if __name__ == "__main__":
    sys.exit(main())
