"""Validators and bindings from other ecosystems on the same vectors: ajv (npm, draft 2020-12,
strict schema mode) on the generated schemas, the generated Rust crate (built with cargo, lint
with clippy -D warnings), the TypeScript declarations under `tsc --strict`, and the TypeScript
reader (compiled with tsc, run with node)."""

from __future__ import annotations

import json
import os
import random
import subprocess

import pytest
from json_support import CARGO_TARGET, NODE_MODULES, RUST_CRATE, TS_DECL, VECTORS, require_tool, run

# Rules TypeScript's types can see (literal unions, required/excess keys, JSON types); ranges
# of plain numbers are beyond them.
TS_VISIBLE = {"object", "required", "unexpected", "enum", "cmd", "length"}


def test_ajv_agrees_with_every_vector(cases, ajv_results):
    bad = []
    for c in cases:
        r = ajv_results[c["id"]]
        if r["own"] != c["valid"]:
            bad.append((c["id"], "own", r))
        if r["received"] != (c["as_received"] is not None):
            bad.append((c["id"], "to_receiver", r))
        if r["any"] != (c["as_any"] is not None):
            bad.append((c["id"], "protocol", r))
        if not c["valid"] and c["field"] not in r["own_fields"]:
            bad.append((c["id"], "field", c["field"], r["own_fields"]))
    assert len(ajv_results) == len(cases)
    assert bad == [], bad[:20]


def test_rust_bindings_agree_with_every_vector(cases, rust_results):
    bad = []
    for c in cases:
        r = rust_results[c["id"]]
        if r["valid"] != c["valid"]:
            bad.append((c["id"], "valid", r))
        elif c["valid"] and not (r["roundtrip"] and r["serde"]):
            bad.append((c["id"], "round trip / serde", r))
        elif not c["valid"] and (r["field"], r["rule"]) != (c["field"], c["rule"]):
            bad.append((c["id"], "fault", r.get("error"), c["field"], c["rule"]))
        if (r["as_received"], r["as_any"]) != (c["as_received"], c["as_any"]):
            bad.append((c["id"], "dispatch", r["as_received"], r["as_any"]))
        if not r["text"]:
            bad.append((c["id"], "the text reader disagrees with the value reader"))
    assert len(rust_results) == len(cases)
    assert bad == [], bad[:20]


def test_typescript_reader_agrees_with_every_vector(cases, ts_results):
    bad = []
    for c in cases:
        r = ts_results[c["id"]]
        if r["valid"] != c["valid"]:
            bad.append((c["id"], "valid", r))
        elif not c["valid"] and (r["field"], r["rule"]) != (c["field"], c["rule"]):
            bad.append((c["id"], "fault", r, c["field"], c["rule"]))
        if (r["as_received"], r["as_any"]) != (c["as_received"], c["as_any"]):
            bad.append((c["id"], "dispatch", r["as_received"], r["as_any"]))
        if not r["text"]:
            bad.append((c["id"], "the text reader disagrees with the value reader"))
    assert len(ts_results) == len(cases)
    assert bad == [], bad[:20]


# JSON texts that json.loads / serde_json::from_str / JSON.parse mishandle, with what every
# binding's text reader must say (valid, message) or (invalid, field, code): NaN and Infinity are no JSON
# (erratum J11: numbers are finite), a key given twice is no message.
CONTROL = '"ts": 1, "bn": 2, "tr": 0, "st": 0, "g": "N", "m": 3, "vts": 0'
TEXTS = [
    ("{" + CONTROL + ', "bk": 1.5}', True, "control"),
    ("{" + CONTROL + ', "bk": NaN}', False, "bk", "json"),
    ("{" + CONTROL + ', "bk": Infinity}', False, "bk", "json"),
    ("{" + CONTROL + ', "bk": -Infinity}', False, "bk", "json"),
    ("{" + CONTROL + ', "bk": 1e400}', False, "bk", "json"),  # beyond every double: read as Infinity would be
    ("{" + CONTROL + ', "bk": 0, "bn": 3}', False, "bn", "duplicate"),
    ('{"cmd": 1, "bn": 1, "bn": 1}', False, "bn", "duplicate"),  # even with the same value
    ("{" + CONTROL + ', "bk": 0', False, "", "json"),  # cut short
    ("NaN", False, "", "json"),
]


