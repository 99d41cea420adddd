"""The shipped DBC as cantools reads it, under the DBC's own signal names (the root `db` fixture
renames signals back to the spec's names for the other targets' tests)."""

from __future__ import annotations

import pytest
from dbc_support import load_cantools
from repo_paths import GENERATED


@pytest.fixture(scope="session")
def raw_db():
    return load_cantools(GENERATED / "dbc" / "kaiwo_gateway.dbc")
