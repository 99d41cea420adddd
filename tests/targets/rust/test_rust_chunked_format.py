"""A large Rust module is formatted by rustfmt in chunks (issue 25, item 5: speed and memory at 1,000
messages); the oracle is rustfmt run on the whole text, which must give the same bytes."""

from __future__ import annotations

import pytest
from canspec.pipeline import compile_spec
from canspec.render.environment import render
from canspec.render.formatters import chunks, rustfmt
from canspec.targets.rust import TARGET_NAME, TEMPLATES, _format
from canspec.targets.rust.model import build_crate
from canspec.targets.rust.monitor import build_supervision
from canspec.targets.rust.tests_view import build_tests
from repo_paths import ROOT


@pytest.fixture(autouse=True)
def _no_format_cache(monkeypatch):
    """rustfmt runs on the whole module and on its chunks here: neither comes from format_cache."""
    monkeypatch.setenv("CANSPEC_NO_CACHE", "1")


@pytest.mark.parametrize("spec_path", [None, ROOT / "tests" / "fixtures" / "valid" / "multiplexed.yaml"], ids=["shipped", "multiplexed"])
@pytest.mark.parametrize("rel", ["src/messages.rs", "tests/vectors.rs"])
def test_chunked_format_equals_whole(spec_path, rel: str) -> None:
    spec = compile_spec(spec_path).spec
    crate = build_crate(spec.can)
    text = render(TEMPLATES[rel], spec, TARGET_NAME, can=spec.can, crate=crate, tests=build_tests(crate), sup=build_supervision(spec.can, crate))
    if rel == "src/messages.rs":
        assert len(chunks(text, 2000)) > 3  # the module really is cut
    assert _format(text, rel, size=2000) == rustfmt(text, rel)
