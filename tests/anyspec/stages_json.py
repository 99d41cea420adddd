"""The JSON stage of the anyspec harness (stages.py): each protocol's generated JSON Schemas held to
the vectors by jsonschema and by ajv, and its Python bindings run on the vectors, ruff-checked and,
on a sample, mypy --strict."""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path
from typing import Any

from anyspec import adapters
from anyspec.harness_base import BUILD, Ctx, sh

HERE = Path(__file__).resolve().parent


def stage_json(ctx: Ctx, mypy: bool) -> None:
    vec_path = ctx.out / "vectors" / "json.json"
    if not vec_path.is_file():
        ctx.fail("json", "vectors", f"no {vec_path}")
        return
    doc = json.loads(vec_path.read_text(encoding="utf-8"))
    ctx.res.checked.append("json")
    schema_root = ctx.out / "jsonschema"
    for proto in doc["protocols"]:
        if _jsonschema_verdicts(ctx, schema_root / proto["protocol"], proto["cases"]):
            _ajv_agrees(ctx, schema_root, vec_path, proto["cases"])
            _python_bindings(ctx, proto["protocol"], vec_path, mypy)


def _jsonschema_verdicts(ctx: Ctx, sdir: Path, cases: list[dict[str, Any]]) -> bool:
    """jsonschema's verdicts on every case, by the message's own schema, the receiver's and the
    protocol's, against the vectors'. False: the schemas themselves do not load."""
    import jsonschema

    try:
        validators = {}
        for path in sorted(sdir.glob("*.schema.json")):
            schema = json.loads(path.read_text(encoding="utf-8"))
            jsonschema.Draft202012Validator.check_schema(schema)
            validators[path.name.removesuffix(".schema.json")] = jsonschema.Draft202012Validator(schema)
    except Exception as exc:  # noqa: BLE001 — a broken schema is reported, never swallowed
        ctx.fail("json", "jsonschema: schemas", f"{type(exc).__name__}: {exc}")
        return False
    bad = []
    for c in cases:
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
    return True


def _ajv_agrees(ctx: Ctx, schema_root: Path, vec_path: Path, cases: list[dict[str, Any]]) -> None:
    """ajv (the JavaScript validator users run) on the same cases."""
    rc, out, err = sh(["node", str(adapters.AJV_CHECK), str(schema_root), str(vec_path)], env=adapters.node_env())
    if rc != 0:
        ctx.fail("json", "ajv", out[-3000:] + err[-3000:])
        return
    results = {r["id"]: r for r in json.loads(out)}
    bad = []
    for c in cases:
        r = results.get(c["id"])
        if r is None:
            bad.append(f"{c['id']}: not checked by ajv")
        elif r["own"] != c["valid"] or r["received"] != (c["as_received"] is not None) or r["any"] != (c["as_any"] is not None):
            bad.append(f"{c['id']}: ajv own={r['own']} received={r['received']} any={r['any']}, "
                       f"vectors valid={c['valid']} as_received={c['as_received']} as_any={c['as_any']}")
    if bad:
        ctx.fail("json", "ajv vs vectors/json.json", f"{len(bad)} case(s) disagree; first: " + "\n".join(bad[:8]))


def _python_bindings(ctx: Ctx, name: str, vec_path: Path, mypy: bool) -> None:
    pkg_dir = ctx.out / "json" / "python" / name
    if not (pkg_dir / name / "__init__.py").is_file():
        ctx.fail("json", "python bindings", f"no package {pkg_dir / name}")
        return
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
