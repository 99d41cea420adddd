"""Helpers shared by the docs tests: paths, building the MkDocs site, the tool requirement rule.

The site tests need MkDocs + Material and the browser test Debian's chromium + chromedriver and
selenium (all installed by .ci/setup.d/70-docs.sh). Without them a developer's run skips those
tests with the reason; under CI (CI=true) a missing tool is a failure, never a silent skip.
"""

from __future__ import annotations

import functools
import importlib.util
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[3]
GENERATED_DOCS = ROOT / "generated" / "docs"
MKDOCS_YML = ROOT / "mkdocs.yml"
SCREENSHOTS = ROOT / "build" / "docs-screenshots"


def require(ok: bool, what: str) -> None:
    if ok:
        return
    message = f"{what} is not installed (run `bash .ci/setup` or `bash .ci/setup.d/70-docs.sh`)"
    if os.environ.get("CI"):
        pytest.fail(message)
    pytest.skip(message)


def require_mkdocs() -> None:
    require(all(importlib.util.find_spec(m) is not None for m in ("mkdocs", "material", "jieba")), "mkdocs / mkdocs-material / jieba")


def mkdocs_build(out: Path, docs_dir: Path | None = None) -> subprocess.CompletedProcess[str]:
    """`mkdocs build --strict` of the repository's mkdocs.yml, optionally on another docs dir."""
    config = MKDOCS_YML
    if docs_dir is not None:
        data = yaml.safe_load(MKDOCS_YML.read_text(encoding="utf-8"))
        data["docs_dir"] = str(docs_dir)
        data["INHERIT"] = str(docs_dir / "mkdocs.nav.yml")
        config = out.parent / f"{out.name}-mkdocs.yml"
        config.write_text(yaml.safe_dump(data, allow_unicode=True), encoding="utf-8")
    env = {**os.environ, "NO_MKDOCS_2_WARNING": "1"}
    return subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-f", str(config), "-d", str(out)],
                          cwd=ROOT, env=env, capture_output=True, text=True, timeout=300, check=False)


@functools.lru_cache(maxsize=1)
def built_site() -> Path:
    """The shipped handbook built once per test run (into a temporary directory, not site/)."""
    out = Path(tempfile.mkdtemp(prefix="canspec-site-")) / "site"
    result = mkdocs_build(out)
    if result.returncode != 0:
        raise AssertionError(f"mkdocs build --strict failed:\n{result.stdout}\n{result.stderr}")
    return out


def copy_docs(dest: Path) -> Path:
    shutil.copytree(GENERATED_DOCS, dest)
    return dest


def _prefixed(node: Any, prefix: str) -> Any:
    if isinstance(node, str):
        return prefix + node
    if isinstance(node, list):
        return [_prefixed(n, prefix) for n in node]
    return {k: _prefixed(v, prefix) for k, v in node.items()}


def mkdocs_build_many(out: Path, handbooks: dict[str, Path]) -> subprocess.CompletedProcess[str]:
    """`mkdocs build --strict` of one site holding several handbooks, each in a folder of its own
    with its own generated nav (one build instead of one per spec: MkDocs takes seconds to start)."""
    docs = out.parent / f"{out.name}-docs"
    nav: list[Any] = [{"Handbooks": "index.md"}]
    for name, handbook in handbooks.items():
        shutil.copytree(handbook, docs / name, ignore=shutil.ignore_patterns("mkdocs.nav.yml"))
        nav.append({name: _prefixed(yaml.safe_load((handbook / "mkdocs.nav.yml").read_text(encoding="utf-8"))["nav"], f"{name}/")})
    (docs / "index.md").write_text("# Handbooks\n\n" + "".join(f"- [{n}]({n}/index.md)\n" for n in handbooks), encoding="utf-8")
    data = yaml.safe_load(MKDOCS_YML.read_text(encoding="utf-8"))
    del data["INHERIT"]
    data.update(docs_dir=str(docs), site_name="canspec handbooks", nav=nav, exclude_docs="",
                extra_css=[f"{next(iter(handbooks))}/assets/handbook.css"])
    config = out.parent / f"{out.name}-mkdocs.yml"
    config.write_text(yaml.safe_dump(data, allow_unicode=True), encoding="utf-8")
    env = {**os.environ, "NO_MKDOCS_2_WARNING": "1"}
    return subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-f", str(config), "-d", str(out)],
                          cwd=ROOT, env=env, capture_output=True, text=True, timeout=600, check=False)
