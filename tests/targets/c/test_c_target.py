"""The C target: generated headers are current and deterministic, compile warning-free alone
with gcc and clang as C99 and C++, agree with the shared vectors (also under ASan/UBSan),
and the C unit tests of J1939, VIN and the receive monitor pass."""

from __future__ import annotations

import json
import shutil
import sys
from pathlib import Path

import pytest
from canspec.render import formatters

sys.path.insert(0, str(Path(__file__).resolve().parent))
import cbuild
from canspec import generation as gen_mod
from canspec.targets import c as c_target

HEADER_NAMES = sorted(p.name for p in cbuild.HEADERS.glob("*.h"))
COMPILERS = ("gcc", "clang")  # a missing one fails its tests (run `make setup`)


def test_generated_headers_are_current_and_deterministic(spec):
    first = c_target.render_c(spec)
    assert first == c_target.render_c(spec)
    committed = {f"c/{p.name}": p.read_bytes() for p in cbuild.HEADERS.iterdir() if p.is_file()}
    assert first == committed, "generated/c is stale: run `make gen`"
    for rel, data in first.items():
        if rel.endswith(".h"):
            text = data.decode()
            assert f"sha256 {spec.sha256}" in text[:400] and "Do not edit" in text[:400], rel
            includes = {line.split()[1] for line in text.splitlines() if line.startswith("#include <")}
            assert includes <= {"<stdint.h>", "<stddef.h>", "<stdbool.h>", "<string.h>"}, rel
            assert "malloc" not in text and "<math.h>" not in text


def test_missing_clang_format_fails_generation(spec, monkeypatch):
    monkeypatch.setattr(formatters, "_clang_format_wheel", lambda: None)
    monkeypatch.setattr(formatters.shutil, "which", lambda name: None)
    with pytest.raises(gen_mod.GenerationError, match="clang-format not found.*install"):
        gen_mod.generate(spec, ["c"])


def test_headers_are_clang_formatted():
    assert cbuild.have("clang-format"), "clang-format missing (run `make setup`)"
    style = cbuild.HEADERS / ".clang-format"
    for name in HEADER_NAMES:
        proc = cbuild.run(["clang-format", f"--style=file:{style}", "--dry-run", "-Werror", str(cbuild.HEADERS / name)])
        assert proc.returncode == 0, proc.stderr[:2000]


@pytest.mark.parametrize("lang", ["c99", "c++"])
@pytest.mark.parametrize("cc", COMPILERS)
def test_each_header_compiles_alone_strict(cc, lang, tmp_path):
    """Each header is self-sufficient and warning-free under the strictest flags."""
    for name in HEADER_NAMES:
        src = tmp_path / f"only_{name}.c"
        src.write_text(f'#include "{name}"\n#include "{name}"\nint canspec_dummy(void);\nint canspec_dummy(void) {{ return 0; }}\n')
        std = ["-std=c99"] if lang == "c99" else ["-x", "c++", "-std=c++11"]
        proc = cbuild.run([cc, *std, *cbuild.STRICT, f"-I{cbuild.HEADERS}", "-fsyntax-only", str(src)])
        assert proc.returncode == 0, f"{cc} {lang} {name}:\n{proc.stderr[:4000]}"


@pytest.fixture(scope="module")
def build(tmp_path_factory):
    return tmp_path_factory.mktemp("c-build")


def _check_runner(exe: Path, lines: Path, n_cases: int, env=None):
    code, out, err = cbuild.run_runner(exe, lines, env)
    m = cbuild.CASES_RE.search(out)
    assert code == 0 and m, f"{out}\n{err[-4000:]}"
    assert int(m.group(1)) == n_cases and int(m.group(3)) == 0
    return int(m.group(1))


def test_vector_runner_all_cases(build, vectors, spec):
    exe = cbuild.build_runner(build, "gcc", cbuild.STRICT)
    lines = cbuild.vectors_lines(cbuild.DEFAULT_VECTORS, build, spec.can)
    assert _check_runner(exe, lines, len(vectors["cases"])) >= 2000
    _, out, _ = cbuild.run_runner(exe, lines)
    assert f", {len(vectors['multiframe'])} multi-frame texts" in out


