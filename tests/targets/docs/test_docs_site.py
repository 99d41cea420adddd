"""`mkdocs build --strict` of the handbook: it builds, it fails on broken links and missing pages,
the site loads nothing from outside, and the search index holds the Chinese text segmented."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from docs_support import built_site, copy_docs, mkdocs_build, require_mkdocs

# Anything that makes a browser fetch from another host: src/href/srcset/url()/@import/fetch targets.
EXTERNAL = re.compile(r"""(?:\b(?:src|href|srcset|action|poster|data)\s*=\s*["']?\s*|url\(\s*["']?|@import\s+["']?)(?:https?:)?//""", re.IGNORECASE)


@pytest.fixture(scope="module")
def site() -> Path:
    require_mkdocs()
    return built_site()


def test_strict_build_produces_every_page(site, can):
    assert (site / "index.html").is_file() and (site / "busload.html").is_file() and (site / "errata.html").is_file()
    for msg in can.messages:
        assert (site / "messages" / f"{msg.name}.html").is_file()
        assert (site / "messages" / f"{msg.name}.svg").is_file()
    assert not (site / "mkdocs.nav.yml").exists()


def test_site_references_nothing_external(site):
    offenders = []
    for path in site.rglob("*"):
        if path.suffix in {".html", ".css", ".svg", ".xml"}:
            for m in EXTERNAL.finditer(path.read_text(encoding="utf-8", errors="replace")):
                offenders.append(f"{path.relative_to(site)}: {m.group(0)}")
    # Only the SVG namespace URI may look like an address (it is a name, never fetched).
    assert offenders == [], offenders
    html = (site / "index.html").read_text(encoding="utf-8")
    assert "fonts.googleapis" not in html and "fonts.gstatic" not in html


def test_search_index_segments_chinese(site):
    index = json.loads((site / "search" / "search_index.json").read_text(encoding="utf-8"))
    config = index["config"]
    assert "\\u200b" in config["separator"] or "\u200b" in config["separator"]
    text = "\n".join(doc["text"] for doc in index["docs"])
    # jieba splits 方向盘角度指令 into words joined by zero-width spaces that the separator splits on.
    assert "方向盘\u200b角度" in text


def test_broken_link_fails_the_strict_build(tmp_path):
    require_mkdocs()
    docs = copy_docs(tmp_path / "docs")
    page = docs / "messages" / "autocar_eps_command.md"
    page.write_text(page.read_text(encoding="utf-8") + "\nSee [nowhere](no_such_page.md).\n", encoding="utf-8")
    result = mkdocs_build(tmp_path / "site", docs)
    assert result.returncode != 0
    assert "no_such_page.md" in result.stdout + result.stderr


def test_broken_anchor_fails_the_strict_build(tmp_path):
    require_mkdocs()
    docs = copy_docs(tmp_path / "docs")
    page = docs / "index.md"
    page.write_text(page.read_text(encoding="utf-8") + "\nSee [E99](errata.md#e99).\n", encoding="utf-8")
    result = mkdocs_build(tmp_path / "site", docs)
    assert result.returncode != 0
    assert "e99" in result.stdout + result.stderr


def test_missing_page_fails_the_strict_build(tmp_path):
    require_mkdocs()
    docs = copy_docs(tmp_path / "docs")
    (docs / "messages" / "vehicle_state_3.md").unlink()
    result = mkdocs_build(tmp_path / "site", docs)
    assert result.returncode != 0
    assert "vehicle_state_3.md" in result.stdout + result.stderr


def test_site_with_an_errata_file_builds_strictly(tmp_path):
    # ERRATA.md as the spec ships it: a title, sections, one table row per erratum, links into the YAML.
    require_mkdocs()
    import shutil

    from canspec import pipeline
    from canspec.targets import docs as docs_target
    from docs_support import ROOT

    shutil.copytree(ROOT / "spec", tmp_path / "spec")
    (tmp_path / "spec" / "ERRATA.md").write_text(
        "# Errata\n\n## CAN protocol (D)\n\n| ID | Where | Resolution | In the YAML |\n|---|---|---|---|\n"
        "| E03 | §2 | receivers ALL | [gateway](can/gateway.yaml) |\n| E10 | §3.1 | range stays [0, 512] | `max_angular_speed` |\n",
        encoding="utf-8")
    compiled = pipeline.compile_spec(tmp_path / "spec")
    assert compiled.spec is not None
    for rel, data in docs_target.render_docs(compiled.spec).items():
        path = tmp_path / "gen" / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(data)
    result = mkdocs_build(tmp_path / "site", tmp_path / "gen" / "docs")
    assert result.returncode == 0, result.stdout + result.stderr
    html = (tmp_path / "site" / "errata.html").read_text(encoding="utf-8")
    assert 'id="e10"' in html and 'id="cited-e10"' in html and "receivers ALL" in html
