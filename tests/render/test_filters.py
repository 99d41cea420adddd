"""Filters per template folder (render/environment.py, nunavut's per-language filters): each
folder's environment holds Jinja's own filters and its FILTERS entry, nothing else; every filter a
template uses is one of those, and every registered filter is used by a template of its folder."""

from __future__ import annotations

import jinja2
import pytest
from canspec import resources
from canspec.render.environment import FILTERS, environment
from jinja2 import nodes

FOLDERS = sorted(p.name for p in resources.templates_dir().iterdir() if p.is_dir())


def used_filters(folder: str) -> set[str]:
    env = environment(folder)
    used: set[str] = set()
    for path in (resources.templates_dir() / folder).rglob("*.j2"):
        used |= {f.name for f in env.parse(path.read_text(encoding="utf-8")).find_all(nodes.Filter)}
    return used


def test_every_folder_with_filters_exists():
    assert set(FILTERS) <= set(FOLDERS)


@pytest.mark.parametrize("folder", FOLDERS)
def test_a_folder_sees_only_its_own_filters_and_uses_each(folder):
    own = set(FILTERS.get(folder, {}))
    assert set(environment(folder).filters) == set(jinja2.defaults.DEFAULT_FILTERS) | own
    used = used_filters(folder)
    assert used <= set(jinja2.defaults.DEFAULT_FILTERS) | own, f"{folder}: filters no environment of the folder has: {used - own}"
    assert own <= used, f"{folder}: registered, used by no template: {own - used}"
