"""The generated Python package, for the property tests against the model."""

from __future__ import annotations

import pytest

from targets.python import pkgpath  # noqa: F401  (puts the generated package on sys.path)


@pytest.fixture(scope="session")
def gw():
    import kaiwo_gateway

    return kaiwo_gateway
