"""A large header is formatted by clang-format in chunks (issue 25, item 5: speed at 1,000
messages); the oracle is clang-format run on the whole text, which must give the same bytes."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from canspec import resources
from canspec.pipeline import compile_spec
from canspec.render import formatters
from canspec.render.environment import render
from canspec.render.formatters import chunks, clang_format, clang_format_files
from canspec.targets.c.model import build_model
from canspec.targets.c.names import HEADERS


@pytest.mark.parametrize(("template", "suffix"), HEADERS)
def test_chunked_format_equals_whole(template: str, suffix: str) -> None:
    spec = compile_spec(None).spec
    text = render(template, spec, "c", c=build_model(spec))
    style = resources.templates_dir() / "c" / ".clang-format"
    if suffix == "_messages.h":
        assert len(chunks(text, 4000)) > 10  # the shipped messages header really is cut
    assert clang_format_files({suffix: text}, style, size=4000) == {suffix: clang_format(text, suffix, style)}


def _shipped_headers() -> tuple[dict[str, str], Path]:
    """The shipped spec's headers before formatting, and the style file."""
    spec = compile_spec(None).spec
    model = build_model(spec)
    return {f"x{suffix}": render(template, spec, "c", c=model) for template, suffix in HEADERS}, resources.templates_dir() / "c" / ".clang-format"


def _recorded_runs(monkeypatch) -> list[list[str]]:
    """The arguments of every formatter process started from now on."""
    calls: list[list[str]] = []
    real_run = formatters.Formatter.run
    monkeypatch.setattr(formatters.Formatter, "run", lambda self, args, text, what, **kw: calls.append(args) or real_run(self, args, text, what, **kw))
    return calls


@pytest.fixture(autouse=True)
def _no_format_cache(monkeypatch):
    """Every test here runs clang-format itself: the oracle, and the processes some of them count."""
    monkeypatch.setenv("CANSPEC_NO_CACHE", "1")


def test_headers_formatted_together_in_one_process_per_core_equal_each_alone(monkeypatch):
    """Every header of the shipped spec in one call, cut in 4,000-character chunks spread over
    two clang-format processes: the same bytes as clang-format on each whole header."""
    monkeypatch.setattr(os, "cpu_count", lambda: 2)
    texts, style = _shipped_headers()
    want = {name: clang_format(text, name, style) for name, text in texts.items()}
    calls = _recorded_runs(monkeypatch)
    assert clang_format_files(texts, style, size=4000) == want
    assert len(calls) == 2 and sum(len(args) - 2 for args in calls) > len(texts)  # two processes, many files


def test_a_failing_clang_format_names_the_header_not_the_private_copy(tmp_path, monkeypatch):
    fake = tmp_path / "clang-format"
    fake.write_text("#!/bin/sh\necho \"error: cannot format $3\" >&2\nexit 1\n", encoding="utf-8")
    fake.chmod(0o755)
    monkeypatch.setitem(formatters.FORMATTERS, "clang-format", formatters.Formatter("clang-format", "-", lambda: str(fake)))
    with pytest.raises(formatters.FormatterError) as err:
        clang_format_files({"gw_messages.h": "int x;\n"}, tmp_path / ".clang-format")
    assert "clang-format failed on gw_messages.h: error: cannot format 00000-gw_messages.h" in str(err.value)
    assert "canspec-c-" not in str(err.value)


def test_without_room_for_working_copies_each_chunk_goes_through_stdin(monkeypatch):
    """A TMPDIR that cannot take the working copies (full, read-only) costs speed, not the bytes."""
    texts, style = _shipped_headers()
    want = {name: clang_format(text, name, style) for name, text in texts.items()}

    def full(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(formatters.tempfile, "TemporaryDirectory", full)
    calls = _recorded_runs(monkeypatch)
    assert clang_format_files(texts, style, size=4000) == want
    assert len(calls) > len(texts) and not any("-i" in args for args in calls)  # a process per chunk, on stdin
