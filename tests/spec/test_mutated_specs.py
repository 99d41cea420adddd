"""Property test: any small mutation of a valid spec — a value swapped for a nasty one (huge,
negative, fractional, non-finite, wrong type, empty) — gives problems or a spec, never an
exception; and a spec that compiles also generates every target without one."""

from __future__ import annotations

import re
import tempfile
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from canspec_cli import FIXTURES

BASES = [(FIXTURES / "valid" / n).read_text(encoding="utf-8") for n in ("minimal_can.yaml", "minimal_json.yaml")]
# `key: value` inside flow mappings and block mappings alike.
VALUE = re.compile(r"(?<=[\s{,])([a-z_0-9]+): ([^,{}\[\]\n]+|\[[^\[\]\n]*\])")
NASTY = [
    "0",
    "-1",
    "1",
    "2",
    "7",
    "8",
    "9",
    "63",
    "64",
    "65",
    "255",
    "256",
    "-128",
    "0x1FFFFFFF",
    "0x20000000",
    "4294967296",
    "1180591620717411303424",
    "-1180591620717411303424",
    "0.5",
    "-0.5",
    "1.0e+400",
    "1.0e-400",
    "-0.0",
    ".nan",
    ".inf",
    "-.inf",
    "0.1",
    "0.001",
    "1000000.5",
    "''",
    "x",
    "null",
    "true",
    "false",
    "[]",
    "{}",
    "[1, 2]",
    "[2, 1]",
    "[0, 1, 2]",
    "[.nan, 1]",
    "[1.0e+400, 2]",
    "'2.0.5'",
    "1.0.0",
    "ALL",
    "ECU",
    "CTRL",
    "mode",
    "counter",
    "checksum",
    "reserved",
    "U8",
]


@st.composite
def mutated(draw: st.DrawFn) -> str:
    text = draw(st.sampled_from(BASES))
    spots = list(VALUE.finditer(text))
    for _ in range(draw(st.integers(1, 3))):
        m = draw(st.sampled_from(spots))
        text = text[: m.start(2)] + draw(st.sampled_from(NASTY)) + text[m.end(2) :]
        spots = list(VALUE.finditer(text))
    return text


@settings(max_examples=1500, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(mutated())
def test_mutated_spec_never_raises(text: str) -> None:
    from canspec.generation import generate
    from canspec.pipeline import compile_spec
    from canspec.targets import registry

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "spec.yaml"
        path.write_text(text, encoding="utf-8")
        compiled = compile_spec(path)  # must not raise
        for p in compiled.problems:
            assert p.loc is not None and p.message, p
        if compiled.spec is not None:  # accepted: every target generates (a GenerationError fails the test)
            generate(compiled.spec, list(registry()))
