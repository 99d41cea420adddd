"""The per-spec stages of the anyspec harness (harness.py): check, gen, then each output held to its own
toolchain and vectors — C (four compilers, strict; the C runner), Python (ruff, mypy, the vector
runner), cantools and canmatrix reading the DBC, the JSON bindings — run for one spec in a worker."""

from __future__ import annotations

import json
import math
import os
import re
import shutil
import struct
import sys
import time
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from anyspec import adapters, cross_stage
from anyspec.harness_base import (
    BUILD,
    C_MODES,
    CANSPEC_TARGETS,
    Ctx,
    SpecRef,
    SpecResult,
    canspec,
    sh,
)
from anyspec.stages_json import stage_json

HERE = Path(__file__).resolve().parent



# --- per-spec stages -----------------------------------------------------------------------


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
    work = ctx.work / "c"
    work.mkdir(exist_ok=True)
    _c_compiles(ctx, cdir, headers, work)
    doc = _vectors(ctx)
    if doc is None or not ctx.want("build vector runner", "C vector runner", "tests/targets/c/gen_runner_tables.py"):
        return
    try:
        (work / "runner_tables.h").write_text(adapters.c_runner_tables(ctx.spec), encoding="utf-8")
    except Exception as exc:  # noqa: BLE001 — a helper's failure is reported, never swallowed
        ctx.fail("c", "tests/targets/c/gen_runner_tables.py", f"{type(exc).__name__}: {exc}")
        return
    _c_vector_runners(ctx, cdir, headers, work, doc)
    sequences = ctx.out / "vectors" / "sequences.json"
    if ctx.want("C sequence runner"):
        try:
            rc, out = adapters.c_sequences(ctx.spec, cdir, sequences, work / "sequences")
        except Exception as exc:  # noqa: BLE001 — a helper's failure is reported, never swallowed
            rc, out = 1, f"{type(exc).__name__}: {exc}"
        if rc != 0 or ", 0 mismatches" not in out:
            ctx.fail("c", "C sequence runner", f"exit {rc}: {out[-4000:]}")


def _c_compiles(ctx: Ctx, cdir: Path, headers: list[str], work: Path) -> None:
    """Each header alone (included twice) under every compiler and standard, strict; the umbrella
    header optimised by gcc and clang (the middle-end warnings)."""
    strict = adapters.c_strict_flags()
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
    for cc in ("gcc", "clang"):
        if not ctx.want(f"{cc} -O2 -c"):
            continue
        rc, out, err = sh([cc, "-std=c99", *strict, "-O2", f"-I{cdir}", "-c", str(umbrella), "-o", os.devnull])
        if rc != 0:
            ctx.fail("c", f"{cc} -O2 -c {umbrella.name[5:-2]}", err)


def _c_vector_runners(ctx: Ctx, cdir: Path, headers: list[str], work: Path, doc: dict[str, Any]) -> None:
    """The C vector runner on every case, with the default strategy and, on every 4th spec (and
    whenever the shrinker asks for it), Cortex-M0+'s (fieldless frames zeroed byte by byte vs
    memset, 64-bit products from 16-bit halves)."""
    strict = adapters.c_strict_flags()
    lines = work / "vectors.lines.txt"
    lines.write_text(adapters.c_vectors_lines(doc, ctx.spec), encoding="ascii")
    macro = None
    for h in headers:
        m = re.search(r"#ifndef\s+(\w+)_STRATEGY\b", (cdir / h).read_text(encoding="utf-8"))
        if m:
            macro = m.group(1)
            break
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


@dataclass
class Job(SpecRef):
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
