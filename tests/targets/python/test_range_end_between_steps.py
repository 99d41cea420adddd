"""A documented maximum that is not a raw step (opendbc's tesla_can.dbc: DAS_jerkMin, 9 bits,
(0.018,-9.1) [-9.1|0.097999999999999]): raw 511 is exactly 0.098, above the maximum, so encoding
it is refused, yet its double 0.09799999999999898 lies below the maximum's double. The error must
say why (the raw value it is and the range's raw values), not only that the value is outside."""

from __future__ import annotations

from fractions import Fraction

import cantools
import pytest
from canspec_cli import run_canspec

from targets.python.vector_runner import load_package

DBC = """VERSION ""
NS_ :
BS_:
BU_: DAS
BO_ 697 DAS_control: 8 DAS
 SG_ DAS_jerkMin : 18|9@1+ (0.018,-9.1) [-9.1|0.097999999999999] "m/s^3" DAS
"""


@pytest.fixture(scope="module")
def pkg(tmp_path_factory):
    root = tmp_path_factory.mktemp("range-end")
    (root / "das.dbc").write_text(DBC, encoding="utf-8")
    for args in (("import", root / "das.dbc", "-o", root / "spec"), ("gen", root / "spec", "-o", root / "out", "-t", "python")):
        proc = run_canspec(*args)
        assert proc.returncode == 0, proc.stderr
    return load_package(next((root / "out" / "python").iterdir()))


def test_the_refusal_names_the_raw_value_and_the_ranges_raw_values(pkg) -> None:
    db = cantools.database.load_string(DBC)
    sig = db.get_message_by_name("DAS_control").get_signal_by_name("DAS_jerkMin")
    decoded = 511 * sig.scale + sig.offset  # what a decoder returns for raw 511 (cantools: the same double)
    assert decoded <= sig.maximum, "the double lies in the range: the message must say more than 'outside'"
    assert Fraction(511) * Fraction("0.018") + Fraction("-9.1") > Fraction("0.097999999999999"), "exactly, raw 511 is above it"
    with pytest.raises(pkg.RangeError) as exc:
        pkg.DasControl(das_jerkmin=decoded).encode()
    assert f"{decoded!r} is outside the allowed range" in str(exc.value)
    assert "(it is raw 511, beyond the range's raw values 0..510)" in str(exc.value), str(exc.value)
    frame = pkg.DasControl(das_jerkmin=510 * sig.scale + sig.offset).encode()
    assert db.decode_message("DAS_control", frame, scaling=False)["DAS_jerkMin"] == 510