def _text_results_python(rd, texts: list[str]) -> list[dict]:
    out = []
    for text in texts:
        try:
            out.append({"valid": True, "message": rd.loads(text).NAME})
        except rd.ValidationError as e:
            out.append({"valid": False, "field": e.field, "rule": e.code})
    return out


def _text_results_ts(ts_runner, texts: list[str], path) -> list[dict]:
    path.write_text("".join(t + "\n" for t in texts), encoding="utf-8")
    return json.loads(run([*ts_runner, "--text", str(path)], "TypeScript JSON text reader").stdout)


def test_text_readers_refuse_nan_infinity_and_duplicate_keys(rust_runner, ts_runner, rd, tmp_path):
    want = [{"valid": True, "message": t[2]} if t[1] else {"valid": False, "field": t[2], "rule": t[3]} for t in TEXTS]
    texts = [t[0] for t in TEXTS]
    assert _text_results_python(rd, texts) == want
    lines = tmp_path / "texts.txt"
    lines.write_text("".join(t + "\n" for t in texts), encoding="utf-8")
    rust = json.loads(run([str(rust_runner), "--text", str(lines)], "Rust JSON text reader").stdout)
    assert rust == want
    assert _text_results_ts(ts_runner, texts, tmp_path / "texts_ts.txt") == want


# Text-level mutations (what a value mutation cannot write): numbers beyond every double, NaN,
# keys given twice (also inside nested objects and arrays), cut-short and damaged text.
ODD_TOKENS = ["1e400", "-1e400", "1E+999", "1.5e308", "1e-400", "NaN", "Infinity", "-Infinity", "-0", "2.0", "1" + "0" * 400, "[1e400]",
              '{"a": 1e400}', '{"a": 1, "a": 2}', '[{"b": NaN}]', "true", "null", '"N"', '"\\u0041"', "01", "1.", ".5", "+1", "tru"]


def _mutate_text(rng: random.Random, text: str) -> str:
    op = rng.random()
    if op < 0.35:  # a member's value replaced by an odd token
        obj = json.loads(text)
        key = rng.choice(list(obj))
        member = json.dumps(key, ensure_ascii=False) + ": " + json.dumps(obj[key], ensure_ascii=False)
        return text.replace(member, json.dumps(key) + ": " + rng.choice(ODD_TOKENS), 1)
    if op < 0.6:  # a key given again, before or after the rest
        key = rng.choice(list(json.loads(text)))
        member = json.dumps(key) + ": " + rng.choice([*ODD_TOKENS[:8], "0", "1", '"N"'])
        return "{" + member + ", " + text[1:] if rng.random() < 0.5 else text[:-1] + ", " + member + "}"
    if op < 0.8:  # cut short, or a character removed
        at = rng.randrange(len(text))
        return text[:at] if rng.random() < 0.5 else text[:at] + text[at + 1 :]
    at = rng.randrange(len(text) + 1)  # a character inserted
    return text[:at] + rng.choice([" ", "\t", ",", ":", "{", "}", "[", "]", '"', "\\", "x", "\u00e9"]) + text[at:]


def test_text_readers_agree_on_random_text_mutations(cases, rd, ts_runner, tmp_path):
    """The Python and TypeScript text readers: the same verdict, message, field and code."""
    rng = random.Random(20261201)
    valid = [json.dumps(c["json"], ensure_ascii=False) for c in cases if c["valid"] and isinstance(c["json"], dict) and c["json"]]
    texts = [_mutate_text(rng, rng.choice(valid)) for _ in range(1500)]
    py = _text_results_python(rd, texts)
    ts = _text_results_ts(ts_runner, texts, tmp_path / "mutations.txt")
    bad = [(t, p, s) for t, p, s in zip(texts, py, ts, strict=True) if p != s]
    assert bad == [], bad[:10]
    codes = {p.get("rule") for p in py}
    assert {"json", "duplicate", None} <= codes, codes  # the mutations reach both refusals and valid messages


