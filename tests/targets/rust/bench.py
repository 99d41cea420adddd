"""`make bench-rust`: encode and decode of every message, canspec's crate vs the code
dbc-codegen generates from the generated DBC, in one optimized binary. Prints ns per frame
and the ratio (dbc-codegen time / canspec time: above 1 means canspec is faster).

Inputs are the shared vectors (every physical-encodable case of each message): encode builds
a message from physical values and produces the bytes; decode parses the bytes and reads
every signal's value. dbc-codegen-cli is installed from crates.io into build/rust-bench/.
Also reported: how many of the vectors dbc-codegen refuses or encodes to other bytes.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
sys.path.insert(0, str(ROOT / "generator"))

from canspec import ir
from canspec.pipeline import compile_spec
from canspec.targets.dbc.naming import signal_names
from canspec.targets.rust.model import RustMessage, build_crate

BUILD = ROOT / "build" / "rust-bench"
# `--spec DIR --generated DIR`: another spec (the second benchmark spec, bench/spec2.py) and its generated outputs
SPEC, GENERATED = ROOT / "spec", ROOT / "generated"
DBC_CODEGEN_VERSION = "0.4.0"


def run(cmd: list[str], **kw) -> subprocess.CompletedProcess:  # type: ignore[type-arg,no-untyped-def]
    print("+", " ".join(cmd), file=sys.stderr)
    return subprocess.run(cmd, check=True, **kw)


def dbc_codegen() -> Path:
    exe = BUILD / "tools" / "bin" / "dbc-codegen"
    if not exe.exists():
        run(["cargo", "install", "--locked", "--quiet", "dbc-codegen-cli", "--version", DBC_CODEGEN_VERSION, "--root", str(BUILD / "tools")])
    return exe


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


def message_module(rm: RustMessage, cases: list[dict], api: tuple, names: dict[str, str]) -> str:  # type: ignore[type-arg]
    news, others, getters = api
    name = rm.name
    params = [(names.get(_folded(p), p), p, ty) for p, ty in news[name]]
    by_name = {f.sig.name: f for f in rm.fields}
    k = len(cases)
    frames = ",\n".join("[" + ", ".join(f"0x{b:02X}" for b in bytes.fromhex(c["data"])) + "]" for c in cases)
    ours = ",\n".join(
        f"{rm.values} {{ " + ", ".join(f"{f.names.field}: {ours_value(f, c['physical'][f.sig.name])}" for f in rm.fields) + " }"
        for c in cases
    )
    theirs = ",\n".join(
        "(" + "".join(f"{theirs_value(ty, others, c['physical'].get(s, c['raw'].get(s)))}, " for s, _, ty in params) + ")" for c in cases
    )
    theirs_types = "(" + "".join(f"dbc::{ty}, " if ty in others else f"{ty}, " for _, _, ty in params) + ")"
    theirs_args = ", ".join(f"t.{i}" for i in range(len(params)))
    ours_sum = consume([
        ("float", f"m.{f.names.getter}()") if f.kind == "float"
        else ("int", f"(m.{f.names.getter}().raw() as u64)" if f.kind == "enum" else f"(m.{f.names.getter}() as u64)")
        for f in rm.fields
    ])
    checksum = rm.msg.checksum.signal if rm.msg.checksum is not None else None
    theirs_sum = consume([read_back(getters[(name, p)], others, f"m.{p}()") for s, p, _ in params if s in by_name or s == checksum])
    checked = ""
    if rm.msg.checksum is not None:
        ck = rm.msg.checksum
        xor = " ^ ".join(f"d[{b}]" for b in ck.covers)
        checked = f"""
    /// dbc-codegen's decode plus the checksum test a user adds to get canspec's guarantee.
    #[inline(never)]
    pub fn theirs_decode_checked() -> f64 {{
        let (mut acc, mut acc_i) = (0.0, 0u64);
        for f in FRAMES.iter() {{
            let d = black_box(&f[..]);
            if d.len() < {rm.msg.dlc} || {xor} != d[{ck.byte}] {{
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
    return f"""
#[allow(clippy::all, unused_imports, unused_variables)]
mod {rm.msg.name} {{
    use super::*;
    use kaiwo::*;
    pub const NAME: &str = "{rm.msg.name}";
    pub static FRAMES: [[u8; {rm.msg.dlc}]; {k}] = [{frames}];
    pub static OURS: [{rm.values}; {k}] = [{ours}];
    pub static THEIRS: [{theirs_types}; {k}] = [{theirs}];

    #[inline(never)]
    pub fn ours_encode() -> u64 {{
        let mut acc = 0u64;
        for v in OURS.iter() {{
            match {name}::from_values(black_box(v)) {{
                Ok(m) => acc ^= {fold("m.encode()", max(rm.msg.dlc, 8))},
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
                Ok(m) => acc ^= {fold("*m.raw()", rm.msg.dlc)},
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
                Ok(m) if m.encode()[..{rm.msg.dlc}] == f[..] => {{}}
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


def main() -> int:
    compiled = compile_spec(SPEC, ["rust", "dbc", "vectors"])  # only the targets benchmarked check the spec
    spec: ir.Spec | None = compiled.spec
    if spec is None or spec.can is None:
        print("bench-rust: the spec does not compile", file=sys.stderr)
        return 1
    if shutil.which("cargo") is None:
        print("bench-rust: cargo not found", file=sys.stderr)
        return 1
    crate = build_crate(spec.can)
    vectors = json.loads((GENERATED / "vectors" / "can.json").read_text(encoding="utf-8"))
    src = BUILD / "crate" / "src"
    src.mkdir(parents=True, exist_ok=True)
    gen_out = BUILD / "dbc-codegen-out"
    shutil.rmtree(gen_out, ignore_errors=True)
    gen_out.mkdir(parents=True)
    try:
        run([str(dbc_codegen()), str(GENERATED / "dbc" / f"{spec.can.name}.dbc"), str(gen_out)], stdout=subprocess.DEVNULL)
    except subprocess.CalledProcessError as exc:
        print(f"bench-rust: dbc-codegen failed on the generated DBC (exit {exc.returncode})", file=sys.stderr)
        return 1
    code = (gen_out / "messages.rs").read_text(encoding="utf-8")
    (src / "dbc.rs").write_text(code, encoding="utf-8")
    api = parse_dbc_code(code)
    missing = [m.name for m in crate.messages if m.name not in api[0]]
    if missing:
        print(f"bench-rust: dbc-codegen produced no constructor for {', '.join(missing)}", file=sys.stderr)
        return 1
    modules, rows = [], []
    counts: dict[str, int] = {}
    dbc_names = signal_names(spec.can)  # the DBC target's own naming (unique names carry the frame ID)
    paged = [rm.msg.name for rm in crate.messages if rm.msg.is_multiplexed]
    if paged:  # dbc-codegen builds a page through an enum of its multiplexer values: no flat constructor to set against ours
        print(f"bench-rust: multiplexed messages not compared (dbc-codegen's pages are enums, not flat constructors): {', '.join(paged)}")
    for rm in crate.messages:
        if rm.msg.is_multiplexed:
            continue
        # Physical-encodable cases; ties of integer-valued signals have no whole-number input.
        cases = [c for c in vectors["cases"] if c["message"] == rm.msg.name and c["kind"] != "raw_only"
                 and all(float(c["physical"][f.sig.name]).is_integer() for f in rm.fields if f.kind == "scaled_int")]
        if not cases:
            continue
        modules.append(message_module(rm, cases, api, spec_names(dbc_names, rm.msg)))
        rows.append((rm.msg.name, rm.msg.checksum is not None))
        counts[rm.msg.name] = len(cases)
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
    body += r"""
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
    (src / "main.rs").write_text(body, encoding="utf-8")
    (BUILD / "crate" / "Cargo.toml").write_text(
        f"""[package]
name = "canspec-rust-bench"
version = "0.0.0"
edition = "2021"
publish = false

[dependencies]
{crate.package} = {{ path = {json.dumps(str(GENERATED / "rust"))}, default-features = false }}
bitvec = {{ version = "1", default-features = false }}
embedded-can = "0.4"

[profile.release]
codegen-units = 1
lto = true
""",
        encoding="utf-8",
    )
    env = {**os.environ, "CARGO_TARGET_DIR": str(BUILD / "target")}
    run(["cargo", "build", "--release", "--quiet"], cwd=BUILD / "crate", env=env)
    exe = BUILD / "target" / "release" / "canspec-rust-bench"
    sys.stdout.flush()
    run([str(exe)], cwd=BUILD / "crate")
    sys.stdout.flush()
    instruction_counts(exe, [(name, counts[name], ck) for name, ck in rows])
    return 0


COUNT_REPS = 64


def instruction_counts(exe: Path, rows: list[tuple[str, int, bool]]) -> None:
    """Instructions per frame of each loop, from callgrind: independent of machine load and
    of code alignment, so two loops LLVM compiled to the same instructions count the same."""
    if shutil.which("valgrind") is None or shutil.which("callgrind_annotate") is None:
        print("\ninstruction counts: valgrind not installed, skipped")
        return
    out = BUILD / "bench.callgrind"
    run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", str(exe), "count"], capture_output=True)
    text = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", str(out)],
                          check=True, capture_output=True, text=True).stdout
    ir: dict[tuple[str, str], int] = {}
    for line in text.splitlines():
        m = re.match(r"\s*([\d,]+)\s.*canspec_rust_bench::(\w+)::(\w+)\b", line)
        if m:
            ir[(m.group(2), m.group(3))] = int(m.group(1).replace(",", ""))
    print("\n| message | encode canspec Ir | encode dbc-codegen Ir | ratio | decode canspec Ir | decode dbc-codegen Ir | ratio | "
          "decode dbc-codegen + XOR check Ir | ratio |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    tot = [0.0] * 5  # the fifth: dbc-codegen's decode with the XOR check on every checksum message (like for like)
    more = []
    for name, k, has_checksum in rows:
        per = {f: ir.get((name, f), 0) / (COUNT_REPS * k) for f in ("ours_encode", "theirs_encode", "ours_decode", "theirs_decode", "theirs_decode_checked")}
        oe, te, od, td, tc = (per[f] for f in ("ours_encode", "theirs_encode", "ours_decode", "theirs_decode", "theirs_decode_checked"))
        for i, v in enumerate((oe, te, od, td, tc if has_checksum else td)):
            tot[i] += v * k
        ck = f"{tc:.1f} | {tc / od:.2f}" if has_checksum else "— | —"
        print(f"| {name} | {oe:.1f} | {te:.1f} | {te / oe:.2f} | {od:.1f} | {td:.1f} | {td / od:.2f} | {ck} |")
        if oe > te:
            more.append(f"{name} encode")
        if od > (tc if has_checksum else td):
            more.append(f"{name} decode")
    print(f"| **all** | {tot[0] / sum(c for _, c, _ in rows):.1f} | {tot[1] / sum(c for _, c, _ in rows):.1f} | {tot[1] / tot[0]:.2f} | "
          f"{tot[2] / sum(c for _, c, _ in rows):.1f} | {tot[3] / sum(c for _, c, _ in rows):.1f} | {tot[3] / tot[2]:.2f} | "
          f"{tot[4] / sum(c for _, c, _ in rows):.1f} | {tot[4] / tot[2]:.2f} |")
    n_ck = sum(1 for _, _, ck in rows if ck)
    print(f"decode like for like (dbc-codegen + the XOR check on all {n_ck} checksum messages, dbc-codegen alone on the others): "
          f"{tot[4] / tot[2]:.2f}x overall; encode {tot[1] / tot[0]:.2f}x (dbc-codegen has no checksum fill: canspec's encode fills it)")
    print("Ir = instructions per frame (callgrind, loop included); ratio = dbc-codegen / canspec")
    print("like for like (checksum messages against dbc-codegen + XOR check): canspec executes more instructions on: "
          + (", ".join(more) if more else "none"))


def parse_args() -> None:
    global SPEC, GENERATED, BUILD
    import argparse

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--spec", type=Path, default=SPEC)
    ap.add_argument("--generated", type=Path, default=GENERATED, help="the spec's generated outputs (dbc/, vectors/, rust/)")
    ap.add_argument("--build", type=Path, default=BUILD)
    args = ap.parse_args()
    SPEC, GENERATED, BUILD = args.spec.resolve(), args.generated.resolve(), args.build.resolve()


if __name__ == "__main__":
    parse_args()
    sys.exit(main())
