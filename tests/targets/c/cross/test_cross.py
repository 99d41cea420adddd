"""The C headers on other machines, under emulation: the vector runner on every case of the
shipped vectors, 0 mismatches, on x86-64, big-endian PowerPC (qemu-ppc), Cortex-M0+ and
Cortex-M4 (arm-none-eabi-gcc for the exact core, qemu-arm), for every compile-time strategy of
the headers (cross.DEFAULT_STRATEGIES, or $CANSPEC_C_STRATEGIES). The headers also compile
warning-free under the strict flags for each of these targets."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
import cross  # noqa: E402

STRATEGIES = cross.strategies_from_env()
TARGETS = list(cross.TARGETS.values())
WORK = [(t, s) for t in TARGETS for s in cross.applicable(t, STRATEGIES)]


def _need(target: cross.Target) -> None:
    missing = target.missing()
    if missing:
        msg = f"{target.name}: {', '.join(missing)} not installed (make setup: .ci/setup.d/35-cross.sh)"
        if os.environ.get("CI"):
            pytest.fail(msg)
        pytest.skip(msg)


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    """Every (target, strategy) built and run once, in parallel (the builds dominate)."""
    build = tmp_path_factory.mktemp("c-cross")
    ready = [t for t in TARGETS if not t.missing()]
    got = cross.check_all(ready, STRATEGIES, build)
    return {(r.target, r.strategy): r for r in got}, build


@pytest.mark.parametrize("target,strategy", WORK, ids=[f"{t.name}-{s.name}" for t, s in WORK])
def test_vectors_on_target(results, vectors, target, strategy):
    _need(target)
    res = results[0][(target.name, strategy.name)]
    assert res.ok, f"{target.name} {strategy.name}: {res.error}"
    assert res.cases == len(vectors["cases"]) and res.texts == len(vectors["multiframe"])
    assert res.mismatches == 0


def test_strategies_cover_every_configuration_macro():
    """A new #if macro in the headers (the C rewrite) must join the strategy list."""
    tested = {m for s in STRATEGIES for m, _ in s.defines}
    assert cross.config_macros(cross.cbuild.HEADERS) <= tested


def test_strategy_parsing():
    got = cross.parse_strategies("A=0,1/le; B=x")
    assert [s.name for s in got] == ["default", "A=0,B=x", "A=1,B=x"]
    assert [s.little_endian_only for s in got] == [False, False, True]
    assert [s.name for s in cross.applicable(cross.TARGETS["ppc"], got)] == ["default", "A=0,B=x"]
    with pytest.raises(ValueError):
        cross.parse_strategies("A")
    with pytest.raises(ValueError):
        cross.parse_strategies("A=1/be")


@pytest.mark.parametrize("name", ["cortex-m0plus", "cortex-m4"])
def test_arm_builds_are_for_the_exact_core(results, name):
    target = cross.TARGETS[name]
    _need(target)
    exe = results[1] / name / "default" / "runner.elf"
    attrs = subprocess.run(["arm-none-eabi-readelf", "-A", str(exe)], capture_output=True, text=True, check=True).stdout
    want = {"cortex-m0plus": "v6S-M", "cortex-m4": "v7E-M"}[name]
    assert f"Tag_CPU_arch: {want}" in attrs and "Microcontroller" in attrs, attrs


@pytest.mark.parametrize("name", ["ppc", "cortex-m0plus"])
def test_emulated_runner_reports_mismatches(results, vectors, can, tmp_path, name):
    """Under emulation too the runner is no rubber stamp: a wrong byte and a wrong raw value
    fail it (and the vectors really are read through the emulated program's file I/O)."""
    target = cross.TARGETS[name]
    _need(target)
    doc = json.loads(json.dumps(vectors))
    doc["cases"] = doc["cases"][:30]
    doc["cases"][2]["data"] = ("%02X" % (int(doc["cases"][2]["data"][:2], 16) ^ 0x80)) + doc["cases"][2]["data"][2:]
    doc["cases"][7]["raw"][next(iter(doc["cases"][7]["raw"]))] += 1
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(doc))
    lines = cross.cbuild.vectors_lines(bad, tmp_path, can)
    exe = results[1] / name / "default" / ("runner.elf" if target.bare_metal else "runner")
    proc = subprocess.run(cross.command(target, exe, str(lines)), capture_output=True, text=True, timeout=120, check=False)
    m = cross.cbuild.CASES_RE.search(proc.stdout)
    assert proc.returncode == 1 and m, proc.stdout + proc.stderr
    assert int(m.group(1)) == 30 and int(m.group(3)) >= 2
    assert proc.stderr.count("line ") >= 2, proc.stderr


def test_bench_cross_smoke(tmp_path, capsys):
    """`make bench-c-cross` still builds, traces and counts, and both sides still do the same
    work (every library unpacks and packs the bench frames back, status 0): one core, one level."""
    _need(cross.TARGETS["cortex-m4-O2"])
    import bench_cross

    rc = bench_cross.main(["bench_cross", "--configs", "cortex-m4:-O2", "--build", str(tmp_path)])
    out = capsys.readouterr().out
    assert rc == 0, out[-3000:]
    assert "bench: 0 mismatches" in out and "overall (sum)" in out and "helper-free" in out


