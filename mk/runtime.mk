# The bindings under real traffic (issue 17): the shared sequence vectors (vectors/sequences.json:
# receive monitor and multi-frame text reassembly) through every language's runner, and the
# rest-bus simulator. `make roundtrip-sequences SEQUENCES=file`.
SEQUENCES ?= $(OUT)/vectors/sequences.json
ROUNDTRIP_TARGETS += roundtrip-sequences
SIM_NODE ?= AUTOCAR
SIM_INTERFACE ?= virtual
SIM_CHANNEL ?= canspec

.PHONY: roundtrip-sequences roundtrip-sequences-c roundtrip-sequences-python roundtrip-sequences-rust simulate

roundtrip-sequences: roundtrip-sequences-c roundtrip-sequences-python roundtrip-sequences-rust  ## every language's sequence runner on $(SEQUENCES)

roundtrip-sequences-c:  ## the C monitor and text reassembly on $(SEQUENCES) (gcc, ASan/UBSan)
	$(PYTHON) tests/targets/c/c_sequences.py $(SEQUENCES) --build build/c-sequences

roundtrip-sequences-python:  ## the generated Python package ($(PYTHON_PACKAGE), default the shipped one) on $(SEQUENCES)
	$(PYTHON) tests/targets/python/sequence_runner.py $(SEQUENCES) $(if $(PYTHON_PACKAGE),--package $(PYTHON_PACKAGE))

roundtrip-sequences-rust:  ## the Rust crate's sequence test on $(SEQUENCES)
	cd $(RUST_CRATE) && CARGO_TARGET_DIR=$(RUST_TARGET_DIR) CANSPEC_SEQUENCES=$(abspath $(SEQUENCES)) \
		$(CARGO) test --locked --all-features --test sequences -- --nocapture

simulate:  ## rest-bus simulation of $(SIM_NODE) on python-can $(SIM_INTERFACE) $(SIM_CHANNEL) (SIM_ARGS=--duration 10 ...)
	$(CANSPEC) simulate $(SPEC) --node $(SIM_NODE) --interface $(SIM_INTERFACE) --channel $(SIM_CHANNEL) $(SIM_ARGS)
