"""`*_decode_fixed(raw)` has no undefined behaviour for any argument of its type, not only for the
values unpack gives. Its result type holds every value of the field; where an argument beyond
the field's bits would overflow it (a 25-bit field in a uint32_t times 10, found by an independent
test on opendbc's vw_meb.dbc under UBSan), the argument is read as the field's bits: the low bits,
sign-extended for a signed field, which is what unpack gives for a frame holding those bits; an
argument that cannot overflow is computed as it is.
Expected values: the spec's factor and offset in exact fractions, times the scale the header
states, on the argument's low bits (Python's own arithmetic, not the generator's)."""

from __future__ import annotations

import re
import sys
from fractions import Fraction
from pathlib import Path

from canspec_cli import run_canspec

sys.path.insert(0, str(Path(__file__).resolve().parent))
import cbuild  # noqa: E402

SPEC = """schema_version: 1
kind: can_protocol
protocol: {name: fx, version: 1.0.0}
bus: {bitrate: 500000, id_format: standard, addressing: none, byte_order: little_endian}
nodes:
  - {name: A}
  - {name: B}
messages:
  - name: m
    id: 0x100
    sender: A
    receivers: [B]
    dlc: 8
    signals:
      - {name: length25, start: 0, len: 25, factor: 0.00001, range: [0, 180]}
      - {name: signed20, start: 25, len: 20, signed: true, factor: 0.0005}
      - {name: small12, start: 45, len: 12, factor: 0.5}
  - name: w
    id: 0x101
    sender: A
    receivers: [B]
    dlc: 8
    signals:
      - {name: wide56, start: 0, len: 56}
"""
# (function, field length, signed, factor, offset, C type of the argument, whether an argument beyond the field can overflow)
FIELDS = [
    ("fx_m_length25", 25, False, "0.00001", "0", "uint32_t", True),
    ("fx_m_signed20", 20, True, "0.0005", "0", "int32_t", True),
    ("fx_m_small12", 12, False, "0.5", "0", "uint16_t", False),
    ("fx_w_wide56", 56, False, "1", "0", "uint64_t", True),
]
ARGUMENTS = {
    "uint16_t": [0, 1, 4095, 4096, 0x8000, 0xFFFF],
    "uint32_t": [0, 1, (1 << 25) - 1, 1 << 25, 0x7FFFFFFF, 0x80000000, 0xA5A5A5A5, 0xFFFFFFFF],
    "int32_t": [0, 1, -1, (1 << 19) - 1, -(1 << 19), 1 << 19, -(1 << 19) - 1, 2**31 - 1, -(2**31), -1515870811],
    "uint64_t": [0, 1, (1 << 56) - 1, 1 << 56, 2**63 - 1, 2**63, 2**64 - 1],
}


def _field_bits(arg: int, length: int, signed: bool) -> int:
    low = arg & ((1 << length) - 1)
    return low - (1 << length) if signed and low >> (length - 1) else low


def _literal(value: int, ctype: str) -> str:
    if ctype == "int32_t" and value == -(2**31):
        return "INT32_MIN"
    return f"({ctype})({value}{'ULL' if ctype == 'uint64_t' else 'LL'})"


def test_decode_fixed_is_total_over_its_argument_type(tmp_path: Path) -> None:
    (tmp_path / "fx.yaml").write_text(SPEC, encoding="utf-8")
    proc = run_canspec("gen", tmp_path / "fx.yaml", "-o", tmp_path / "out", "-t", "c")
    assert proc.returncode == 0, proc.stderr
    header = (tmp_path / "out" / "c" / "fx_messages.h").read_text(encoding="utf-8")
    scales, calls = {}, []
    for fn, length, signed, _, _, ctype, overflows in FIELDS:
        body = re.search(rf"raw → physical × (\d+), integers only\. \*/\nstatic inline \w+ {fn}_decode_fixed\({ctype} raw\) \{{\n(.*?)\n\}}", header, re.S)
        assert body is not None, fn
        scales[fn] = int(body.group(1))
        assert ("field" in body.group(2)) == overflows, body.group(2)  # read as the field's bits only where it matters
        calls += [f'    printf("%s %lld\\n", "{fn}", (long long){fn}_decode_fixed({_literal(a, ctype)}));' for a in ARGUMENTS[ctype]]
    main = tmp_path / "main.c"
    main.write_text('#include <stdio.h>\n#include <stdint.h>\n#include "fx.h"\nint main(void) {\n' + "\n".join(calls) + "\n    return 0;\n}\n")
    exe = tmp_path / "main"
    cbuild.compile_c("gcc", [main], exe, ["-std=c99", "-O1", "-Wall", "-Wextra", "-Werror", "-fsanitize=undefined", "-fno-sanitize-recover=all"],
                     include=[tmp_path / "out" / "c"])
    run = cbuild.run([str(exe)])
    assert run.returncode == 0 and not run.stderr, run.stderr  # UBSan stops the run at the first overflow
    got = [line.split() for line in run.stdout.splitlines()]
    # an argument beyond the field: its low bits where it could overflow, else the argument as it is (both defined)
    expected = [[fn, str(int(((_field_bits(a, length, signed) if overflows else a) * Fraction(factor) + Fraction(offset)) * scales[fn]))]
                for fn, length, signed, factor, offset, ctype, overflows in FIELDS for a in ARGUMENTS[ctype]]
    assert got == expected
