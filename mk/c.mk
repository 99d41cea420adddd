# C target: vector runner and benchmark (see tests/targets/c/). `make roundtrip-c VECTORS=path`.
ROUNDTRIP_TARGETS += roundtrip-c
BENCH_TARGETS += bench-c
.PHONY: roundtrip-c bench-c

roundtrip-c:  ## C vector runner on $(VECTORS)
	$(PYTHON) tests/targets/c/cbuild.py $(VECTORS) build/c

bench-c:  ## canspec C vs cantools generate_c_source: x86-64 ns + callgrind (call and inline modes), code size; then bench-c-cross; the example ECU's footprint
	$(PYTHON) tests/targets/c/bench.py build/c-bench
	$(MAKE) --no-print-directory bench-c-cross
	$(PYTHON) tests/examples/ecu_bench.py --build build/ecu
	$(MAKE) --no-print-directory bench-c-spec2 bench-c-cross-spec2  # the second benchmark spec (mk/bench.mk)

FUZZ_SECONDS ?= 60
.PHONY: fuzz-c
fuzz-c:  ## libFuzzer (ASan+UBSan) on the C unpack, dispatch, VIN and monitor, FUZZ_SECONDS each
	$(PYTHON) tests/targets/c/fuzz/run_fuzz.py $(FUZZ_SECONDS) build/c-fuzz

# C on other machines and firmware-grade measurements (tests/targets/c/cross/).
ROUNDTRIP_TARGETS += roundtrip-c-cross
MISRA_DEVIATIONS ?= generated/c/MISRA.md
.PHONY: roundtrip-c-cross bench-c-cross misra-c

roundtrip-c-cross:  ## C vector runner on $(VECTORS): x86-64, big-endian ppc, Cortex-M0+/M4 (qemu), every compile-time strategy
	$(PYTHON) tests/targets/c/cross/cross.py --vectors $(VECTORS) --build build/c-cross

bench-c-cross:  ## Cortex-M0+/M4 (-Os/-O2): qemu-arm instruction counts vs cantools(+XOR), .text, stack, helper calls; MISRA counts
	$(PYTHON) tests/targets/c/cross/bench_cross.py --build build/c-bench-cross
	$(PYTHON) tests/targets/c/cross/misra.py --deviations $(MISRA_DEVIATIONS) --no-fail

misra-c:  ## MISRA C:2012 (cppcheck misra addon) on the headers; fails on a finding not in $(MISRA_DEVIATIONS)
	$(PYTHON) tests/targets/c/cross/misra.py --deviations $(MISRA_DEVIATIONS)
