# JSON remote-driving protocol: schemas, bindings and vectors (issue 6).
JSON_VECTORS ?= $(OUT)/vectors/json.json
JSON_CARGO_TARGET ?= $(CURDIR)/build/json-rust

ROUNDTRIP_TARGETS += roundtrip-json

.PHONY: roundtrip-json test-json

roundtrip-json:  ## generated Python and Rust JSON bindings over $(JSON_VECTORS); fails on any mismatch
	$(PYTHON) tests/targets/json_bindings/py_runner.py $(JSON_VECTORS)
	CARGO_TARGET_DIR=$(JSON_CARGO_TARGET) cargo run --quiet --locked --manifest-path tests/targets/json_bindings/rust_runner/Cargo.toml -- --check $(JSON_VECTORS)

test-json:  ## only the JSON-protocol tests (schemas, ajv, Python/Rust/TypeScript bindings)
	$(PYTHON) -m pytest tests/targets/json_bindings $(PYTEST_ARGS)
