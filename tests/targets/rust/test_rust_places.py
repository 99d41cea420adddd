"""The Rust target's field places beyond the Intel frame word: Motorola fields in classic frames
(the word read by `swap_bytes`) and fields of either order in FD frames (byte windows of the
`fd` module), for widths 1..64, signed and unsigned, at the first, a middle and the last start
bit that fit frames of 3, 8, 12 and 64 bytes. Compiled by clippy with warnings denied and run
against a bit-by-bit oracle that reads the field at the DBC bit positions (ir.bits.positions,
which tests/ir checks against cantools): getters and stores."""

from __future__ import annotations

import dataclasses
import os
import subprocess
from pathlib import Path

from canspec import ir
from canspec.ir.bits import fits, positions, segments, storage_bits, word_shift
from canspec.ir.encoding import raw_type_range
from canspec.targets.rust.bits import place, raw_type, store_stmt, unpack_expr
from repo_paths import ROOT
from test_rust_bits import TEMPLATE

FD_MODULE = ROOT / "templates" / "rust" / "static" / "src" / "fd.rs"
LENGTHS = (1, 7, 12, 32, 57, 64)


def field(start: int, length: int, signed: bool, order: str, dlc: int) -> ir.Signal:
    lo, hi = raw_type_range(length, signed)
    shift = word_shift(start, length, order, dlc)
    return dataclasses.replace(TEMPLATE, start=start, length=length, signed=signed, raw_type_min=lo, raw_type_max=hi, raw_min=lo, raw_max=hi,
                               storage_bits=storage_bits(length), segments=segments(start, length, order), word_shift=shift,
                               word_mask=((1 << length) - 1) << shift, byte_order=order, sign_bit=1 << (length - 1) if signed else 0)


