"""DBC → SYM / KCD / ARXML → DBC through canmatrix and cantools, for the shipped DBC and every
valid fixture's: exactly the original comes back, minus exactly what interop.py says each
converter loses (the README's DBC section lists the same). And the renaming is what makes it so."""

from __future__ import annotations

from dataclasses import replace

from pathlib import Path

import canmatrix
import interop
import pytest
import tomllib
from dbc_support import can_fixtures, compiled, write_dbc
from repo_paths import GENERATED, ROOT

SHIPPED = GENERATED / "dbc" / "kaiwo_gateway.dbc"
SOURCES = [ROOT / "spec", *can_fixtures()]
CORE = ("name", "dlc", "cycle", "start", "length", "order", "signed", "scale", "offset", "min", "max", "unit", "choices")


def _dbc(source: Path, tmp_path: Path) -> Path:
    """The spec's DBC with `dbc_signal_names: unique`, as a team converting it to SYM, KCD or ARXML
    writes it: those formats keep one definition per signal name."""
    spec = compiled(source)
    assert spec.can is not None
    return write_dbc(replace(spec, can=replace(spec.can, dbc_signal_names="unique")), tmp_path)


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


# What each conversion keeps of the issue-24 features (the README's DBC table says the same); a
# feature a converter drops must be taken out here, and in the README, before the test passes.
FEATURES = ("byte order", "float", "fd", "length", "brs", "bus type", "data bitrate")
KEEPS = {
    ("canmatrix", "sym"): {"byte order", "float", "length"},
    ("canmatrix", "kcd"): {"byte order", "float", "length"},
    ("canmatrix", "arxml"): {"byte order", "float", "fd", "length", "bus type"},
    ("cantools", "sym"): {"byte order", "float", "length"},
    ("cantools", "kcd"): {"byte order", "float", "length"},
}
MOTOROLA_FD_FLOAT = ROOT / "tests" / "fixtures" / "valid" / "motorola_fd_float.yaml"


def _features(snap: dict) -> dict[str, object]:
    messages = [snap["messages"][k] for k in sorted(snap["messages"])]
    signals = [(m["name"].removeprefix("FRAME_"), n, s) for m in messages for n, s in sorted(m["signals"].items())]
    return {"byte order": [(m, n, s["order"]) for m, n, s in signals], "float": [(m, n, s["float"]) for m, n, s in signals],
            "fd": [m["fd"] for m in messages], "length": [m["dlc"] for m in messages], "brs": [m["brs"] for m in messages],
            "bus type": snap["bus"]["type"], "data bitrate": snap["bus"]["data_bitrate"]}


@pytest.mark.parametrize("tool,fmt", interop.PATHS, ids=lambda v: v)
def test_each_conversion_keeps_what_the_table_says_of_byte_order_float_and_fd(tool, fmt, tmp_path):
    dbc = write_dbc(compiled(MOTOROLA_FD_FLOAT), tmp_path)
    before = _features(interop.snapshot(dbc))
    # the fixture has every feature, so a lost one shows: both orders, floats, FD with and without BRS
    assert {o for *_, o in before["byte order"]} == {"big_endian", "little_endian"} and {f for *_, f in before["float"]} == {True, False}
    assert set(before["fd"]) == {True, False} and set(before["brs"]) == {None, 0, 1} and before["data bitrate"] and before["bus type"] == "CAN FD"
    after = _features(interop.snapshot(interop.round_trip(tool, fmt, dbc, tmp_path)))
    assert {f for f in FEATURES if before[f] == after[f]} == KEEPS[(tool, fmt)]


def test_without_unique_names_canmatrix_mixes_definitions_up(tmp_path):
    """The shipped DBC as generated (per-message names, the default): canmatrix's SYM shares one
    value table per name and its ARXML one signal definition per name — why `unique` exists."""
    text = SHIPPED.read_text(encoding="utf-8")
    assert "SpecSignalName\" SG_" not in text
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
