# Generation speed (issue 25, item 5): time and peak memory per target over 10..1,000 messages,
# the gcc -O2 time of the 1,000-message headers and `gen --check`. Not part of `make test`.
BENCH_GEN_SIZES ?= 10 100 300 1000
.PHONY: bench-gen

bench-gen:  ## canspec gen per target: seconds and peak MB over spec sizes (goal: 1,000 messages in 10 s / 500 MB)
	$(PYTHON) bench/bench_gen.py --sizes $(BENCH_GEN_SIZES)
