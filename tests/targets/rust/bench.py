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
from canspec.targets.rust.model import RustCrate, RustMessage, build_crate

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_source import COUNT_REPS, main_rs, message_module, parse_dbc_code, spec_names  # the Rust text of the harness

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
    code = dbc_codegen_code(spec.can.name)
    if code is None:
        return 1
    api = parse_dbc_code(code)
    missing = [m.name for m in crate.messages if m.name not in api[0]]
    if missing:
        print(f"bench-rust: dbc-codegen produced no constructor for {', '.join(missing)}", file=sys.stderr)
        return 1
    paged = [rm.msg.name for rm in crate.messages if rm.msg.is_multiplexed]
    if paged:  # dbc-codegen builds a page through an enum of its multiplexer values: no flat constructor to set against ours
        print(f"bench-rust: multiplexed messages not compared (dbc-codegen's pages are enums, not flat constructors): {', '.join(paged)}")
    vectors = json.loads((GENERATED / "vectors" / "can.json").read_text(encoding="utf-8"))
    dbc_names = signal_names(spec.can)  # the DBC target's own naming (unique names carry the frame ID)
    modules, rows, counts = [], [], {}
    for rm in crate.messages:
        cases = bench_cases(rm, vectors["cases"])
        if rm.msg.is_multiplexed or not cases:
            continue
        modules.append(message_module(rm, cases, api, spec_names(dbc_names, rm.msg)))
        rows.append((rm.msg.name, rm.msg.checksum is not None))
        counts[rm.msg.name] = len(cases)
    exe = build_bench(crate, code, main_rs(crate, modules, rows))
    sys.stdout.flush()
    run([str(exe)], cwd=BUILD / "crate")
    sys.stdout.flush()
    instruction_counts(exe, [(name, counts[name], ck) for name, ck in rows])
    return 0


def dbc_codegen_code(protocol: str) -> str | None:
    """What dbc-codegen generates from the generated DBC (None, said on stderr, when it fails)."""
    gen_out = BUILD / "dbc-codegen-out"
    shutil.rmtree(gen_out, ignore_errors=True)
    gen_out.mkdir(parents=True)
    try:
        run([str(dbc_codegen()), str(GENERATED / "dbc" / f"{protocol}.dbc"), str(gen_out)], stdout=subprocess.DEVNULL)
    except subprocess.CalledProcessError as exc:
        print(f"bench-rust: dbc-codegen failed on the generated DBC (exit {exc.returncode})", file=sys.stderr)
        return None
    return (gen_out / "messages.rs").read_text(encoding="utf-8")


def bench_cases(rm: RustMessage, cases: list[dict]) -> list[dict]:  # type: ignore[type-arg]
    """The message's physical-encodable cases; ties of integer-valued signals have no whole-number input."""
    return [c for c in cases if c["message"] == rm.msg.name and c["kind"] != "raw_only"
            and all(float(c["physical"][f.sig.name]).is_integer() for f in rm.fields if f.kind == "scaled_int")]


def build_bench(crate: RustCrate, dbc_code: str, main_source: str) -> Path:
    """The harness crate (ours by path, dbc-codegen's code as module `dbc`) built with LTO; its executable."""
    src = BUILD / "crate" / "src"
    src.mkdir(parents=True, exist_ok=True)
    (src / "dbc.rs").write_text(dbc_code, encoding="utf-8")
    (src / "main.rs").write_text(main_source, encoding="utf-8")
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
    return BUILD / "target" / "release" / "canspec-rust-bench"


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
