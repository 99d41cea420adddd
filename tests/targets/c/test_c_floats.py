"""IEEE float fields in C (corners/c_corners.yaml: float32 and float64, both byte orders, with and
without a documented range, classic and FD frames), against the reference codec: every encode of
the doubles around each boundary (the documented range, the largest float32, ±Inf, NaN, subnormals)
gives the reference codec's bit pattern or refuses where it refuses, a NaN giving the canonical
quiet NaN (COMMON rule: NaN encodes to 0x7FC00000 / 0x7FF8000000000000); every decode of a bit
pattern is the float those bits hold; pack(unpack(frame)) keeps every bit pattern (signalling NaN
payloads too) as the reference codec packs it, at strategy 0 and 3. Built with gcc and clang
under UBSan with float-cast-overflow (a finite double beyond the largest float converted to float
is undefined behaviour, which the sanitizer traps)."""

from __future__ import annotations

import math
import struct
import subprocess
from pathlib import Path

import pytest
from canspec.ir.encoding import float_of_bits
from canspec.pipeline import compile_spec
from canspec.reference import codec
from canspec.reference.codec import CodecError
from canspec.targets import registry
from canspec.targets.c.model import build_model

SPEC = Path(__file__).resolve().parent / "corners" / "c_corners.yaml"
FLT_MAX = struct.unpack("<f", b"\xff\xff\x7f\x7f")[0]
QUIET_NAN = {32: 0x7FC00000, 64: 0x7FF8000000000000}


def _double(bits: int) -> float:
    return struct.unpack("<d", bits.to_bytes(8, "little"))[0]


def _bits(value: float) -> int:
    return int.from_bytes(struct.pack("<d", value), "little")


def _inputs() -> list[int]:
    """Doubles (as bit patterns) at and beside every boundary the fields have."""
    edges = [0.0, 1.0, 0.1, 250.3, 0.1, 1000.5, 3.0000001, FLT_MAX, 1e39, 1.401298464324817e-45, 7e-46, 1e-46, 5e-324, 1.7976931348623157e308,
             3.4028235677973366e38, 3.4028235677973362e38]
    out: set[int] = set()
    for x in edges:
        for v in (x, -x):
            out |= {_bits(v), _bits(math.nextafter(v, math.inf)), _bits(math.nextafter(v, -math.inf))}
    out |= {_bits(math.inf), _bits(-math.inf), 0x7FF8000000000000, 0xFFF8000000000000, 0x7FF0000000000001, 0x7FF4000000000000}
    return sorted(out)


PATTERNS = {32: [0, 0x80000000, 1, 0x00800000, 0x7F7FFFFF, 0xFF7FFFFF, 0x7F800000, 0xFF800000, 0x7FC00000, 0x7F800001, 0xFFFFFFFF, 0x3F800000, 0x43FA2666],
            64: [0, 1 << 63, 1, 0x7FEFFFFFFFFFFFFF, 0x7FF0000000000000, 0xFFF0000000000000, 0x7FF8000000000000, 0x7FF0000000000001,
                 0xFFFFFFFFFFFFFFFF, 0x3FF0000000000000, 0xC08F440000000000]}


def _program(c) -> str:  # type: ignore[no-untyped-def]
    lines = [f'#include "{c.prefix}.h"', "#include <stdio.h>", "#include <string.h>", "",
             "static double dbl(uint64_t b) { double d; memcpy(&d, &b, sizeof d); return d; }",
             "static unsigned long long fbits(float f) { uint32_t b; memcpy(&b, &f, sizeof b); return b; }",
             "static unsigned long long dbits(double d) { uint64_t b; memcpy(&b, &d, sizeof b); return b; }",
             "static float flt(uint64_t b) { const uint32_t u = (uint32_t)b; float f; memcpy(&f, &u, sizeof f); return f; }",
             "static const uint64_t inputs[] = {" + ", ".join(f"UINT64_C({b})" for b in _inputs()) + "};", "",
             "int main(void) {", "    size_t i;", "    int st;"]
    for cm in c.messages:
        for s in cm.signals:
            if s.float is None:
                continue
            narrow = s.float.narrows
            lines += [
                "    for (i = 0; i < sizeof inputs / sizeof inputs[0]; i++) {",
                f"        {s.type} r = 0;",
                f"        st = (int){s.fn}_encode(dbl(inputs[i]), &r);",
                f'        printf("E {s.sig.name} %llu %d %llu\\n", (unsigned long long)inputs[i], st, st == 0 ? {"fbits" if narrow else "dbits"}(r) : 0ull);',
                "    }",
            ]
            pats = ", ".join(f"UINT64_C({p})" for p in PATTERNS[s.length])
            lines += [
                "    {", f"        static const uint64_t pats[] = {{{pats}}};", "        for (i = 0; i < sizeof pats / sizeof pats[0]; i++) {",
                f'            printf("D {s.sig.name} %llu %llu\\n", (unsigned long long)pats[i], dbits({s.fn}_decode({"flt" if narrow else "dbl"}(pats[i]))));',
                "        }", "    }",
            ]
    return "\n".join([*lines, "    return 0;", "}", ""])


