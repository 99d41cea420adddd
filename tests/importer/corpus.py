"""The public corpus `canspec import` is measured on: the 115 DBCs of the `opendbc` package on PyPI
(a test dependency, pinned in .ci/setup.d/45-opendbc.sh), read through cantools as the oracle."""

from __future__ import annotations

import importlib.util
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Any

import cantools
from canspec.importer.load import load
from canspec.importer.run import import_loaded
from canspec.importer.yamlout import dump_with_lines
from canspec.ir.dbc_attributes import COMPUTED
from canspec.targets.dbc import render_dbc

OPENDBC_FILES = 115  # opendbc 0.3.1


def opendbc_files() -> list[Path]:
    spec = importlib.util.find_spec("opendbc")
    assert spec is not None and spec.submodule_search_locations, "the opendbc package is missing: bash .ci/setup.d/45-opendbc.sh"
    root = Path(next(iter(spec.submodule_search_locations))) / "dbc"
    files = sorted(root.rglob("*.dbc"))
    assert len(files) == OPENDBC_FILES, f"opendbc holds {len(files)} DBCs, the corpus table counts {OPENDBC_FILES}"
    return files


@dataclass
class Imported:
    source: Path
    warnings: list[tuple[str, int | None, str]]
    spec_dir: Path
    problems: list[str]  # canspec check's errors
    dbc: str | None  # the DBC `canspec gen` writes from the imported spec
    loaded: Any = None  # the source as the importer read it (cantools' database after the repairs)
    spec: Any = None
    skipped: dict[str, str] = field(default_factory=dict)


def import_one(path: Path, out: Path) -> Imported:
    loaded = load(path, path.name)
    spec, report, compiled = import_loaded([loaded])
    out.mkdir(parents=True, exist_ok=True)
    name = spec["protocol"]["name"]
    (out / f"{name}.yaml").write_text(dump_with_lines(spec, ["corpus import"])[0], encoding="utf-8")
    if compiled.spec is None:
        return Imported(path, report.warnings, out, [str(p) for p in compiled.errors], None, loaded)
    dbc = render_dbc(compiled.spec)[f"dbc/{compiled.spec.can.name}.dbc"].decode()
    return Imported(path, report.warnings, out, [], dbc, loaded, compiled.spec)


def load_generated(path: Path) -> tuple[Any, dict[str, str]]:
    """The generated DBC, strictly — through the same repairs: it keeps a source's digit-first names."""
    loaded = load(path, path.name)
    return cantools.database.load_string(loaded.text, database_format="dbc", strict=True), loaded.renamed


def _num(value: Any) -> Fraction | None:
    return None if value is None else Fraction(str(value))


def kept_attributes(obj: Any) -> dict[str, Any]:
    """An object's attribute values but those canspec computes from the spec's fields (compared as the
    facts they give: cycle time, frame format, ...)."""
    attributes = getattr(getattr(obj, "dbc", None), "attributes", None) or {}
    return {name: a.value for name, a in attributes.items() if name not in COMPUTED}


def signal_facts(sig: Any) -> dict[str, Any]:
    """What a signal means, as cantools reads it (names of value labels as written)."""
    return {
        "receivers": sorted(sig.receivers), "comment": sig.comment or None, "attributes": kept_attributes(sig),
        "start": sig.start, "length": sig.length, "byte_order": sig.byte_order, "signed": bool(sig.is_signed) and not sig.is_float,
        "float": sig.is_float, "scale": _num(sig.scale), "offset": _num(sig.offset), "minimum": _num(sig.minimum),
        "maximum": _num(sig.maximum), "unit": sig.unit or "",
        "choices": {int(k): str(getattr(v, "name", v)) for k, v in (sig.choices or {}).items()},
        "multiplexer": bool(sig.is_multiplexer), "page": (sig.multiplexer_signal, sorted(sig.multiplexer_ids)) if sig.multiplexer_ids else None,
    }


def message_facts(msg: Any) -> dict[str, Any]:
    return {"frame_id": msg.frame_id, "extended": bool(msg.is_extended_frame), "length": msg.length, "cycle_time": msg.cycle_time or None,
            "fd": bool(msg.is_fd), "senders": sorted(msg.senders), "send_type": msg.send_type, "comment": msg.comment or None,
            "attributes": kept_attributes(msg)}


def network_facts(db: Any) -> dict[str, Any]:
    """The nodes (name → comment, attributes) and the network's own attributes."""
    return {"nodes": {n.name: (n.comment or None, kept_attributes(n)) for n in db.nodes}, "attributes": kept_attributes(db)}


def one_signal(message: Any, name: str) -> Any:
    """cantools' decoder of one source signal alone: a source message whose signals overlap (kept
    by cantools' non-strict reading, left out by the import with a warning) does not decode whole."""
    sig = message.get_signal_by_name(name)
    return cantools.database.can.Message(frame_id=message.frame_id, name=message.name, length=message.length, signals=[sig],
                                         is_extended_frame=message.is_extended_frame, strict=False)
