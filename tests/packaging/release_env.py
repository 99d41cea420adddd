"""Running commands as a user of the release: outside this checkout, in a virtual environment."""

from __future__ import annotations

import os
import subprocess
from dataclasses import dataclass
from pathlib import Path


def run(cmd: list[str] | str, cwd: Path | None = None, env: dict[str, str] | None = None, timeout: int = 600,
        stdin: str | None = None) -> subprocess.CompletedProcess[str]:
    """`cmd` (a string: through the shell, as a CI runs a script line)."""
    return subprocess.run(cmd, check=False, cwd=cwd, env=env, shell=isinstance(cmd, str), input=stdin, capture_output=True, text=True, timeout=timeout)


def ok(result: subprocess.CompletedProcess[str]) -> subprocess.CompletedProcess[str]:
    assert result.returncode == 0, f"{result.args}: exit {result.returncode}\n{result.stdout}\n{result.stderr}"
    return result


def user_env(bin_dir: Path | None = None) -> dict[str, str]:
    """The environment outside this checkout: no PYTHONPATH (the test session points it at
    generator/), the venv's scripts first on PATH (cargo's rustfmt stays reachable)."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    if bin_dir is not None:
        env["PATH"] = f"{bin_dir}{os.pathsep}{env['PATH']}"
    return env


@dataclass(frozen=True)
class Dist:
    sdist: Path
    wheel: Path  # built from the sdist, as `python -m build` does
    direct_wheel: Path  # built from the source tree


@dataclass(frozen=True)
class Venv:
    root: Path

    @property
    def bin(self) -> Path:
        return self.root / "bin"

    @property
    def env(self) -> dict[str, str]:
        return user_env(self.bin)

    def canspec(self, *args: str, cwd: Path, timeout: int = 600) -> subprocess.CompletedProcess[str]:
        return run([str(self.bin / "canspec"), *args], cwd=cwd, env=self.env, timeout=timeout)
