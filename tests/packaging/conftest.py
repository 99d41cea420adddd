"""The release as a user gets it: `python -m build` once (an sdist, the wheel built from it, and a
wheel built straight from the tree), one empty virtual environment with that wheel installed.
Network: PyPI only (the build backend, canspec's dependencies; pip's cache makes reruns fast)."""

from __future__ import annotations

import os
import subprocess
import sys
import venv
from dataclasses import dataclass
from pathlib import Path

import pytest

from repo_paths import ROOT


def run(cmd: list[str] | str, cwd: Path | None = None, env: dict[str, str] | None = None, timeout: int = 600) -> subprocess.CompletedProcess[str]:
    return subprocess.run(cmd, cwd=cwd, env=env, shell=isinstance(cmd, str), capture_output=True, text=True, timeout=timeout)


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


@pytest.fixture(scope="session")
def dist(tmp_path_factory) -> Dist:
    out = tmp_path_factory.mktemp("dist")
    ok(run([sys.executable, "-m", "build", "--outdir", str(out / "release"), str(ROOT)], env=user_env()))
    ok(run([sys.executable, "-m", "build", "--wheel", "--outdir", str(out / "direct"), str(ROOT)], env=user_env()))
    sdists, wheels, direct = (sorted((out / d).glob(g)) for d, g in (("release", "*.tar.gz"), ("release", "*.whl"), ("direct", "*.whl")))
    assert len(sdists) == len(wheels) == len(direct) == 1, (sdists, wheels, direct)
    return Dist(sdists[0], wheels[0], direct[0])


@pytest.fixture(scope="session")
def release_venv(dist, tmp_path_factory) -> Venv:
    """An empty virtual environment (no system site-packages) with only the wheel and what it requires."""
    root = tmp_path_factory.mktemp("venv") / "env"
    venv.EnvBuilder(with_pip=True, system_site_packages=False).create(root)
    env = Venv(root)
    ok(run([str(env.bin / "python"), "-m", "pip", "install", "--quiet", str(dist.wheel)], env=env.env))
    return env
