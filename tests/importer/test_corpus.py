"""Proof on the corpus (issue 25 item 4): every opendbc DBC imports, `canspec check` accepts the
result, and the DBC `canspec gen` writes from it means what the source meant, compared in cantools
field by field — for every message and signal the import did not leave out with a warning."""

from __future__ import annotations

from pathlib import Path

import pytest

from canspec.ir.encoding import raw_range, raw_type_range
from tests.importer.corpus import import_one, load_generated, load_source, message_facts, opendbc_files, signal_facts

FILES = opendbc_files()


def _allowed(f: dict, minimum, maximum) -> tuple[int, int] | None:
    """The raw values a range allows: the meaning of [min|max] ([0|0] and none: every value)."""
    if f["float"] or f["scale"] == 0:
        return (minimum, maximum) if (minimum, maximum) != (0, 0) else None
    if minimum is None or maximum is None or (minimum, maximum) == (0, 0):
        return raw_type_range(f["length"], f["signed"])
    lo, hi = raw_range(f["length"], f["signed"], f["scale"], f["offset"], (min(minimum, maximum), max(minimum, maximum)))
    return (lo, hi) if lo <= hi else raw_type_range(f["length"], f["signed"])


def _left_out(warnings) -> set[str]:
    """Names of the messages and signals the import left out, each with its own warning."""
    out = set()
    for _, _, text in warnings:
        words = text.split()
        if "left out" in text and words[0] in ("message", "signal"):
            out.add(words[1] if words[0] == "message" else f"{words[3]}.{words[1]}")
    return out


@pytest.mark.parametrize("path", FILES, ids=[p.name for p in FILES])
def test_import_is_faithful(path: Path, tmp_path: Path) -> None:
    imported = import_one(path, tmp_path)
    assert not imported.problems, f"canspec check refuses the import of {path.name}:\n" + "\n".join(imported.problems[:10])
    (tmp_path / "generated.dbc").write_text(imported.dbc, encoding="utf-8")
    (source, source_names), (ours, our_names) = load_source(path), load_generated(tmp_path / "generated.dbc")
    left_out = _left_out(imported.warnings)
    dropped_values = {w[2] for w in imported.warnings if w[2].startswith("value ")}
    mismatches = []
    for msg in source.messages:
        if msg.name in left_out or msg.is_multiplexed():
            continue
        mine = ours.get_message_by_frame_id(msg.frame_id)
        if message_facts(mine) != message_facts(msg) or our_names.get(mine.name, mine.name) != source_names.get(msg.name, msg.name):
            mismatches.append(f"{msg.name}: {message_facts(msg)} became {mine.name} {message_facts(mine)}")
            continue
        for sig in msg.signals:
            if f"{msg.name}.{sig.name}" in left_out:
                continue
            a, b = signal_facts(sig), signal_facts(mine.get_signal_by_name(sig.name))
            for raw in set(a["choices"]) - set(b["choices"]):  # a value the field cannot hold is dropped with a word
                if f"value {raw} of signal {source_names.get(sig.name, sig.name)} does not fit its {sig.length} bits: dropped" in dropped_values:
                    del a["choices"][raw]
            ranges = _allowed(a, a.pop("minimum"), a.pop("maximum")), _allowed(b, b.pop("minimum"), b.pop("maximum"))
            if a != b or ranges[0] != ranges[1]:
                diff = {k: (a[k], b[k]) for k in a if a[k] != b[k]}
                mismatches.append(f"{msg.name}.{sig.name}: {diff or ranges}")
    assert not mismatches, f"{len(mismatches)} differences, first: " + "\n".join(mismatches[:8])
