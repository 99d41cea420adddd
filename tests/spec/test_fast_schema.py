"""The schema's fast path (fastjsonschema, spec/fastschema.py) says *valid* exactly where the full
check (jsonschema, as the loader configures it) finds no error: a differential test over every YAML
file the tests and the repository hold, and over thousands of single mutations of valid specs (a
value swapped for one of another type or size, a key added, a key turned into a number). Both read
a pattern's `$` as JSON Schema does, the end of the text (Python's `re` also matches before a final
newline: the first version of this test found the name "abc\\n" accepted as an identifier)."""

from __future__ import annotations

import copy
import random
from decimal import Decimal
from pathlib import Path
from typing import Any

import pytest
from canspec import resources
from canspec.pipeline import compile_spec
from canspec.spec import fastschema, loader
from canspec.spec.problems import SpecError
from canspec.spec.yamlsource import LocDict, load_yaml
from canspec_cli import FIXTURES, ROOT

SCHEMA = resources.spec_schema_path(1)
ALIENS = ["x", "", "Name With Space", "abc\n", 0, -1, 1.5, Decimal("0.5"), Decimal("1.0"), 2**70, True, None, [], {}, [1, 2, 3], {"a": 1}]
MUTATIONS_PER_FILE = 400  # fewer in a large file (each mutant is a full check): about 100,000 nodes checked per file


_FULL = loader._validator(1)


def full_check(document: Any) -> bool:
    return not any(True for _ in _FULL.iter_errors(document))


def _documents() -> list[Path]:
    found = [*FIXTURES.rglob("*.yaml"), *(ROOT / "spec").rglob("*.yaml"), *(ROOT / "bench").rglob("*.yaml"), *(ROOT / "examples").rglob("*.yaml")]
    out = []
    for path in sorted(found):
        try:
            data = load_yaml(path)
        except SpecError:  # not YAML the loader takes: never reaches the schema
            continue
        if isinstance(data, LocDict) and data.get("schema_version") == 1:
            out.append(path)
    return out


DOCUMENTS = _documents()


def _fast() -> fastschema.Check:
    fast = fastschema.checker(SCHEMA)
    assert fast is not None, "fastjsonschema is a dependency (pyproject.toml): install it"
    return fast


def test_the_files_cover_both_verdicts() -> None:
    fast = _fast()
    verdicts = [fast(load_yaml(path)) for path in DOCUMENTS]
    assert len(DOCUMENTS) > 150
    assert verdicts.count(True) > 50 and verdicts.count(False) >= 5, verdicts.count(False)


@pytest.mark.parametrize("path", DOCUMENTS, ids=lambda p: str(p.relative_to(ROOT)))
def test_fast_and_full_agree_on_every_file(path: Path) -> None:
    document = load_yaml(path)
    assert _fast()(document) == full_check(document)


def _slots(node: Any, out: list[tuple[Any, Any]]) -> list[tuple[Any, Any]]:
    """Every (container, key) of the document, depth first."""
    items = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else ()
    for key, value in items:
        out.append((node, key))
        _slots(value, out)
    return out


def _mutants(document: Any, rng: random.Random) -> list[Any]:
    out = []
    for _ in range(_how_many(document)):
        mutant = copy.deepcopy(document)
        container, key = rng.choice(_slots(mutant, []))
        move = rng.randrange(4)
        if move == 0 or not isinstance(container, dict):
            container[key] = copy.deepcopy(rng.choice(ALIENS))
        elif move == 1:
            container["zz_unknown"] = 1
        elif move == 2 and isinstance(key, str):
            container[len(key)] = container.pop(key)  # a number where a name was
        else:
            container[str(key)] = container.pop(key)  # a quoted number where a number was (or a no-op)
        out.append(mutant)
    return out


def _how_many(document: Any) -> int:
    return max(40, min(MUTATIONS_PER_FILE, 100_000 // len(_slots(document, []))))


VALID = [p for p in DOCUMENTS if p.parent.name == "valid" or p.is_relative_to(ROOT / "spec")]


@pytest.mark.parametrize("path", VALID[:: max(1, len(VALID) // 12)], ids=lambda p: p.name)
def test_fast_and_full_agree_on_mutations(path: Path) -> None:
    fast = _fast()
    base = load_yaml(path)
    assert fast(base) and full_check(base), "the base must be valid, so that its mutants test both verdicts"
    disagree, rejected = [], 0
    for mutant in _mutants(base, random.Random(path.name)):
        verdict = fast(mutant)
        rejected += not verdict
        if verdict != full_check(mutant):
            disagree.append((verdict, mutant))
    assert not disagree, f"{len(disagree)} mutants judged differently; first (fast path's verdict, mutant): {disagree[0]!r}"[:3000]
    assert rejected > _how_many(base) // 10


def test_a_name_ending_in_a_newline_is_refused_where_it_stands(tmp_path):
    text = (FIXTURES / "valid" / "minimal_can.yaml").read_text(encoding="utf-8")
    assert "  - name: command\n" in text
    bad = tmp_path / "spec.yaml"
    bad.write_text(text.replace("  - name: command\n", '  - name: "command\\n"\n'), encoding="utf-8")
    line = text[: text.index("  - name: command")].count("\n") + 1
    problems = compile_spec(bad).errors
    assert [(p.rule, p.loc.line, p.message) for p in problems] == [("schema", line, "messages.0.name: 'command\\n' does not match ^[a-z][a-z0-9_]*$")]
