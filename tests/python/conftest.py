"""Fixtures of the Python-target tests: the generated package (from generated/python) and
cantools reading the generated DBC as the independent oracle."""

from __future__ import annotations

import pytest

from python import pkgpath  # noqa: F401  (puts generated/python on sys.path)


@pytest.fixture(scope="session")
def gw():
    import kaiwo_gateway

    return kaiwo_gateway


@pytest.fixture(scope="session")
def db():
    import cantools

    return cantools.database.load_file(str(pkgpath.DBC), encoding="utf-8", strict=True)
