"""Run the `canspec` CLI of this checkout as a subprocess, the way a user does."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
FIXTURES = ROOT / "tests" / "fixtures"


def canspec_env(**extra: str) -> dict[str, str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT / "generator") + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    env.update(extra)
    return env


def run_canspec(*args: str | Path, cwd: Path | str | None = None, timeout: float = 300, env: dict[str, str] | None = None) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "canspec", *map(str, args)],
        cwd=cwd or ROOT,
        env=env or canspec_env(),
        capture_output=True,
        text=True,
        timeout=timeout,
        check=False,
    )


_EXCEPTION_LINE = re.compile(r"^[A-Za-z_.]*(Error|Exception|Interrupt)(: |$)", re.MULTILINE)


def assert_no_traceback(proc: subprocess.CompletedProcess[str]) -> None:
    """No traceback and no bare `SomeError: ...` line: every failure is a sentence for a human."""
    for stream in (proc.stdout, proc.stderr):
        assert "Traceback" not in stream, stream
        assert not _EXCEPTION_LINE.search(stream), stream
