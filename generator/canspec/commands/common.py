"""Helpers shared by subcommands: compile a spec and print its problems; numeric arguments checked
where argparse reads them."""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Callable
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
    """The compiled spec, its problems printed. `cached`: through the compiled-spec cache (every
    command but `check`, which always compiles)."""
    compiled = (compile_cached if cached else compile_spec)(spec, targets)
    shown = compiled.errors if quiet_warnings else compiled.problems
    print_problems(shown)
    if strict and compiled.warnings and compiled.spec is not None:
        compiled.spec = None
    return compiled


def add_spec_argument(parser, nargs: str | None = "?") -> None:  # type: ignore[no-untyped-def]
    parser.add_argument("spec", nargs=nargs, default=None, help="spec bundle, directory or file (default: the shipped spec)")


def number_in(kind: type, low: float, high: float, what: str = "") -> Callable[[str], float]:
    """An argparse `type`: a finite number of `kind` in low..high, else argparse's usage error (nan,
    inf, a negative duration or a bitrate of -5 would otherwise run, or fail deep inside as an
    internal error)."""

    def parse(text: str) -> float:
        shown = text if len(text) <= 40 else text[:37] + "..."
        try:
            value = kind(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{shown!r} is not {'an integer' if kind is int else 'a number'}") from None
        if kind is not int and not math.isfinite(value):  # an int is finite (and may not fit a float)
            raise argparse.ArgumentTypeError(f"{shown} is not a finite number")
        if not low <= value <= high:
            bounds = "..".join(str(int(b)) if float(b).is_integer() else f"{b:g}" for b in (low, high))
            raise argparse.ArgumentTypeError(f"{shown} is not in {bounds}{f' ({what})' if what else ''}")
        return value

    return parse


def add_encoding_argument(parser) -> None:  # type: ignore[no-untyped-def]
    """--encoding of the commands that read DBC (and SYM) text: a codec Python knows, checked
    before any file is read."""
    import codecs

    def name(text: str) -> str:
        try:
            codecs.lookup(text)
        except LookupError:
            raise argparse.ArgumentTypeError(f"unknown encoding {text!r} (e.g. utf-8, cp1252, gbk, gb18030)") from None
        return text

    parser.add_argument("--encoding", type=name, metavar="NAME",
                        help="the encoding of .dbc and .sym text (default: UTF-8; a file that is not is read as cp1252, "
                             "or as GB18030 when its text is plainly Chinese, with a warning)")
