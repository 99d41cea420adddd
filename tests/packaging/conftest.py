"""The release as a user gets it: `python -m build` once (an sdist, the wheel built from it, and a
wheel built straight from the tree), one empty virtual environment with that wheel installed.
Network: PyPI only (the build backend, canspec's dependencies; pip's cache makes reruns fast)."""

from __future__ import annotations

import sys
import venv

import pytest

from release_env import Dist, Venv, ok, run, user_env
from repo_paths import ROOT


@pytest.fixture(scope="session")
def dist(tmp_path_factory) -> Dist:
    out = tmp_path_factory.mktemp("dist")
    ok(run([sys.executable, "-m", "build", "--outdir", str(out / "release"), str(ROOT)], env=user_env()))
    ok(run([sys.executable, "-m", "build", "--wheel", "--outdir", str(out / "direct"), str(ROOT)], env=user_env()))
    sdists, wheels, direct = (sorted((out / d).glob(g)) for d, g in (("release", "*.tar.gz"), ("release", "*.whl"), ("direct", "*.whl")))
    assert len(sdists) == len(wheels) == len(direct) == 1, (sdists, wheels, direct)
    return Dist(sdists[0], wheels[0], direct[0])


def _venv(tmp_path_factory, requirement: str) -> Venv:
    root = tmp_path_factory.mktemp("venv") / "env"
    venv.EnvBuilder(with_pip=True, system_site_packages=False).create(root)
    env = Venv(root)
    ok(run([str(env.bin / "python"), "-m", "pip", "install", "--quiet", requirement], env=env.env))
    return env


@pytest.fixture(scope="session")
def release_venv(dist, tmp_path_factory) -> Venv:
    """An empty virtual environment (no system site-packages) with only the wheel and what it requires."""
    return _venv(tmp_path_factory, str(dist.wheel))


@pytest.fixture(scope="session")
def import_venv(dist, tmp_path_factory) -> Venv:
    """Another, with the wheel and its `import` extra (cantools), as `pip install 'canspec[import]'` gives."""
    return _venv(tmp_path_factory, f"{dist.wheel}[import]")
