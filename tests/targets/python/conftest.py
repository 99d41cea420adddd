"""Fixtures of the Python-target tests: the generated package (from generated/python) (cantools
reading the generated DBC, the `db` fixture, is in tests/conftest.py)."""

from __future__ import annotations

import pytest

from targets.python import pkgpath  # noqa: F401  (puts the generated package on sys.path)


@pytest.fixture(scope="session")
def gw():
    import kaiwo_gateway

    return kaiwo_gateway