def fields() -> list[tuple[ir.Signal, int, bool]]:
    """Fields and the frames they are in: the length, and whether held as bytes (FD frames, and
    classic 8-byte ones whose fields each lie in one byte or are 2 or 4 whole Intel bytes, layout.py)."""
    out = []
    for dlc in (3, 8, 12, 64):
        for order in ("little_endian", "big_endian"):
            for length in LENGTHS + ((2, 8, 16) if dlc == 8 else ()):
                starts = [s for s in range(8 * dlc) if fits(s, length, order, dlc)]
                for start in sorted({starts[0], starts[len(starts) // 2], starts[-1]} if starts else set()):
                    for signed in (False, True):
                        sig = field(start, length, signed, order, dlc)
                        if order == "big_endian" or dlc > 8:  # the Intel frame word: test_rust_bits.py
                            out.append((sig, dlc, dlc > 8))
                        whole = order == "little_endian" and length in (16, 32) and start % 8 == 0
                        if dlc == 8 and (whole or len({seg.byte for seg in sig.segments}) == 1):
                            out.append((sig, dlc, True))
    return out


def case(i: int, sig: ir.Signal, dlc: int, as_bytes: bool) -> str:
    ty = raw_type(sig)
    at = place(sig, dlc, as_bytes)
    holder = f"bytes: [u8; {dlc}]" if as_bytes else "bits: u64"
    load = "bytes: frame.try_into().unwrap()" if as_bytes else "bits: u64::from_le_bytes(padded(frame))"
    unload = "self.bytes.to_vec()" if as_bytes else f"self.bits.to_le_bytes()[..{dlc}].to_vec()"
    pos = ", ".join(str(p) for p in positions(sig.start, sig.length, sig.byte_order))
    return f"""
struct F{i} {{ {holder} }}
impl F{i} {{
    fn new(frame: &[u8]) -> Self {{ Self {{ {load} }} }}
    fn frame(&self) -> Vec<u8> {{ {unload} }}
    fn get(&self) -> {ty} {{ {unpack_expr(sig, at=at)} }}
    fn store(&mut self, value: {ty}) {{ {store_stmt(sig, at=at)} }}
}}
fn check{i}(frames: &[Vec<u8>]) {{
    let at = [{pos}];
    for frame in frames {{
        let frame = &frame[..{dlc}];
        let f = F{i}::new(frame);
        assert_eq!(i128::from(f.get()), field(frame, &at, {str(sig.signed).lower()}), "get {i} {sig.start}/{sig.length}/{sig.byte_order}");
        let other: Vec<u8> = frame.iter().map(|b| !b).collect();
        let mut g = F{i}::new(&other);
        g.store(f.get());
        assert_eq!(g.frame(), merged(&other, frame, &at), "store {i} {sig.start}/{sig.length}/{sig.byte_order}");
    }}
}}
"""


ORACLE = f"""
#[path = "{FD_MODULE}"]
mod fd;

/// The field's raw value, bit by bit: value bit i is frame bit at[i] (bit k of byte n is 8n + k).
fn field(frame: &[u8], at: &[u32], signed: bool) -> i128 {{
    let mut value: i128 = 0;
    for (i, &p) in at.iter().enumerate() {{
        value |= i128::from(frame[(p / 8) as usize] >> (p % 8) & 1) << i;
    }}
    if signed && value >> (at.len() - 1) & 1 == 1 {{
        value -= 1 << at.len();
    }}
    value
}}

/// `outside` with the bits at `at` taken from `inside`.
fn merged(outside: &[u8], inside: &[u8], at: &[u32]) -> Vec<u8> {{
    let mut out = outside.to_vec();
    for &p in at {{
        let (byte, bit) = ((p / 8) as usize, p % 8);
        out[byte] = (out[byte] & !(1 << bit)) | (inside[byte] & (1 << bit));
    }}
    out
}}

fn padded(frame: &[u8]) -> [u8; 8] {{
    let mut out = [0u8; 8];
    out[..frame.len()].copy_from_slice(frame);
    out
}}
"""


def test_motorola_and_fd_places(tmp_path: Path) -> None:
    cases = fields()
    assert len(cases) > 100
    source = ["#![allow(dead_code, clippy::unusual_byte_groupings)]", ORACLE]
    source += [case(i, s, dlc, as_bytes) for i, (s, dlc, as_bytes) in enumerate(cases)]
    source.append(
        "fn main() {\n    let mut s = 0x9E37_79B9_7F4A_7C15_u64;\n"
        "    let mut frames = vec![vec![0u8; 64], vec![0xFF; 64], vec![0x55; 64], vec![0xAA; 64]];\n"
        "    for _ in 0..100 {\n        let mut f = Vec::new();\n"
        "        for _ in 0..8 { s ^= s << 13; s ^= s >> 7; s ^= s << 17; f.extend(s.to_le_bytes()); }\n        frames.push(f);\n    }\n"
        + "".join(f"    check{i}(&frames);\n" for i in range(len(cases)))
        + f'    println!("ok {len(cases)}");\n}}\n'
    )
    src = tmp_path / "places.rs"
    src.write_text("\n".join(source), encoding="utf-8")
    env = {k: v for k, v in os.environ.items() if k != "RUSTFLAGS"}
    lint = subprocess.run(
        ["clippy-driver", "--edition", "2021", "-D", "warnings", "-o", str(tmp_path / "places"), str(src)],
        capture_output=True, text=True, env=env, check=False,
    )
    assert lint.returncode == 0, lint.stderr[-6000:]
    run = subprocess.run([str(tmp_path / "places")], capture_output=True, text=True, check=False)
    assert run.returncode == 0 and run.stdout.strip() == f"ok {len(cases)}", run.stdout + run.stderr[-3000:]


def test_each_field_is_read_as_the_narrowest_integer_that_holds_its_bytes() -> None:
    """An FD frame's field is read as u8, u16, u32, u64 or u128, the narrowest that holds the bytes
    its bits lie in (from the bit positions, not the segments the place is computed from); a field
    of a classic frame held as bytes is its byte indexed, or its whole bytes as one integer; a Motorola field inside
    one byte of the frame word is read unswapped, like an Intel one (the two orders agree within a byte)."""
    seen = set()
    for sig, dlc, as_bytes in fields():
        at = place(sig, dlc, as_bytes)
        touched = {p // 8 for p in positions(sig.start, sig.length, sig.byte_order)}
        span = max(touched) - min(touched) + 1
        if dlc <= 8 and as_bytes and span == 1:
            assert at.bits == 8 and at.read == f"self.bytes[{min(touched)}]", (sig.start, sig.length, sig.byte_order, dlc, at)
            seen.add("classic byte held as bytes")
        elif dlc <= 8 and as_bytes:
            assert at.bits == 8 * span and at.read.startswith(f"u{8 * span}::from_le_bytes([self.bytes[{min(touched)}], "), (sig.start, dlc, at)
            seen.add("classic whole bytes")
        elif as_bytes:
            want = next(n for n in (1, 2, 4, 8, 16) if n >= span)
            assert at.bits == 8 * want and at.read.startswith(f"u{8 * want}::from_"), (sig.start, sig.length, sig.byte_order, dlc, at)
            assert at.window is not None and at.window[0] == min(touched)
            seen.add(want)
        elif span == 1:
            assert not at.swapped and at.read == "self.bits", (sig.start, sig.length, dlc, at)
            seen.add("classic byte")
        else:
            assert at.swapped, (sig.start, sig.length, dlc, at)
    assert seen == {1, 2, 4, 8, 16, "classic byte", "classic byte held as bytes", "classic whole bytes"}
