# C target: vector runner and benchmark (see tests/c/). `make roundtrip-c VECTORS=path`.
ROUNDTRIP_TARGETS += roundtrip-c
BENCH_TARGETS += bench-c
.PHONY: roundtrip-c bench-c

roundtrip-c:  ## C vector runner on $(VECTORS)
	$(PYTHON) tests/c/cbuild.py $(VECTORS) build/c

bench-c:  ## canspec C vs cantools generate_c_source: pack+unpack ns and callgrind instructions (call and inline modes), code size
	$(PYTHON) tests/c/bench.py build/c-bench

FUZZ_SECONDS ?= 60
.PHONY: fuzz-c
fuzz-c:  ## libFuzzer (ASan+UBSan) on the C unpack, dispatch, VIN and monitor, FUZZ_SECONDS each
	$(PYTHON) tests/c/fuzz/run_fuzz.py $(FUZZ_SECONDS) build/c-fuzz
