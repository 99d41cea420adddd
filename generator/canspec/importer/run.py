"""The import as one call: each source loaded and converted, the sources merged, target-name
clashes resolved. Warnings come back in the report; a source no repair makes readable raises
DbcError."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from canspec.importer import merge, tospec
from canspec.importer.clashes import resolve_clashes
from canspec.importer.load import load


def import_sources(sources: list[str]) -> tuple[dict[str, Any], tospec.Report]:
    report = tospec.Report()
    specs = []
    for source in sources:
        loaded = load(Path(source), source)
        for line, text in loaded.warnings:
            report.warn(source, line, text)
        specs.append((source, tospec.build_spec(loaded, report)))
    spec = merge.merge(specs)
    resolve_clashes(spec, lambda text: report.warn(sources[0] if len(sources) == 1 else "import", None, text))
    return spec, report
