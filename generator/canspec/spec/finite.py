"""What generated code computes with: a number a double holds."""

from __future__ import annotations

import math
from typing import Any


def finite(value: Any) -> bool:
    """A finite number that a double can hold (generated code computes in doubles): not
    infinite or NaN, not beyond the double range, and not so small it becomes 0."""
    try:
        as_double = float(value)
    except OverflowError:  # an int beyond the double range
        return False
    return math.isfinite(as_double) and (as_double != 0 or value == 0)
