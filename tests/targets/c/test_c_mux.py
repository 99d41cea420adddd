"""The C target's page tests (targets/c/mux.py `holds`): each condition, read back as Python, is
true for exactly the values of its ranges among those the earlier branches left, for every value
of the field's type. The generated pack/unpack themselves are checked by the vector runner on the
multiplexed fixtures (test_c_any_spec.py, cross/test_cross.py)."""

from __future__ import annotations

import dataclasses
import random
import re
from pathlib import Path

from canspec.ir.mux import holds as in_ranges
from canspec.ir.mux import ranges_of
from canspec.pipeline import compile_spec
from canspec.targets.c.model import build_model
from canspec.targets.c.mux import holds

CORNERS = Path(__file__).resolve().parent / "corners" / "c_mux_corners.yaml"


def _evaluate(test: str, value: int) -> bool:
    """A condition over `m->f` as Python: `u` suffixes dropped, && / || as and / or ("" is true)."""
    if not test:
        return True
    py = re.sub(r"(\d+)u\b", r"\1", test).replace("&&", " and ").replace("||", " or ").replace("m->f", str(value))
    return bool(eval(py))  # our own condition over integers


def _runs(draw: random.Random, top: int) -> tuple[tuple[int, int], ...]:
    cuts = sorted(draw.sample(range(top + 2), draw.choice([2, 4, 6])))
    return ranges_of([(a, b - 1) for a, b in zip(cuts[::2], cuts[1::2], strict=True)])


def test_each_branch_test_holds_exactly_its_values_among_those_left():
    compiled = compile_spec(CORNERS, ("c", "vectors"))
    assert compiled.spec is not None
    sel = next(s for cm in build_model(compiled.spec).messages for s in cm.signals if s.sig.name == "sel")  # 8 bits in a uint8_t
    field = dataclasses.replace(sel, field="f")
    draw = random.Random(24)
    for _ in range(100):
        ranges, excluded = _runs(draw, 255), _runs(draw, 255) if draw.random() < 0.6 else ()
        excluded = tuple((lo, hi) for lo, hi in excluded if not any(a <= hi and lo <= b for a, b in ranges))
        test = holds(field, ranges, "m->", excluded)
        for value in range(256):
            if not in_ranges(excluded, value):
                assert _evaluate(test, value) == in_ranges(ranges, value), (test, ranges, excluded, value)
    assert holds(field, ((0, 0),), "m->") == "m->f == 0u"
    assert holds(field, ((128, 255),), "m->", ((0, 127),)) == ""  # every value left: the last branch, no test
