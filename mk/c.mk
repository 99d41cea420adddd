# C target: vector runner and benchmark (see tests/c/). `make roundtrip-c VECTORS=path`.
ROUNDTRIP_TARGETS += roundtrip-c
BENCH_TARGETS += bench-c
.PHONY: roundtrip-c bench-c

roundtrip-c:  ## C vector runner on $(VECTORS)
	$(PYTHON) tests/c/cbuild.py $(VECTORS) build/c

bench-c:  ## canspec C vs cantools generate_c_source: pack+unpack ns/frame, .text size
	$(PYTHON) tests/c/bench.py build/c-bench
