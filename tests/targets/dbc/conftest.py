"""The shipped DBC as cantools reads it, under the DBC's own signal names (the root `db` fixture
renames signals back to the spec's names for the other targets' tests), and the same spec's DBC
written with `dbc_signal_names: unique`."""

from __future__ import annotations

from dataclasses import replace

import pytest
from dbc_support import compiled, load_cantools, write_dbc
from repo_paths import GENERATED, ROOT


@pytest.fixture(scope="session")
def raw_db():
    return load_cantools(GENERATED / "dbc" / "kaiwo_gateway.dbc")


@pytest.fixture(scope="session")
def unique_db(tmp_path_factory):
    spec = compiled(ROOT / "spec")
    assert spec.can is not None
    return load_cantools(write_dbc(replace(spec, can=replace(spec.can, dbc_signal_names="unique")), tmp_path_factory.mktemp("unique")))
