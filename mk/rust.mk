# Rust bindings (generated/rust): vector round trip and the benchmark against dbc-codegen.
RUST_CRATE := $(OUT)/rust
RUST_TARGET_DIR ?= $(CURDIR)/build/rust/target
CARGO ?= cargo

ROUNDTRIP_TARGETS += roundtrip-rust
BENCH_TARGETS += bench-rust

.PHONY: roundtrip-rust bench-rust

roundtrip-rust:  ## the Rust crate's vector test on $(VECTORS); fails on any mismatch
	cd $(RUST_CRATE) && CARGO_TARGET_DIR=$(RUST_TARGET_DIR) CANSPEC_VECTORS=$(abspath $(VECTORS)) \
		$(CARGO) test --locked --all-features --test vectors -- --nocapture

bench-rust:  ## canspec's crate vs dbc-codegen on the generated DBC: ns/frame and ratio per message
	$(PYTHON) tests/targets/rust/bench.py
	$(MAKE) --no-print-directory bench-rust-spec2
