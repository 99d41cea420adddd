"""Per-node C (`canspec gen --target c --node NAME`): for every node of the shipped spec and of
every valid fixture, the node's headers compile alone, warning-free, with gcc and clang as C99
and C++ (speccheck.compile_matrix), and declare nothing of the messages the node neither sends
nor receives (judged by the DBC of the full spec, read by cantools)."""

from __future__ import annotations

import re
from pathlib import Path

import cantools
import pytest
import speccheck
from canspec.ir.nodeview import for_node, node_names
from canspec.pipeline import compile_spec
from canspec.targets import registry
from repo_paths import SPEC

FIXTURES = sorted((Path(__file__).resolve().parents[2] / "fixtures" / "valid").glob("*.yaml"))
CASES = [(p.stem, p, n) for p in [SPEC, *FIXTURES] if (c := compile_spec(p).spec) is not None for n in node_names(c)]


def _write(spec, out: Path, target: str) -> None:
    for rel, data in registry()[target].render(spec).items():
        (out / rel).parent.mkdir(parents=True, exist_ok=True)
        (out / rel).write_bytes(data)


@pytest.mark.parametrize(("stem", "path", "node"), CASES, ids=[f"{s}-{n}" for s, _, n in CASES])
def test_node_headers_compile_and_hold_only_its_messages(stem, path, node, tmp_path):
    spec = compile_spec(path).spec
    _write(spec, tmp_path / "full", "dbc")
    (dbc,) = (tmp_path / "full" / "dbc").glob("*.dbc")
    db = cantools.database.load_file(str(dbc), strict=False)
    foreign = [m for m in db.messages if node not in m.senders and not any(node in s.receivers for s in m.signals) and m.signals]
    _write(for_node(spec, node), tmp_path / "node", "c")
    headers = tmp_path / "node" / "c"
    failures = speccheck.compile_matrix(headers, tmp_path)
    assert failures == [], "\n\n".join(failures)
    text = "\n".join(h.read_text(encoding="utf-8") for h in headers.glob("*.h"))
    for msg in foreign:
        spec_name = next(m.name for m in spec.can.messages if m.frame_id == msg.frame_id and m.is_extended == msg.is_extended_frame)
        assert not re.search(rf"_{spec_name}_t\b|_{spec_name.upper()}_FRAME_ID\b", text), (node, spec_name)


def test_cases_cover_nodes_that_miss_messages():
    """At least one node of the shipped spec leaves messages out (else the test proves nothing)."""
    spec = compile_spec(SPEC).spec
    assert any(len(for_node(spec, n).can.messages) < len(spec.can.messages) for n in node_names(spec))
