"""Output targets. Each package in this folder defines `TARGET`, a `Target`; they are found by
discovery, so adding a target is adding a package (its view model and helpers) and its template
family under templates/. A target that cannot express something a valid spec may hold says so in
its `check`, which `canspec check` runs: the user gets file:line:col and a hint, never a failed
generation."""

from __future__ import annotations

import importlib
import pkgutil
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass
from functools import lru_cache

from canspec import ir
from canspec.spec.problems import Problem, error


@dataclass(frozen=True)
class Target:
    name: str
    description: str
    directory: str  # the output subdirectory this target owns, e.g. "dbc/"
    render: Callable[[ir.Spec], dict[str, bytes]]  # relative path (under the output dir) → bytes
    order: int = 50  # generation order; lower first
    cost: int = 1  # relative render time, to schedule slow targets first
    check: Callable[[ir.Spec], Iterable[Problem]] | None = None  # what this target cannot express
    multiplexing: bool = False  # it carries multiplexed messages (or reads no CAN protocol); else it refuses them


def multiplexing_refusals(spec: ir.Spec, who: str) -> Iterator[Problem]:
    """`who` (a target, a command) does not carry multiplexing yet: each multiplexed message is refused."""
    carry = " ".join(f"--target {t.name}" for t in registry().values() if t.multiplexing)
    for msg in spec.can.messages if spec.can is not None else ():
        if msg.is_multiplexed:
            yield error(f"{who}: multiplexed message {msg.name!r} is not supported yet", msg.loc,
                        f"generate the targets that carry multiplexing: canspec gen {carry}", "mux-unsupported")


def target_problems(spec: ir.Spec, names: Iterable[str] | None = None) -> list[Problem]:
    """The refusals of a spec the spec rules accept, by the named targets (default: all)."""
    targets = registry()
    chosen = [targets[n] for n in names] if names is not None else list(targets.values())
    found = [p for target in chosen if target.check is not None for p in target.check(spec)]
    return found + [p for target in chosen if not target.multiplexing for p in multiplexing_refusals(spec, f"target {target.name}")]


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
