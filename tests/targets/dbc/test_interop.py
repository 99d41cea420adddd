"""DBC → SYM / KCD / ARXML → DBC through canmatrix and cantools, for the shipped DBC and every
valid fixture's: exactly the original comes back, minus exactly what interop.py says each
converter loses (the README's DBC section lists the same). And the renaming is what makes it so.
Multiplexed messages, which no converter keeps, are compared apart: what each does with them."""

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


def _dbc(source: Path, tmp_path: Path, pages: bool = False) -> Path:
    """The spec's DBC with `dbc_signal_names: unique`, as a team converting it to SYM, KCD or ARXML
    writes it: those formats keep one definition per signal name. Without its multiplexed messages
    unless `pages`: no converter keeps those (test_what_each_conversion_does_with_pages)."""
    spec = compiled(source)
    assert spec.can is not None
    messages = spec.can.messages if pages else tuple(m for m in spec.can.messages if not m.is_multiplexed)
    return write_dbc(replace(spec, can=replace(spec.can, dbc_signal_names="unique", messages=messages)), tmp_path)


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


# What each conversion does with multiplexing (canmatrix 1.2, cantools 45.1; the README's DBC section
# says the same), on tests/fixtures/valid/multiplexed.yaml: a nested multiplexer (`channel`, under
# `mode` = 2), pages of several values and ranges (`pressure`: 1, 4..6; `voltage`: channel 1..3),
# fields of every frame (`status`, `counter`). Per message: signal → (multiplexer?, its
# multiplexer, the values that select it), as cantools reads the DBC that comes back.
MUX = ROOT / "tests" / "fixtures" / "valid" / "multiplexed.yaml"
PAGES_BACK = {
    # the multiplexer renamed <message>_MUX, pages numbered 0, 1, ... in order (not their values), the
    # nested multiplexer dropped and its pages put under the top one, every frame's fields copied per page
    ("canmatrix", "sym"): {"sensor_report": {
        "sensor_report_MUX": (True, None, ()), "status0": (False, "sensor_report_MUX", (0,)), "status1": (False, "sensor_report_MUX", (1,)),
        "temperature": (False, "sensor_report_MUX", (0,)), "gain": (False, "sensor_report_MUX", (0,)), "counter0": (False, "sensor_report_MUX", (0,)),
        "pressure": (False, "sensor_report_MUX", (1,)), "voltage": (False, "sensor_report_MUX", (1,)), "level": (False, "sensor_report_MUX", (1,)),
        "counter1": (False, "sensor_report_MUX", (1,))},
        "host_command": {"host_command_MUX": (True, None, ()), "argument": (False, "host_command_MUX", (0,))}},
    # the nested multiplexer replaces the top one (`mode` dropped), pages numbered 0, 1, ... in order
    ("canmatrix", "kcd"): {"sensor_report": {
        "status": (False, None, ()), "channel": (True, None, ()), "temperature": (False, "channel", (0,)), "pressure": (False, "channel", (1,)),
        "gain": (False, "channel", (0,)), "voltage": (False, "channel", (1,)), "level": (False, "channel", (1,)), "counter": (False, None, ())},
        "host_command": {"command": (True, None, ()), "argument": (False, "command", (0,))}},
    ("canmatrix", "arxml"): {},  # multiplexed messages are left out
    # single values kept; a page of several values or a range keeps its first; the nested multiplexer is no multiplexer
    ("cantools", "kcd"): {"sensor_report": {
        "mode": (True, None, ()), "status": (False, None, ()), "channel": (False, "mode", (2,)), "temperature": (False, "mode", (0,)),
        "pressure": (False, "mode", (1,)), "gain": (False, "channel", (0,)), "voltage": (False, "channel", (1,)), "level": (False, "mode", (1,)),
        "counter": (False, None, ())},
        "host_command": {"command": (True, None, ()), "argument": (False, "command", (0,))}},
}


def _pages(path: Path) -> dict[str, dict[str, tuple]]:  # type: ignore[type-arg]
    db = interop.load_cantools(path, strict=False)
    return {m.name: {s.name: (s.is_multiplexer, s.multiplexer_signal, tuple(s.multiplexer_ids or ())) for s in m.signals} for m in db.messages}


@pytest.mark.parametrize("tool,fmt", interop.PATHS, ids=lambda v: v)
def test_what_each_conversion_does_with_pages(tool, fmt, tmp_path):
    """No conversion keeps multiplexing: each does what PAGES_BACK says (cantools' SYM writer fails)."""
    dbc = _dbc(MUX, tmp_path, pages=True)
    before = _pages(dbc)
    assert before["sensor_report"]["channel"] == (True, "mode", (2,)) and before["sensor_report"]["pressure"] == (False, "mode", (1, 4, 5, 6))
    if (tool, fmt) == ("cantools", "sym"):
        with pytest.raises(TypeError, match="unhashable"):  # cantools' SYM writer on extended multiplexing
            interop.round_trip(tool, fmt, dbc, tmp_path)
        return
    after = _pages(interop.round_trip(tool, fmt, dbc, tmp_path))
    assert after == PAGES_BACK[(tool, fmt)] and after != before
