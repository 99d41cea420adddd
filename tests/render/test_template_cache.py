"""Compiled templates are kept in the cache directory (render/environment.py), and the cache is only a
shortcut: a kept template renders what a freshly compiled one does, and a damaged entry or a cache
directory that cannot be made costs the compile, never an error."""

from __future__ import annotations

from pathlib import Path

import pytest
from canspec.render import environment as env_module
from canspec.render.environment import environment
from canspec.targets import registry


@pytest.fixture
def fresh(monkeypatch: pytest.MonkeyPatch, tmp_path: Path):
    """A cache directory of this test's own, and environments made anew for it (and again after)."""
    monkeypatch.setenv("CANSPEC_CACHE_DIR", str(tmp_path / "cache"))
    environment.cache_clear()
    yield tmp_path / "cache"
    environment.cache_clear()


def _render_anew(spec) -> dict[str, bytes]:
    environment.cache_clear()
    return registry()["dbc"].render(spec)


def test_a_kept_template_renders_as_a_compiled_one(fresh: Path, spec) -> None:
    compiled = _render_anew(spec)
    kept = list(fresh.glob("templates-dbc-*/*"))
    assert kept, "the compiled template should be kept"
    assert _render_anew(spec) == compiled


def test_a_damaged_entry_is_compiled_again(fresh: Path, spec) -> None:
    compiled = _render_anew(spec)
    for entry in fresh.glob("templates-dbc-*/*"):
        entry.write_bytes(entry.read_bytes()[:40])  # cut after Jinja's header: the code is missing
    assert _render_anew(spec) == compiled


def test_a_cache_directory_that_cannot_be_made_is_no_error(monkeypatch: pytest.MonkeyPatch, tmp_path: Path, spec) -> None:
    blocker = tmp_path / "a-file"
    blocker.write_text("not a directory", encoding="utf-8")
    monkeypatch.setenv("CANSPEC_CACHE_DIR", str(blocker / "cache"))
    try:
        assert env_module._bytecode_cache("dbc") is None
        assert _render_anew(spec)
    finally:
        environment.cache_clear()