def test_strategy_outside_its_levels_is_a_compile_error(tmp_path):
    src = tmp_path / "main.c"
    src.write_text('#include "kaiwo_gateway.h"\nint main(void) { return 0; }\n')
    proc = cbuild.run(["gcc", "-std=c99", "-DKAIWO_GATEWAY_STRATEGY=4", f"-I{cbuild.HEADERS}", "-fsyntax-only", str(src)])
    assert proc.returncode != 0 and "KAIWO_GATEWAY_STRATEGY must be 0, 1, 2 or 3" in proc.stderr, proc.stderr


def test_a_64_bit_form_is_written_only_where_it_differs():
    """A pack or unpack whose strategy-3 form is its byte form has no #if: each #if holds two
    different bodies."""
    import re

    text = (cbuild.HEADERS / "kaiwo_gateway_messages.h").read_text(encoding="utf-8")
    blocks = re.findall(r"#if KAIWO_GATEWAY_STRATEGY >= 3[^\n]*\n(.*?)#else\n(.*?)#endif", text, re.DOTALL)
    assert blocks and all(word != byte for word, byte in blocks)


def test_vector_runner_byte_wise_path(build, vectors, spec):
    """The strategy of cores without unaligned word stores or a long multiply (Cortex-M0+:
    fieldless frames zeroed byte by byte, 64-bit products from 16-bit halves) agrees with the
    vectors too, built on this host."""
    exe = cbuild.build_runner(build, "gcc", [*cbuild.STRICT, "-DKAIWO_GATEWAY_STRATEGY=0"], name="runner-bytes")
    lines = cbuild.vectors_lines(cbuild.DEFAULT_VECTORS, build, spec.can)
    _check_runner(exe, lines, len(vectors["cases"]))


def test_vector_runner_reports_mismatches(build, vectors, spec):
    """The runner is not a rubber stamp: a wrong byte, raw value or physical value fails it."""
    exe = cbuild.build_runner(build, "gcc", name="runner-neg")
    doc = json.loads(json.dumps(vectors))
    doc["cases"] = doc["cases"][:40]
    doc["cases"][3]["data"] = ("%02X" % (int(doc["cases"][3]["data"][:2], 16) ^ 0x01)) + doc["cases"][3]["data"][2:]
    sig = next(iter(doc["cases"][10]["raw"]))
    doc["cases"][10]["raw"][sig] += 1
    case = next(c for c in doc["cases"][11:] if any(isinstance(v, float) for v in c["physical"].values()))
    name = next(k for k, v in case["physical"].items() if isinstance(v, float))
    case["physical"][name] += 1.0
    doc["multiframe"][0]["text"] = "X" + doc["multiframe"][0]["text"][1:]
    bad = build / "bad.json"
    bad.write_text(json.dumps(doc))
    code, out, err = cbuild.run_runner(exe, cbuild.vectors_lines(bad, build, spec.can))
    assert code != 0
    assert "40 cases" in out and "mismatches" in out
    assert err.count("line ") >= 4, err


def test_vector_runner_checks_the_fixed_point_expectations(build, vectors, spec):
    """The exact fixed-point values come with the lines (vectors_to_lines.py): a wrong
    decode_fixed value, a physical text that is not raw × factor + offset, and a wrong
    encode_fixed raw value each fail the runner."""
    exe = cbuild.build_runner(build, "gcc", name="runner-fixed")
    doc = build / "fixed.json"
    doc.write_text(json.dumps({"cases": vectors["cases"][:40], "multiframe": []}))
    lines = cbuild.vectors_lines(doc, build, spec.can).read_text(encoding="ascii").splitlines()
    fixed = [i for i, line in enumerate(lines) if line.startswith("P ") and len(line.split()) == 8 and line.split()[6] != "-"]
    for i, (field, wrong) in zip(fixed, ((4, lambda v: str(int(v) + 1)), (5, lambda _: "0"), (7, lambda v: str(int(v) + 1)))):
        words = lines[i].split()
        words[field] = wrong(words[field])
        lines[i] = " ".join(words)
    bad = build / "fixed.lines.txt"
    bad.write_text("\n".join(lines) + "\n", encoding="ascii")
    code, out, err = cbuild.run_runner(exe, bad)
    assert code == 1 and "40 cases" in out and ", 3 mismatches" in out, out + err
    assert "fixed decode" in err and "is not raw × factor + offset" in err and "fixed encode" in err, err


