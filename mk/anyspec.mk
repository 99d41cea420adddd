# The "any valid spec" harness (tests/anyspec/): random valid specs through check, gen and every
# target's toolchain. `make test` runs 100 specs (tests/anyspec/test_anyspec.py); the long run:
#   make test-any-spec N=1000 [SEED=first-seed] [ANYSPEC_FEATURES=all|current] [ANYSPEC_RUST=<how many crates through cargo clippy + test, default 12>]
N ?= 1000
ANYSPEC_FEATURES ?= all
ANYSPEC_RUST ?= 12
ANYSPEC_ARGS ?=

.PHONY: test-any-spec

test-any-spec:  ## N random valid specs (default 1000) through every target's checks; failures saved under build/anyspec/failures/
	$(PYTHON) tests/anyspec/run.py -n $(N) $(if $(SEED),--base-seed $(SEED)) --features $(ANYSPEC_FEATURES) --rust $(ANYSPEC_RUST) $(ANYSPEC_ARGS)
