"""`make gen` reproduces the committed generated/ byte for byte (all targets): what a firmware
repo's CI checks with `canspec gen --check`."""

from __future__ import annotations

import subprocess
import sys

from repo_paths import CANSPEC_ENV as ENV
from repo_paths import ROOT


def test_generated_tree_is_up_to_date():
    r = subprocess.run(
        [sys.executable, "-m", "canspec", "gen", "spec", "-o", "generated", "--check"], cwd=ROOT, env=ENV, capture_output=True, text=True, timeout=600
    )
    assert r.returncode == 0, f"generated/ is stale — run `make gen` and commit:\n{r.stdout}{r.stderr}"