@pytest.mark.parametrize("num,den,want", [(5, 10, 1), (-5, 10, -1), (5, -10, -1), (4, 10, 0), (15, 10, 2), (-15, 10, -2)])
def test_fixed_encode_rounds_half_away_from_zero_exactly(num, den, want):
    """vectors_to_lines.div_round: the exact rounding the fixed encode of a tie must give."""
    from vectors_to_lines import div_round

    assert div_round(num, den) == want


def test_vector_runner_under_sanitizers(build, vectors, spec):
    exe = cbuild.build_runner(build, "clang", cbuild.SANITIZE, name="runner-asan")
    lines = cbuild.vectors_lines(cbuild.DEFAULT_VECTORS, build, spec.can)
    _check_runner(exe, lines, len(vectors["cases"]), {"ASAN_OPTIONS": "detect_leaks=1", "UBSAN_OPTIONS": "print_stacktrace=1"})


@pytest.mark.parametrize("cc,flags", [("gcc", ["-std=c99", "-O2", *cbuild.STRICT]), ("clang", ["-std=c99", "-O1", *cbuild.STRICT, *cbuild.SANITIZE])])
def test_unit_tests_in_c(cc, flags, build):
    assert cbuild.have(cc), f"{cc} missing (run `make setup`)"
    exe = build / f"unit-{cc}"
    cbuild.compile_c(cc, [cbuild.HERE / "unit_tests.c"], exe, flags)
    proc = cbuild.run([str(exe)])
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert ", 0 failures" in proc.stdout and " 0 checks" not in proc.stdout


def test_mock_firmware_project_generates_and_builds(tmp_path):
    """A firmware repo's `make gen` + build: canspec generates the C target into its own tree."""
    assert cbuild.have("make"), "make missing (run `make setup`)"
    fw = tmp_path / "firmware"
    shutil.copytree(cbuild.HERE / "firmware", fw)
    env = {"CANSPEC": f"{sys.executable} -m canspec", "PYTHONPATH": str(cbuild.ROOT / "generator")}
    proc = cbuild.run(["make", "-C", str(fw), "all", "run"], env={**__import__("os").environ, **env})
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    assert (fw / "gen" / "c" / "kaiwo_gateway.h").is_file()
    assert "firmware ok" in proc.stdout
    # AUTOCAR's headers: a message between other nodes (RC → Wire_Car_ECU) is absent, its own are there
    messages = (fw / "gen" / "c" / "kaiwo_gateway_messages.h").read_text(encoding="utf-8")
    assert "kaiwo_gateway_autocar_eps_command_t" in messages and "kaiwo_gateway_eps_state_t" in messages
    assert "kaiwo_gateway_tele_control_command_1_t" not in messages
    proc = cbuild.run(["make", "-C", str(fw), "check-gen"], env={**__import__("os").environ, **env})
    assert proc.returncode == 0, proc.stderr


def _signed(sig, lo: int, hi: int):
    import dataclasses

    return dataclasses.replace(sig, signed=True, sign_bit=1 << (sig.length - 1), raw_type_min=lo, raw_type_max=hi, raw_min=lo, raw_max=hi,
                               phys_min=lo, phys_max=hi, check_min=lo, check_max=hi, doc_min=None, doc_max=None,
                               value_table=None, specials=())


