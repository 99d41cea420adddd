"""The "any valid spec" harness: draw specs, run canspec's CLI on each, then hold every output
to its own toolchain and its own vectors. Batch-shaped for speed: every spec is written
first, the per-spec work (check, gen, C, Python, cantools/canmatrix, JSON) runs in a process
pool, and the Rust crates (one cargo workspace, one target directory) and the TypeScript
declarations and readers (one tsc program) are checked together at the end.

Entry points: `run_batch(...)` (pytest, `make test-any-spec`), `run_one(...)` (reproduce or
shrink one spec). See tests/anyspec/README.md.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import time
from collections.abc import Iterable
from concurrent.futures import ProcessPoolExecutor
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
if str(HERE.parent) not in sys.path:
    sys.path.insert(0, str(HERE.parent))

from anyspec import adapters, cross_stage, strategy

ROOT = adapters.ROOT
BUILD = ROOT / "build" / "anyspec"
FAILURES = BUILD / "failures"
TIMEOUT_S = 600
CANSPEC_TARGETS = ("dbc", "vectors", "json_vectors", "c", "python", "jsonschema", "rust", "json_bindings", "docs")
C_MODES = (
    ("gcc", ["-std=c99"], "c99"), ("clang", ["-std=c99"], "c99"), ("g++", ["-x", "c++", "-std=c++11"], "c++11"),
    ("clang++", ["-x", "c++", "-std=c++11"], "c++11"))
TOOLS = ("gcc", "clang", "g++", "clang++", "cargo", "node", "ruff")


# --- results -------------------------------------------------------------------------------


@dataclass
class Failure:
    sid: str
    seed: int | None
    target: str  # check | gen:<target> | c | python | cantools | canmatrix | json | typescript | rust
    stage: str  # what ran, e.g. "gcc c99 fixture_messages.h", "vector runner", "mypy --strict"
    message: str
    spec_dir: str
    features: list[str] = field(default_factory=list)
    refusal: list[str] | None = None  # check refusals: the NEW features that explain it ([] = none)

    @property
    def signature(self) -> str:
        return f"{self.target} | {signature_text(self.message)}"


@dataclass
class SpecResult:
    sid: str
    seed: int | None
    spec_dir: str
    entry: str
    out_dir: str
    features: list[str]
    facts: dict[str, Any]
    accepted: bool = False
    generated: list[str] = field(default_factory=list)
    checked: list[str] = field(default_factory=list)  # toolchains that ran on this spec
    failures: list[Failure] = field(default_factory=list)
    seconds: float = 0.0


SIGNATURE_LINES = (
    r"^[A-Z]+\d+ ",  # a ruff rule
    r"(?<![\w.])error(\[\w+\])?:",  # compilers, mypy, rustc, canspec
    r"\berror\b|Error\b|mismatch|failed|panicked|refused|disagree",
)


def signature_text(message: str) -> str:
    """A failure message without the details that differ between specs (names, numbers, paths)."""
    lines = [ln for ln in message.splitlines() if ln.strip() and not re.match(r"\s*(\d+\s*)?[|>]|\s*-->|\s*from \.|\s*In file included|\s+from ", ln)]
    line = next((ln for rx in SIGNATURE_LINES for ln in lines if re.search(rx, ln)), lines[0] if lines else "")
    runner = [ln for ln in lines if re.match(r"line \d+: ", ln)]  # the C runner's first mismatch
    exc = [ln for ln in lines if re.match(r"\w+(Error|Exception): ", ln)]  # a traceback's exception
    panic = [lines[i + 1] for i, ln in enumerate(lines[:-1]) if "panicked at" in ln]  # a Rust test's panic message
    mismatch = [ln for ln in lines if re.match(r"(case \d+|multiframe|MISMATCH) ", ln)]  # the Python runners
    line = (runner or panic or exc[-1:] or mismatch or [line])[0]
    line = re.sub(r"^line \d+: \S+ \(\w+\)", "line N: MSG (KIND)", line)
    line = re.sub(r"(mismatch: |^\w+Error: )\w+:", r"\1X:", line)
    line = re.sub(r"\b\w+?_(common|messages|enums|dispatch|monitor|text)\.h\b", r"P_\1.h", line)
    line = re.sub(r"\b[\w/.-]*?(\w+\.(py|rs|ts|h))\b", r"P/\1", line)
    m = re.match(r"(canspec gen: target \w+: )(.*)", line)
    if m:  # names from the spec in canspec's own messages
        line = m.group(1) + re.sub(
            r"(?<![/\w.])(?!error\b)(?:[a-z_][a-z0-9_]*\.)?[a-z_][a-z0-9_]*(?=:)(?!\d)|(?<=value table )\w+|(?<=JSON field )\S+", "X", m.group(2)
        )
    line = re.sub(r"/\S+/", "", line)
    line = re.sub(r"\bs\d{4}\b", "S", line)
    line = re.sub(r"'[^']*'|\"[^\"]*\"|`[^`]*`|‘[^’]*’", "X", line)
    line = re.sub(r"0x[0-9A-Fa-f]+|\b\d+(\.\d+)?\b", "N", line)
    return line.strip()[:160]


def clip(text: str, limit: int = 6000) -> str:
    """The first `limit` characters of a tool's output, cut at a line end."""
    text = text.strip()
    return text if len(text) <= limit else text[: text.rfind("\n", 0, limit)] + "\n[...]"


