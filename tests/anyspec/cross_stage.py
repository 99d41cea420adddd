"""A drawn spec's C on the machines firmware runs on, under emulation: its vector runner on
big-endian PowerPC (qemu-ppc), Cortex-M0+ and Cortex-M4 (arm-none-eabi-gcc for the exact core,
qemu-arm), every case, 0 mismatches — what the x86-64 runner checks, where byte order, word size
and the float ABI differ (tests/targets/c/cross/cross.py builds and runs them). Each build takes
seconds, so the batch runs it on every `cross_every`th spec."""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

CROSS = Path(__file__).resolve().parents[1] / "targets" / "c" / "cross"
CORES = ("ppc", "cortex-m0plus", "cortex-m4")


def _cross() -> Any:
    if str(CROSS) not in sys.path:
        sys.path.insert(0, str(CROSS))
    import cross

    return cross


def missing_tools() -> list[str]:
    cross = _cross()
    return [f"{tool} (for {name}; make setup: .ci/setup.d/35-cross.sh)" for name in CORES for tool in cross.TARGETS[name].missing()]


def stage_c_cross(ctx: Any) -> None:
    """Every case of the spec's vectors on each core, with the headers' own strategy choice."""
    cross = _cross()
    vectors = ctx.out / "vectors" / "can.json"
    cases = len(json.loads(vectors.read_text(encoding="utf-8"))["cases"])
    targets = [cross.TARGETS[name] for name in CORES]
    results = cross.check_all(targets, [cross.Strategy()], ctx.work / "cross", ctx.out / "c", ctx.spec, vectors, jobs=1)
    ctx.res.checked.append("c-cross")
    for r in results:
        if not r.ok or r.cases != cases:
            ctx.fail("c", f"vector runner on {r.target} (qemu)", r.error or f"{r.cases} of {cases} cases ran")
