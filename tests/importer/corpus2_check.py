"""The second import corpus (tests/importer/cantools_files, run by `make test-import-corpus`, not
by `make test`): cantools' own test files — DBC, KCD, SYM and ARXML. Each file imports faithfully
(`canspec check` accepts the import; the generated DBC means, in cantools, what the source meant,
message by message and signal by signal, for what the import kept) or is refused with a one-line
reason (canspec's DbcError); nothing ends in another exception."""

from __future__ import annotations

import re
from collections import Counter
from pathlib import Path

import pytest
from canspec.importer.dbctext import DbcError

from importer.corpus import import_one, load_generated, message_facts, signal_facts

HERE = Path(__file__).resolve().parent / "cantools_files"
FILES = sorted(p for p in HERE.rglob("*") if p.suffix in (".dbc", ".kcd", ".sym", ".arxml"))
TALLY: Counter[str] = Counter()


def _left_out(warnings) -> set[str]:
    return {t.split()[1] for _, _, t in warnings if "left out" in t and t.startswith("message ")}


def _spelt(warnings) -> dict[str, str]:
    """Source name → the DBC's, from the warnings `name 'Switch Outputs' is not a DBC identifier: the DBC writes Switch_Outputs`."""
    out = {}
    for _, _, text in warnings:
        if (m := re.match(r"name '(.*)' is not a DBC identifier: the DBC writes (\w+)$", text)) is not None:
            out[m.group(1)] = m.group(2)
    return out


def _compare(imported, tmp_path: Path) -> list[str]:
    (tmp_path / "generated.dbc").write_text(imported.dbc, encoding="utf-8")
    ours, _ = load_generated(tmp_path / "generated.dbc")
    source, skipped, out = imported.loaded.db, _left_out(imported.warnings), []
    for msg in source.messages:
        if msg.name in skipped:
            continue
        mine = next((m for m in ours.messages if (m.frame_id, m.is_extended_frame) == (msg.frame_id, msg.is_extended_frame)), None)
        if mine is None:  # left out: a warning must name it
            if not any(msg.name in text for _, _, text in imported.warnings):
                out.append(f"{msg.name}: missing without a warning")
            continue
        a, b = message_facts(msg), message_facts(mine)
        spelt = _spelt(imported.warnings)  # a name a DBC cannot write, as the warning says the DBC writes it
        a["senders"] = sorted(spelt.get(n, n) for n in a["senders"])
        for key in ("fd", "send_type", "attributes"):  # a KCD/SYM/ARXML source has no DBC attributes; FD: compared by the opendbc corpus
            a.pop(key), b.pop(key)
        if a != b:
            out.append(f"{msg.name}: {a} became {b}")
        kept = {s.name for s in mine.signals}
        for sig in msg.signals:
            name = spelt.get(sig.name, sig.name)
            if name not in kept or any(f" {sig.name} " in f" {text} " for _, _, text in imported.warnings):
                continue  # left out, or changed with a word (a float's scaling, a label outside the field)
            x, y = signal_facts(sig), signal_facts(mine.get_signal_by_name(name))
            if x["page"] is not None:
                x["page"] = (spelt.get(x["page"][0], x["page"][0]), x["page"][1])
            for key in ("minimum", "maximum", "attributes", "receivers"):
                x.pop(key), y.pop(key)
            if x != y:
                out.append(f"{msg.name}.{sig.name}: " + str({k: (x[k], y[k]) for k in x if x[k] != y[k]}))
    return out


@pytest.mark.parametrize("path", FILES, ids=[str(p.relative_to(HERE)) for p in FILES])
def test_imports_faithfully_or_is_refused_in_one_line(path: Path, tmp_path: Path) -> None:
    try:
        imported = import_one(path, tmp_path / "spec")
    except DbcError as exc:
        assert "\n" not in str(exc).strip() and str(exc).strip(), repr(exc)
        TALLY["refused"] += 1
        return
    if imported.problems:
        TALLY["import refused by canspec check"] += 1
        pytest.fail(f"canspec check refuses the import of {path.name}:\n" + "\n".join(imported.problems[:5]))
    differences = _compare(imported, tmp_path)
    assert not differences, "\n".join(differences[:8])
    TALLY["imported, no warning" if not imported.warnings else "imported with warnings"] += 1


def test_zz_tally() -> None:
    print(f"\nsecond corpus ({len(FILES)} files): " + ", ".join(f"{k}: {v}" for k, v in sorted(TALLY.items())))
