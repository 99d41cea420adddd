"""The Python bindings of tests/fixtures/valid/multiplexed.yaml against its vectors (the vector runner's
page checks: None for another page's field, `update` keeps it, encode and pack_raw ignore it), and
mypy --strict on the package."""

from __future__ import annotations

import subprocess
import sys

from canspec.generation import generate
from canspec.pipeline import compile_spec
from repo_paths import ROOT
from targets.python.vector_runner import load_package, run

MUX = ROOT / "tests" / "fixtures" / "valid" / "multiplexed.yaml"


def test_every_vector_and_page_round_trips(tmp_path):
    out = generate(compile_spec(MUX).spec, ["python", "vectors"])
    for files in out.values():
        for rel, data in files.items():
            (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
            (tmp_path / rel).write_bytes(data)
    count, failures = run(tmp_path / "vectors" / "can.json", load_package(tmp_path / "python" / "mux_bus"))
    assert count > 400 and not failures, failures[:5]
    mypy = subprocess.run([sys.executable, "-m", "mypy", "--strict", "mux_bus"], cwd=tmp_path / "python", capture_output=True, text=True, check=False)
    assert mypy.returncode == 0, mypy.stdout
