"""The Rust source of `make bench-rust` (bench.py): one module per message with the same cases
set against canspec's crate and dbc-codegen's code (encode from physical values, decode and read
every signal, dbc-codegen's decode with the XOR check a user adds), and a main that times each
pair or, given `count`, runs every loop COUNT_REPS times for callgrind."""

from __future__ import annotations

import re

from canspec.targets.rust.model import RustCrate, RustMessage

COUNT_REPS = 64


def parse_dbc_code(text: str) -> tuple[dict[str, list[tuple[str, str]]], dict[str, str], dict[tuple[str, str], str]]:
    """dbc-codegen's API as generated: `new` parameters per struct, the catch-all payload type
    of each enum, and each getter's return type."""
    news: dict[str, list[tuple[str, str]]] = {}
    getters: dict[tuple[str, str], str] = {}
    for m in re.finditer(r"^impl (\w+) \{\n(.*?)^\}", text, re.DOTALL | re.MULTILINE):
        body = m.group(2)
        new = re.search(r"    pub fn new\(\n?(.*?)\) -> Result<Self, CanError>", body, re.DOTALL)
        if new is None:
            continue
        params = re.findall(r"(\w+): ([\w:]+)(?:,|$)", new.group(1).strip())  # rustfmt: one line (no trailing comma) or one per line
        news[m.group(1)] = params
        for g in re.finditer(r"    pub fn (\w+)\(\s*&self,?\s*\) -> ([\w:]+) \{", body):  # rustfmt wraps long ones
            getters[(m.group(1), g.group(1))] = g.group(2)
    others = dict(re.findall(r"pub enum (\w+) \{[^}]*?_Other\((\w+)\),", text, re.DOTALL))
    # Named variants by value, so both sides are given the same kind of enum values.
    variants: dict[str, dict[str, str]] = {}
    for m in re.finditer(r"impl From<(\w+)> for \w+ \{(.*?)\n\}", text, re.DOTALL):
        variants[m.group(1)] = {value.strip(): name for name, value in re.findall(r"\w+::(\w+) => ([^,]+),", m.group(2)) if name != "_Other"}
    VARIANTS.update(variants)
    return news, others, getters


VARIANTS: dict[str, dict[str, str]] = {}


def f64_lit(value: float) -> str:
    text = repr(float(value))
    return text if any(c in text for c in ".e") else f"{text}.0"


def ours_value(f, value) -> str:  # type: ignore[no-untyped-def]
    if f.kind == "float":
        return f64_lit(value)
    if f.kind == "enum":
        return f"{f.enum.name}::from_raw({int(value)})"
    if f.kind == "scaled_int" and value != int(value):
        return ""  # a tie input the integer-typed API cannot take
    return str(int(value))


def theirs_value(ty: str, others: dict[str, str], value) -> str:  # type: ignore[no-untyped-def]
    if ty in others:
        inner = theirs_value(others[ty], others, value)
        named = VARIANTS.get(ty, {}).get(inner)
        return f"dbc::{ty}::{named}" if named else f"dbc::{ty}::_Other({inner})"
    if ty == "bool":
        return "true" if value else "false"
    if ty in ("f32", "f64"):
        return f"{f64_lit(value)} as {ty}"
    return str(int(value))


def read_back(ty: str, others: dict[str, str], expr: str) -> tuple[str, str]:
    """A dbc-codegen getter's value: ("int", expression as u64) or ("float", expression as f64)."""
    if ty in others:
        return read_back(others[ty], others, f"{others[ty]}::from({expr})")
    if ty in ("f32", "f64"):
        return "float", f"(({expr}) as f64)"
    return "int", f"(({expr}) as u64)"


def consume(parts: list[tuple[str, str]]) -> str:
    """Statements adding every value to the accumulators: integer values (enums, flags,
    counters) as integers and fractional ones as doubles, the same on both sides, so that the
    time measured is the codec's and not that of integer→double conversions (a 0/1 flag
    converted to a double compiles to a data-dependent branch)."""
    out = [f"acc_i = acc_i.wrapping_add({e});" for k, e in parts if k == "int"]
    out += [f"acc += {e};" for k, e in parts if k == "float"]
    return " ".join(out)


