#!/usr/bin/env bash
# Rust bindings: fetch the crate's dependencies (crates.io) so the tests build offline.
set -euo pipefail
if ! command -v cargo >/dev/null 2>&1; then
  echo "setup: cargo not found; the Rust tests will be skipped" >&2
  exit 0
fi
(cd generated/rust && cargo fetch --locked --quiet)
