"""A command whose optional extra is not installed names the extra (`pip install 'canspec[logs]'`)
and exits non-zero, never with a traceback or an internal error — whichever of the extra's modules
is missing, wherever the command first needs it. The development environment has every extra, so
each module is hidden in turn (an import of a name set to None in sys.modules fails as if absent).
The release venv test (test_release.py) checks the same with no extra installed at all."""

from __future__ import annotations

import importlib.metadata
import re
import sys
import tomllib

import can
import pytest

from canspec.commands.extras import MODULE_EXTRA
from release_env import run
from repo_paths import ROOT

HIDE_AND_RUN = "import sys\nsys.modules[sys.argv[1]] = None\nfrom canspec.cli import main\nsys.exit(main(sys.argv[2:]))"


def _normalized(requirement: str) -> str:
    return re.split(r"[\[<>=!~; ]", requirement, maxsplit=1)[0].lower().replace("_", "-")


def test_every_module_of_an_extra_is_known_with_its_distribution():
    extras = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["optional-dependencies"]
    for extra in ("logs", "pdf"):
        assert sorted(d for d, e in MODULE_EXTRA.values() if e == extra) == sorted(map(_normalized, extras[extra]))
    installed = importlib.metadata.packages_distributions()
    for module, (dist, _) in MODULE_EXTRA.items():
        assert dist in [d.lower() for d in installed.get(module, [])], f"{module} is not the import name of {dist}"


@pytest.fixture(scope="module")
def logs(tmp_path_factory):
    """One frame as candump, Vector ASC and ASAM MF4 (python-can's writers)."""
    root = tmp_path_factory.mktemp("logs")
    (root / "drive.log").write_text("(1.000000) can0 1801B0A0#0000000000000000\n", encoding="ascii")
    for name, writer in (("drive.asc", can.ASCWriter), ("drive.mf4", can.MF4Writer)):
        with writer(str(root / name)) as w:
            w.on_message_received(can.Message(timestamp=1.0, arbitration_id=0x1801B0A0, is_extended_id=True, data=bytes(8)))
    return root


@pytest.mark.parametrize(("module", "args", "status"), [
    ("numpy", ["decode", "drive.log"], 2),
    ("pyarrow", ["decode", "drive.log", "--format", "parquet", "-o", "tables"], 2),
    ("can", ["decode", "drive.asc"], 2),
    ("asammdf", ["decode", "drive.mf4"], 2),
    ("pyarrow", ["plot", "drive.log", "steering_angle_cmd", "-o", "drive.png"], 2),
    ("matplotlib", ["plot", "drive.log", "steering_angle_cmd", "-o", "drive.png"], 2),
    ("can", ["simulate", "--node", "AUTOCAR", "--duration", "0.1"], 2),
    ("markdown", ["pdf", "-o", "handbook.pdf"], 1),
    ("weasyprint", ["pdf", "-o", "handbook.pdf"], 1),
])
def test_a_missing_module_names_its_extra(logs, module, args, status):
    out = run([sys.executable, "-c", HIDE_AND_RUN, module, *args], cwd=logs)
    extra = MODULE_EXTRA[module][1]
    assert out.returncode == status, out
    assert f"pip install 'canspec[{extra}]'" in out.stderr, out.stderr
    assert "Traceback" not in out.stderr and "internal error" not in out.stderr, out.stderr