def _folded(name: str) -> str:
    return name.replace("_", "").lower()


def spec_names(dbc_names: dict[tuple[str, str], str], msg) -> dict[str, str]:  # type: ignore[no-untyped-def]
    """dbc-codegen's parameter name (snake case of the DBC's signal name, which may carry the
    frame ID to be unique in the DBC) → the spec's signal name; both fold to the same letters."""
    return {_folded(dbc): spec for (m, spec), dbc in dbc_names.items() if m == msg.name}




MODULE = """
#[allow(clippy::all, unused_imports, unused_variables)]
mod {msg} {{
    use super::*;
    use kaiwo::*;
    pub const NAME: &str = "{msg}";
    pub static FRAMES: [[u8; {dlc}]; {k}] = [{frames}];
    pub static OURS: [{values}; {k}] = [{ours}];
    pub static THEIRS: [{theirs_types}; {k}] = [{theirs}];

    #[inline(never)]
    pub fn ours_encode() -> u64 {{
        let mut acc = 0u64;
        for v in OURS.iter() {{
            match {name}::from_values(black_box(v)) {{
                Ok(m) => acc ^= {ours_fold},
                Err(_) => acc += 1,
            }}
        }}
        acc
    }}

    #[inline(never)]
    pub fn theirs_encode() -> u64 {{
        let mut acc = 0u64;
        for t in THEIRS.iter() {{
            let t = black_box(t);
            match dbc::{name}::new({theirs_args}) {{
                Ok(m) => acc ^= {theirs_fold},
                Err(_) => acc += 1,
            }}
        }}
        acc
    }}

    #[inline(never)]
    pub fn ours_decode() -> f64 {{
        let (mut acc, mut acc_i) = (0.0, 0u64);
        for f in FRAMES.iter() {{
            match {name}::decode(black_box(&f[..])) {{
                Ok(m) => {{ {ours_sum} }}
                Err(_) => acc += 1.0,
            }}
        }}
        acc + acc_i as f64
    }}

    #[inline(never)]
    pub fn theirs_decode() -> f64 {{
        let (mut acc, mut acc_i) = (0.0, 0u64);
        for f in FRAMES.iter() {{
            match dbc::{name}::try_from(black_box(&f[..])) {{
                Ok(m) => {{ {theirs_sum} }}
                Err(_) => acc += 1.0,
            }}
        }}
        acc + acc_i as f64
    }}

{checked}
    /// (ours refused, ours wrong bytes, theirs refused, theirs wrong bytes)
    pub fn correctness() -> (usize, usize, usize, usize) {{
        let mut out = (0, 0, 0, 0);
        for ((v, t), f) in OURS.iter().zip(THEIRS.iter()).zip(FRAMES.iter()) {{
            match {name}::from_values(v) {{
                Ok(m) if m.encode()[..{dlc}] == f[..] => {{}}
                Ok(_) => out.1 += 1,
                Err(_) => out.0 += 1,
            }}
            match dbc::{name}::new({theirs_args}) {{
                Ok(m) if m.raw() == f => {{}}
                Ok(_) => out.3 += 1,
                Err(_) => out.2 += 1,
            }}
        }}
        out
    }}
}}
"""

CHECKED = """
    /// dbc-codegen's decode plus the checksum test a user adds to get canspec's guarantee.
    #[inline(never)]
    pub fn theirs_decode_checked() -> f64 {{
        let (mut acc, mut acc_i) = (0.0, 0u64);
        for f in FRAMES.iter() {{
            let d = black_box(&f[..]);
            if d.len() < {dlc} || {xor} != d[{byte}] {{
                acc += 1.0;
                continue;
            }}
            match dbc::{name}::try_from(d) {{
                Ok(m) => {{ {theirs_sum} }}
                Err(_) => acc += 1.0,
            }}
        }}
        acc + acc_i as f64
    }}
"""


