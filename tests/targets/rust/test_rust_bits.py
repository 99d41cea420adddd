"""The Rust target's bit expressions for every field width 1..64, signed and unsigned, at the
first, a middle and the last start bit: compiled by clippy with warnings denied (no cast to the
same type, no identity mask or shift) and run against a bit-by-bit oracle on pseudo-random frame
words — getters, stores and the raw setters' fit checks."""

from __future__ import annotations

import dataclasses
import os
import subprocess
from pathlib import Path

from canspec import ir
from canspec.ir.bits import segments, storage_bits
from canspec.ir.encoding import raw_type_range
from canspec.render.literals import RUST
from canspec.targets.rust.bits import misfit_expr, raw_type, store_stmt, unpack_expr

TEMPLATE = ir.Signal(
    name="x", c_name="x", zh="", desc="", desc_zh="", start=0, length=1, signed=False, factor=1, offset=0, unit="", role="data", doc_min=None, doc_max=None,  # type: ignore[arg-type]
    raw_type_min=0, raw_type_max=1, raw_min=0, raw_max=1, phys_min=0, phys_max=1, check_min=0, check_max=1, accept_min=0, accept_max=1,  # type: ignore[arg-type]
    storage_bits=8, value_table=None, specials=(), segments=(), word_shift=0, word_mask=1, sign_bit=0, labels=(), decimals=0, is_integer=True,
    is_identity=True, since=None, errata=(),
)


def field(start: int, length: int, signed: bool) -> ir.Signal:
    lo, hi = raw_type_range(length, signed)
    return dataclasses.replace(TEMPLATE, start=start, length=length, signed=signed, raw_type_min=lo, raw_type_max=hi, raw_min=lo, raw_max=hi,
                               storage_bits=storage_bits(length), segments=segments(start, length), word_shift=start, word_mask=((1 << length) - 1) << start,
                               sign_bit=1 << (length - 1) if signed else 0)


FIELDS = [field(start, length, signed) for length in range(1, 65) for signed in (False, True) for start in sorted({0, (64 - length) // 2, 64 - length})]


def case(i: int, sig: ir.Signal) -> str:
    ty = raw_type(sig)
    lo, hi = raw_type_range(sig.storage_bits, sig.signed)
    probes = sorted({lo, hi, sig.raw_type_min, sig.raw_type_max, 0, min(sig.raw_type_max + 1, hi), max(sig.raw_type_min - 1, lo)})
    misfit = misfit_expr(sig)
    check = f"fn misfit(value: {ty}) -> bool {{ {misfit} }}" if misfit else f"fn misfit(_: {ty}) -> bool {{ false }}"  # every value fits
    return f"""
struct F{i} {{ bits: u64 }}
impl F{i} {{
    fn get(&self) -> {ty} {{ {unpack_expr(sig)} }}
    fn store(&mut self, value: {ty}) {{ {store_stmt(sig)} }}
    {check}
}}
fn check{i}(words: &[u64]) {{
    for &w in words {{
        let f = F{i} {{ bits: w }};
        let want = field(w, {sig.start}, {sig.length}, {str(sig.signed).lower()});
        assert_eq!(i128::from(f.get()), want, "get {sig.start}/{sig.length}/{sig.signed} of {{w:#x}}");
        let mut g = F{i} {{ bits: !w }};
        g.store(f.get());
        assert_eq!(g.bits, merged(!w, w, {RUST.integer(sig.word_mask)}), "store {sig.start}/{sig.length}");
    }}
    for v in [{", ".join(f"{RUST.integer(p)}_i128" for p in probes)}] {{
        let fits = ({sig.raw_type_min}_i128..={sig.raw_type_max}_i128).contains(&v);
        assert_eq!(F{i}::misfit(v as {ty}), !fits, "misfit {sig.start}/{sig.length}/{sig.signed} {{v}}");
    }}
}}
"""


ORACLE = """
/// The field's raw value, bit by bit.
fn field(word: u64, start: u32, length: u32, signed: bool) -> i128 {
    let mut value: i128 = 0;
    for i in 0..length {
        value |= i128::from((word >> (start + i)) & 1) << i;
    }
    if signed && value >> (length - 1) & 1 == 1 {
        value -= 1 << length;
    }
    value
}

/// `outside` with the bits of `mask` taken from `inside`.
fn merged(outside: u64, inside: u64, mask: u64) -> u64 {
    (outside & !mask) | (inside & mask)
}
"""


def test_bit_expressions_for_every_width(tmp_path: Path) -> None:
    source = ["#![allow(dead_code, clippy::unusual_byte_groupings)]", ORACLE]
    source += [case(i, s) for i, s in enumerate(FIELDS)]
    source.append(
        "fn main() {\n    let mut s = 0x9E37_79B9_7F4A_7C15_u64;\n    let mut words = vec![0, u64::MAX, 0x5555_5555_5555_5555, 0xAAAA_AAAA_AAAA_AAAA];\n"
        "    for _ in 0..200 { s ^= s << 13; s ^= s >> 7; s ^= s << 17; words.push(s); }\n"
        + "".join(f"    check{i}(&words);\n" for i in range(len(FIELDS)))
        + '    println!("ok {}", '
        + str(len(FIELDS))
        + ");\n}\n"
    )
    src = tmp_path / "bits.rs"
    src.write_text("\n".join(source), encoding="utf-8")
    env = {k: v for k, v in os.environ.items() if k != "RUSTFLAGS"}
    lint = subprocess.run(
        ["clippy-driver", "--edition", "2021", "-D", "warnings", "-o", str(tmp_path / "bits"), str(src)], capture_output=True, text=True, env=env, check=False
    )
    assert lint.returncode == 0, lint.stderr[-6000:]
    run = subprocess.run([str(tmp_path / "bits")], capture_output=True, text=True, check=False)
    assert run.returncode == 0 and run.stdout.strip() == f"ok {len(FIELDS)}", run.stdout + run.stderr[-3000:]
