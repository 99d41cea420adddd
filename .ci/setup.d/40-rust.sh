#!/usr/bin/env bash
# Rust bindings: fetch the crate's dependencies (crates.io) so the tests build offline (the fixture
# crates of tests/targets/rust/test_rust_fixtures.py and the anyspec harness use the same pinned ones).
set -euo pipefail
if ! command -v cargo >/dev/null 2>&1; then
  echo "setup: cargo not found; the Rust tests need it (and clippy, rustfmt)" >&2
  exit 0
fi
(cd generated/rust && cargo fetch --locked --quiet)