def test_rust_runner_check_mode(rust_runner, cases):
    proc = run([str(rust_runner), "--check", str(VECTORS)], "Rust JSON vectors runner --check")
    assert f"{len(cases)} passed, 0 failed" in proc.stdout


def test_rust_crate_is_warning_free_and_formatted():
    cargo = require_tool("cargo")
    env = {**os.environ, "CARGO_TARGET_DIR": str(CARGO_TARGET)}
    manifest = ["--manifest-path", str(RUST_CRATE / "Cargo.toml")]
    run([cargo, "rustc", "--quiet", "--locked", "--lib", *manifest, "--", "-D", "warnings"], "cargo rustc -D warnings", env=env)
    rustfmt = require_tool("rustfmt")
    run([rustfmt, "--check", "--edition", "2021", str(RUST_CRATE / "src" / "lib.rs")], "rustfmt --check")  # lib.rs pulls in rt.rs


def test_rust_crate_is_clippy_clean():
    cargo = require_tool("cargo")
    if subprocess.run([cargo, "clippy", "--version"], capture_output=True, check=False).returncode != 0:
        pytest.fail("clippy is not installed with this Rust toolchain (rustup component add clippy)")
    env = {**os.environ, "CARGO_TARGET_DIR": str(CARGO_TARGET)}
    run(
        [cargo, "clippy", "--quiet", "--locked", "--all-targets", "--manifest-path", str(RUST_CRATE / "Cargo.toml"), "--", "-D", "warnings"], "cargo clippy",
        env=env)


def _ts_case(i: int, c: dict) -> str:
    type_name = "".join(w.capitalize() for w in c["message"].split("_"))
    value = c["json"]
    visible = c["valid"] is False and (
        c["rule"] in TS_VISIBLE
        or (c["rule"] == "type" and not (isinstance(value.get(c["field"]), float) and not isinstance(value.get(c["field"]), bool)))
        or (c["rule"] == "type_range" and c["field"] in ("m", "res", "cmd"))
    )
    if not c["valid"] and not visible:
        return ""
    line = f"const c{i}: rd.{type_name} = {json.dumps(value, ensure_ascii=False)};  // {c['id']}\n"
    return ("// @ts-expect-error\n" if visible else "") + line


def test_typescript_declarations_compile_and_type_the_vectors(cases, tmp_path):
    node = require_tool("node")
    tsc = NODE_MODULES / "typescript" / "bin" / "tsc"
    assert tsc.is_file(), f"typescript is not installed in {NODE_MODULES}: run `make setup`"
    rel = os.path.relpath(TS_DECL.with_suffix("").with_suffix(""), tmp_path)
    body = [f'import type * as rd from "{rel}";\n', "export {};\n"]
    body += [_ts_case(i, c) for i, c in enumerate(cases)]
    body.append("const r: rd.ReplyTo<rd.RecordRequest> = { cmd: 3, res: 0, bn: 1, ro: true };\n")
    body.append("// @ts-expect-error\nconst w: rd.ReplyTo<rd.PhotoRequest> = { cmd: 3, res: 0, bn: 1 };\n")
    body.append("const all: rd.Message[] = [r];\nvoid all; void w;\n")
    src = tmp_path / "vectors.ts"
    src.write_text("".join(body), encoding="utf-8")
    opts = ["--noEmit", "--strict", "--noUnusedLocals", "false", "--target", "es2020", "--module", "es2020", "--moduleResolution", "node"]
    run([node, str(tsc), *opts, str(TS_DECL)], "tsc (declarations)")
    proc = subprocess.run([node, str(tsc), *opts, str(src)], capture_output=True, text=True, timeout=600, check=False)
    assert proc.returncode == 0, proc.stdout[-4000:] + proc.stderr[-2000:]
    assert src.read_text().count("@ts-expect-error") > 50
