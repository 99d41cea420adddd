"""Output targets. Each package in this folder defines `TARGET`, a `Target`; they are found by
discovery, so adding a target is adding a package (its view model and helpers) and its template
family under templates/. A target that cannot express something a valid spec may hold says so in
its `check`, which `canspec check` runs: the user gets file:line:col and a hint, never a failed
generation."""

from __future__ import annotations

import importlib
import pkgutil
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from functools import lru_cache

from canspec import ir
from canspec.spec.problems import Problem


@dataclass(frozen=True)
class Target:
    name: str
    description: str
    directory: str  # the output subdirectory this target owns, e.g. "dbc/"
    render: Callable[[ir.Spec], dict[str, bytes]]  # relative path (under the output dir) → bytes
    order: int = 50  # generation order; lower first
    cost: int = 1  # relative render time, to schedule slow targets first
    check: Callable[[ir.Spec], Iterable[Problem]] | None = None  # what this target cannot express
    formatters: tuple[str, ...] = ()  # the external formatters its output goes through (render/formatters.py)


def target_problems(spec: ir.Spec, names: Iterable[str] | None = None) -> list[Problem]:
    """The refusals of a spec the spec rules accept, by the named targets (default: all)."""
    targets = registry()
    chosen = [targets[n] for n in names] if names is not None else list(targets.values())
    return [p for target in chosen if target.check is not None for p in target.check(spec)]


@lru_cache(maxsize=1)
def registry() -> dict[str, Target]:
    found: dict[str, Target] = {}
    for info in pkgutil.iter_modules(__path__):
        module = importlib.import_module(f"{__name__}.{info.name}")
        target = getattr(module, "TARGET", None)
        if isinstance(target, Target):
            found[target.name] = target
    return dict(sorted(found.items(), key=lambda kv: (kv[1].order, kv[0])))


def target_names() -> list[str]:
    """The names `canspec.generate` accepts, in generation order (what `canspec targets` lists)."""
    return list(registry())
