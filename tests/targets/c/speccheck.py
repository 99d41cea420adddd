"""The C target's checks on any spec: generate its C headers and vectors, compile each header
alone with gcc and clang as C99 and as C++ under the strict warning flags (and the umbrella
header optimised, where the middle-end warnings live), run the vector runner on the spec's own
vectors through both pack/unpack paths and under the sanitizers, and hold every global name the headers declare to the
list `canspec check` checks for clashes (targets/c/names.py). Used by test_c_any_spec.py for
every valid fixture, and from the command line for any spec:

    python3 tests/targets/c/speccheck.py SPEC [WORK_DIR]
"""

from __future__ import annotations

import json
import re
import sys
import tempfile
from pathlib import Path

import cbuild
from canspec import ir
from canspec.pipeline import compile_spec
from canspec.targets import registry
from canspec.targets.c.names import declared
from vectors_to_lines import convert

MODES = (("gcc", ["-std=c99"]), ("clang", ["-std=c99"]), ("g++", ["-x", "c++", "-std=c++11"]), ("clang++", ["-x", "c++", "-std=c++11"]))
# The headers' own flags on top of the strict ones: float fields convert only where the code says so
# (no implicit float -> double promotion, no narrowing, no == on floating values).
HEADER_FLAGS = [*cbuild.STRICT, "-Wdouble-promotion", "-Wfloat-conversion", "-Wfloat-equal"]


# What the headers declare at file scope: macros, typedef names, enumerators, functions.
DECLARATIONS = re.compile(
    r"^#define (\w+)|^typedef \w+ (\w+);|^\} (\w+);|^typedef char (\w+)|^ +([A-Z][A-Z0-9_]*) = "
    r"|^static (?:inline )?[^(=]*?\b(\w+)\(|^ *static const \w+ (\w+) =",
    re.MULTILINE,
)


def generate_c(spec: ir.Spec, out: Path) -> tuple[Path, dict]:  # type: ignore[type-arg]
    """Write the spec's C headers and vectors under `out`; (headers dir, vectors document)."""
    for target in ("c", "vectors"):  # in this process: the callers run specs side by side
        for rel, data in registry()[target].render(spec).items():
            (out / rel).parent.mkdir(parents=True, exist_ok=True)
            (out / rel).write_bytes(data)
    return out / "c", json.loads((out / "vectors" / "can.json").read_text(encoding="utf-8"))


def compile_matrix(headers: Path, work: Path) -> list[str]:
    """Each header alone (included twice: the guards), every compiler and language; the
    umbrella header at -O2. Returns the failures."""
    names = sorted(p.name for p in headers.glob("*.h"))
    units = []
    for name in names:
        unit = work / f"only_{name}.c"
        unit.write_text(f'#include "{name}"\n#include "{name}"\nint canspec_dummy(void);\nint canspec_dummy(void) {{ return 0; }}\n', encoding="utf-8")
        units.append(unit)
    failures = []
    for cc, std in MODES:
        proc = cbuild.run([cc, *std, *HEADER_FLAGS, f"-I{headers}", "-fsyntax-only", *map(str, units)])
        if proc.returncode != 0:
            failures.append(f"{cc} {' '.join(std)}, each header alone:\n{proc.stderr[-4000:]}")
    umbrella = min(units, key=lambda u: len(u.name))
    for cc in ("gcc", "clang"):
        proc = cbuild.run([cc, "-std=c99", "-O2", *HEADER_FLAGS, f"-I{headers}", "-c", str(umbrella), "-o", str(work / f"umbrella-{cc}.o")])
        if proc.returncode != 0:
            failures.append(f"{cc} -O2 {umbrella.name}:\n{proc.stderr[-4000:]}")
    return failures


def run_vectors(spec_path: Path, can: ir.CanProtocol, headers: Path, doc: dict, work: Path) -> list[str]:  # type: ignore[type-arg]
    """The vector runner on the spec's own vectors: the host's strategy and Cortex-M0+'s (STRATEGY 0), and under ASan and UBSan."""
    lines = work / "vectors.lines.txt"
    lines.write_text(convert(doc, can), encoding="ascii")
    macro = next(p.read_text(encoding="utf-8") for p in headers.glob("*_common.h")).split("#ifndef ", 1)[1].split("_COMMON_H", 1)[0]
    failures = []
    variants = (("runner", "gcc", cbuild.STRICT), ("runner-bytes", "gcc", [*cbuild.STRICT, f"-D{macro}_STRATEGY=0"]), ("runner-asan", "clang", cbuild.SANITIZE))
    for name, cc, flags in variants:
        try:
            exe = cbuild.build_runner(work / name, cc, flags, name, spec_path, headers)
        except RuntimeError as exc:
            failures.append(f"{name}: {exc}")
            continue
        code, out, err = cbuild.run_runner(exe, lines)
        m = cbuild.CASES_RE.search(out)
        if code != 0 or m is None or int(m.group(1)) != len(doc["cases"]) or int(m.group(2)) != len(doc["multiframe"]) or int(m.group(3)) != 0:
            failures.append(f"{name}: exit {code}: {out.strip()}\n{err[-4000:]}")
    return failures


def undeclared(headers: Path, can: ir.CanProtocol) -> list[str]:
    """Global names in the headers that names.declared() does not list (its clash check would miss them)."""
    listed = {name for name, _ in declared(can)}
    found = {n for p in headers.glob("*.h") for m in DECLARATIONS.finditer(p.read_text(encoding="utf-8")) for n in m.groups() if n}
    # the line after a wrapped `static [inline] <type>` starts with the function's name
    found |= {m.group(1) for p in headers.glob("*.h") for m in re.finditer(r"^static [\w *]+\n(\w+)\(", p.read_text(encoding="utf-8"), re.MULTILINE)}
    return [f"the headers declare {name}, which targets/c/names.py does not list" for name in sorted(found - listed)]


def check_spec(spec_path: Path, work: Path) -> list[str]:
    """Every C check of one spec (the C target writes nothing for a spec without a CAN
    protocol); the failures (empty: all passed)."""
    compiled = compile_spec(spec_path, cbuild.C_TARGETS)
    if compiled.spec is None:
        return ["canspec check refuses it:\n" + "\n".join(p.format() for p in compiled.errors)]
    if compiled.spec.can is None:
        written = registry()["c"].render(compiled.spec)
        return [f"the C target wrote {sorted(written)} for a spec without a CAN protocol"] if written else []
    work.mkdir(parents=True, exist_ok=True)
    headers, doc = generate_c(compiled.spec, work / "out")
    can = compiled.spec.can
    return undeclared(headers, can) + compile_matrix(headers, work) + run_vectors(spec_path, can, headers, doc, work)


def main(argv: list[str]) -> int:
    if len(argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    work = Path(argv[2]) if len(argv) > 2 else Path(tempfile.mkdtemp(prefix="canspec-c-"))
    failures = check_spec(Path(argv[1]), work)
    for f in failures:
        print(f, file=sys.stderr)
    print(f"{argv[1]}: {len(failures)} C failure(s) ({work})")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