def sh(cmd: list[str], cwd: Path | None = None, env: dict[str, str] | None = None, timeout: float = TIMEOUT_S) -> tuple[int, str, str]:
    try:
        proc = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout, check=False)
    except subprocess.TimeoutExpired as exc:
        return 124, str(exc.stdout or ""), f"timeout after {timeout} s: {' '.join(cmd)}"
    return proc.returncode, proc.stdout, proc.stderr


def canspec_env() -> dict[str, str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = str(adapters.GENERATOR) + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    return env


def canspec(*args: str) -> tuple[int, str, str]:
    return sh([sys.executable, "-m", "canspec", *args], env=canspec_env())


def missing_tools() -> list[str]:
    """Toolchains the harness needs and cannot find (each one fails the run, never skips it)."""
    out = [f"{t} (not on PATH)" for t in TOOLS if shutil.which(t) is None] + cross_stage.missing_tools()
    if shutil.which("cargo") and sh(["cargo", "clippy", "--version"])[0] != 0:
        out.append("cargo clippy (rustup component add clippy)")
    for mod in ("cantools", "canmatrix", "jsonschema", "mypy", "hypothesis", "yaml"):
        try:
            __import__(mod)
        except ImportError:
            out.append(f"python module {mod}")
    if not (adapters.NODE_MODULES / "ajv").is_dir() or not adapters.TSC.is_file():
        out.append(f"ajv/typescript in {adapters.NODE_MODULES} (run `make setup`: .ci/setup.d/60-json.sh)")
    return out


# --- per-spec stages -----------------------------------------------------------------------


class Ctx:
    def __init__(self, res: SpecResult) -> None:
        self.res = res
        self.spec = Path(res.spec_dir) / res.entry
        self.out = Path(res.out_dir)
        self.stage_filter: str | None = None
        self.bytewise = True
        self.work = Path(res.out_dir).parent / "work"
        self.work.mkdir(parents=True, exist_ok=True)

    def want(self, *labels: str) -> bool:
        """Whether to run a sub-stage (the shrinker re-runs only the one that failed)."""
        f = self.stage_filter
        return f is None or any(label.startswith(f) or f.startswith(label) for label in labels)

    def fail(self, target: str, stage: str, message: str) -> None:
        self.res.failures.append(Failure(self.res.sid, self.res.seed, target, stage, clip(message), self.res.spec_dir, self.res.features))


def multiplexed(spec: Path) -> bool:
    """Whether the spec multiplexes a message (the runners' counts report those apart)."""
    from canspec.pipeline import compile_spec

    compiled = compile_spec(spec, targets=())  # the spec rules only: `canspec check` reports a problem there
    can = compiled.spec.can if compiled.spec is not None else None
    return can is not None and any(m.is_multiplexed for m in can.messages)


def stage_check(ctx: Ctx) -> bool:
    ctx.res.facts.update(multiplexed=multiplexed(ctx.spec))
    rc, out, err = canspec("check", str(ctx.spec))  # every target's refusals: a drawn (valid) spec must pass them all
    if rc != 0:
        ctx.fail("check", "canspec check", err or out)
        return False
    ctx.res.accepted = True
    return True


def stage_gen(ctx: Ctx, targets: Iterable[str] | None = None) -> None:
    targets = list(targets or CANSPEC_TARGETS)
    todo = list(targets)
    first_err = None
    # A target that fails makes `gen` write nothing: drop it (reported), generate the rest.
    while todo:
        args = [] if todo == list(CANSPEC_TARGETS) else [x for t in todo for x in ("--target", t)]
        rc, out, err = canspec("gen", str(ctx.spec), "-o", str(ctx.out), *args)
        if rc == 0:
            ctx.res.generated = todo
            break
        first_err = first_err or (err or out)
        m = re.search(r"canspec gen: target (\w+):", err)
        if m is None or m.group(1) not in todo:
            if len(todo) == 1:
                ctx.fail(f"gen:{todo[0]}", f"canspec gen --target {todo[0]}", err or out)
                break
            for t in todo:  # no target named: try each alone
                rc1, out1, err1 = canspec("gen", str(ctx.spec), "-o", str(ctx.out), "--target", t)
                if rc1 == 0:
                    ctx.res.generated.append(t)
                else:
                    ctx.fail(f"gen:{t}", f"canspec gen --target {t}", err1 or out1)
            break
        ctx.fail(f"gen:{m.group(1)}", f"canspec gen (target {m.group(1)})", err)
        todo.remove(m.group(1))


def _vectors(ctx: Ctx) -> dict[str, Any] | None:
    path = ctx.out / "vectors" / "can.json"
    return json.loads(path.read_text(encoding="utf-8")) if path.is_file() else None


def stage_c(ctx: Ctx) -> None:
    cdir = ctx.out / "c"
    headers = sorted(p.name for p in cdir.glob("*.h"))
    if not headers:
        ctx.fail("c", "headers", f"no headers in {cdir}")
        return
    ctx.res.checked.append("c")
    strict = adapters.c_strict_flags()
    work = ctx.work / "c"
    work.mkdir(exist_ok=True)
    units = []
    for h in headers:
        unit = work / f"only_{h}.c"
        unit.write_text(f'#include "{h}"\n#include "{h}"\nint canspec_dummy(void);\nint canspec_dummy(void) {{ return 0; }}\n', encoding="utf-8")
        units.append(unit)
    for cc, std, label in C_MODES:
        if not ctx.want(f"{cc} {label} strict, each header alone"):
            continue
        rc, out, err = sh([cc, *std, *strict, f"-I{cdir}", "-fsyntax-only", *map(str, units)])
        if rc != 0:
            bad = sorted({m.group(1) for m in re.finditer(r"only_([\w.]+\.h)\.c", err)}) or headers
            ctx.fail("c", f"{cc} {label} strict, each header alone ({', '.join(bad)})", err)
    umbrella = next((u for u in units if u.name == f"only_{ctx.res.facts.get('c_prefix', '')}.h.c"), None)
    umbrella = umbrella or min(units, key=lambda u: len(u.name))
    for cc in ("gcc", "clang"):  # optimised code generation: the middle-end warnings
        if not ctx.want(f"{cc} -O2 -c"):
            continue
        rc, out, err = sh([cc, "-std=c99", *strict, "-O2", f"-I{cdir}", "-c", str(umbrella), "-o", os.devnull])
        if rc != 0:
            ctx.fail("c", f"{cc} -O2 -c {umbrella.name[5:-2]}", err)
    doc = _vectors(ctx)
    if doc is None or not ctx.want("build vector runner", "C vector runner", "tests/targets/c/gen_runner_tables.py"):
        return
    try:
        (work / "runner_tables.h").write_text(adapters.c_runner_tables(ctx.spec), encoding="utf-8")
    except Exception as exc:  # noqa: BLE001 — a helper's failure is reported, never swallowed
        ctx.fail("c", "tests/targets/c/gen_runner_tables.py", f"{type(exc).__name__}: {exc}")
        return
    lines = work / "vectors.lines.txt"
    lines.write_text(adapters.c_vectors_lines(doc, ctx.spec), encoding="ascii")
    macro = None
    for h in headers:
        m = re.search(r"#ifndef\s+(\w+)_STRATEGY\b", (cdir / h).read_text(encoding="utf-8"))
        if m:
            macro = m.group(1)
            break
    # the other strategy, Cortex-M0+'s (fieldless frames zeroed byte by byte vs memset, 64-bit
    # products from 16-bit halves), on every 4th spec (and whenever the shrinker asks for it)
    other = macro is not None and (ctx.bytewise or ctx.stage_filter is not None)
    variants = [("runner", [])] + ([("runner-bytes", [f"-D{macro}_STRATEGY=0"])] if other else [])
    for name, extra in variants:
        exe = work / name
        rc, out, err = sh(["gcc", "-std=gnu99", "-O1", *strict[:-1], *extra, f"-I{cdir}", f"-I{work}", str(adapters.C_RUNNER), "-o", str(exe), "-lm"])
        if rc != 0:
            ctx.fail("c", f"build vector runner {' '.join(extra)}".strip(), err)
            continue
        rc, out, err = sh([str(exe), str(lines)])
        m = adapters.c_cases_re().search(out)
        if rc != 0 or not m or int(m.group(3)) != 0 or int(m.group(1)) != len(doc["cases"]):
            ctx.fail("c", f"C vector runner{' (byte-wise path)' if extra else ''}", f"exit {rc}: {out.strip()}\n{err[-4000:]}")
    sequences = ctx.out / "vectors" / "sequences.json"
    if ctx.want("C sequence runner"):
        try:
            rc, out = adapters.c_sequences(ctx.spec, cdir, sequences, work / "sequences")
        except Exception as exc:  # noqa: BLE001 — a helper's failure is reported, never swallowed
            rc, out = 1, f"{type(exc).__name__}: {exc}"
        if rc != 0 or ", 0 mismatches" not in out:
            ctx.fail("c", "C sequence runner", f"exit {rc}: {out[-4000:]}")


def _python_package(pydir: Path) -> str | None:
    pkgs = sorted(p.parent.name for p in pydir.glob("*/__init__.py") if p.parent.name != "examples")
    return pkgs[0] if len(pkgs) == 1 else None


def stage_python(ctx: Ctx, mypy: bool) -> None:
    pydir = ctx.out / "python"
    pkg = _python_package(pydir)
    if pkg is None:
        ctx.fail("python", "package", f"expected one package in {pydir}, found {sorted(p.name for p in pydir.iterdir())}")
        return
    ctx.res.checked.append("python")
    if ctx.want("import + vector runner"):
        rc, out, err = sh([sys.executable, str(HERE / "py_vectors.py"), str(pydir), pkg, str(ctx.out / "vectors" / "can.json")])
        if rc != 0:
            ctx.fail("python", "import + vector runner", f"exit {rc}\n{out[-4000:]}\n{err[-4000:]}")
    if ctx.want("sequence runner"):
        rc, out, err = sh([sys.executable, str(adapters.PY_SEQUENCE_RUNNER), str(ctx.out / "vectors" / "sequences.json"), "--package", str(pydir / pkg)])
        if rc != 0:
            ctx.fail("python", "sequence runner", f"exit {rc}\n{out[-4000:]}\n{err[-4000:]}")
    if ctx.want("ruff check"):
        rc, out, err = sh(["ruff", "check", "--no-cache", "."], cwd=pydir)
        if rc != 0:
            ctx.fail("python", "ruff check", out + err)
    if mypy and ctx.want("mypy --strict"):
        ctx.res.checked.append("python-mypy")
        targets = [pkg] + (["examples"] if (pydir / "examples").is_dir() else [])
        rc, out, err = sh([sys.executable, "-m", "mypy", "--strict", f"--cache-dir={BUILD / 'mypy-cache' / str(os.getpid())}", *targets], cwd=pydir)
        if rc != 0:
            ctx.fail("python", "mypy --strict", out + err)


def _cantools_raw(msg: Any, raw: dict[str, int]) -> dict[str, Any]:
    """The vectors' raw values as cantools takes them: an IEEE float signal's as the float its bits hold."""
    out: dict[str, Any] = dict(raw)
    for sig in msg.signals:
        if sig.is_float and sig.name in out:
            out[sig.name] = struct.unpack("<f" if sig.length == 32 else "<d", out[sig.name].to_bytes(sig.length // 8, "little"))[0]
    return out


def _bits(values: dict[str, Any]) -> dict[str, Any]:
    """Values compared exactly: floats by their bits (NaN equal to the same NaN, -0.0 unlike 0.0)."""
    return {k: struct.pack("<d", v) if isinstance(v, float) else v for k, v in values.items()}


def _ir(ctx: Ctx) -> Any:
    """The spec's CAN IR (for its `dbc_name`s), or None."""
    from canspec.pipeline import compile_spec

    compiled = compile_spec(ctx.spec, targets=("dbc", "vectors"))  # the targets this runner reads
    return compiled.spec.can if compiled.spec is not None else None


def stage_cantools(ctx: Ctx) -> None:
    import canmatrix.formats

    dbc = next((ctx.out / "dbc").glob("*.dbc"), None)
    doc = _vectors(ctx)
    if dbc is None or doc is None:
        ctx.fail("cantools", "inputs", "no DBC or no vectors")
        return
    ctx.res.checked.append("cantools")
    try:
        db = adapters.load_dbc_with_spec_names(dbc, _ir(ctx))  # cantools, strict; DBC names read back as the spec's
    except Exception as exc:  # noqa: BLE001
        ctx.fail("cantools", "load_file(strict=True)", f"{type(exc).__name__}: {exc}")
        db = None
    if db is not None:
        bad = []
        for i, case in enumerate(doc["cases"]):
            try:
                data = bytes.fromhex(case["data"])
                # by name: get_message_by_frame_id needs force_extended_id for extended IDs <= 0x7FF
                msg = db.get_message_by_name(case["message"])
                if msg.frame_id != case["frame_id"]:
                    bad.append(f"case {i} ({case['message']}): the DBC gives it ID 0x{msg.frame_id:X}, the vectors 0x{case['frame_id']:X}")
                    continue
                want = _cantools_raw(msg, case["raw"])
                raw = msg.decode(data, decode_choices=False, scaling=False)
                if _bits(raw) != _bits(want):
                    bad.append(f"case {i} ({case['message']}, {case['kind']}): cantools decodes raw {raw}, vectors say {case['raw']}")
                    continue
                enc = msg.encode(want, scaling=False, strict=False)
                if enc != data:
                    bad.append(f"case {i} ({case['message']}, {case['kind']}): cantools encodes {enc.hex().upper()}, vectors say {case['data']}")
                phys = msg.decode(data, decode_choices=False, scaling=True)
                if set(phys) != set(case["physical"]):  # a multiplexed frame: only the selected pages' fields
                    bad.append(f"case {i} ({case['message']}, {case['kind']}): cantools decodes fields {sorted(phys)}, vectors give {sorted(case['physical'])}")
                    continue
                for sig in (s for s in msg.signals if s.name in phys):
                    expected = case["physical"][sig.name]
                    if sig.is_float:  # the float itself, bit for bit ("NaN" any NaN; -0.0 keeps its sign)
                        x = phys[sig.name]
                        if not (math.isnan(x) if expected == "NaN" else _bits({0: x}) == _bits({0: float(expected)})):
                            bad.append(f"case {i} ({case['message']}, {case['kind']}): cantools physical {sig.name} = {x!r}, vectors say {expected!r}")
                        continue
                    ulps = 4 * math.ulp(float(expected))  # the double arithmetic of both sides
                    tol = (abs(sig.scale) / 2 * (1 + 1e-9) if case["kind"] == "tie" else 1e-9 * max(1.0, abs(expected))) + ulps
                    if not math.isclose(phys[sig.name], expected, abs_tol=tol):
                        bad.append(f"case {i} ({case['message']}, {case['kind']}): cantools physical {sig.name} = {phys[sig.name]!r}, vectors say {expected!r}")
            except Exception as exc:  # noqa: BLE001
                bad.append(f"case {i} ({case.get('message')}, {case.get('kind')}): cantools raised {type(exc).__name__}: {exc}")
        if bad:
            ctx.fail("cantools", "vectors vs cantools encode/decode", f"{len(bad)} case(s) disagree; first: " + "\n".join(bad[:8]))
    ctx.res.checked.append("canmatrix")
    try:
        dbs = canmatrix.formats.loadp(str(dbc), dbcImportEncoding="utf-8")
        cm = next(iter(dbs.values()))
        n = len({c["frame_id"] for c in doc["cases"]} | {f.arbitration_id.id for f in cm.frames})
        if len(cm.frames) != ctx.res.facts.get("messages", len(cm.frames)) or n != len(cm.frames):
            ctx.fail("canmatrix", "loadp", f"canmatrix reads {len(cm.frames)} frames; the spec has {ctx.res.facts.get('messages')} messages")
    except Exception as exc:  # noqa: BLE001
        ctx.fail("canmatrix", "loadp", f"{type(exc).__name__}: {exc}")


def stage_json(ctx: Ctx, mypy: bool) -> None:
    import jsonschema

    vec_path = ctx.out / "vectors" / "json.json"
    if not vec_path.is_file():
        ctx.fail("json", "vectors", f"no {vec_path}")
        return
    doc = json.loads(vec_path.read_text(encoding="utf-8"))
    ctx.res.checked.append("json")
    schema_root = ctx.out / "jsonschema"
    for proto in doc["protocols"]:
        name = proto["protocol"]
        sdir = schema_root / name
        try:
            schemas = {p.name.removesuffix(".schema.json"): json.loads(p.read_text(encoding="utf-8")) for p in sorted(sdir.glob("*.schema.json"))}
            validators = {}
            for sname, s in schemas.items():
                jsonschema.Draft202012Validator.check_schema(s)
                validators[sname] = jsonschema.Draft202012Validator(s)
        except Exception as exc:  # noqa: BLE001
            ctx.fail("json", "jsonschema: schemas", f"{type(exc).__name__}: {exc}")
            continue
        bad = []
        for c in proto["cases"]:
            try:
                if validators[c["message"]].is_valid(c["json"]) != c["valid"]:
                    bad.append(f"{c['id']}: own schema says {not c['valid']} ({c.get('note', '')})")
                if validators[f"to_{c['receiver']}"].is_valid(c["json"]) != (c["as_received"] is not None):
                    bad.append(f"{c['id']}: to_{c['receiver']} schema disagrees (expected {c['as_received']})")
                if validators["protocol"].is_valid(c["json"]) != (c["as_any"] is not None):
                    bad.append(f"{c['id']}: protocol schema disagrees (expected {c['as_any']})")
            except KeyError as exc:
                bad.append(f"{c['id']}: no schema {exc}")
        if bad:
            ctx.fail("json", "jsonschema vs vectors/json.json", f"{len(bad)} case(s) disagree; first: " + "\n".join(bad[:8]))
        rc, out, err = sh(["node", str(adapters.AJV_CHECK), str(schema_root), str(vec_path)], env=adapters.node_env())
        if rc != 0:
            ctx.fail("json", "ajv", out[-3000:] + err[-3000:])
        else:
            results = {r["id"]: r for r in json.loads(out)}
            bad = []
            for c in proto["cases"]:
                r = results.get(c["id"])
                if r is None:
                    bad.append(f"{c['id']}: not checked by ajv")
                elif r["own"] != c["valid"] or r["received"] != (c["as_received"] is not None) or r["any"] != (c["as_any"] is not None):
                    bad.append(f"{c['id']}: ajv own={r['own']} received={r['received']} any={r['any']}, "
                               f"vectors valid={c['valid']} as_received={c['as_received']} as_any={c['as_any']}")
            if bad:
                ctx.fail("json", "ajv vs vectors/json.json", f"{len(bad)} case(s) disagree; first: " + "\n".join(bad[:8]))
        pkg_dir = ctx.out / "json" / "python" / name
        if not (pkg_dir / name / "__init__.py").is_file():
            ctx.fail("json", "python bindings", f"no package {pkg_dir / name}")
            continue
        rc, out, err = sh([sys.executable, str(HERE / "py_json.py"), str(pkg_dir), name, str(vec_path)])
        if rc != 0:
            ctx.fail("json", "python bindings: import + vectors", f"exit {rc}\n{out[-4000:]}\n{err[-4000:]}")
        # The bindings declare no ruff configuration: ruff's defaults, isolated from whatever
        # configuration an ancestor directory or the user may have.
        rc, out, err = sh(["ruff", "check", "--no-cache", "--isolated", "--target-version", "py310", "."], cwd=pkg_dir)
        if rc != 0:
            ctx.fail("json", "python bindings: ruff check", out + err)
        if mypy:
            ctx.res.checked.append("json-mypy")
            rc, out, err = sh([sys.executable, "-m", "mypy", "--strict", f"--cache-dir={BUILD / 'mypy-cache' / str(os.getpid())}", name], cwd=pkg_dir)
            if rc != 0:
                ctx.fail("json", "python bindings: mypy --strict", out + err)


@dataclass
class Job:
    sid: str
    seed: int | None
    spec_dir: str
    entry: str
    out_dir: str
    features: list[str]
    facts: dict[str, Any]
    mypy: bool = False
    cross: bool = False  # also the C vector runner on PowerPC and Cortex-M under qemu
    only: list[str] | None = None  # restrict to these targets (the shrinker)
    stage_filter: str | None = None  # and to this sub-stage
    bytewise: bool = True  # also the C runner with the word path off


def guarded(ctx: Ctx, target: str, stage: Any, *args: Any) -> None:
    """Run a stage; a crash of its test helpers (a runner that cannot read a case yet) is that
    target's failure on this spec, not the end of the batch."""
    try:
        stage(*args)
    except Exception as exc:  # noqa: BLE001
        import traceback

        where = traceback.extract_tb(exc.__traceback__)[-1]
        ctx.fail(target, "test helper crashed", f"{type(exc).__name__}: {exc} ({Path(where.filename).name}:{where.lineno})")


def run_spec(job: Job) -> SpecResult:
    """check → gen → every output's own checks (not Rust/TypeScript: see the batch stages)."""
    t0 = time.monotonic()
    res = SpecResult(job.sid, job.seed, job.spec_dir, job.entry, job.out_dir, job.features, job.facts)
    ctx = Ctx(res)
    ctx.stage_filter = job.stage_filter
    ctx.bytewise = job.bytewise
    shutil.rmtree(job.out_dir, ignore_errors=True)
    want = set(job.only) if job.only else None

    def wanted(*names: str) -> bool:
        return want is None or bool(want & set(names))

    if stage_check(ctx) and (want is None or want - {"check"}):
        gen_targets = list(CANSPEC_TARGETS)
        if want is not None:
            needs = {"c": ["c", "vectors"], "python": ["python", "vectors"], "cantools": ["dbc", "vectors"], "canmatrix": ["dbc", "vectors"],
                     "json": ["jsonschema", "json_vectors", "json_bindings"], "typescript": ["json_bindings", "json_vectors"], "rust": ["rust", "vectors"]}
            gen_targets = sorted({t for w in want for t in needs.get(w, [w.split(":", 1)[-1]]) if t in gen_targets})
        stage_gen(ctx, gen_targets)
        g = set(res.generated)
        if not (ctx.out / "vectors" / "can.json").is_file():  # a JSON-only spec: no CAN outputs to check
            g -= {"c", "python", "dbc", "rust", "vectors"}
            res.facts["has_json"] = True
        if wanted("c") and {"c", "vectors"} <= g:
            guarded(ctx, "c", stage_c, ctx)
            if job.cross:
                guarded(ctx, "c", cross_stage.stage_c_cross, ctx)
        if wanted("python") and {"python", "vectors"} <= g:
            guarded(ctx, "python", stage_python, ctx, job.mypy)
        if wanted("cantools", "canmatrix") and {"dbc", "vectors"} <= g:
            guarded(ctx, "cantools", stage_cantools, ctx)
        if wanted("json") and res.facts.get("has_json") and {"jsonschema", "json_vectors", "json_bindings"} <= g:
            guarded(ctx, "json", stage_json, ctx, job.mypy)
    res.seconds = time.monotonic() - t0
    return res


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


# --- refusals: the relaxations of this issue ----------------------------------------------

REFUSAL_PATTERNS = [
    ("j1939_derived", r"\[j1939-missing\]"),
    ("event_driven", r"cycle time 0 ms .*\[cycle-time\]|'cycle_ms' is required"),
    ("empty_signals", r"\[empty-message\]"),
    ("optional_signal_zh", r"(signals|add)\.\d+: 'zh' is required"),
    ("bare_value_ident", r"value_tables\.\w+\.-?\d+: expected array, got text"),
    ("optional_node_sa", r"nodes\.\d+: 'sa' is required|KeyError: 'sa'"),
]


def classify_refusal(text: str) -> tuple[list[str], list[str]]:
    """(NEW features explaining the refusal, error lines no NEW feature explains)."""
    features, unexplained = [], []
    for line in text.splitlines():
        if ": error:" not in line and "Traceback" not in line:
            continue
        hit = [f for f, rx in REFUSAL_PATTERNS if re.search(rx, line)]
        if hit:
            features += [f for f in hit if f not in features]
        else:
            unexplained.append(line)
    return features, unexplained


# --- driving a batch -----------------------------------------------------------------------


@dataclass
class Batch:
    base_seed: int
    n: int
    features: frozenset[str]
    results: list[SpecResult]
    seconds: float
    timings: dict[str, float]

    @property
    def failures(self) -> list[Failure]:
        return [f for r in self.results for f in r.failures]

    def count(self, what: str, multiplexed: bool = False) -> int:
        """Specs `what` ran on (only the multiplexed ones: `multiplexed`)."""
        return sum(1 for r in self.results if what in r.checked and (r.facts.get("multiplexed") or not multiplexed))

    def runners(self) -> str:
        """What each runner ran on: `C 100 (31 multiplexed)`."""
        names = {"c": "C", "c-cross": "C on PowerPC/Cortex-M", "python": "Python", "python-mypy": "mypy", "cantools": "cantools", "canmatrix": "canmatrix",
                 "json": "JSON", "json-mypy": "JSON mypy", "typescript": "TypeScript", "rust": "Rust"}
        return ", ".join(f"{label} {self.count(k)} ({self.count(k, multiplexed=True)} multiplexed)" for k, label in names.items())


def prepare(spec: strategy.GeneratedSpec, sid: str, run_dir: Path) -> Job:
    d = run_dir / sid
    shutil.rmtree(d, ignore_errors=True)
    spec.write(d / "spec")
    (d / "choices.json").write_text(json.dumps({"seed": spec.seed, "features": sorted(spec.features), "choices": spec.choices}), encoding="utf-8")
    return Job(sid, spec.seed, str(d / "spec"), spec.entry, str(d / "out"), sorted(spec.features), dict(spec.facts))


def run_batch(n: int, base_seed: int, features: frozenset[str] = strategy.ALL, rust: int = 12, mypy_every: int = 10, cross_every: int = 10,
              jobs: int | None = None, run_dir: Path | None = None, log: Any = print) -> Batch:
    t0 = time.monotonic()
    run_dir = run_dir or BUILD / "run"
    if run_dir.exists():
        for child in run_dir.glob("s[0-9][0-9][0-9][0-9]"):
            shutil.rmtree(child, ignore_errors=True)
    run_dir.mkdir(parents=True, exist_ok=True)
    timings = {}
    jobs_list = []
    for i in range(n):
        spec = strategy.example(base_seed + i, features)
        job = prepare(spec, f"s{i:04d}", run_dir)
        job.mypy = mypy_every > 0 and i % mypy_every == 0
        job.cross = cross_every > 0 and i % cross_every == cross_every // 2  # other specs than mypy's
        job.bytewise = i % 4 == 0
        jobs_list.append(job)
    timings["draw specs"] = time.monotonic() - t0
    log(f"anyspec: {n} specs drawn (seeds {base_seed}..{base_seed + n - 1}, features: {','.join(sorted(features)) or 'current'}) "
        f"in {timings['draw specs']:.1f} s")
    t1 = time.monotonic()
    workers = jobs or os.cpu_count() or 2
    results: list[SpecResult] = []
    with ProcessPoolExecutor(max_workers=workers) as pool:
        for k, res in enumerate(pool.map(run_spec, jobs_list, chunksize=1)):
            results.append(res)
            if (k + 1) % 25 == 0 or k + 1 == n:
                log(f"anyspec: {k + 1}/{n} specs through check/gen/C/Python/cantools/JSON ({time.monotonic() - t1:.0f} s)")
    timings["per-spec stages"] = time.monotonic() - t1
    ts_specs = [r for r in results if r.accepted and "json_bindings" in r.generated and r.facts.get("has_json")]
    timings["typescript"] = stage_typescript(ts_specs, run_dir)
    crates = [r for r in results if r.accepted and "rust" in r.generated]
    rust_specs = interleave([r for r in crates if r.facts.get("multiplexed")], [r for r in crates if not r.facts.get("multiplexed")])[: max(rust, 0)]
    timings["rust"] = stage_rust(rust_specs, run_dir)
    log(f"anyspec: Rust workspace of {len(rust_specs)} crates in {timings['rust']:.0f} s; tsc over {len(ts_specs)} specs in {timings['typescript']:.0f} s")
    for r in results:
        for f in r.failures:
            if f.target == "check":
                f.refusal, _ = classify_refusal(f.message)
    batch = Batch(base_seed, n, features, results, time.monotonic() - t0, timings)
    save_failures(batch)
    return batch


def interleave(a: list[SpecResult], b: list[SpecResult]) -> list[SpecResult]:
    """a[0], b[0], a[1], b[1], …, then the rest of the longer one: the Rust workspace takes
    multiplexed and plain specs alike."""
    out = [x for pair in zip(a, b) for x in pair]
    return out + a[len(b):] + b[len(a):]


def repro_command(f: Failure | SpecResult, features: frozenset[str] | list[str] | None = None) -> str:
    seed = f.seed
    feats = "" if features is None or frozenset(features) == strategy.ALL else f" --features {','.join(sorted(features)) or 'current'}"
    if seed is not None:
        return f"python3 tests/anyspec/run.py --seed {seed}{feats}"
    return f"python3 tests/anyspec/run.py --spec {f.spec_dir}"


def save_failures(batch: Batch) -> None:
    for r in batch.results:
        if not r.failures:
            continue
        dest = FAILURES / f"seed-{r.seed}"
        shutil.rmtree(dest, ignore_errors=True)
        shutil.copytree(r.spec_dir, dest)
        shutil.copy(Path(r.spec_dir).parent / "choices.json", dest / "choices.json")
        lines = [
            f"seed {r.seed} ({r.sid}); features used: {', '.join(r.features) or 'none'}; features allowed: {','.join(sorted(batch.features)) or 'current'}",
            f"reproduce: {repro_command(r, batch.features)}", f"   or: python3 tests/anyspec/run.py --spec {dest / r.entry}", ""]
        for f in r.failures:
            lines += [f"== {f.target}: {f.stage}", f.message, ""]
        (dest / "FAILURE.txt").write_text("\n".join(lines), encoding="utf-8")


def report(batch: Batch, verbose_specs: int = 3) -> str:
    """The summary printed after a run: counts, then each distinct failure once (seed, repro,
    stage, error, the spec's YAML for the first few), then the other seeds."""
    out = []
    accepted = sum(r.accepted for r in batch.results)
    out.append(f"anyspec: {batch.n} specs (seeds {batch.base_seed}..{batch.base_seed + batch.n - 1}) in {batch.seconds:.0f} s; "
               f"{accepted} accepted by canspec check, {sum(bool(r.facts.get('multiplexed')) for r in batch.results)} multiplexed; "
               f"checked: {batch.runners()}")
    out.append("timings: " + ", ".join(f"{k} {v:.0f} s" for k, v in batch.timings.items()))
    groups: dict[str, list[Failure]] = {}
    for f in batch.failures:
        key = f.signature
        if f.target == "check":
            refused = classify_refusal(f.message)[1]
            key = f"check | refused: {', '.join(sorted(f.refusal or [])) or 'UNEXPLAINED'} | {signature_text(refused[0]) if refused else ''}"
        groups.setdefault(key, []).append(f)
    if not groups:
        out.append("anyspec: no failures")
        return "\n".join(out)
    out.append(f"anyspec: {len(batch.failures)} failure(s) in {len({f.sid for f in batch.failures})} spec(s), {len(groups)} distinct; "
               f"each spec is saved under {FAILURES.relative_to(ROOT)}/seed-<seed>/ (FAILURE.txt says how to reproduce)")
    shown = 0
    for key, fs in sorted(groups.items(), key=lambda kv: (-len(kv[1]), kv[0])):
        f = fs[0]
        out.append("")
        out.append(f"--- {key}  [{len({x.sid for x in fs})} spec(s)]")
        out.append(f"seed {f.seed}: {f.target}: {f.stage}")
        out.append(f"reproduce: {repro_command(f, batch.features)}")
        out.append("error: " + "\n       ".join(f.message.strip().splitlines()[:14]))
        if shown < verbose_specs:
            shown += 1
            r = next(r for r in batch.results if r.sid == f.sid)
            out.append("spec:")
            for p in sorted(Path(r.spec_dir).iterdir()):
                out.append(f"# file: {p.name}")
                out.append(p.read_text(encoding="utf-8").rstrip())
        if len(fs) > 1:
            seeds = list(dict.fromkeys(x.seed for x in fs[1:] if x.sid != f.sid))
            if seeds:
                out.append("also seeds: " + ", ".join(map(str, seeds[:12])) + (" ..." if len(seeds) > 12 else ""))
    return "\n".join(out)


def to_json(batch: Batch) -> dict[str, Any]:
    return {"base_seed": batch.base_seed, "n": batch.n, "features": sorted(batch.features), "seconds": batch.seconds, "timings": batch.timings,
            "results": [asdict(r) for r in batch.results]}