def _frames(msg) -> list[bytes]:  # type: ignore[no-untyped-def]
    """Frames whose float fields hold every pattern above (other bits from a fixed byte pattern)."""
    out = [bytes([0xFF] * msg.dlc), bytes(msg.dlc), bytes((37 * k + 11) % 256 for k in range(msg.dlc))]
    for sig in msg.signals:
        if sig.is_float:
            for p in PATTERNS[sig.length]:
                raw = {s.name: 0 for s in msg.signals if not s.is_reserved}
                raw[sig.name] = p
                out.append(codec.pack(msg, raw))
    return out


def _roundtrip_program(c, msg_frames) -> str:  # type: ignore[no-untyped-def]
    lines = [f'#include "{c.prefix}.h"', "#include <stdio.h>", "", "int main(void) {", "    size_t k;"]
    for cm, frames in msg_frames:
        data = ", ".join("{" + ", ".join(str(b) for b in f) + "}" for f in frames)
        lines += ["    {", f"        static const uint8_t in[{len(frames)}][{cm.msg.dlc}] = {{{data}}};",
                  "        for (k = 0; k < sizeof in / sizeof in[0]; k++) {", f"            {cm.type} v;", f"            uint8_t out[{cm.msg.dlc}];",
                  "            size_t j;",
                  f"            const int u = (int){cm.fn}_unpack(&v, in[k], sizeof in[k]);",
                  f"            const int p = (int){cm.fn}_pack(out, sizeof out, &v);",
                  f'            printf("R {cm.msg.name} %d %d ", u, p);', '            for (j = 0; j < sizeof out; j++) printf("%02X", out[j]);',
                  '            printf("\\n");', "        }", "    }"]
    return "\n".join([*lines, "    return 0;", "}", ""])


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    work = tmp_path_factory.mktemp("c-floats")
    spec = compile_spec(SPEC).spec
    assert spec is not None and spec.can is not None
    for rel, data in registry()["c"].render(spec).items():
        (work / rel).parent.mkdir(parents=True, exist_ok=True)
        (work / rel).write_bytes(data)
    return spec.can, build_model(spec), work


CONFIGS = [("gcc", "3"), ("clang", "3"), ("gcc", "0"), ("clang", "0")]
SANITIZE = ["-fsanitize=undefined,float-cast-overflow", "-fno-sanitize-recover=all"]
WARN = ["-Wall", "-Wextra", "-Wpedantic", "-Wconversion", "-Wdouble-promotion", "-Wfloat-equal", "-Werror"]


def _run(work: Path, name: str, source: str, cc: str, strategy: str) -> str:
    src = work / f"{name}.c"
    src.write_text(source, encoding="utf-8")
    exe = work / f"{name}-{cc}-{strategy}"
    cmd = [cc, "-std=c99", "-O2", *WARN, *SANITIZE, f"-DC_CORNERS_STRATEGY={strategy}", f"-I{work / 'c'}", str(src), "-o", str(exe)]
    subprocess.run(cmd, check=True, capture_output=True, text=True)
    proc = subprocess.run([str(exe)], capture_output=True, text=True, check=False)
    assert proc.returncode == 0 and "runtime error" not in proc.stderr, proc.stderr[-3000:]
    return proc.stdout


def _want_encode(sig, x: float) -> int | None:  # type: ignore[no-untyped-def]
    if math.isnan(x):
        return None if sig.doc_min is not None else QUIET_NAN[sig.length]
    try:
        return codec.float_raw(sig, x)
    except (CodecError, OverflowError):
        return None


@pytest.mark.parametrize("cc,strategy", CONFIGS)
def test_float_encode_and_decode_agree_with_the_reference_codec(built, cc, strategy):
    can, c, work = built
    sigs = {s.name: s for m in can.messages for s in m.signals if s.is_float}
    out = _run(work, "edges", _program(c), cc, strategy)
    bad, checked = [], 0
    for line in out.splitlines():
        kind, name, arg, *got = line.split()
        sig = sigs[name]
        if kind == "E":
            st, bits = int(got[0]), int(got[1])
            want = _want_encode(sig, _double(int(arg)))
            ok = (st != 0) if want is None else (st == 0 and bits == want)
        else:
            value, want_value = _double(int(got[0])), float_of_bits(int(arg), sig.length)
            ok = math.isnan(value) if math.isnan(want_value) else int(got[0]) == _bits(want_value)
        checked += 1
        if not ok:
            bad.append(f"{line}  (want {want if kind == 'E' else want_value!r})")
    assert checked == len(sigs) * len(_inputs()) + sum(len(PATTERNS[s.length]) for s in sigs.values())
    assert not bad, "\n".join(bad[:40])


@pytest.mark.parametrize("cc,strategy", CONFIGS)
def test_pack_of_unpack_keeps_every_float_bit_pattern(built, cc, strategy):
    can, c, work = built
    by_name = {cm.msg.name: cm for cm in c.messages}
    msg_frames = [(by_name[m.name], _frames(m)) for m in can.messages if m.has_float]
    out = _run(work, "roundtrip", _roundtrip_program(c, msg_frames), cc, strategy)
    want = [f"R {cm.msg.name} 0 0 {codec.pack(cm.msg, codec.unpack(cm.msg, f)).hex().upper()}" for cm, frames in msg_frames for f in frames]
    assert out.splitlines() == want
