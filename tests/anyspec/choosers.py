"""The sources of the strategy's integer choices (strategy.py): a seeded random stream, a recorded sequence
(the shrinker's), or Hypothesis draws."""

from __future__ import annotations

import random
from collections.abc import Sequence
from typing import Any

from hypothesis import strategies as st


class Chooser:
    """A source of integer choices; `integer(lo, hi)` shrinks towards `lo`."""

    def integer(self, lo: int, hi: int) -> int:
        raise NotImplementedError

    def boolean(self, p: float) -> bool:
        """True with probability `p`; shrinks to False."""
        return self.integer(0, 999) >= round(1000 * (1 - p))

    def choice(self, seq: Sequence[Any]) -> Any:
        """An element of `seq`; shrinks to the first."""
        return seq[self.integer(0, len(seq) - 1)]


class RandomChooser(Chooser):
    def __init__(self, seed: int) -> None:
        self.rnd = random.Random(seed)
        self.choices: list[int] = []

    def integer(self, lo: int, hi: int) -> int:
        v = self.rnd.randint(lo, hi)
        self.choices.append(v - lo)
        return v


class ReplayChooser(Chooser):
    """Replays recorded offsets (value - lo); out of range → clamped, exhausted → lo."""

    def __init__(self, choices: Sequence[int]) -> None:
        self.source = list(choices)
        self.i = 0
        self.choices: list[int] = []

    def integer(self, lo: int, hi: int) -> int:
        off = self.source[self.i] if self.i < len(self.source) else 0
        self.i += 1
        v = lo + max(0, min(off, hi - lo))
        self.choices.append(v - lo)
        return v


class DrawChooser(Chooser):
    def __init__(self, draw: Any) -> None:
        self.draw, self.st = draw, st
        self.choices: list[int] = []

    def integer(self, lo: int, hi: int) -> int:
        v = self.draw(self.st.integers(lo, hi))
        self.choices.append(v - lo)
        return v
