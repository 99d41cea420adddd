"""DBC → SYM / KCD / ARXML → DBC through canmatrix and cantools, for the shipped DBC and every
valid fixture's: exactly the original comes back, minus exactly what interop.py says each
converter loses (the README's DBC section lists the same). And the renaming is what makes it so."""

from __future__ import annotations

import re
from pathlib import Path

import canmatrix
import interop
import pytest
import tomllib
from dbc_support import can_fixtures, compiled, write_dbc
from repo_paths import GENERATED, ROOT

SHIPPED = GENERATED / "dbc" / "kaiwo_gateway.dbc"
SOURCES = [SHIPPED, *can_fixtures()]
CORE = ("name", "dlc", "cycle", "start", "length", "order", "signed", "scale", "offset", "min", "max", "unit", "choices")


def _dbc(source: Path, tmp_path: Path) -> Path:
    return source if source.suffix == ".dbc" else write_dbc(compiled(source), tmp_path)


@pytest.mark.parametrize("tool,fmt", interop.PATHS, ids=lambda v: v)
@pytest.mark.parametrize("source", SOURCES, ids=lambda p: p.stem)
def test_round_trip_loses_only_what_the_converter_loses(source, tool, fmt, tmp_path):
    dbc = _dbc(source, tmp_path)
    rewrites = tool == "canmatrix" and fmt != "sym"
    original = interop.snapshot(dbc, exact=rewrites)
    back = interop.round_trip(tool, fmt, dbc, tmp_path)
    assert interop.differences(interop.expected(tool, fmt, original), interop.snapshot(back), as_doubles=rewrites) == []


@pytest.mark.parametrize("tool,fmt", [("canmatrix", "sym"), ("cantools", "sym"), ("cantools", "kcd")], ids=lambda v: v)
@pytest.mark.parametrize("source", SOURCES, ids=lambda p: p.stem)
def test_sym_and_kcd_keep_every_message_and_signal_exactly(source, tool, fmt, tmp_path):
    """What the loss model leaves untouched on these paths: every message and signal, bit position,
    length, sign, factor, offset, range, unit, value table and cycle time (canmatrix's SYM: units of
    up to 16 characters)."""
    original = interop.snapshot(_dbc(source, tmp_path))
    want = interop.expected(tool, fmt, original)
    for key, m in original["messages"].items():
        assert {f: want["messages"][key][f] for f in CORE if f in m} == {f: m[f] for f in CORE if f in m}
        for name, s in m["signals"].items():
            fields = [f for f in CORE if f in s and not (f == "unit" and tool == "canmatrix" and len(s["unit"]) > 16)]
            assert {f: want["messages"][key]["signals"][name][f] for f in fields} == {f: s[f] for f in fields}


def test_without_unique_names_canmatrix_mixes_definitions_up(tmp_path):
    """The shipped DBC with the spec's names put back (what it was before): canmatrix's SYM shares
    one value table per name and its ARXML one signal definition per name."""
    text = SHIPPED.read_text(encoding="utf-8")
    for dbc_name, spec_name in re.findall(r'^BA_ "SpecSignalName" SG_ \d+ (\w+) "(\w+)";$', text, re.MULTILINE):
        text = re.sub(rf"\b{dbc_name}\b", spec_name, text)
    shared = tmp_path / "shared_names.dbc"
    shared.write_text(text, encoding="utf-8")
    original = interop.snapshot(shared, exact=True)
    sym = interop.differences(interop.expected("canmatrix", "sym", interop.snapshot(shared)),
                              interop.snapshot(interop.round_trip("canmatrix", "sym", shared, tmp_path)), as_doubles=False)
    assert any(".choices:" in d and "drive_mode_cmd" in d for d in sym), sym
    arxml = interop.differences(interop.expected("canmatrix", "arxml", original),
                                interop.snapshot(interop.round_trip("canmatrix", "arxml", shared, tmp_path)), as_doubles=True)
    assert any("counter.length: 4 != 8" in d for d in arxml), arxml


def test_canmatrix_is_the_pinned_version():
    """The loss model above is checked against the canmatrix the test extra pins (the README states
    what 1.2 and 1.3.3 each keep); another version is a different converter."""
    extra = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["optional-dependencies"]["test"]
    (pin,) = [d for d in extra if d.startswith("canmatrix")]
    assert pin.endswith(f"=={canmatrix.__version__}"), f"installed canmatrix {canmatrix.__version__}, pyproject's test extra: {pin} (run `make setup`)"