def message_module(rm: RustMessage, cases: list[dict], api: tuple, names: dict[str, str]) -> str:  # type: ignore[type-arg]
    """The message's module: its frames and both sides' inputs, and the loops timed."""
    news, others, getters = api
    params = [(names.get(_folded(p), p), p, ty) for p, ty in news[rm.name]]
    by_name = {f.sig.name: f for f in rm.fields}
    checksum = rm.msg.checksum.signal if rm.msg.checksum is not None else None
    theirs_sum = consume([read_back(getters[(rm.name, p)], others, f"m.{p}()") for s, p, _ in params if s in by_name or s == checksum])
    fields = {"msg": rm.msg.name, "dlc": rm.msg.dlc, "name": rm.name, "theirs_sum": theirs_sum}
    checked = ""
    if rm.msg.checksum is not None:
        ck = rm.msg.checksum
        checked = CHECKED.format(**fields, byte=ck.byte, xor=" ^ ".join(f"d[{b}]" for b in ck.covers))
    return MODULE.format(
        **fields,
        k=len(cases),
        values=rm.values,
        frames=",\n".join("[" + ", ".join(f"0x{b:02X}" for b in bytes.fromhex(c["data"])) + "]" for c in cases),
        ours=",\n".join(f"{rm.values} {{ " + ", ".join(f"{f.names.field}: {ours_value(f, c['physical'][f.sig.name])}" for f in rm.fields) + " }"
                         for c in cases),
        theirs=",\n".join("(" + "".join(f"{theirs_value(ty, others, c['physical'].get(s, c['raw'].get(s)))}, " for s, _, ty in params) + ")"
                           for c in cases),
        theirs_types="(" + "".join(f"dbc::{ty}, " if ty in others else f"{ty}, " for _, _, ty in params) + ")",
        theirs_args=", ".join(f"t.{i}" for i in range(len(params))),
        ours_sum=_ours_sum(rm),
        checked=checked,
        ours_fold=fold("m.encode()", max(rm.msg.dlc, 8)),
        theirs_fold=fold("*m.raw()", rm.msg.dlc),
    )


def _ours_sum(rm: RustMessage) -> str:
    return consume([
        ("float", f"m.{f.names.getter}()") if f.kind == "float"
        else ("int", f"(m.{f.names.getter}().raw() as u64)" if f.kind == "enum" else f"(m.{f.names.getter}() as u64)")
        for f in rm.fields
    ])


MAIN_HEAD = """// Benchmark harness written by tests/targets/rust/bench.py (build directory only, not committed).
use std::hint::black_box;
use std::time::Instant;
use {package} as kaiwo;

#[allow(clippy::all, dead_code, unused_imports, unused_variables, unused_comparisons, unreachable_patterns, non_camel_case_types)]
mod dbc;

/// Calls of `f` that take at least 1 ms.
fn calibrate<T>(mut f: impl FnMut() -> T) -> u32 {{
    let mut reps = 1u32;
    loop {{
        let start = Instant::now();
        for _ in 0..reps {{
            black_box(f());
        }}
        if start.elapsed().as_micros() >= 1000 {{
            return reps;
        }}
        reps *= 2;
    }}
}}

fn run<T>(reps: u32, frames: usize, f: &mut impl FnMut() -> T) -> f64 {{
    let start = Instant::now();
    for _ in 0..reps {{
        black_box(f());
    }}
    start.elapsed().as_nanos() as f64 / (reps as f64 * frames as f64)
}}

/// Nanoseconds per frame of `a` and `b` (each handles `frames` frames per call): the best of
/// 61 alternating short runs, so both see the same machine load and the best of each is a run
/// no other process interrupted.
fn time_pair<T, U>(frames: usize, mut a: impl FnMut() -> T, mut b: impl FnMut() -> U) -> (f64, f64) {{
    let (ra, rb) = (calibrate(&mut a), calibrate(&mut b));
    let (mut ta, mut tb) = (f64::INFINITY, f64::INFINITY);
    for _ in 0..61 {{
        ta = ta.min(run(ra, frames, &mut a));
        tb = tb.min(run(rb, frames, &mut b));
    }}
    (ta, tb)
}}
"""


