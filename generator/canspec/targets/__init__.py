"""Output targets. Each module in this package defines `TARGET`, a `Target`; they are found
by discovery, so adding a target is adding a module (and its template family)."""

from __future__ import annotations

import importlib
import pkgutil
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache

from canspec import ir


@dataclass(frozen=True)
class Target:
    name: str
    description: str
    directory: str  # the output subdirectory this target owns, e.g. "dbc/"
    render: Callable[[ir.Spec], dict[str, bytes]]  # relative path (under the output dir) → bytes
    order: int = 50  # generation order; lower first
    cost: int = 1  # relative render time, to schedule slow targets first


@lru_cache(maxsize=1)
def registry() -> dict[str, Target]:
    found: dict[str, Target] = {}
    for info in pkgutil.iter_modules(__path__):
        module = importlib.import_module(f"{__name__}.{info.name}")
        target = getattr(module, "TARGET", None)
        if isinstance(target, Target):
            found[target.name] = target
    return dict(sorted(found.items(), key=lambda kv: (kv[1].order, kv[0])))
