"""examples/ecu built and run as its README says: configure with the arm-none-eabi toolchain file and
canspec's CMake package, build every core's image, run one under user-mode qemu-arm with a bench
script on stdin (board/qemu/board_qemu.c) and read back what it printed. Shared by the test
(test_ecu.py) and `make bench-c` (ecu_bench.py)."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
EXAMPLE = ROOT / "examples" / "ecu"
TOOLCHAIN = EXAMPLE / "cmake" / "arm-none-eabi.cmake"
CORES = ("cortex-m0plus", "cortex-m4")
NODE = "Wire_Car_ECU"
TOOLS = ("cmake", "arm-none-eabi-gcc", "arm-none-eabi-size", "qemu-arm")
ENV = {**os.environ, "PYTHONPATH": str(ROOT / "generator")}  # this checkout's canspec


class ImageError(RuntimeError):
    pass


def _run(cmd: list[str], **kw) -> subprocess.CompletedProcess:  # type: ignore[no-untyped-def,type-arg]
    return subprocess.run(cmd, env=ENV, capture_output=True, text=True, timeout=600, check=False, **kw)


def missing_tools() -> list[str]:
    return [t for t in (*TOOLS, "ninja") if shutil.which(t) is None]


def build(tree: Path, generator: str = "Ninja") -> dict[str, Path]:
    """Configures (once) and builds the images: {core: elf}."""
    cmake_dir = _run([sys.executable, "-m", "canspec", "--cmake-dir"]).stdout.strip()
    if not (tree / "CMakeCache.txt").exists():
        r = _run(["cmake", "-S", str(EXAMPLE), "-B", str(tree), "-G", generator, f"--toolchain={TOOLCHAIN}",
                  f"-Dcanspec_DIR={cmake_dir}", f"-DCANSPEC_COMMAND={sys.executable};-m;canspec"])
        if r.returncode != 0:
            raise ImageError(f"configure failed:\n{r.stdout[-3000:]}{r.stderr[-3000:]}")
    r = _run(["cmake", "--build", str(tree)])
    if r.returncode != 0:
        raise ImageError(f"build failed:\n{r.stdout[-4000:]}{r.stderr[-3000:]}")
    return {core: tree / f"ecu-{core}.elf" for core in CORES}


def run(elf: Path, script: str) -> str:
    r = _run(["qemu-arm", str(elf)], input=script)
    if r.returncode != 0:
        raise ImageError(f"{elf.name} exit {r.returncode}:\n{r.stdout[-2000:]}{r.stderr[-2000:]}")
    return r.stdout


def sizes(elf: Path) -> dict[str, int]:
    """.text/.data/.bss as arm-none-eabi-size (Berkeley format) reports them."""
    r = _run(["arm-none-eabi-size", str(elf)])
    text, data, bss = (int(x) for x in r.stdout.splitlines()[1].split()[:3])
    return {"text": text, "data": data, "bss": bss}


def stack(output: str) -> tuple[int, int]:
    """(bytes used, stack size) from the image's last line: the painted stack's high-water mark."""
    m = re.search(r"^STACK used=(\d+) size=(\d+)$", output, re.MULTILINE)
    if m is None:
        raise ImageError(f"no STACK line in the image's output:\n{output[-1000:]}")
    return int(m.group(1)), int(m.group(2))
