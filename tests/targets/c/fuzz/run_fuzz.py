"""Build the libFuzzer targets (clang, ASan + UBSan) and run each for a bounded time on a copy
of the committed seed corpus. `python3 tests/targets/c/fuzz/run_fuzz.py [SECONDS] [BUILD_DIR]`.
Prints, per target: executions, coverage (cov = edges, ft = features) and corpus size."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[3]
TARGETS = ("unpack", "dispatch", "vin", "monitor")
FLAGS = ["-std=gnu99", "-g", "-O1", "-fsanitize=fuzzer,address,undefined", "-fno-sanitize-recover=all"]
DONE_RE = re.compile(r"#(\d+)\s+DONE\s+cov: (\d+) ft: (\d+) corp: (\d+)/")


def build(target: str, out: Path) -> Path:
    exe = out / f"fuzz_{target}"
    cmd = ["clang", *FLAGS, f"-I{ROOT / 'generated' / 'c'}", str(HERE / f"fuzz_{target}.c"), "-o", str(exe)]
    proc = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if proc.returncode != 0:
        raise RuntimeError(f"building fuzz_{target} failed:\n{proc.stderr[-4000:]}")
    return exe


def run(target: str, seconds: int, out: Path) -> dict:  # type: ignore[type-arg]
    exe = build(target, out)
    work = out / f"corpus_{target}"
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    proc = subprocess.run(
        [str(exe), f"-max_total_time={seconds}", "-print_final_stats=1", "-timeout=10", "-rss_limit_mb=1536",
         f"-artifact_prefix={out}/crash_{target}_", str(work), str(HERE / "corpus" / target)],
        capture_output=True, text=True, check=False,
    )
    log = proc.stderr
    m = DONE_RE.search(log)
    execs = re.search(r"stat::number_of_executed_units: (\d+)", log)
    return {
        "target": target, "returncode": proc.returncode, "log": log[-6000:],
        "executions": int(execs.group(1)) if execs else 0,
        "cov": int(m.group(2)) if m else 0, "ft": int(m.group(3)) if m else 0, "corpus": int(m.group(4)) if m else 0,
        "clean": proc.returncode == 0 and "ERROR:" not in log and "runtime error" not in log,
    }


def main(argv: list[str]) -> int:
    seconds = int(argv[1]) if len(argv) > 1 else 20
    out = Path(argv[2]) if len(argv) > 2 else ROOT / "build" / "c-fuzz"
    out.mkdir(parents=True, exist_ok=True)
    bad = 0
    for target in TARGETS:
        r = run(target, seconds, out)
        print(f"fuzz_{target}: {r['executions']} executions in {seconds} s, cov {r['cov']}, ft {r['ft']}, corpus {r['corpus']}, "
              f"{'clean' if r['clean'] else 'FAILED'}")
        if not r["clean"]:
            bad += 1
            print(r["log"], file=sys.stderr)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
