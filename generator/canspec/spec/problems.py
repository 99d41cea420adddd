"""Problems found in a spec: each has a severity, a location and a hint, never a traceback."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass


@dataclass(frozen=True, order=True)
class Loc:
    file: str
    line: int = 0
    col: int = 0

    def __str__(self) -> str:
        if self.line:
            return f"{self.file}:{self.line}:{self.col or 1}"
        return self.file


@dataclass(frozen=True)
class Problem:
    severity: str  # "error" | "warning"
    message: str
    loc: Loc | None = None
    hint: str | None = None
    rule: str = ""

    def format(self) -> str:
        where = f"{self.loc}: " if self.loc else ""
        text = f"{where}{self.severity}: {self.message}"
        if self.rule:
            text += f" [{self.rule}]"
        if self.hint:
            text += f"\n  hint: {self.hint}"
        return text


class SpecError(Exception):
    """Raised with every problem found so far; the CLI prints them and exits 1."""

    def __init__(self, problems: Iterable[Problem]):
        self.problems = list(problems)
        super().__init__("\n".join(p.format() for p in self.problems))


def error(message: str, loc: Loc | None = None, hint: str | None = None, rule: str = "") -> Problem:
    return Problem("error", message, loc, hint, rule)


def warning(message: str, loc: Loc | None = None, hint: str | None = None, rule: str = "") -> Problem:
    return Problem("warning", message, loc, hint, rule)
