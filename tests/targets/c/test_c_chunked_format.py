"""A large header is formatted by clang-format in chunks (issue 25, item 5: speed at 1,000
messages); the oracle is clang-format run on the whole text, which must give the same bytes."""

from __future__ import annotations

import pytest
from canspec import resources
from canspec.pipeline import compile_spec
from canspec.render.environment import render
from canspec.render.formatters import clang_format
from canspec.render.formatters import chunks
from canspec.targets.c import _format
from canspec.targets.c.model import build_model
from canspec.targets.c.names import HEADERS


@pytest.mark.parametrize(("template", "suffix"), HEADERS)
def test_chunked_format_equals_whole(template: str, suffix: str) -> None:
    spec = compile_spec(None).spec
    text = render(template, spec, "c", c=build_model(spec))
    style = resources.templates_dir() / "c" / ".clang-format"
    if suffix == "_messages.h":
        assert len(chunks(text, 4000)) > 10  # the shipped messages header really is cut
    assert _format(text, suffix, style, size=4000) == clang_format(text, suffix, style)
