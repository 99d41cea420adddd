"""The handbook of every valid fixture (tests/fixtures/valid/): bilingual where the spec is,
English-only where it is, no J1939 where the bus has no J1939 addressing, event-driven messages
shown as such and kept out of the bus-load figures, DLC-0 messages without a bit diagram — and all
of them together build with `mkdocs build --strict` (one site, one build)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from canspec.pipeline import compile_spec
from canspec.targets import docs
from docs_support import ROOT, mkdocs_build_many, require_mkdocs

FIXTURES = sorted((ROOT / "tests" / "fixtures" / "valid").glob("*.yaml"))
CJK = re.compile(r"[\u3000-\u9fff\uff00-\uffef]")


def _spec(path: Path):  # type: ignore[no-untyped-def]
    result = compile_spec(path)
    assert result.spec is not None, [p.format() for p in result.problems]
    return result.spec


def _pages(spec) -> dict[str, str]:  # type: ignore[no-untyped-def]
    return {rel.removeprefix("docs/"): data.decode("utf-8") for rel, data in docs.render_docs(spec).items()}


def _section(page: str, anchor: str) -> str:
    """The text under the heading with this id, up to the next heading ("" when there is none)."""
    m = re.search(r"^## .*\{#" + anchor + r"\}\n(.*?)(?=^## |\Z)", page, re.MULTILINE | re.DOTALL)
    return m.group(1) if m else ""


def _has_chinese(path: Path) -> bool:
    """Whether the spec's files hold Chinese text (read from the YAML, not from the IR; a bundle's
    parts included)."""
    import yaml

    files = [path]
    data = yaml.safe_load(path.read_text(encoding="utf-8"))
    if data.get("kind") == "bundle":
        files += [path.parent / f for f in data["files"]]
    text = "\n".join(line for f in files for line in f.read_text(encoding="utf-8").splitlines() if not line.lstrip().startswith("#"))
    return bool(CJK.search(text))


@pytest.mark.parametrize("path", FIXTURES, ids=lambda p: p.stem)
def test_languages_follow_the_spec(path):
    pages = _pages(_spec(path))
    bilingual = _has_chinese(path)
    assert ("## 更多 More {#more}" if bilingual else "## More {#more}") in pages["index.md"]
    for rel, text in pages.items():
        assert bilingual or not CJK.search(text), f"{rel}: {CJK.search(text)}"
        assert not re.search(r"\(\s*\)|^#+ — | — (\{#.*)?$", text, re.MULTILINE), rel  # nothing left empty


@pytest.mark.parametrize("path", FIXTURES, ids=lambda p: p.stem)
def test_can_facts_follow_the_spec(path):
    spec = _spec(path)
    if spec.can is None:
        assert not any(rel.startswith("messages/") for rel in _pages(spec))
        return
    can, pages = spec.can, _pages(spec)
    index, load = pages["index.md"], pages["busload.md"]
    assert ("(J1939)" in index and "| PGN |" in index) == can.bus.is_j1939
    for msg in can.messages:
        page = pages[f"messages/{msg.name}.md"]
        assert f"`{msg.id_text}`" in page and ("11-bit standard" in page) != msg.is_extended
        assert ("| PGN |" in page) == (msg.j1939 is not None)
        if msg.j1939 is not None:
            assert f"{msg.j1939.pgn} ({msg.j1939.pgn_text})" in page
        row = next(line for line in index.splitlines() if line.startswith(f"| [`{msg.id_text}`](messages/{msg.name}.md)"))
        link = f"(messages/{msg.name}.md)"
        assert (link in _section(load, "per-message")) == msg.is_cyclic  # event-driven: not in the figures …
        assert (link in _section(load, "event-driven")) == (not msg.is_cyclic)  # … but listed apart
        assert (f"| {msg.cycle_ms} ms |" if msg.is_cyclic else "| event-driven") in row
        # one diagram, or one per page layout of a multiplexed message (ir.Message.page_layouts), each linked from the page
        diagrams = [f"{msg.name}.svg"] if not msg.is_multiplexed else [f"{msg.name}.page-{n}.svg" for n in range(1, len(msg.page_layouts) + 1)]
        assert all((f"messages/{d}" in pages) == (msg.dlc > 0) and (d in page) == (msg.dlc > 0) for d in diagrams), diagrams
        for sig in msg.signals:
            for lb in sig.labels:
                assert (f"{lb.raw} = " if not lb.is_special else f"0x{lb.raw:X} = " if lb.raw >= 0 else f"-0x{-lb.raw:X} = ") in page


def test_every_fixture_handbook_builds_strictly(tmp_path):
    require_mkdocs()
    handbooks = {}
    for path in FIXTURES:
        for rel, data in docs.render_docs(_spec(path)).items():
            target = tmp_path / "gen" / path.stem / rel
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(data)
        handbooks[path.stem] = tmp_path / "gen" / path.stem / "docs"
    result = mkdocs_build_many(tmp_path / "site", handbooks)
    assert result.returncode == 0, result.stdout + result.stderr
    for name in handbooks:
        assert (tmp_path / "site" / name / "index.html").is_file()