def fold(frame: str, dlc: int) -> str:
    """A u64 the encoded frame feeds into (so the compiler keeps the encode): the 8-byte word of a classic frame,
    the first and last 8 bytes of a longer CAN FD one, the first byte of a shorter one."""
    if dlc == 8:
        return f"u64::from_le_bytes({frame})"
    if dlc < 8:
        return f"{{ let b = {frame}; u64::from(b[0]) }}"
    return f"{{ let b = {frame}; u64::from_le_bytes(b[..8].try_into().unwrap()) ^ u64::from_le_bytes(b[{dlc - 8}..].try_into().unwrap()) }}"




REPORT = r"""
    println!("| message | cases | encode canspec ns | encode dbc-codegen ns | ratio | decode canspec ns | decode dbc-codegen ns | ratio | \
              decode ratio vs dbc-codegen + XOR check | dbc-codegen refused / wrong bytes |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let (mut slower, mut ours_bad) = (Vec::new(), 0);
    let (mut te, mut ce, mut td, mut cd, mut n) = (0.0, 0.0, 0.0, 0.0, 0usize);
    for (name, k, oe, de, od, dd, ck, c) in &rows {
        let (re, rd) = (de / oe, dd / od);
        let checked = ck.map_or("—".to_string(), |(o, t)| format!("{:.2} ({o:.1} / {t:.1} ns)", t / o));
        println!("| {name} | {k} | {oe:.1} | {de:.1} | {re:.2} | {od:.1} | {dd:.1} | {rd:.2} | {checked} | {} / {} |", c.2, c.3);
        // Within 3 %: the same speed (identical layouts differ by that much from run to run).
        if re < 0.97 || rd < 0.97 {
            slower.push(*name);
        }
        ours_bad += c.0 + c.1;
        ce += oe * *k as f64; te += de * *k as f64; cd += od * *k as f64; td += dd * *k as f64; n += k;
    }
    let n = n as f64;
    println!("| **all** | {} | {:.1} | {:.1} | {:.2} | {:.1} | {:.1} | {:.2} | | |", n, ce / n, te / n, te / ce, cd / n, td / n, td / cd);
    println!("ratio = dbc-codegen ns / canspec ns (above 1: canspec faster); canspec's decode also verifies the XOR checksum, which dbc-codegen's \
              does not: the XOR-check column times dbc-codegen with that test added");
    if ours_bad > 0 {
        println!("canspec refused or mis-encoded {ours_bad} vector cases");
        std::process::exit(1);
    }
    if slower.is_empty() {
        println!("canspec is at least as fast as dbc-codegen on every message (within 3 % noise)");
    } else {
        println!("canspec is more than 3 % slower than dbc-codegen on: {}", slower.join(", "));
    }
}
"""


def main_rs(crate: RustCrate, modules: list[str], rows: list[tuple[str, bool]]) -> str:
    """The harness: every module, then a main that times each message's pairs (or counts them)."""
    body = MAIN_HEAD.format(package=crate.package) + "".join(modules)
    body += "\nfn main() {\n"
    # `count`: one pass of every loop COUNT_REPS times, for callgrind's instruction counts.
    body += f"    if std::env::args().nth(1).as_deref() == Some(\"count\") {{\n        for _ in 0..{COUNT_REPS} {{\n"
    for name, has_checksum in rows:
        fns = ["ours_encode", "theirs_encode", "ours_decode", "theirs_decode"] + (["theirs_decode_checked"] if has_checksum else [])
        body += "".join(f"            black_box({name}::{f}());\n" for f in fns)
    body += "        }\n        return;\n    }\n    let mut rows = Vec::new();\n"
    for name, has_checksum in rows:
        body += (
            f"    let (oe, de) = time_pair({name}::FRAMES.len(), {name}::ours_encode, {name}::theirs_encode);\n"
            f"    let (od, dd) = time_pair({name}::FRAMES.len(), {name}::ours_decode, {name}::theirs_decode);\n"
            + (
                f"    let ck = Some(time_pair({name}::FRAMES.len(), {name}::ours_decode, {name}::theirs_decode_checked));\n"
                if has_checksum
                else "    let ck: Option<(f64, f64)> = None;\n"
            )
            + f"    rows.push(({name}::NAME, {name}::FRAMES.len(), oe, de, od, dd, ck, {name}::correctness()));\n"
        )
    return body + REPORT
