# The release (README "Install / release"): the sdist and the wheel, and their test in an empty
# virtual environment (tests/packaging/, also part of `make test`; needs PyPI).
DIST ?= dist

.PHONY: dist test-release

dist:  ## python -m build: the sdist and the wheel in $(DIST)/
	$(PYTHON) -m build --outdir $(DIST) .

test-release:  ## the release in an empty venv: sdist = wheel, every target outside the repo, pre-commit hooks, CI snippets, Rust user build
	$(PYTHON) -m pytest -q tests/packaging $(PYTEST_ARGS)
