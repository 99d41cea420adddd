# canspec — `make gen` is the main job. Targets of later features live in mk/*.mk.
PYTHON ?= python3
export PYTHONPATH := $(CURDIR)/generator$(if $(PYTHONPATH),:$(PYTHONPATH))
CANSPEC ?= $(PYTHON) -m canspec
SPEC ?= spec
OUT ?= generated

# Feature fragments (mk/*.mk) append to these. Each language's vector runner is a target
# `roundtrip-<lang>` that reads $(VECTORS) and fails on any mismatch.
BENCH_TARGETS :=
TEST_PREREQS :=
ROUNDTRIP_TARGETS :=
VECTORS ?= $(OUT)/vectors/can.json
# The suite runs in one worker per core (pytest-xdist); a test file stays in one worker, so its
# module fixtures are built once. TEST_WORKERS=0 runs it in this process.
TEST_WORKERS ?= 2

.PHONY: help setup gen check test bench roundtrip
.DEFAULT_GOAL := help

setup:  ## install everything the generator and the tests need (apt, pip, cargo)
	bash .ci/setup

gen:  ## generate every target from the spec into generated/
	$(CANSPEC) gen $(SPEC) -o $(OUT)

check:  ## validate the spec and verify generated/ is up to date
	$(CANSPEC) check $(SPEC)
	$(CANSPEC) gen $(SPEC) -o $(OUT) --check

test: $(TEST_PREREQS)  ## run the whole test suite
	$(PYTHON) -m pytest $(if $(filter-out 0,$(TEST_WORKERS)),-n $(TEST_WORKERS) --dist loadfile) $(PYTEST_ARGS)

-include mk/*.mk

bench: $(BENCH_TARGETS)  ## benchmarks against cantools and peers (prints ratios)

roundtrip: $(ROUNDTRIP_TARGETS)  ## every language's vector runner on $(VECTORS)

help:  ## list the make targets
	@grep -hE '^[a-z][a-z0-9-]*:.*## ' $(MAKEFILE_LIST) | sed -E 's/^([a-z0-9-]+):.*## /\1\t/' | expand -t 20
