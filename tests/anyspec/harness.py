"""The "any valid spec" harness: draw specs, run canspec's CLI on each, then hold every output
to its own toolchain and its own vectors. Batch-shaped for speed: every spec is written
first, the per-spec work (check, gen, C, Python, cantools/canmatrix, JSON) runs in a process
pool, and the Rust crates (one cargo workspace, one target directory) and the TypeScript
declarations and readers (one tsc program) are checked together at the end.

Entry points: `run_batch(...)` (pytest, `make test-any-spec`), `run_spec(prepare(...))` (reproduce or
shrink one spec). See tests/anyspec/README.md. The per-spec stages are in `stages.py`, the batch
ones in `batch_stages.py`, what they share in `harness_base.py`; this module drives a batch and
reports it.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
if str(HERE.parent) not in sys.path:
    sys.path.insert(0, str(HERE.parent))

from anyspec import strategy
from anyspec.batch_stages import stage_rust, stage_typescript
from anyspec.harness_base import (  # noqa: F401  (the harness's interface: run.py, shrink.py and the tests use them as harness.X)
    BUILD,
    C_MODES,
    FAILURES,
    ROOT,
    Failure,
    SpecResult,
    canspec,
    missing_tools,
    signature_text,
)
from anyspec.stages import Job, run_spec

# --- refusals: the relaxations of this issue ----------------------------------------------

REFUSAL_PATTERNS = [
    ("j1939_derived", r"\[j1939-missing\]"),
    ("event_driven", r"cycle time 0 ms .*\[cycle-time\]|'cycle_ms' is required"),
    ("empty_signals", r"\[empty-message\]"),
    ("optional_signal_zh", r"(signals|add)\.\d+: 'zh' is required"),
    ("bare_value_ident", r"value_tables\.\w+\.-?\d+: expected array, got text"),
    ("optional_node_sa", r"nodes\.\d+: 'sa' is required|KeyError: 'sa'"),
]


def classify_refusal(text: str) -> tuple[list[str], list[str]]:
    """(NEW features explaining the refusal, error lines no NEW feature explains)."""
    features, unexplained = [], []
    for line in text.splitlines():
        if ": error:" not in line and "Traceback" not in line:
            continue
        hit = [f for f, rx in REFUSAL_PATTERNS if re.search(rx, line)]
        if hit:
            features += [f for f in hit if f not in features]
        else:
            unexplained.append(line)
    return features, unexplained


# --- driving a batch -----------------------------------------------------------------------


@dataclass
class Batch:
    base_seed: int
    n: int
    features: frozenset[str]
    results: list[SpecResult]
    seconds: float
    timings: dict[str, float]

    @property
    def failures(self) -> list[Failure]:
        return [f for r in self.results for f in r.failures]

    def count(self, what: str, multiplexed: bool = False) -> int:
        """Specs `what` ran on (only the multiplexed ones: `multiplexed`)."""
        return sum(1 for r in self.results if what in r.checked and (r.facts.get("multiplexed") or not multiplexed))

    def runners(self) -> str:
        """What each runner ran on: `C 100 (31 multiplexed)`."""
        names = {"c": "C", "c-cross": "C on PowerPC/Cortex-M", "python": "Python", "python-mypy": "mypy", "cantools": "cantools", "canmatrix": "canmatrix",
                 "json": "JSON", "json-mypy": "JSON mypy", "typescript": "TypeScript", "rust": "Rust"}
        return ", ".join(f"{label} {self.count(k)} ({self.count(k, multiplexed=True)} multiplexed)" for k, label in names.items())


def prepare(spec: strategy.GeneratedSpec, sid: str, run_dir: Path) -> Job:
    d = run_dir / sid
    shutil.rmtree(d, ignore_errors=True)
    spec.write(d / "spec")
    (d / "choices.json").write_text(json.dumps({"seed": spec.seed, "features": sorted(spec.features), "choices": spec.choices}), encoding="utf-8")
    return Job(sid, spec.seed, str(d / "spec"), spec.entry, str(d / "out"), sorted(spec.features), dict(spec.facts))


def run_batch(n: int, base_seed: int, features: frozenset[str] = strategy.ALL, rust: int = 12, mypy_every: int = 10, cross_every: int = 10,
              jobs: int | None = None, run_dir: Path | None = None, log: Any = print) -> Batch:
    t0 = time.monotonic()
    run_dir = run_dir or BUILD / "run"
    if run_dir.exists():
        for child in run_dir.glob("s[0-9][0-9][0-9][0-9]"):
            shutil.rmtree(child, ignore_errors=True)
    run_dir.mkdir(parents=True, exist_ok=True)
    timings = {}
    jobs_list = []
    for i in range(n):
        spec = strategy.example(base_seed + i, features)
        job = prepare(spec, f"s{i:04d}", run_dir)
        job.mypy = mypy_every > 0 and i % mypy_every == 0
        job.cross = cross_every > 0 and i % cross_every == cross_every // 2  # other specs than mypy's
        job.bytewise = i % 4 == 0
        jobs_list.append(job)
    timings["draw specs"] = time.monotonic() - t0
    log(f"anyspec: {n} specs drawn (seeds {base_seed}..{base_seed + n - 1}, features: {','.join(sorted(features)) or 'current'}) "
        f"in {timings['draw specs']:.1f} s")
    t1 = time.monotonic()
    workers = jobs or os.cpu_count() or 2
    results: list[SpecResult] = []
    with ProcessPoolExecutor(max_workers=workers) as pool:
        for k, res in enumerate(pool.map(run_spec, jobs_list, chunksize=1)):
            results.append(res)
            if (k + 1) % 25 == 0 or k + 1 == n:
                log(f"anyspec: {k + 1}/{n} specs through check/gen/C/Python/cantools/JSON ({time.monotonic() - t1:.0f} s)")
    timings["per-spec stages"] = time.monotonic() - t1
    ts_specs = [r for r in results if r.accepted and "json_bindings" in r.generated and r.facts.get("has_json")]
    timings["typescript"] = stage_typescript(ts_specs, run_dir)
    crates = [r for r in results if r.accepted and "rust" in r.generated]
    rust_specs = interleave([r for r in crates if r.facts.get("multiplexed")], [r for r in crates if not r.facts.get("multiplexed")])[: max(rust, 0)]
    timings["rust"] = stage_rust(rust_specs, run_dir)
    log(f"anyspec: Rust workspace of {len(rust_specs)} crates in {timings['rust']:.0f} s; tsc over {len(ts_specs)} specs in {timings['typescript']:.0f} s")
    for r in results:
        for f in r.failures:
            if f.target == "check":
                f.refusal, _ = classify_refusal(f.message)
    batch = Batch(base_seed, n, features, results, time.monotonic() - t0, timings)
    save_failures(batch)
    return batch


def interleave(a: list[SpecResult], b: list[SpecResult]) -> list[SpecResult]:
    """a[0], b[0], a[1], b[1], …, then the rest of the longer one: the Rust workspace takes
    multiplexed and plain specs alike."""
    out = [x for pair in zip(a, b) for x in pair]
    return out + a[len(b):] + b[len(a):]


def repro_command(f: Failure | SpecResult, features: frozenset[str] | list[str] | None = None) -> str:
    seed = f.seed
    feats = "" if features is None or frozenset(features) == strategy.ALL else f" --features {','.join(sorted(features)) or 'current'}"
    if seed is not None:
        return f"python3 tests/anyspec/run.py --seed {seed}{feats}"
    return f"python3 tests/anyspec/run.py --spec {f.spec_dir}"


def save_failures(batch: Batch) -> None:
    for r in batch.results:
        if not r.failures:
            continue
        dest = FAILURES / f"seed-{r.seed}"
        shutil.rmtree(dest, ignore_errors=True)
        shutil.copytree(r.spec_dir, dest)
        shutil.copy(Path(r.spec_dir).parent / "choices.json", dest / "choices.json")
        lines = [
            f"seed {r.seed} ({r.sid}); features used: {', '.join(r.features) or 'none'}; features allowed: {','.join(sorted(batch.features)) or 'current'}",
            f"reproduce: {repro_command(r, batch.features)}", f"   or: python3 tests/anyspec/run.py --spec {dest / r.entry}", ""]
        for f in r.failures:
            lines += [f"== {f.target}: {f.stage}", f.message, ""]
        (dest / "FAILURE.txt").write_text("\n".join(lines), encoding="utf-8")


def report(batch: Batch, verbose_specs: int = 3) -> str:
    """The summary printed after a run: counts, then each distinct failure once (seed, repro,
    stage, error, the spec's YAML for the first few), then the other seeds."""
    out = []
    accepted = sum(r.accepted for r in batch.results)
    out.append(f"anyspec: {batch.n} specs (seeds {batch.base_seed}..{batch.base_seed + batch.n - 1}) in {batch.seconds:.0f} s; "
               f"{accepted} accepted by canspec check, {sum(bool(r.facts.get('multiplexed')) for r in batch.results)} multiplexed; "
               f"checked: {batch.runners()}")
    out.append("timings: " + ", ".join(f"{k} {v:.0f} s" for k, v in batch.timings.items()))
    groups: dict[str, list[Failure]] = {}
    for f in batch.failures:
        key = f.signature
        if f.target == "check":
            refused = classify_refusal(f.message)[1]
            key = f"check | refused: {', '.join(sorted(f.refusal or [])) or 'UNEXPLAINED'} | {signature_text(refused[0]) if refused else ''}"
        groups.setdefault(key, []).append(f)
    if not groups:
        out.append("anyspec: no failures")
        return "\n".join(out)
    out.append(f"anyspec: {len(batch.failures)} failure(s) in {len({f.sid for f in batch.failures})} spec(s), {len(groups)} distinct; "
               f"each spec is saved under {FAILURES.relative_to(ROOT)}/seed-<seed>/ (FAILURE.txt says how to reproduce)")
    shown = 0
    for key, fs in sorted(groups.items(), key=lambda kv: (-len(kv[1]), kv[0])):
        f = fs[0]
        out.append("")
        out.append(f"--- {key}  [{len({x.sid for x in fs})} spec(s)]")
        out.append(f"seed {f.seed}: {f.target}: {f.stage}")
        out.append(f"reproduce: {repro_command(f, batch.features)}")
        out.append("error: " + "\n       ".join(f.message.strip().splitlines()[:14]))
        if shown < verbose_specs:
            shown += 1
            r = next(r for r in batch.results if r.sid == f.sid)
            out.append("spec:")
            for p in sorted(Path(r.spec_dir).iterdir()):
                out.append(f"# file: {p.name}")
                out.append(p.read_text(encoding="utf-8").rstrip())
        if len(fs) > 1:
            seeds = list(dict.fromkeys(x.seed for x in fs[1:] if x.sid != f.sid))
            if seeds:
                out.append("also seeds: " + ", ".join(map(str, seeds[:12])) + (" ..." if len(seeds) > 12 else ""))
    return "\n".join(out)


def to_json(batch: Batch) -> dict[str, Any]:
    return {"base_seed": batch.base_seed, "n": batch.n, "features": sorted(batch.features), "seconds": batch.seconds, "timings": batch.timings,
            "results": [asdict(r) for r in batch.results]}
