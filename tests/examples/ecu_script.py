"""The bench script for the example ECU, made from the shared sequence vectors
(generated/vectors/sequences.json): every monitor sequence of messages the ECU receives, run with
the monitor's default parameters, one power-on each (the vectors start each on a fresh monitor).
A sequence's `start` step is the power-on supervising its messages, a `frame` step a received
frame, a `check` step a diagnostic request answered after that millisecond's pass (the image
checks timeouts on every tick; a check step only asks for the result)."""

from __future__ import annotations

import itertools
import json
import sys
from dataclasses import dataclass
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(ROOT / "generator"))

from canspec import ir  # noqa: E402
from canspec.ir.nodeview import for_node  # noqa: E402
from canspec.pipeline import compile_spec  # noqa: E402

SEQUENCES = ROOT / "generated" / "vectors" / "sequences.json"
DEFAULTS = {"counter_tolerance": 1, "valid_after": 2}  # the monitor's defaults, which the ECU keeps
MAX_SPAN_MS = 100_000  # the image ticks through every millisecond of a sequence


@dataclass(frozen=True)
class Sequence:
    vector: dict  # type: ignore[type-arg]
    boot_t: int
    supervised: tuple[int, ...]


def node_spec(node: str) -> ir.Spec:
    compiled = compile_spec(ROOT / "spec")
    assert compiled.spec is not None, [p.format() for p in compiled.errors]
    return for_node(compiled.spec, node)


def received(spec: ir.Spec, node: str) -> set[str]:
    assert spec.can is not None
    return {m.name for m in spec.can.messages if m.sender != node and node in m.receivers}


def sequences(spec: ir.Spec, node: str, path: Path = SEQUENCES) -> list[Sequence]:
    """The sequences the ECU can be fed, in file order. Raises on a sequence whose shape the bench
    cannot script, rather than leaving it out."""
    assert spec.can is not None
    ids = {m.name: m.frame_id for m in spec.can.messages}
    rx = received(spec, node)
    out = []
    for vector in json.loads(path.read_text(encoding="utf-8"))["monitor"]:
        if not set(vector["messages"]) <= rx or vector["params"] != DEFAULTS:
            continue
        steps = vector["steps"]
        starts = [i for i, s in enumerate(steps) if s["action"] == "start"]
        if starts not in ([], [0]):
            raise ValueError(f"sequence {vector['id']}: a start step after the first: the bench powers on only at the start")
        for a, b in itertools.pairwise(steps):
            if a["action"] == "check" and b["action"] == "frame" and a["t"] == b["t"]:
                raise ValueError(f"sequence {vector['id']}: a check before a frame of the same millisecond: the image answers after the pass")
        boot = steps[0]["t"]
        if (steps[-1]["t"] - boot) % 2**32 > MAX_SPAN_MS:
            raise ValueError(f"sequence {vector['id']}: longer than {MAX_SPAN_MS} ms")
        supervised = tuple(ids[name] for name in steps[0]["messages"]) if starts else ()
        out.append(Sequence(vector, boot, supervised))
    return out


def script(chosen: list[Sequence]) -> str:
    lines = []
    for seq in chosen:
        lines.append(f"B {seq.boot_t} {len(seq.supervised)} " + " ".join(f"{i:X}" for i in seq.supervised))
        for step in seq.vector["steps"]:
            if step["action"] == "frame":
                data = step["data"]
                lines.append(f"F {step['t']} {step['frame_id']:X} {int(step['extended'])} {len(data) // 2} {data}")
            elif step["action"] == "check":
                lines.append(f"R {step['t']}")
    return "\n".join(lines) + "\n"
