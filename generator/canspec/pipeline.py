"""load → resolve → validate → build: one call that gives the IR or the problems."""

from __future__ import annotations

import gc
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

from canspec import ir
from canspec.spec.problems import Problem, SpecError, error


@dataclass
class Compiled:
    spec: ir.Spec | None
    problems: list[Problem]
    files: tuple[Path, ...] = ()  # every file the compile read or looked for (the compiled-spec cache checks them)

    @property
    def errors(self) -> list[Problem]:
        return [p for p in self.problems if p.severity == "error"]

    @property
    def warnings(self) -> list[Problem]:
        return [p for p in self.problems if p.severity == "warning"]


def _example_problems(spec: ir.Spec, res: object) -> list[Problem]:
    from canspec.reference.jsonvalue import message_problems

    out = []
    for proto, doc in zip(spec.json, res.json):  # type: ignore[attr-defined]
        for msg, raw in zip(proto.messages, doc.data["messages"]):
            examples = raw.get("examples", [])
            for i, example in enumerate(msg.examples):
                for text in message_problems(msg, example):
                    out.append(error(
                        f"example {i + 1} of {msg.name!r} is invalid: {text}", examples.loc_of(i),
                        "fix the example or the field definition (and record the erratum)", "json-example"))
    return out


@contextmanager
def paused_gc() -> Iterator[None]:
    """Loading and rendering build millions of small acyclic objects; the cyclic collector
    would rescan them over and over (40% of the time on a 100x spec, growing faster than
    the spec). Reference counting still frees everything; cycles wait until the end."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()


def compile_spec(path: Path | str | None = None, targets: Iterable[str] | None = None) -> Compiled:
    """Never raises for a bad spec: every problem comes back in `problems`. `targets`: whose
    refusals apply (default: every target's — a spec is valid when all of them can express it)."""
    with paused_gc():
        return _compile(path, targets)


def _compile(path: Path | str | None, targets: Iterable[str] | None) -> Compiled:
    # the stages are imported here: a cached compile (spec_cache) needs none of them
    from canspec.ir.build import build
    from canspec.spec.loader import load
    from canspec.spec.resolve import resolve
    from canspec.spec.validate import validate
    from canspec.targets import target_problems

    try:
        loaded = load(path)
    except SpecError as exc:
        return Compiled(None, exc.problems)
    res = resolve(loaded)
    problems = validate(res)
    if any(p.severity == "error" for p in problems):
        return Compiled(None, problems)
    spec = build(loaded, res)
    problems += _example_problems(spec, res)
    problems += target_problems(spec, targets)
    if any(p.severity == "error" for p in problems):
        return Compiled(None, problems)
    return Compiled(spec, problems, tuple(loaded.files))
