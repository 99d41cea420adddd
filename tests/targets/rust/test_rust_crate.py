"""The generated Rust crate, built and tested with cargo: its vector test on the shared
vectors (and proof that it catches a wrong vector), the property tests, clippy, rustdoc and
a no_std build. One target directory (build/rust/target) is shared by all of them."""

from __future__ import annotations

import json
import os
import re
import subprocess

import pytest
from canspec.targets.rust.model import build_crate
from repo_paths import GENERATED, ROOT

CRATE = GENERATED / "rust"


def cargo(*args: str, env: dict[str, str] | None = None, check: bool = True) -> subprocess.CompletedProcess[str]:
    full_env = {**os.environ, "CARGO_TARGET_DIR": os.environ.get("CARGO_TARGET_DIR", str(ROOT / "build" / "rust" / "target")), **(env or {})}
    full_env.pop("RUSTFLAGS", None)
    proc = subprocess.run(["cargo", *args], cwd=CRATE, env=full_env, capture_output=True, text=True, check=False)
    if check and proc.returncode != 0:
        pytest.fail(f"cargo {' '.join(args)} failed ({proc.returncode}):\n{proc.stdout[-4000:]}\n{proc.stderr[-6000:]}")
    return proc


def test_cargo_test_passes_and_checks_every_vector(vectors, can):
    proc = cargo("test", "--locked", "--all-features", "--", "--nocapture")
    found = re.search(r"rust vectors: (\d+) cases \+ (\d+) multi-frame texts from .*, (\d+) mismatches; (\d+) physical encodes not", proc.stdout)
    assert found, proc.stdout[-3000:]
    assert int(found.group(1)) == len(vectors["cases"])
    assert int(found.group(2)) == len(vectors["multiframe"])
    assert int(found.group(3)) == 0
    # Only rounding ties of integer-valued signals (e.g. -14999.5 rpm) lack a whole-number input.
    integer_signals = {(m.msg.name, f.sig.name) for m in build_crate(can).messages for f in m.fields if f.kind == "scaled_int"}
    integer_ties = [c for c in vectors["cases"] if c["kind"] == "tie" and (c["message"], c["note"].split()[0]) in integer_signals
                    and not float(c["physical"][c["note"].split()[0]]).is_integer()]
    assert integer_ties
    assert int(found.group(4)) == len(integer_ties)
    assert "test result: FAILED" not in proc.stdout


def test_vector_runner_reports_a_wrong_vector(vectors, tmp_path):
    """The runner is not vacuous: one flipped bit in one frame and one wrong raw value fail it."""
    bad = json.loads(json.dumps(vectors))
    case = next(c for c in bad["cases"] if c["message"] == "eps_state" and c["kind"] == "max")
    data = bytearray.fromhex(case["data"])
    data[0] ^= 0x01
    case["data"] = data.hex().upper()
    other = next(c for c in bad["cases"] if c["message"] == "vehicle_state_2" and c["kind"] == "random")
    other["raw"]["battery_voltage"] += 1
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(bad))
    proc = cargo("test", "--locked", "--all-features", "--test", "vectors", "--", "--nocapture", env={"CANSPEC_VECTORS": str(path)}, check=False)
    assert proc.returncode != 0
    assert re.search(rf"rust vectors: {len(vectors['cases'])} cases .*, 2 mismatches", proc.stdout), proc.stdout[-3000:]


def test_no_std_build():
    cargo("check", "--locked", "--no-default-features", "--lib")


def test_clippy_is_clean():
    cargo("clippy", "--locked", "--all-targets", "--all-features", "--", "-D", "warnings")


def test_docs_build_without_warnings():
    cargo("doc", "--locked", "--no-deps", "--all-features", env={"RUSTDOCFLAGS": "-D warnings"})


def test_committed_crate_is_formatted():
    proc = subprocess.run(["cargo", "fmt", "--check"], cwd=CRATE, capture_output=True, text=True, check=False)
    assert proc.returncode == 0, proc.stdout[-3000:]
