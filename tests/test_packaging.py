"""`pip install .` gives a `canspec` that carries its templates and the shipped spec, so
`canspec gen` works outside the repository with no arguments — and with a user's own spec."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys

from repo_paths import GENERATED, ROOT, SPEC


def test_wheel_install_runs_outside_the_repo(tmp_path):
    site = tmp_path / "site"
    build = subprocess.run(
        [sys.executable, "-m", "pip", "install", "--quiet", "--no-deps", "--target", str(site), str(ROOT)],
        capture_output=True, text=True, timeout=600,
    )
    assert build.returncode == 0, build.stdout + build.stderr
    assert (site / "canspec" / "_data" / "spec" / "canspec.yaml").is_file()
    assert (site / "canspec" / "_data" / "templates" / "dbc" / "protocol.dbc.j2").is_file()
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = str(site)
    work = tmp_path / "firmware"
    work.mkdir()
    run = subprocess.run([sys.executable, "-m", "canspec", "gen", "-t", "dbc", "-t", "vectors"], cwd=work, env=env, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    for rel in ("dbc/kaiwo_gateway.dbc", "vectors/can.json"):
        assert (work / "generated" / rel).read_bytes() == (GENERATED / rel).read_bytes()
    # A user's own spec: a renamed copy of the shipped one.
    own = tmp_path / "own"
    shutil.copytree(SPEC, own)
    bundle = own / "canspec.yaml"
    bundle.write_text(bundle.read_text(encoding="utf-8").replace("name: kaiwo_gateway", "name: my_gateway"), encoding="utf-8")
    run = subprocess.run([sys.executable, "-m", "canspec", "check", str(own)], cwd=work, env=env, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0 and "my_gateway 2.0.5: ok" in run.stderr, run.stderr
