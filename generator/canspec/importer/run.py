"""The import as one call: each source loaded and converted, the sources merged, target-name
clashes resolved. Warnings come back in the report; a source no repair makes readable raises
DbcError."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from canspec.importer import merge, tospec
from canspec.importer.clashes import RoundCompile, compile_in_temp, resolve_clashes
from canspec.importer.load import Loaded, load
from canspec.pipeline import Compiled


def import_sources(sources: list[str], encoding: str | None = None,
                   compile_round: RoundCompile = compile_in_temp) -> tuple[dict[str, Any], tospec.Report, Compiled]:
    """The spec, the warnings, and the spec compiled (its problems are what `canspec check` says).
    `compile_round`: how each round of clash resolution compiles the spec (default: privately)."""
    return import_loaded([load(Path(source), source, encoding) for source in sources], compile_round)


def import_loaded(sources: list[Loaded], compile_round: RoundCompile = compile_in_temp) -> tuple[dict[str, Any], tospec.Report, Compiled]:
    report = tospec.Report()
    specs = []
    for loaded in sources:
        for line, text in loaded.warnings:
            report.warn(loaded.source, line, text)
        specs.append((loaded.source, tospec.build_spec(loaded, report)))
    spec = merge.merge(specs)
    compiled = resolve_clashes(spec, lambda text: report.warn(sources[0].source if len(sources) == 1 else "import", None, text), compile_round)
    return spec, report, compiled
