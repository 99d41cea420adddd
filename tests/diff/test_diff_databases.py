"""Every database `canspec import` reads, `canspec diff` compares (one reading of a source, not two):
KCD and SYM written by cantools from the shipped DBC, a DBC canspec wrote with renamed signals, and
the special values canspec writes in a DBC's comments."""

from __future__ import annotations

from dataclasses import replace

import cantools
import pytest
from canspec.pipeline import compile_spec
from cantools.database.conversion import BaseConversion
from diff_helpers import ROOT, diff_paths, run_cli

DBC = ROOT / "generated" / "dbc" / "kaiwo_gateway.dbc"
SPEC = ROOT / "spec"


def _written(db, fmt: str, path):  # type: ignore[no-untyped-def]
    path.write_text(getattr(db, f"as_{fmt}_string")(), encoding="utf-8")
    return path


def _unique_dbc(tmp_path):  # type: ignore[no-untyped-def]
    """The shipped spec's DBC with `dbc_signal_names: unique` (one definition per signal name, as SYM needs)."""
    from canspec.targets import registry

    compiled = compile_spec(SPEC)
    assert compiled.spec is not None and compiled.spec.can is not None
    spec = replace(compiled.spec, can=replace(compiled.spec.can, dbc_signal_names="unique"))
    ((_, data),) = registry()["dbc"].render(spec).items()
    dbc = tmp_path / "unique.dbc"
    dbc.write_bytes(data)
    return dbc


@pytest.mark.parametrize("fmt", ["kcd", "sym"])
def test_an_edit_of_a_kcd_or_sym_file_is_the_only_change(tmp_path, fmt):
    """The shipped spec's DBC (unique names) as KCD/SYM (cantools' writers), then one factor changed
    in cantools' own model and written again: diff names that change and nothing else."""
    db = cantools.database.load_file(str(_unique_dbc(tmp_path)))
    old = _written(db, fmt, tmp_path / f"old.{fmt}")
    sig = db.get_message_by_name("vehicle_state_1").get_signal_by_name("vehicle_speed")
    sig.conversion = BaseConversion.factory(scale=0.5, offset=sig.offset, choices=sig.choices, is_float=sig.is_float)
    new = _written(db, fmt, tmp_path / f"new.{fmt}")
    assert diff_paths(old, old) == []
    changes = {(c.kind, c.cls, c.signal) for c in diff_paths(old, new)}
    assert ("signal_rescaled", "wire", "vehicle_speed") in changes
    assert {k for k, _, s in changes if s != "vehicle_speed"} == set(), changes


def test_a_spec_and_its_dbc_with_renamed_signals_compare_equal(tmp_path):
    """`dbc_signal_names: unique` writes `counter_1805B0A0`-style names with SpecSignalName: the
    import gives the spec's names back, so the only differences are the docs a DBC cannot hold."""
    dbc = _unique_dbc(tmp_path)
    text = dbc.read_text(encoding="utf-8")
    assert "SpecSignalName" in text and "counter_1805B0A0" in text  # the renaming this test is about
    assert [c for c in diff_paths(SPEC, dbc) if c.cls != "docs"] == []


def test_special_values_in_comments_are_specials_not_enum_entries(tmp_path):
    """sensor_1_distance's 0x3FF = no_obstacle is a special value (the DBC's comment says so, VAL_
    lists it): relabelling it in both places is a special renamed, not a value-table change."""
    text = DBC.read_text(encoding="utf-8")
    edited = text.replace("CM_ SG_ 2566848803 sensor_1_distance \"传感器 1 距离 | 0x3FF = no_obstacle (无障碍物)\"",
                          "CM_ SG_ 2566848803 sensor_1_distance \"传感器 1 距离 | 0x3FF = nothing_near (无障碍物)\"")
    edited = edited.replace("VAL_ 2566848803 sensor_1_distance 1023 \"no_obstacle\"", "VAL_ 2566848803 sensor_1_distance 1023 \"nothing_near\"")
    assert edited.count("nothing_near") == 2
    path = tmp_path / "edited.dbc"
    path.write_text(edited, encoding="utf-8")
    changes = {(c.kind, c.signal) for c in diff_paths(DBC, path)}
    assert changes == {("special_renamed", "sensor_1_distance")}, changes
    code, out, _ = run_cli("diff", DBC, path, "--fail-on", "wire")
    assert code == 0 and "no_obstacle" in out and "nothing_near" in out
