"""Formatted pieces kept in the cache (canspec/render/format_cache.py): a second render of a spec runs
no formatter and gives the bytes a render without the cache gives; an edit reformats only the
pieces that hold it (chunks are cut where the text says); a corrupt entry is formatted again."""

from __future__ import annotations

import subprocess

import pytest
from canspec import resources
from canspec.pipeline import compile_spec
from canspec.render import format_cache, formatters
from canspec.render.formatters import chunks, clang_format, clang_format_files
from canspec.targets import registry
from repo_paths import ROOT

TARGETS = ("c", "python", "rust", "json_bindings")  # every target whose output goes through a formatter
STYLE = resources.templates_dir() / "c" / ".clang-format"


@pytest.fixture
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("CANSPEC_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.delenv("CANSPEC_NO_CACHE", raising=False)
    return tmp_path / "cache"


def _no_formatter(monkeypatch) -> None:
    def refuse(*args, **kwargs):
        raise AssertionError(f"a formatter ran: {args[0][:2]}")

    monkeypatch.setattr(formatters.subprocess, "run", refuse)


def _render(spec) -> dict[str, bytes]:
    return {rel: data for name in TARGETS for rel, data in registry()[name].render(spec).items()}


@pytest.mark.parametrize("fixture", ["shipped", "mux_pages_fill_bits"])
def test_a_second_render_runs_no_formatter_and_gives_the_same_bytes(cache, monkeypatch, fixture):
    spec = compile_spec(None if fixture == "shipped" else ROOT / "tests" / "fixtures" / "valid" / f"{fixture}.yaml").spec
    monkeypatch.setenv("CANSPEC_NO_CACHE", "1")
    fresh = _render(spec)  # the oracle: every formatter run, nothing kept
    monkeypatch.delenv("CANSPEC_NO_CACHE")
    assert _render(spec) == fresh and len(list(cache.glob("format-*"))) > len(TARGETS)
    _no_formatter(monkeypatch)
    assert _render(spec) == fresh


def test_an_edit_reformats_only_the_pieces_that_hold_it(cache, monkeypatch):
    """One function of the shipped messages header changes: the pieces before and after it come from
    the cache, and the whole is what clang-format makes of the edited header."""
    spec = compile_spec(None).spec
    text = _unformatted_messages_header(spec)
    size = 4000
    assert len(chunks(text, size)) > 20
    clang_format_files({"x_messages.h": text}, STYLE, size=size)
    middle = text.index("_unpack(", len(text) // 2)
    edited = text[:middle] + "_unpack_edited(" + text[middle + len("_unpack(") :]
    formatted: list[int] = []
    real = formatters._clang_format_in_place
    monkeypatch.setattr(formatters, "_clang_format_in_place", lambda paths, *a: formatted.extend(p.stat().st_size for p in paths) or real(paths, *a))
    got = clang_format_files({"x_messages.h": edited}, STYLE, size=size)
    monkeypatch.setenv("CANSPEC_NO_CACHE", "1")
    assert got == {"x_messages.h": clang_format(edited, "x_messages.h", STYLE)}
    assert len(formatted) <= 2 and sum(formatted) < len(edited) // 10, formatted


def test_cut_points_depend_on_the_items_not_on_offsets():
    spec = compile_spec(None).spec
    text = _unformatted_messages_header(spec)
    before = chunks(text, 4000)
    middle = text.index("_unpack(", len(text) // 2)
    after = chunks(text[:middle] + "/* an inserted comment, longer than a few characters */" + text[middle:], 4000)
    assert "\n".join(after) != "\n".join(before)
    assert len(set(before) - set(after)) <= 2 and len(set(after) - set(before)) <= 2


def test_a_corrupt_or_foreign_entry_is_formatted_again(cache, monkeypatch):
    spec = compile_spec(None).spec
    monkeypatch.setenv("CANSPEC_NO_CACHE", "1")
    fresh = _render(spec)
    monkeypatch.delenv("CANSPEC_NO_CACHE")
    _render(spec)
    for entry in cache.glob("format-*"):
        entry.write_bytes(b"not zlib")
    calls: list[object] = []
    real = subprocess.run
    monkeypatch.setattr(formatters.subprocess, "run", lambda *a, **k: calls.append(a) or real(*a, **k))
    assert _render(spec) == fresh and calls


def test_the_key_names_the_formatter_its_arguments_style_and_text(tmp_path):
    exe, style = tmp_path / "fmt", tmp_path / ".style"
    exe.write_text("#!/bin/sh\n", encoding="utf-8")
    style.write_text("IndentWidth: 4\n", encoding="utf-8")
    args = [f"--style=file:{style}", "--assume-filename=a.h"]
    base = format_cache.key(str(exe), args, "int x;")
    assert base is not None and base == format_cache.key(str(exe), args, "int x;")
    assert format_cache.key(str(exe), args, "int y;") != base
    assert format_cache.key(str(exe), [args[0], "--assume-filename=b.h"], "int x;") != base
    style.write_text("IndentWidth: 2\n", encoding="utf-8")
    assert format_cache.key(str(exe), args, "int x;") != base
    exe.write_text("#!/bin/sh\n# another version\n", encoding="utf-8")
    assert format_cache.key(str(exe), args, "int x;") not in (base, None)
    assert format_cache.key(str(tmp_path / "absent"), args, "int x;") is None
    config = tmp_path / "rustfmt.toml"
    config.write_text("", encoding="utf-8")
    rust = format_cache.key(str(exe), ["--config-path", str(config)], "fn f() {}")
    config.write_text("max_width = 40\n", encoding="utf-8")
    assert format_cache.key(str(exe), ["--config-path", str(config)], "fn f() {}") not in (rust, None)


def _unformatted_messages_header(spec) -> str:
    from canspec.render.environment import render
    from canspec.targets.c.model import build_model
    from canspec.targets.c.names import HEADERS

    template = next(t for t, suffix in HEADERS if suffix == "_messages.h")
    return render(template, spec, "c", c=build_model(spec))
