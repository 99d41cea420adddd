"""The CMake package as a firmware project uses it: find_package(canspec CONFIG) from the directory
`canspec --cmake-dir` prints, canspec_add_protocol() on a copy of the shipped spec, built with
Ninja and with Unix Makefiles: the headers appear, a second build does nothing, touching a spec
file regenerates (without recompiling what includes unchanged headers), and a spec error fails
the build with canspec's file:line message."""

from __future__ import annotations

import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest
from repo_paths import CANSPEC_ENV, SPEC

GENERATORS = ["Ninja", "Unix Makefiles"]
GENERATING = "--node AUTOCAR --quiet --depfile"  # the canspec command line, as --verbose prints it

CMAKELISTS = """\
cmake_minimum_required(VERSION 3.20)
project(scratch_ecu C)
find_package(canspec 0.1 CONFIG REQUIRED)
canspec_add_protocol(gateway SPEC spec/canspec.yaml NODE AUTOCAR)
add_executable(ecu main.c)
target_link_libraries(ecu PRIVATE gateway)
"""

MAIN_C = """\
#include "kaiwo_gateway.h"
int main(void) {
    kaiwo_gateway_monitor_t mon;
    kaiwo_gateway_monitor_init(&mon);
    return (int)kaiwo_gateway_monitor_state(&mon, KAIWO_GATEWAY_MSG_AUTOCAR_EPS_COMMAND);
}
"""


def run(cmd: list[str], cwd: Path) -> subprocess.CompletedProcess:  # type: ignore[type-arg]
    return subprocess.run(cmd, cwd=cwd, env=CANSPEC_ENV, capture_output=True, text=True, timeout=300, check=False)


def cmake_dir() -> str:
    r = subprocess.run([sys.executable, "-m", "canspec", "--cmake-dir"], env=CANSPEC_ENV, capture_output=True, text=True, timeout=60, check=False)
    assert r.returncode == 0, r.stderr
    path = Path(r.stdout.strip())
    assert (path / "canspecConfig.cmake").is_file() and (path / "canspecConfigVersion.cmake").is_file()
    return str(path)


@pytest.fixture(scope="module")
def tools():
    for tool in ("cmake", "ninja", "make", "cc"):
        assert shutil.which(tool), f"{tool} not installed (make setup: .ci/setup.d/30-c.sh)"


def scratch(root: Path) -> Path:
    src = root / "src"
    shutil.copytree(SPEC, src / "spec", ignore=shutil.ignore_patterns("source", "history"))
    shutil.copytree(SPEC / "history", src / "spec" / "history")
    (src / "CMakeLists.txt").write_text(CMAKELISTS, encoding="utf-8")
    (src / "main.c").write_text(MAIN_C, encoding="utf-8")
    return src


def build(tree: Path) -> subprocess.CompletedProcess:  # type: ignore[type-arg]
    return run(["cmake", "--build", str(tree), "--verbose"], tree)


@pytest.mark.parametrize("generator", GENERATORS)
def test_find_package_build_and_regenerate(tmp_path, tools, generator):
    src, tree = scratch(tmp_path), tmp_path / "build"
    launcher = f"{sys.executable};-m;canspec"  # this checkout's canspec (PYTHONPATH), not a pip-installed one
    r = run(["cmake", "-S", str(src), "-B", str(tree), "-G", generator, f"-Dcanspec_DIR={cmake_dir()}", f"-DCANSPEC_COMMAND={launcher}"], tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    first = build(tree)
    assert first.returncode == 0, first.stdout + first.stderr
    header = tree / "gateway" / "c" / "kaiwo_gateway.h"
    assert "Node AUTOCAR: only the messages it sends or receives" in header.read_text(encoding="utf-8")
    assert GENERATING in first.stdout
    objects = [p for p in tree.rglob("main.c.o")]
    assert len(objects) == 1
    times = {p: p.stat().st_mtime_ns for p in (header, objects[0], tree / "gateway" / ".canspec-manifest.json")}

    again = build(tree)  # nothing changed: no generation, no compile
    assert again.returncode == 0 and GENERATING not in again.stdout, again.stdout
    assert {p: p.stat().st_mtime_ns for p in times} == times

    time.sleep(0.05)
    (src / "spec" / "can" / "value_tables.yaml").touch()  # read through the bundle: known from the depfile alone
    touched = build(tree)
    assert touched.returncode == 0 and GENERATING in touched.stdout, touched.stdout + touched.stderr
    assert header.stat().st_mtime_ns == times[header] and objects[0].stat().st_mtime_ns == times[objects[0]]  # same bytes: no recompile

    bad = src / "spec" / "can" / "gateway.yaml"
    bad.write_text(bad.read_text(encoding="utf-8") + "\n  - name: [\n", encoding="utf-8")
    broken = build(tree)
    assert broken.returncode != 0
    assert "gateway.yaml:" in broken.stdout + broken.stderr and "nothing written" in broken.stdout + broken.stderr
    assert "Traceback" not in broken.stdout + broken.stderr
