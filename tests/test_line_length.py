"""No line of canspec's own Python over the configured 160 characters (issue 23): ruff's E501 over
the package, the tools, the benchmarks and the tests."""

from __future__ import annotations

import subprocess
import sys

from repo_paths import ROOT


def test_no_line_over_160_characters() -> None:
    proc = subprocess.run(
        [sys.executable, "-m", "ruff", "check", "--isolated", "--select", "E501", "--line-length", "160", "--output-format", "concise",
         "generator", "tools", "bench", "tests"],
        cwd=ROOT, capture_output=True, text=True, timeout=120, check=False,
    )
    assert proc.returncode == 0, f"lines over 160 characters (wrap them):\n{proc.stdout}{proc.stderr}"
