# The second import corpus (issue 25 item 4): cantools' own test files — DBC, KCD, SYM, ARXML —
# through `canspec import`, check and the generated DBC against the source. Not part of `make test`.
.PHONY: test-import-corpus

test-import-corpus:  ## canspec import on a second corpus (tests/importer/cantools_files: DBC, KCD, SYM, ARXML); prints the tally
	cd tests && $(PYTHON) -m pytest -p no:randomly -q -s importer/corpus2_check.py $(PYTEST_ARGS)
