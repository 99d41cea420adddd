"""Helpers shared by subcommands: compile a spec and print its problems."""

from __future__ import annotations

import sys
from pathlib import Path

from canspec.pipeline import Compiled, compile_spec
from canspec.spec.problems import Problem
from canspec.spec_cache import compile_cached


def print_problems(problems: list[Problem], stream=None) -> None:  # type: ignore[no-untyped-def]
    stream = stream or sys.stderr
    for p in sorted(problems, key=lambda p: (p.loc is None, p.loc or "", p.message)):  # type: ignore[arg-type,operator]
        print(p.format(), file=stream)


def compile_or_report(spec: str | Path | None, strict: bool = False, quiet_warnings: bool = False, targets: list[str] | None = None,
                      cached: bool = False) -> Compiled:
    """The compiled spec, its problems printed. `cached`: through the compiled-spec cache (for
    commands that only read the spec; gen and check always compile)."""
    compiled = (compile_cached if cached else compile_spec)(spec, targets)
    shown = compiled.errors if quiet_warnings else compiled.problems
    print_problems(shown)
    if strict and compiled.warnings and compiled.spec is not None:
        compiled.spec = None
    return compiled


def add_spec_argument(parser, nargs: str | None = "?") -> None:  # type: ignore[no-untyped-def]
    parser.add_argument("spec", nargs=nargs, default=None, help="spec bundle, directory or file (default: the shipped spec)")
