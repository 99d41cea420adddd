# Generation speed (issue 25, item 5): time and peak memory per target over 10..1,000 messages,
# the gcc -O2 time of the 1,000-message headers and `gen --check`. Not part of `make test`.
BENCH_GEN_SIZES ?= 10 100 300 1000
BENCH_CORPUS_RUNS ?= 3
.PHONY: bench-gen bench-corpus

bench-gen:  ## canspec gen per target: seconds and peak MB over spec sizes (goal: 1,000 messages in 10 s / 500 MB)
	$(PYTHON) bench/bench_gen.py --sizes $(BENCH_GEN_SIZES)

bench-corpus:  ## the largest opendbc DBC: canspec import and gen of every target, seconds, CPU s and peak MB of each (goal: within 5 s)
	$(PYTHON) bench/bench_gen.py --corpus-only --runs $(BENCH_CORPUS_RUNS)

# The second benchmark spec (issue 24 item 4): bench/motorola_fd, imported from public opendbc DBCs — Motorola-heavy,
# CAN FD frames up to 64 bytes, two multiplexed messages (every target carries them; BENCH_SPEC2_PAGES=--no-pages
# runs the spec without them).
BENCH_SPEC2_PAGES ?=
BENCH_SPEC2_DIR := build/bench-spec2/$(if $(BENCH_SPEC2_PAGES),no-pages,pages)
BENCH_SPEC2 := $(if $(BENCH_SPEC2_PAGES),$(BENCH_SPEC2_DIR)/spec,bench/motorola_fd)
BENCH_SPEC2_GEN := $(BENCH_SPEC2_DIR)/generated
BENCH_SPEC2_C_ARGS = --spec $(BENCH_SPEC2) --headers $(BENCH_SPEC2_GEN)/c --dbc $(BENCH_SPEC2_GEN)/dbc/gwm.dbc --vectors $(BENCH_SPEC2_GEN)/vectors/can.json
.PHONY: bench-spec2 bench-c-spec2 bench-c-bound bench-c-cross-spec2 bench-python-spec2 bench-rust-spec2

bench-spec2:  ## generate the second benchmark spec's C, DBC, vectors, Python and Rust into build/bench-spec2/
	$(PYTHON) bench/spec2.py $(BENCH_SPEC2_PAGES)

bench-c-spec2: bench-spec2  ## bench-c (x86-64 -O2) on the second benchmark spec
	$(PYTHON) tests/targets/c/bench.py build/c-bench-spec2 $(BENCH_SPEC2_C_ARGS)

bench-c-bound: bench-spec2  ## bench-c-spec2, then the fewest instructions any C codec could run per message (bench/c_bound.py): the best ratio to cantools reachable
	$(PYTHON) tests/targets/c/bench.py build/c-bench-spec2 $(BENCH_SPEC2_C_ARGS) > build/bench-c-spec2.txt || { cat build/bench-c-spec2.txt; exit 1; }
	$(PYTHON) bench/c_bound.py $(BENCH_SPEC2) build/bench-c-spec2.txt

bench-c-cross-spec2: bench-spec2  ## bench-c-cross (Cortex-M0+/M4) on the second benchmark spec
	$(PYTHON) tests/targets/c/cross/bench_cross.py --build build/c-bench-cross-spec2 $(BENCH_SPEC2_C_ARGS)

bench-python-spec2: bench-spec2  ## bench-python on the second benchmark spec
	$(PYTHON) tests/targets/python/bench.py --log-frames 0 --spec $(BENCH_SPEC2)

bench-rust-spec2:  ## bench-rust (against dbc-codegen) on the second benchmark spec, without its multiplexed messages
	$(MAKE) --no-print-directory bench-spec2 BENCH_SPEC2_PAGES=--no-pages  # dbc-codegen 0.4.0's code for them does not compile (a 1-bit multiplexer's setter takes bool, its mux code passes 0 and 1)
	$(PYTHON) tests/targets/rust/bench.py --spec build/bench-spec2/no-pages/spec --generated build/bench-spec2/no-pages/generated --build build/rust-bench-spec2
