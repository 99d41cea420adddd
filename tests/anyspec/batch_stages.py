"""The batch stages of the anyspec harness (harness.py): every spec's Rust crate in one cargo workspace,
and every spec's TypeScript declarations and readers in one tsc program."""

from __future__ import annotations

import hashlib
import json
import os
import re
import shutil
import time
from pathlib import Path

from anyspec import adapters
from anyspec.harness_base import BUILD, ROOT, Failure, SpecResult, clip, sh

# --- batch stages: Rust (one workspace) and TypeScript (one program) -----------------------


def _rust_members(results: list[SpecResult], root: Path) -> dict[str, SpecResult]:
    members = {}
    for r in results:
        crate = Path(r.out_dir) / "rust"
        toml = crate / "Cargo.toml"
        if not toml.is_file() or not (Path(r.out_dir) / "vectors" / "can.json").is_file():
            continue
        text = toml.read_text(encoding="utf-8")
        m = re.search(r'^\[package\]\s*\nname = "([^"]+)"', text, re.MULTILINE)
        if m is None:
            r.failures.append(Failure(r.sid, r.seed, "rust", "Cargo.toml", "no [package] name", r.spec_dir, r.features))
            continue
        lib = m.group(1)
        if "anyspec-" not in text:
            # One workspace holds every spec's crate: unique package names (the lib keeps its
            # name). Cargo hashes path packages relative to the workspace root, so the name also
            # carries a digest of the crate: two workspaces sharing the target directory never
            # share artifacts.
            digest = hashlib.sha256(str(crate.resolve()).encode() + b"".join(p.read_bytes() for p in sorted(crate.rglob("*.rs")))).hexdigest()[:10]
            text = (
                text.replace(m.group(0), f'[package]\nname = "anyspec-{r.sid}-{digest}"', 1)
                + f'\n[lib]\nname = "{lib.replace("-", "_")}"\npath = "src/lib.rs"\n'
            )
            toml.write_text(text, encoding="utf-8")
        members[os.path.relpath(crate, root)] = r
    return members


def stage_rust(results: list[SpecResult], root: Path, proptest_cases: int = 32) -> float:
    t0 = time.monotonic()
    members = _rust_members(results, root)
    if not members:
        return 0.0
    by_pkg = {re.search(r'^name = "(anyspec-[^"]+)"', (Path(r.out_dir) / "rust" / "Cargo.toml").read_text(encoding="utf-8"), re.MULTILINE).group(1): r
              for r in members.values()}
    (root / "Cargo.toml").write_text(
        "# The anyspec harness's workspace: one crate per generated spec, one target directory.\n[workspace]\nresolver = \"2\"\nmembers = [\n"
        + "".join(f'    "{m}",\n' for m in sorted(members)) + "]\n", encoding="utf-8")
    lock = ROOT / "generated" / "rust" / "Cargo.lock"
    if lock.is_file() and not (root / "Cargo.lock").exists():
        shutil.copy(lock, root / "Cargo.lock")  # the shipped crate's pins: same dependencies
    env = {**os.environ, "CARGO_TARGET_DIR": str(BUILD / "cargo-target"), "CANSPEC_PROPTEST_CASES": str(proptest_cases), "CARGO_TERM_COLOR": "never"}
    env.pop("RUSTFLAGS", None)
    for r in members.values():
        r.checked.append("rust")
    rc, out, err = sh(
        ["cargo", "clippy", "--offline", "--workspace", "--all-targets", "--all-features", "--keep-going", "--message-format=short", "--", "-D", "warnings"],
        cwd=root, env=env, timeout=1800)
    if rc != 0:
        _attribute_rust(err, members, by_pkg, "cargo clippy --all-targets -- -D warnings")
    rc, out, err = sh(["cargo", "test", "--offline", "--workspace", "--all-features", "--no-run", "--message-format=short"], cwd=root, env=env, timeout=1800)
    built_ok = rc == 0
    if not built_ok:
        _attribute_rust(err, members, by_pkg, "cargo test (build)")
    for pkg, r in sorted(by_pkg.items()):
        if any(f.target == "rust" and f.stage == "cargo test (build)" for f in r.failures):
            continue
        rc, out, err = sh(["cargo", "test", "--offline", "--all-features", "-p", pkg, "--", "--nocapture"], cwd=root, env=env, timeout=1800)
        if rc != 0 or "rust vectors:" not in out:
            # the tests' own output (mismatches, panics) first, then cargo's
            keep = [ln for ln in out.splitlines() if not ln.startswith(("test ", "running ")) and ln.strip() and "... ok" not in ln]
            errs = [ln for ln in err.splitlines() if ln.startswith(("error", "thread", "  left", " right")) or "panicked" in ln]
            r.failures.append(Failure(r.sid, r.seed, "rust", "cargo test", clip("\n".join(keep + errs)), r.spec_dir, r.features))
        else:
            m = re.search(r"rust vectors: .*?(\d+) mismatches", out)
            if not m or m.group(1) != "0":
                r.failures.append(Failure(r.sid, r.seed, "rust", "cargo test (vectors)", out[-3000:], r.spec_dir, r.features))
    return time.monotonic() - t0


