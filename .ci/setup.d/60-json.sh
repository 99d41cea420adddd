#!/usr/bin/env bash
# JSON protocol tests: ajv (independent JSON Schema validator) and the TypeScript compiler from
# npm into build/json-node (gitignored, pinned by tests/targets/json_bindings/node/package-lock.json), and the
# crates of the generated Rust JSON bindings and their vector runner (pinned by Cargo.lock).
set -euo pipefail
cd "$(dirname "$0")/../.."

if ! command -v node >/dev/null || ! command -v npm >/dev/null; then apt_install nodejs npm; fi

node_dir=build/json-node
mkdir -p "$node_dir"
if ! cmp -s tests/targets/json_bindings/node/package-lock.json "$node_dir/package-lock.json" || [ ! -d "$node_dir/node_modules/ajv" ] || [ ! -d "$node_dir/node_modules/typescript" ]; then
  cp tests/targets/json_bindings/node/package.json tests/targets/json_bindings/node/package-lock.json "$node_dir/"
  (cd "$node_dir" && npm ci --no-audit --no-fund --loglevel=error)
fi

if command -v cargo >/dev/null; then
  cargo fetch --locked --manifest-path tests/targets/json_bindings/rust_runner/Cargo.toml
  cargo fetch --locked --manifest-path generated/json/rust/remote_driving/Cargo.toml
fi
