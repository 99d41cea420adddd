"""Shrink a failing spec: edit its recorded choice sequence (strategy.replay) the way
Hypothesis does — shorter prefixes, deleted and zeroed blocks, smaller values — and keep an
edit whenever the spec still fails the same way (same target, same normalised error).
Smaller choices mean a simpler spec, so the result is a small spec with the same failure."""

from __future__ import annotations

import hashlib
import time
from pathlib import Path
from typing import Callable

from anyspec import harness, strategy

SHRINK_DIR = harness.BUILD / "shrink"


class Shrinker:
    def __init__(self, features: frozenset[str], target: str, signature: str, budget_s: float = 900, log: Callable[[str], None] = print) -> None:
        self.features, self.target, self.signature = features, target, signature
        self.deadline = time.monotonic() + budget_s
        self.log = log
        self.cache: dict[str, bool] = {}
        self.tries = 0
        self.best: strategy.GeneratedSpec | None = None
        self.best_failure: harness.Failure | None = None

    def still_fails(self, choices: list[int]) -> bool:
        spec = strategy.replay(choices, self.features)
        key = hashlib.sha256(spec.text().encode()).hexdigest()
        if key in self.cache:
            return self.cache[key]
        self.tries += 1
        failure = failure_of(spec, self.target, self.signature)
        self.cache[key] = failure is not None
        if failure is not None and (self.best is None or _size(spec) <= _size(self.best)):
            self.best, self.best_failure = spec, failure
        return failure is not None

    def out_of_time(self) -> bool:
        return time.monotonic() > self.deadline

    def run(self, choices: list[int]) -> tuple[strategy.GeneratedSpec | None, harness.Failure | None]:
        cur = list(choices)
        if not self.still_fails(cur):
            self.log("shrink: the spec does not fail this way on its own (flaky, or the failure needs the batch)")
            return None, None
        cur = list(self.best.choices) if self.best else cur
        improved = True
        while improved and not self.out_of_time():
            improved = False
            # 1. shortest failing prefix (the rest of the choices become their minimum)
            lo, hi = 0, len(cur)
            while lo < hi and not self.out_of_time():
                mid = (lo + hi) // 2
                if self.still_fails(cur[:mid]):
                    hi = mid
                else:
                    lo = mid + 1
            if hi < len(cur):
                cur, improved = list(self.best.choices) if self.best else cur[:hi], True
            # 2. delete, then zero, blocks of choices
            for k in (16, 8, 4, 2, 1):
                i = len(cur) - k
                while i >= 0 and not self.out_of_time():
                    for edit in (cur[:i] + cur[i + k:], cur[:i] + [0] * k + cur[i + k:]):
                        if edit != cur and self.still_fails(edit):
                            cur, improved = list(self.best.choices) if self.best else edit, True
                            break
                    i -= k
                    i = min(i, len(cur) - k)
            # 3. smaller single values
            for i in range(len(cur)):
                if self.out_of_time():
                    break
                if i >= len(cur) or cur[i] == 0:
                    continue
                for v in (0, cur[i] // 2, cur[i] - 1):
                    edit = cur[:i] + [v] + cur[i + 1:]
                    if v < cur[i] and self.still_fails(edit):
                        cur, improved = list(self.best.choices) if self.best else edit, True
                        break
            self.log(f"shrink: {self.tries} specs tried; now {_size(self.best) if self.best else '?'} bytes of YAML")
        return self.best, self.best_failure


def _size(spec: strategy.GeneratedSpec) -> int:
    return len(spec.text())


def failure_of(spec: strategy.GeneratedSpec, target: str, signature: str) -> harness.Failure | None:
    """Run just what `target` needs on `spec`; the failure with `signature`, if it happens."""
    job = harness.prepare(spec, "s9999", SHRINK_DIR)
    job.only = [target if not target.startswith("gen:") else target]
    job.mypy = True
    res = harness.run_spec(job)
    if target == "rust" and res.accepted:
        harness.stage_rust([res], SHRINK_DIR)
    if target == "typescript" and res.accepted:
        harness.stage_typescript([res], SHRINK_DIR)
    return next((f for f in res.failures if f.signature == signature), None)


def shrink_failure(seed: int | None, choices: list[int], features: frozenset[str], failure: harness.Failure, budget_s: float = 900,
                   log: Callable[[str], None] = print) -> tuple[strategy.GeneratedSpec | None, harness.Failure | None]:
    s = Shrinker(features, failure.target, failure.signature, budget_s, log)
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
