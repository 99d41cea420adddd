# canspec — `make gen` is the main job. Targets of later features live in mk/*.mk.
PYTHON ?= python3
export PYTHONPATH := $(CURDIR)/generator$(if $(PYTHONPATH),:$(PYTHONPATH))
CANSPEC ?= $(PYTHON) -m canspec
SPEC ?= spec
OUT ?= generated

# Feature fragments append to these.
BENCH_TARGETS :=
TEST_PREREQS :=

.PHONY: setup gen check test bench clean-build

setup:  ## install everything the generator and the tests need (apt, pip, cargo)
	bash .ci/setup

gen:  ## generate every target from the spec into generated/
	$(CANSPEC) gen $(SPEC) -o $(OUT)

check:  ## validate the spec and verify generated/ is up to date
	$(CANSPEC) check $(SPEC)
	$(CANSPEC) gen $(SPEC) -o $(OUT) --check

test: $(TEST_PREREQS)  ## run the whole test suite
	$(PYTHON) -m pytest $(PYTEST_ARGS)

-include mk/*.mk

bench: $(BENCH_TARGETS)  ## benchmarks against cantools and peers (prints ratios)
