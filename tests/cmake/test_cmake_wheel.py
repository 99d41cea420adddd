"""The CMake package as installed from the wheel: the files are in it, `canspec --cmake-dir` of the
installed canspec points at them, and find_package() reads the installed version (a request of
another major version, or a newer one, is refused)."""

from __future__ import annotations

import os
import subprocess
import sys
import zipfile
from pathlib import Path

from repo_paths import ROOT

PROJECT = (
    "cmake_minimum_required(VERSION 3.20)\nproject(probe NONE)\n"
    'find_package(canspec {version} CONFIG REQUIRED)\nmessage(STATUS "canspec ${{canspec_VERSION}}")\n'
)


def run(cmd: list[str], cwd: Path, env: dict[str, str] | None = None) -> subprocess.CompletedProcess:  # type: ignore[type-arg]
    return subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=300, check=False)


def test_installed_cmake_package(tmp_path):
    wheel_dir, site = tmp_path / "wheel", tmp_path / "site"
    r = run([sys.executable, "-m", "pip", "wheel", str(ROOT), "--no-deps", "--no-build-isolation", "-q", "-w", str(wheel_dir)], ROOT)
    assert r.returncode == 0, r.stderr
    (wheel,) = wheel_dir.glob("canspec-*.whl")
    with zipfile.ZipFile(wheel) as z:
        names = set(z.namelist())
        assert {"canspec/cmake/canspecConfig.cmake", "canspec/cmake/canspecConfigVersion.cmake", "canspec/depfile.py"} <= names
        z.extractall(site)
    env = {**os.environ, "PYTHONPATH": str(site)}
    where = run([sys.executable, "-m", "canspec", "--cmake-dir"], tmp_path, env)
    assert where.returncode == 0 and Path(where.stdout.strip()) == site / "canspec" / "cmake", where.stdout + where.stderr
    from canspec import __version__

    for version, ok in (("", True), ("0.1", True), (__version__, True), ("1.0", False), ("99", False)):
        src = tmp_path / f"probe{version or 'any'}"
        src.mkdir()
        (src / "CMakeLists.txt").write_text(PROJECT.format(version=version), encoding="utf-8")
        r = run(["cmake", "-S", str(src), "-B", str(src / "build"), f"-Dcanspec_DIR={where.stdout.strip()}", "-DCANSPEC_COMMAND=canspec"], tmp_path)
        assert (r.returncode == 0) == ok, (version, r.stdout + r.stderr)
        if ok:
            assert f"canspec {__version__}" in r.stdout
