"""The Python sequence runner: every sequence of a sequence-vectors file through a generated
package's receive monitor (`new_monitor`) and multi-frame text assemblers, step by step.

    python3 tests/targets/python/sequence_runner.py [SEQUENCES.json] [--package DIR]

SEQUENCES defaults to generated/vectors/sequences.json, DIR to the shipped package. Exit 0 when
every step agrees, 1 otherwise (each mismatch printed)."""

from __future__ import annotations

import argparse
import json
import sys
from collections import Counter
from pathlib import Path
from types import ModuleType
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
import pkgpath
from vector_runner import load_package, shipped_package

STATS = ("frames", "accepted", "length_errors", "checksum_errors", "counter_repeats", "counter_jumps", "lost_frames", "timeouts")


def frame_result(ev: Any) -> dict[str, Any]:
    return {
        "message": ev.message, "faults": [f.value for f in ev.faults], "accepted": ev.accepted, "state": ev.state.value if ev.state else None,
        "counter_delta": ev.counter_delta, "checksum_ok": ev.checksum_ok, "recovered": ev.recovered, "codes": dict(ev.fault_codes),
    }


def run_monitor(pkg: ModuleType, seq: dict[str, Any]) -> list[str]:
    mon = pkg.new_monitor(**seq["params"])
    errors = []
    for i, step in enumerate(seq["steps"]):
        t, action = step["t"], step["action"]
        if action == "start":
            mon.start(t, step["messages"])
            continue
        if action == "frame":
            got = frame_result(mon.feed(t, step["frame_id"], step["extended"], bytes.fromhex(step["data"])))
        else:
            timeouts = [e.message for e in mon.check(t)]
            got = {"timeouts": timeouts, "states": {m: mon.state(m).value for m in seq["messages"]}, "codes": mon.fault_codes()}
        if got != step["expect"]:
            errors.append(f"step {i} ({action} at {t}): got {got}, expected {step['expect']}")
    stats = {m: {k: getattr(mon.stats(m), k) for k in STATS} for m in seq["messages"]}
    end = {"stats": stats, "unknown_frames": mon.unknown_frames}
    if end != seq["end"]:
        errors.append(f"end: got {end}, expected {seq['end']}")
    return errors


def text_step(pkg: ModuleType, assembler: Any, cls: Any, data: bytes) -> dict[str, Any]:
    """One frame through decode and the assembler: the feed's result and the text after it."""
    try:
        message = cls.decode(data)
    except pkg.FrameLengthError:
        result = "length"
    except pkg.ChecksumError:
        result = "checksum"
    else:
        try:
            assembler.feed(message)
            result = "ok"
        except pkg.TextIndexError:
            result = "index"
        except pkg.InconsistentTextError:
            result = "inconsistent"
        except pkg.InvalidTextError:
            result = "ok"  # the frame was taken; text() tells
    try:
        text: str | bool | None = assembler.text()
    except pkg.InvalidTextError:
        text = False
    return {"result": result, "text": text}


def run_text(pkg: ModuleType, seq: dict[str, Any]) -> list[str]:
    cls = pkg.BY_ID[seq["frame_id"]]
    assembler = pkg.TEXT_ASSEMBLERS[cls.NAME]()
    errors = []
    for i, step in enumerate(seq["steps"]):
        got = text_step(pkg, assembler, cls, bytes.fromhex(step["data"]))
        if got != step["expect"]:
            errors.append(f"step {i}: got {got}, expected {step['expect']}")
    return errors


def run(path: Path, pkg: ModuleType | None = None) -> tuple[Counter[str], list[str]]:
    """(steps run per kind, mismatches)."""
    pkg = pkg or shipped_package()
    data = json.loads(path.read_text(encoding="utf-8"))
    counts: Counter[str] = Counter()
    errors = []
    for seq in data["monitor"]:
        counts["monitor sequences"] += 1
        counts["monitor steps"] += len(seq["steps"])
        errors += [f"monitor {seq['id']} ({seq['note']}): {e}" for e in run_monitor(pkg, seq)]
    for seq in data["texts"]:
        counts["text sequences"] += 1
        counts["text steps"] += len(seq["steps"])
        errors += [f"text {seq['id']} ({seq['note']}): {e}" for e in run_text(pkg, seq)]
    return counts, errors


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sequences", nargs="?", type=Path, default=pkgpath.ROOT / "generated" / "vectors" / "sequences.json")
    ap.add_argument("--package", type=Path, help="the generated package's directory (default: the shipped one)")
    args = ap.parse_args()
    counts, errors = run(args.sequences, load_package(args.package) if args.package else None)
    for e in errors:
        print(e)
    print(f"python sequences: {dict(counts)}, {len(errors)} mismatches")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
