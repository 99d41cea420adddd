"""Shrink a failing spec: edit its recorded choice sequence (strategy.replay) the way
Hypothesis does — shorter prefixes, deleted and zeroed blocks, smaller values — and keep an
edit whenever the spec still fails the same way (same target, same normalised error).
Smaller choices mean a simpler spec, so the result is a small spec with the same failure."""

from __future__ import annotations

import hashlib
import json
import os
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from anyspec import harness, strategy

SHRINK_DIR = harness.BUILD / "shrink"


class Shrinker:
    """`fails(spec)` returns the failure (anything truthy) when `spec` still fails the same way."""

    def __init__(
        self, features: frozenset[str], fails: Callable[[strategy.GeneratedSpec], Any], budget_s: float = 900, log: Callable[[str], None] = print
    ) -> None:
        self.features, self.fails = features, fails
        self.deadline = time.monotonic() + budget_s
        self.log = log
        self.cache: dict[str, bool] = {}
        self.tries = 0
        self.best: strategy.GeneratedSpec | None = None
        self.best_failure: Any = None

    def key(self, spec: strategy.GeneratedSpec) -> tuple[int, int, list[int]]:
        return (_size(spec), len(spec.choices), spec.choices)

    def try_edit(self, choices: list[int]) -> bool:
        """True when `choices` gives a spec that still fails and is smaller than the best one."""
        spec = strategy.replay(choices, self.features)
        text = spec.text()
        if self.best is not None and self.key(spec) >= self.key(self.best):
            return False
        digest = hashlib.sha256(text.encode()).hexdigest()
        if digest in self.cache:
            return False  # tried before: failed to fail, or not smaller than what it led to
        self.tries += 1
        failure = self.fails(spec)
        self.cache[digest] = failure is not None
        if failure is None:
            return False
        self.best, self.best_failure = spec, failure
        return True

    def out_of_time(self) -> bool:
        return time.monotonic() > self.deadline

    def run(self, choices: list[int]) -> tuple[strategy.GeneratedSpec | None, Any]:
        if not self.try_edit(list(choices)):
            self.log("shrink: the spec does not fail this way on its own (flaky, or the failure needs the batch)")
            return None, None
        improved = True
        while improved and not self.out_of_time():
            improved = False
            assert self.best is not None
            # 1. shortest failing prefix (the rest of the choices become their minimum)
            cur = self.best.choices
            lo, hi = 0, len(cur)
            while lo < hi and not self.out_of_time():
                mid = (lo + hi) // 2
                if self.try_edit(cur[:mid]):
                    hi = mid
                    improved = True
                else:
                    lo = mid + 1
            # 2. delete, then zero, blocks of choices
            for k in (16, 8, 4, 2, 1):
                i = len(self.best.choices) - k
                while i >= 0 and not self.out_of_time():
                    cur = self.best.choices
                    for edit in (cur[:i] + cur[i + k:], cur[:i] + [0] * k + cur[i + k:]):
                        if edit != cur and self.try_edit(edit):
                            improved = True
                            break
                    i = min(i - k, len(self.best.choices) - k)
            # 3. smaller single values
            i = 0
            while i < len(self.best.choices) and not self.out_of_time():
                cur = self.best.choices
                for v in sorted({0, cur[i] // 2, cur[i] - 1}):
                    if v < cur[i] and self.try_edit(cur[:i] + [v] + cur[i + 1:]):
                        improved = True
                        break
                i += 1
            self.log(f"shrink: {self.tries} specs tried; now {_size(self.best)} bytes of YAML")
        return self.best, self.best_failure


def _size(spec: strategy.GeneratedSpec) -> int:
    return len(spec.text())


def _work_dir() -> Path:
    return SHRINK_DIR / f"p{os.getpid()}"


def failure_of(spec: strategy.GeneratedSpec, target: str, signature: str, stage: str | None = None) -> harness.Failure | None:
    """Run just what `target` (and its sub-stage `stage`) needs on `spec`; the failure with
    `signature`, if it happens."""
    job = harness.prepare(spec, "s9999", _work_dir())
    job.only = [target]
    job.stage_filter = stage.split(" (")[0] if stage and target in ("c", "python") else None
    job.mypy = True
    res = harness.run_spec(job)
    if target == "rust" and res.accepted:
        harness.stage_rust([res], _work_dir())
    if target == "typescript" and res.accepted:
        harness.stage_typescript([res], _work_dir())
    return next((f for f in res.failures if f.signature == signature), None)


def shrink_failure(seed: int | None, choices: list[int], features: frozenset[str], failure: harness.Failure, budget_s: float = 900,
                   log: Callable[[str], None] = print) -> tuple[strategy.GeneratedSpec | None, harness.Failure | None]:
    s = Shrinker(features, lambda spec: failure_of(spec, failure.target, failure.signature, failure.stage), budget_s, log)
    log(f"shrink: seed {seed}: {failure.signature}")
    return s.run(choices)


def save(spec: strategy.GeneratedSpec, failure: harness.Failure, name: str) -> Path:
    dest = harness.BUILD / "shrunk" / name
    dest.mkdir(parents=True, exist_ok=True)
    for old in dest.iterdir():
        if old.is_file():
            old.unlink()
    path = spec.write(dest)
    (dest / "FAILURE.txt").write_text(f"{failure.target}: {failure.stage}\n{failure.message}\n", encoding="utf-8")
    return Path(path)


def _shrink_job(args: tuple[int, list[int], list[str], dict[str, Any], float, str]) -> tuple[str, str | None, str | None]:
    seed, choices, features, fdict, budget, name = args
    failure = harness.Failure(**fdict)
    small, got = Shrinker(frozenset(features), lambda spec: failure_of(spec, failure.target, failure.signature, failure.stage), budget, log=lambda _: None).run(
        choices
    )
    if small is None or got is None:
        return name, None, None
    path = save(small, got, name)
    return name, str(path), got.signature


def shrink_batch(results_json: Path, budget_s: float = 180, jobs: int = 2, log: Callable[[str], None] = print) -> list[tuple[str, str | None, str | None]]:
    """Shrink the first spec of every distinct failure (not refusals) of a `run.py --json` file."""
    from concurrent.futures import ProcessPoolExecutor

    doc = json.loads(Path(results_json).read_text(encoding="utf-8"))
    firsts: dict[str, tuple[dict[str, Any], dict[str, Any]]] = {}
    for r in doc["results"]:
        for f in r["failures"]:
            fobj = harness.Failure(**f)
            if fobj.target != "check":
                firsts.setdefault(fobj.signature, (r, f))
    tasks = []
    for k, (r, f) in enumerate(firsts.values()):
        run_dir = Path(r["spec_dir"]).parent
        choices = json.loads((run_dir / "choices.json").read_text(encoding="utf-8"))["choices"] if (run_dir / "choices.json").is_file() else None
        if choices is None:
            choices = strategy.example(r["seed"], frozenset(doc["features"])).choices
        tasks.append((r["seed"], choices, doc["features"], f, budget_s, f"{k:02d}-seed-{r['seed']}-{f['target'].replace(':', '-')}"))
    log(f"shrink: {len(tasks)} distinct failures, {budget_s:.0f} s each, {jobs} at a time")
    out = []
    with ProcessPoolExecutor(max_workers=jobs) as pool:
        for name, path, sig in pool.map(_shrink_job, tasks):
            log(f"shrink: {name}: {path or 'did not reproduce alone'}  [{sig}]")
            out.append((name, path, sig))
    return out
