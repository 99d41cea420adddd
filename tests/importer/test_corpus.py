"""Proof on the corpus (issue 25 item 4): every opendbc DBC imports, `canspec check` accepts the
result, and the DBC `canspec gen` writes from it means what the source meant, compared in cantools
field by field — for every message and signal the import did not leave out with a warning — and
`canspec diff` of the two files says so too."""

from __future__ import annotations

from pathlib import Path

import pytest
from canspec.diff.compare import compare
from canspec.diff.fromdb import from_database
from canspec.diff.inputs import load_model
from canspec.importer.tospec import NO_NODE
from canspec.ir.encoding import raw_range, raw_type_range
from repo_paths import ROOT

from importer.corpus import Imported, import_one, load_generated, message_facts, network_facts, opendbc_files, signal_facts
from importer.kinds import KINDS, kind_of

FILES = opendbc_files()


def _allowed(f: dict, minimum, maximum) -> tuple[int, int] | None:
    """The raw values a range allows: the meaning of [min|max] ([0|0] and none: every value)."""
    if f["float"] or f["scale"] == 0:
        return (minimum, maximum) if (minimum, maximum) != (0, 0) else None
    if minimum is None or maximum is None or (minimum, maximum) == (0, 0):
        return raw_type_range(f["length"], f["signed"])
    lo, hi = raw_range(f["length"], f["signed"], f["scale"], f["offset"], (min(minimum, maximum), max(minimum, maximum)))
    return (lo, hi) if lo <= hi else raw_type_range(f["length"], f["signed"])


def _changed(a: dict, b: dict) -> dict:
    """What differs between two dictionaries of dictionaries, key by key."""
    return {k: ({n: (v, b[k].get(n)) for n, v in a[k].items() if b[k].get(n) != v} | {n: (None, v) for n, v in b[k].items() if n not in a[k]}
                if isinstance(a[k], dict) else (a[k], b[k])) for k in a if a[k] != b[k]}


def _named(warnings, words: str) -> set[str]:
    """The second word (a message's or node's name) of each warning holding `words`."""
    return {text.split()[1] for _, _, text in warnings if words in text}


def _left_out(warnings) -> set[str]:
    """Names of the messages and signals the import left out, each with its own warning."""
    out = set()
    for _, _, text in warnings:
        words = text.split()
        if "left out" in text and words[0] in ("message", "signal"):
            out.add(words[1] if words[0] == "message" else f"{words[3]}.{words[1]}")
    return out


_CACHE: dict[Path, Imported] = {}


@pytest.fixture(scope="module")
def imports(tmp_path_factory):
    """Each file imported once, on first use (the README table's test reads them all)."""
    def get(path: Path) -> Imported:
        if path not in _CACHE:
            _CACHE[path] = import_one(path, tmp_path_factory.mktemp(path.stem))
        return _CACHE[path]
    return get


@pytest.mark.parametrize("path", FILES, ids=[p.name for p in FILES])
def test_import_is_faithful(path: Path, imports, tmp_path: Path) -> None:
    imported = imports(path)
    assert not imported.problems, f"canspec check refuses the import of {path.name}:\n" + "\n".join(imported.problems[:10])
    (tmp_path / "generated.dbc").write_text(imported.dbc, encoding="utf-8")
    (source, source_names), (ours, our_names) = (imported.loaded.db, imported.loaded.renamed), load_generated(tmp_path / "generated.dbc")
    left_out, taken_fd = _left_out(imported.warnings), _named(imported.warnings, "no CAN FD frame format")
    dropped_values = {w[2] for w in imported.warnings if w[2].startswith("value ")}
    mine_net, source_net = network_facts(ours), network_facts(source)
    source_net["nodes"].pop(NO_NODE, None)  # a DBC's "no node", not a node
    for name in _named(imported.warnings, "not declared in BU_"):  # added to the nodes, with a word
        mine_net["nodes"].pop(name, None)
    mismatches = [f"network: {_changed(source_net, mine_net)}"] if mine_net != source_net else []
    for msg in source.messages:
        if msg.name in left_out:
            continue
        mine, facts = ours.get_message_by_frame_id(msg.frame_id), message_facts(msg)
        facts["fd"] |= source_names.get(msg.name, msg.name) in taken_fd
        if message_facts(mine) != facts or our_names.get(mine.name, mine.name) != source_names.get(msg.name, msg.name):
            mismatches.append(f"{msg.name}: {facts} became {mine.name} {message_facts(mine)}")
            continue
        for sig in msg.signals:
            if f"{msg.name}.{sig.name}" in left_out:
                continue
            a, b = signal_facts(sig), signal_facts(mine.get_signal_by_name(sig.name))
            said = [text for _, _, text in imported.warnings if text.startswith(f"signal {source_names.get(sig.name, sig.name)} of ")]
            a["multiplexer"] |= any(text.endswith("taken as their multiplexer") for text in said)  # the pages decide, with a word
            a["multiplexer"] &= not any(text.endswith("taken as a plain field") for text in said)
            for raw in set(a["choices"]) - set(b["choices"]):  # a value the field cannot hold is dropped with a word
                if f"value {raw} of signal {source_names.get(sig.name, sig.name)} does not fit its {sig.length} bits: dropped" in dropped_values:
                    del a["choices"][raw]
            ranges = _allowed(a, a.pop("minimum"), a.pop("maximum")), _allowed(b, b.pop("minimum"), b.pop("maximum"))
            if a != b or ranges[0] != ranges[1]:
                diff = {k: (a[k], b[k]) for k in a if a[k] != b[k]}
                mismatches.append(f"{msg.name}.{sig.name}: {diff or ranges}")
    assert not mismatches, f"{len(mismatches)} differences, first: " + "\n".join(mismatches[:8])
    if not left_out:  # what cantools found equal, `canspec diff` must too (it refuses a file whose import leaves a part out)
        changes = compare(from_database(imported.spec, imported.loaded, str(path), True), load_model(str(tmp_path / "generated.dbc"), True))
        assert not changes, f"canspec diff {path.name} against its own import's DBC: {len(changes)} changes, first: {changes[0]}"


def corpus_table(imports) -> str:
    """The README's corpus table, from the imports themselves."""
    clean = sum(1 for p in FILES if not imports(p).warnings and not imports(p).problems)
    warned = sum(1 for p in FILES if imports(p).warnings and not imports(p).problems)
    refused = [p.name for p in FILES if imports(p).problems]
    kinds: dict[str, list] = {}
    for p in FILES:
        for source, line, text in imports(p).warnings:
            kinds.setdefault(kind_of(text), []).append((p.name, line, text))
    lines = [f"| opendbc {len(FILES)} DBCs | imported, no warning: **{clean}** | with warnings: **{warned}** | refused: **{len(refused)}** |",
             "|---|---|---|---|", "", "| warning | count | files | example |", "|---|---|---|---|"]
    for kind, _ in KINDS:
        found = kinds.get(kind, [])
        if found:
            name, line, text = found[0]
            where = f"{name}:{line}" if line else name
            lines.append(f"| {kind} | {len(found)} | {len({f[0] for f in found})} | `{where}`: {text.replace('|', '/')} |")
    return "\n".join(lines)


def test_the_readme_table_is_what_the_corpus_gives(imports) -> None:
    table = corpus_table(imports)
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert table + "\n\n" in readme, "README's corpus table is stale; it should read:\n" + table