SIGNED_MAIN = r"""
#include <stdio.h>
#include "kaiwo_gateway.h"
int main(void) {
    uint8_t f[8] = {0};
    kaiwo_gateway_eps_state_t s = kaiwo_gateway_eps_state_init(), t;
    s.controller_temp = -5;   /* 6 bits at 40: 0x3B */
    s.steering_angle = 0xBEEFu;
    s.eps_ctrl_state = 0x81u;
    if (kaiwo_gateway_eps_state_pack(f, 8, &s) != KAIWO_GATEWAY_OK || f[5] != 0x3Bu || f[0] != 0x81u || f[3] != 0xEFu) return 1;
    f[5] |= 0xC0u; /* reserved bits set on the wire: not part of the field */
    if (kaiwo_gateway_eps_state_unpack(&t, f, 8) != KAIWO_GATEWAY_OK || t.controller_temp != -5 || t.steering_angle != 0xBEEFu) return 2;
    s.controller_temp = -33; /* does not fit 6 signed bits */
    if (kaiwo_gateway_eps_state_pack(f, 8, &s) != KAIWO_GATEWAY_ERR_RANGE) return 3;
    s.controller_temp = 31;
    if (kaiwo_gateway_eps_state_pack(f, 8, &s) != KAIWO_GATEWAY_OK || f[5] != 0x1Fu) return 4;
    if (kaiwo_gateway_eps_state_unpack(&t, f, 8) != KAIWO_GATEWAY_OK || t.controller_temp != 31) return 5;
    kaiwo_gateway_front_sensor_distance_1_t d = kaiwo_gateway_front_sensor_distance_1_init(), e;
    d.sensor_2_distance = -3; /* 10 bits at 10, across bytes 1 and 2: 0x3FD */
    d.sensor_3_distance = 0x155u;
    if (kaiwo_gateway_front_sensor_distance_1_pack(f, 8, &d) != KAIWO_GATEWAY_OK || f[0] != 0u || f[1] != 0xF4u || f[2] != 0x5Fu || f[3] != 0x15u) return 6;
    if (kaiwo_gateway_front_sensor_distance_1_unpack(&e, f, 8) != KAIWO_GATEWAY_OK || e.sensor_2_distance != -3 || e.sensor_3_distance != 0x155u) return 7;
    d.sensor_2_distance = -513; /* does not fit 10 signed bits */
    if (kaiwo_gateway_front_sensor_distance_1_pack(f, 8, &d) != KAIWO_GATEWAY_ERR_RANGE) return 8;
    d.sensor_2_distance = 511;
    if (kaiwo_gateway_front_sensor_distance_1_pack(f, 8, &d) != KAIWO_GATEWAY_OK || f[1] != 0xFCu || f[2] != 0x57u) return 9;
    if (kaiwo_gateway_front_sensor_distance_1_unpack(&e, f, 8) != KAIWO_GATEWAY_OK || e.sensor_2_distance != 511) return 10;
    puts("signed ok");
    return 0;
}
"""


@pytest.mark.parametrize("strategy", ["3", "0"])
def test_signed_fields_pack_and_unpack(spec, tmp_path, strategy):
    """No signal of this document is signed: a spec variant with a 6-bit signed field inside a
    byte and a 10-bit one across bytes (read and written through the frame word under
    KAIWO_GATEWAY_STRATEGY 3) checks the sign extension and the signed range check, on both code
    paths."""
    import dataclasses

    signed = {("eps_state", "controller_temp"): (-32, 31), ("front_sensor_distance_1", "sensor_2_distance"): (-512, 511)}
    messages = tuple(
        dataclasses.replace(m, signals=tuple(_signed(s, *signed[(m.name, s.name)]) if (m.name, s.name) in signed else s for s in m.signals))
        for m in spec.can.messages
    )
    variant = dataclasses.replace(spec, can=dataclasses.replace(spec.can, messages=messages))
    out = tmp_path / "c"
    out.mkdir()
    for rel, data in c_target.render_c(variant).items():
        (tmp_path / rel).write_bytes(data)
    src = tmp_path / "main.c"
    src.write_text(SIGNED_MAIN)
    exe = tmp_path / "signed"
    cbuild.compile_c("gcc", [src], exe, ["-std=c99", "-O2", *cbuild.STRICT, f"-DKAIWO_GATEWAY_STRATEGY={strategy}"], [out])
    proc = cbuild.run([str(exe)])
    assert proc.returncode == 0 and "signed ok" in proc.stdout, (proc.returncode, proc.stdout, proc.stderr)
