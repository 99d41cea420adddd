#!/usr/bin/env bash
# The public corpus `canspec import` is measured on (tests/importer/): the 115 DBC files of the
# opendbc package. Only its data is used, so its own dependencies (pycapnp, …) are not installed.
set -euo pipefail
OPENDBC_VERSION=0.3.1   # keep equal to what tests/importer/corpus.py counts (OPENDBC_FILES)
have=$(python3 -c "from importlib.metadata import version; print(version('opendbc'))" 2>/dev/null || true)
if [ "$have" != "$OPENDBC_VERSION" ]; then
  echo "setup: pip install --no-deps opendbc==$OPENDBC_VERSION"
  python3 -m pip install -q --disable-pip-version-check --no-deps "opendbc==$OPENDBC_VERSION"
fi
