#!/usr/bin/env bash
# Bus logs (canspec decode / plot): the `logs` extra and the test peers that read its tables.
set -euo pipefail
want=(python-can numpy pyarrow asammdf matplotlib tqdm duckdb pandas polars dask distributed)
if ! python3 -c "import can, numpy, pyarrow, asammdf, matplotlib, tqdm, duckdb, pandas, polars, dask, distributed" 2>/dev/null; then
  echo "setup: pip install ${want[*]}"
  python3 -m pip install -q --disable-pip-version-check "python-can>=4.3" "numpy>=1.24" "pyarrow>=14" "asammdf>=7.4" "matplotlib>=3.7" \
    "tqdm>=4.66" "duckdb>=0.10" "pandas>=2.0" "polars>=0.20" "dask[distributed]>=2024.1"
fi
