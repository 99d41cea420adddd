#!/usr/bin/env bash
# Python target: the formatter the generator runs (pinned: its version is part of the output),
# the type checker and hatchling the tests run, python-can for the bus integration test.
set -euo pipefail
RUFF_VERSION=0.17.6   # keep equal to RUFF_VERSION in generator/canspec/render/formatters.py
want=("ruff==$RUFF_VERSION" "mypy>=1.8" "hypothesis>=6.90" "pytest-xdist>=3.5" "python-can>=4.3" "hatchling>=1.18")
missing=()
for spec in "${want[@]}"; do
  python3 - "$spec" <<'PY' || missing+=("$spec")
import sys
from importlib.metadata import PackageNotFoundError, version
spec = sys.argv[1]
name, _, pinned = spec.partition("==")
name = name.split(">=")[0]
try:
    have = version(name)
except PackageNotFoundError:
    sys.exit(1)
sys.exit(1 if pinned and have != pinned else 0)
PY
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: pip install ${missing[*]}"
  python3 -m pip install -q --disable-pip-version-check "${missing[@]}"
fi
