# Robustness and scale (issue 9): scale benchmark and the big cross-language vectors file.
BENCH_TARGETS += bench-scale
BIG_VECTORS ?= build/big.json
BIG_CASES ?= 100000
BIG_SEED ?= 1

.PHONY: bench-scale big-vectors roundtrip-big

bench-scale:  ## check/gen wall and CPU times at 1x, 10x, 100x the shipped spec; shipped gen vs the 2 s target
	$(PYTHON) bench/bench_scale.py

big-vectors:  ## a seeded vectors file of $(BIG_CASES) cases over every message (incl. boundaries and ties)
	$(PYTHON) tools/big_vectors.py $(SPEC) -o $(BIG_VECTORS) --cases $(BIG_CASES) --seed $(BIG_SEED)

roundtrip-big: big-vectors  ## every language's runner on the big vectors file
	$(MAKE) roundtrip VECTORS=$(BIG_VECTORS)
