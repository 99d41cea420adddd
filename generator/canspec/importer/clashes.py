"""Target names the imported spec must not share. A target refuses two spec names that become one
identifier in its language (rules c-name-clash, rust-name-clash: `gas_pedal` beside
`gas_pedal_raw`, `parkaid_data2` beside `parkaid_data_2`); in a spec someone wrote, which to rename
is theirs to choose. Here the importer chose the spec names, so it renames the later one (`_2`,
`_3`, …) and keeps the source's spelling as its `dbc_name`: the DBC is unchanged."""

from __future__ import annotations

import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

from canspec.importer.yamlout import dump_with_lines
from canspec.pipeline import Compiled, compile_spec
from canspec.targets.rust.naming import type_name

CLASH_RULES = ("c-name-clash", "rust-name-clash")
MAX_ROUNDS = 50

# A round's compile of the spec as it stands: the compiled spec, the name of the file the spec's
# YAML was compiled from, and each message's and signal's line in it (yamlout.dump_with_lines).
RoundCompile = Callable[[dict[str, Any]], tuple[Compiled, str, dict[int, tuple[int, ...]]]]


def compile_in_temp(spec: dict[str, Any]) -> tuple[Compiled, str, dict[int, tuple[int, ...]]]:
    """The spec compiled from a private temporary file (nothing the user sees is written)."""
    text, where = dump_with_lines(spec, [])
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "spec.yaml"
        path.write_text(text, encoding="utf-8")
        return compile_spec(path), path.name, where


def resolve_clashes(spec: dict[str, Any], warn: Any, compile_round: RoundCompile = compile_in_temp) -> Compiled:
    """Rename until no target reports a clash (at most MAX_ROUNDS rounds); the last compile, whose
    other problems `canspec check` would report, comes back."""
    _rename_rust_types(spec, warn)
    for _ in range(MAX_ROUNDS):
        compiled, name, where = compile_round(spec)
        clashes = [p for p in compiled.problems
                   if p.rule in CLASH_RULES and p.loc is not None and Path(p.loc.file).name == name and p.loc.line in where]
        if not clashes:
            return compiled
        for line in sorted({p.loc.line for p in clashes if p.loc is not None}):
            _rename(spec, where[line], warn)
    return compiled


def _rename_rust_types(spec: dict[str, Any], warn: Any) -> None:
    """The clash real DBCs have most (`ParkAid_Data2` beside `ParkAid_Data_2`: one Rust type), found
    by the Rust target's own naming before the first compile and renamed as a round would rename it
    (the later message): one compile of the spec fewer, 1 s of the largest opendbc DBC's import."""
    seen: set[str] = set()
    for i, msg in enumerate(spec["messages"]):
        if type_name(msg["name"]) in seen:
            _rename(spec, (i,), warn)
        seen.add(type_name(msg["name"]))


def _rename(spec: dict[str, Any], at: tuple[int, ...], warn: Any) -> None:
    msg = spec["messages"][at[0]]
    item, siblings = (msg, spec["messages"]) if len(at) == 1 else (msg["signals"][at[1]], msg["signals"])
    taken = {s["name"] for s in siblings}
    n = 2
    while f"{item['name']}_{n}" in taken:
        n += 1
    old, item["name"] = item["name"], f"{item['name']}_{n}"
    if "dbc_name" not in item:
        item["dbc_name"] = old
        item.update({k: item.pop(k) for k in list(item) if k not in ("name", "dbc_name")})  # dbc_name right after name
    what = "message" if len(at) == 1 else f"signal of {msg.get('dbc_name', msg['name'])}"
    warn(f"{what} {item['dbc_name']}: its C or Rust name clashes with another's: spec name {item['name']} (the DBC keeps {item['dbc_name']})")
