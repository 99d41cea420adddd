"""Build and run the C test programs against the generated headers (used by the pytest
suite, `make roundtrip-c` and `make bench-c`). Standard library only."""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
HEADERS = ROOT / "generated" / "c"
DEFAULT_VECTORS = ROOT / "generated" / "vectors" / "can.json"
STRICT = ["-Wall", "-Wextra", "-Wpedantic", "-Wconversion", "-Wsign-conversion", "-Wshadow", "-Werror"]
SANITIZE = ["-fsanitize=address,undefined", "-fno-sanitize-recover=all", "-fno-omit-frame-pointer"]
CASES_RE = re.compile(r"c runner: (\d+) cases, (\d+) multi-frame texts checked, (\d+) mismatches")

sys.path.insert(0, str(HERE))
from canspec import ir
from canspec.pipeline import compile_spec
from gen_runner_tables import C_TARGETS, tables
from vectors_to_lines import convert


def have(tool: str) -> bool:
    return shutil.which(tool) is not None


def run(cmd: list[str], **kw) -> subprocess.CompletedProcess:  # type: ignore[type-arg]
    return subprocess.run(cmd, capture_output=True, text=True, check=False, **kw)


def compile_c(cc: str, sources: list[Path], out: Path, flags: list[str], include: list[Path] | None = None) -> None:
    cmd = [cc, *flags, *[f"-I{p}" for p in (include or [HEADERS])], *map(str, sources), "-o", str(out), "-lm"]
    proc = run(cmd)
    if proc.returncode != 0:
        raise RuntimeError(f"compile failed: {' '.join(cmd)}\n{proc.stderr[-6000:]}")


def build_runner(
    build: Path, cc: str = "gcc", flags: list[str] | None = None, name: str = "runner", spec: Path = ROOT / "spec", headers: Path = HEADERS
) -> Path:
    """The vector runner of `spec`'s generated headers (in `headers`), built in `build`."""
    build.mkdir(parents=True, exist_ok=True)
    (build / "runner_tables.h").write_text(tables(str(spec)), encoding="utf-8")
    exe = build / name
    compile_c(cc, [HERE / "runner.c"], exe, ["-std=c99", "-O1", "-g", *(flags or [])], [headers, build])
    return exe


def spec_can(spec: Path) -> ir.CanProtocol:
    """The CAN protocol of `spec`'s IR (what vectors_lines needs)."""
    compiled = compile_spec(spec, C_TARGETS)
    if compiled.spec is None or compiled.spec.can is None:
        raise ValueError(f"{spec}: no CAN protocol (canspec check {spec} tells why)")
    return compiled.spec.can


def vectors_lines(vectors: Path, build: Path, can: ir.CanProtocol) -> Path:
    """The runner's line form of a vectors file, each physical value with what its encodes and
    fixed-point decode must give under the spec's IR `can` (vectors_to_lines.py)."""
    doc = json.loads(vectors.read_text(encoding="utf-8"))
    out = build / (vectors.stem + ".lines.txt")
    out.write_text(convert(doc, can), encoding="ascii")
    return out


def run_runner(exe: Path, lines: Path, env: dict[str, str] | None = None) -> tuple[int, str, str]:
    proc = run([str(exe), str(lines)], env={**os.environ, **(env or {})})
    return proc.returncode, proc.stdout, proc.stderr


def main(argv: list[str]) -> int:
    """`run_vectors VECTORS [BUILD_DIR]`: build the runner and check every case."""
    vectors = Path(argv[1]) if len(argv) > 1 and argv[1] else DEFAULT_VECTORS
    build = Path(argv[2]) if len(argv) > 2 else ROOT / "build" / "c"
    try:
        exe = build_runner(build)
        lines = vectors_lines(vectors, build, spec_can(ROOT / "spec"))
    except (OSError, ValueError, KeyError, RuntimeError) as exc:
        print(f"roundtrip-c: {exc}", file=sys.stderr)
        return 1
    code, out, err = run_runner(exe, lines)
    sys.stderr.write(err[-20000:])
    sys.stdout.write(out)
    return code


if __name__ == "__main__":
    sys.exit(main(sys.argv))