def _helpers(headers: Path, work: Path, core: str, opt: str) -> list[str]:
    """The routines an object needs that takes the address of every pack, unpack and
    integer-only physical function of the headers, built for the exact core."""
    text = "".join(h.read_text(encoding="utf-8") for h in sorted(headers.glob("*_messages.h")))
    names = re.findall(r"^static inline [^(]*?\b(\w+_(?:pack|unpack|encode_fixed|decode_fixed))\(", text, re.MULTILINE)
    assert any(n.endswith("_encode_fixed") for n in names)
    umbrella = min(headers.glob("*.h"), key=lambda h: len(h.name)).name
    src = work / "api.c"
    src.write_text(f'#include "{umbrella}"\ntypedef void (*any_fn)(void);\nextern const any_fn api[];\nconst any_fn api[] = {{\n'
                   + "".join(f"    (any_fn){n},\n" for n in names) + "};\n")
    obj = work / "api.o"
    subprocess.run([cross.ARM_CC, *cross.ARM_CORES[core], opt, "-std=c99", "-c", str(src), "-o", str(obj), "-I", str(headers)],
                   check=True, capture_output=True, text=True)
    undefined = subprocess.run(["arm-none-eabi-nm", "-u", str(obj)], check=True, capture_output=True, text=True).stdout.split()
    return [u for u in undefined if u != "U"]


@pytest.mark.parametrize("core", ["cortex-m0plus", "cortex-m4"])
@pytest.mark.parametrize("opt", ["-Os", "-O2"])
def test_integer_path_calls_no_helper(tmp_path, core, opt):
    """pack, unpack and the integer-only physical functions emitted out of line for the exact
    core: the object needs no libgcc or libc routine (no __aeabi_uidivmod on Cortex-M0+, which
    has no divide instruction, no __aeabi_lmul where it has no long multiply)."""
    _need(cross.TARGETS[core])
    assert _helpers(cross.cbuild.HEADERS, tmp_path, core, opt) == []


FIXTURES = Path(__file__).resolve().parents[3] / "fixtures" / "valid"
# specs whose integer path computes in 64 bits (fields wide or scaled beyond 32 bits); the last
# one takes every form of the 64-bit rounding division
WIDE_SPECS = (FIXTURES / "wide_fields.yaml", FIXTURES / "wide_and_scaled_fields.yaml", FIXTURES / "py_wide_and_keywords.yaml",
              Path(__file__).resolve().parent / "wide_fixed_point.yaml")


@pytest.mark.parametrize("core", ["cortex-m0plus", "cortex-m4"])
@pytest.mark.parametrize("opt", ["-Os", "-O2"])
def test_64_bit_integer_path_calls_no_helper(tmp_path, core, opt):
    """The same for specs whose integer-only path works in int64_t / uint64_t: no 64-bit divide
    or multiply helper (__aeabi_ldivmod, __aeabi_uldivmod, __aeabi_lmul) nor 64-bit shift."""
    _need(cross.TARGETS[core])
    from canspec.pipeline import compile_spec
    from canspec.targets import registry

    for spec in WIDE_SPECS:
        headers = tmp_path / spec.stem
        headers.mkdir()
        for rel, data in registry()["c"].render(compile_spec(spec).spec).items():
            (headers / Path(rel).name).write_bytes(data)
        assert "int64_t value" in "".join(h.read_text(encoding="utf-8") for h in headers.glob("*_messages.h")), spec.name
        assert _helpers(headers, headers, core, opt) == [], spec.name


def _new_dialect(path: Path) -> bool:
    from canspec.pipeline import compile_spec

    can = getattr(compile_spec(path, cross.cbuild.C_TARGETS).spec, "can", None)
    return can is not None and (can.has_big_endian or can.has_fd or can.has_float)


DIALECT_FIXTURES = [p for p in sorted(FIXTURES.glob("*.yaml")) if _new_dialect(p)]
DIALECT_FIXTURES += [Path(__file__).resolve().parents[1] / "corners" / name for name in ("c_corners.yaml", "c_mux_corners.yaml")]


def test_the_dialect_fixtures_are_there():
    assert "motorola_fd_float" in [p.stem for p in DIALECT_FIXTURES]


@pytest.mark.parametrize("spec", DIALECT_FIXTURES, ids=[p.stem for p in DIALECT_FIXTURES])
def test_motorola_fd_float_fixture_vectors_on_every_target(spec, tmp_path):
    """Motorola fields, CAN FD frames and IEEE floats where byte order, word size and float ABI
    differ: the fixture's own vectors on big-endian PowerPC, Cortex-M0+ and M4 (soft float) and
    x86-64, at every strategy of its headers."""
    from canspec.pipeline import compile_spec
    from canspec.targets import registry

    compiled = compile_spec(spec, cross.cbuild.C_TARGETS).spec
    for target in ("c", "vectors"):
        for rel, data in registry()[target].render(compiled).items():
            (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
            (tmp_path / rel).write_bytes(data)
    headers, vectors = tmp_path / "c", tmp_path / "vectors" / "can.json"
    targets = [t for t in TARGETS if t.name in ("x86-64", "ppc", "cortex-m0plus", "cortex-m4")]
    for t in targets:
        _need(t)
    strategies = cross.parse_strategies(f"{cross.header_prefix(headers).upper()}_STRATEGY=0,1,2,3")
    results = cross.check_all(targets, strategies, tmp_path / "build", headers, spec, vectors, jobs=2)
    cases = len(json.loads(vectors.read_text(encoding="utf-8"))["cases"])
    assert len(results) == len(targets) * 5
    assert all(r.ok and r.cases == cases for r in results), "\n".join(f"{r.target} {r.strategy}: {r.error}" for r in results if not r.ok)
