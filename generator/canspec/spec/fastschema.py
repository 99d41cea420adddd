"""A fast yes/no answer to "does this document meet the spec schema?", before the full check.

jsonschema walks a 1,000-message spec in about a second: a third of a compile. fastjsonschema
turns the schema into Python code that answers the same question 7x faster, but it gives one
terse error, so it only ever says *valid*: any document it rejects (or anything unexpected) goes
to jsonschema, which finds every error with its location. The verdicts agree on every fixture and
on targeted corner cases (tests/spec/test_fast_schema.py).

fastjsonschema reads draft-07; the spec schema is draft 2020-12 and uses one keyword draft-07
lacks, `prefixItems`, which is draft-07's array form of `items` (our arrays that use it also give
`maxItems`). Generating the validator costs 0.2 s, so its compiled code is kept in the cache
directory of spec_cache, named by everything it depends on."""

from __future__ import annotations

import contextlib
import hashlib
import marshal
import sys
from collections.abc import Callable
from functools import cache
from pathlib import Path
from typing import Any

Check = Callable[[Any], bool]


def _draft07(node: Any) -> Any:
    if isinstance(node, dict):
        out = {("items" if key == "prefixItems" else key): _draft07(value) for key, value in node.items()}
        if "$schema" in out:
            out["$schema"] = "http://json-schema.org/draft-07/schema#"
        return out
    if isinstance(node, list):
        return [_draft07(item) for item in node]
    return node


def _code(schema: dict[str, Any], schema_text: str) -> Any:
    """The validator module's code object, from the cache or generated (and then cached)."""
    import fastjsonschema

    from canspec.spec_cache import cache_dir, store

    key = hashlib.sha256(f"{schema_text}\0{fastjsonschema.VERSION}\0{sys.version}".encode()).hexdigest()[:24]
    folder = cache_dir()
    entry = folder / f"schema-{key}.marshal" if folder is not None else None
    if entry is not None:
        with contextlib.suppress(Exception):  # missing, unreadable or corrupt: generate it again
            return marshal.loads(entry.read_bytes())
    source = fastjsonschema.compile_to_code(_draft07(schema), use_default=False, use_formats=False)
    code = compile(source, "<canspec spec schema>", "exec")
    if entry is not None:
        store(entry, marshal.dumps(code), ".schema-")
    return code


@cache
def checker(schema_path: Path) -> Check | None:
    """A function telling whether a document meets the schema at `schema_path`; None when
    fastjsonschema is not installed (then every document takes the full check)."""
    try:
        import fastjsonschema  # noqa: F401 - only whether it is there
    except ImportError:
        return None
    import json

    text = schema_path.read_text(encoding="utf-8")
    namespace: dict[str, Any] = {}
    exec(_code(json.loads(text), text), namespace)  # noqa: S102 - code fastjsonschema generated from our own schema
    # the schema's own function; the others, one per `$defs` entry, extend its name
    validate = namespace[min((name for name in namespace if name.startswith("validate")), key=len)]

    def meets(document: Any) -> bool:
        try:
            validate(document)
        except Exception:  # noqa: BLE001 - a rejection, or a document the fast code cannot take: the full check decides
            return False
        return True

    return meets