def _attribute_rust(err: str, members: dict[str, SpecResult], by_pkg: dict[str, SpecResult], stage: str) -> None:
    found: dict[str, list[str]] = {}
    for line in err.splitlines():
        m = re.match(r"(s\d{4})/out/rust/(\S+): error(?:\[\w+\])?: (.*)", line)
        if m:
            found.setdefault(m.group(1), []).append(f"{m.group(2)}: error: {m.group(3)}")
    failed_pkgs = set(re.findall(r"could not compile `anyspec-(s\d{4})-\w+`", err))
    for sid in failed_pkgs:
        found.setdefault(sid, ["could not compile (see the cargo output)"])
    if not found:
        first = next(iter(members.values()))
        first.failures.append(Failure("workspace", None, "rust", stage, err[-6000:], str(BUILD), []))
        return
    by_sid = {r.sid: r for r in by_pkg.values()}
    for sid, lines in found.items():
        r = by_sid.get(sid)
        if r is not None:
            r.failures.append(Failure(r.sid, r.seed, "rust", stage, "\n".join(dict.fromkeys(lines))[:6000], r.spec_dir, r.features))


def stage_typescript(results: list[SpecResult], root: Path) -> float:
    t0 = time.monotonic()
    files = []
    owners = {}
    for r in results:
        vec = Path(r.out_dir) / "vectors" / "json.json"
        decls = sorted((Path(r.out_dir) / "json" / "typescript").glob("*.d.ts"))
        if not decls or not vec.is_file():
            continue
        r.checked.append("typescript")
        doc = json.loads(vec.read_text(encoding="utf-8"))
        for d in decls:
            files += [d, d.with_name(d.name.removesuffix(".d.ts") + ".reader.ts")]  # the reader pulls in canspec-json.ts
            owners[r.sid] = r
            proto = next((p for p in doc["protocols"] if p["protocol"] == d.name.removesuffix(".d.ts")), None)
            if proto is None:
                continue
            body = [f'import type * as rd from "./{d.name.removesuffix(".d.ts")}";\n', "export {};\n"]
            for i, c in enumerate(proto["cases"]):
                if c["valid"]:
                    schema = Path(r.out_dir) / "jsonschema" / proto["protocol"] / f"{c['message']}.schema.json"
                    tname = json.loads(json.loads(schema.read_text(encoding="utf-8"))["$comment"])["x-canspec"]["type_name"]  # the name the bindings allocated
                    body.append(f"export const c{i}: rd.{tname} = {json.dumps(c['json'], ensure_ascii=False)};  // {c['id']}\n")
            cases = d.parent / f"{d.name.removesuffix('.d.ts')}.cases.ts"
            cases.write_text("".join(body), encoding="utf-8")
            files.append(cases)
    if not files:
        return 0.0
    opts = ["--noEmit", "--strict", "--target", "es2020", "--module", "es2020", "--moduleResolution", "node", "--skipLibCheck", "false"]
    rc, out, err = sh(["node", str(adapters.TSC), *opts, *[os.path.relpath(f, root) for f in files]], cwd=root, timeout=1800)
    if rc != 0:
        per: dict[str, list[str]] = {}
        for line in (out + err).splitlines():
            m = re.match(r"(s\d{4})/\S+", line)
            if m:
                per.setdefault(m.group(1), []).append(line)
        for sid, lines in per.items():
            r = owners[sid]
            r.failures.append(Failure(r.sid, r.seed, "typescript", "tsc --strict", "\n".join(lines)[:6000], r.spec_dir, r.features))
        if not per:
            r = next(iter(owners.values()))
            r.failures.append(Failure("all", None, "typescript", "tsc --strict", (out + err)[-6000:], str(root), []))
    return time.monotonic() - t0
