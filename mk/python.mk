# Python bindings (generated/python): vector runner and benchmark.
ROUNDTRIP_TARGETS += roundtrip-python
BENCH_TARGETS += bench-python

.PHONY: roundtrip-python bench-python

PYTHON_PACKAGE ?=
roundtrip-python:  ## the generated Python package ($(PYTHON_PACKAGE), default the shipped one) on $(VECTORS); fails on any mismatch
	$(PYTHON) tests/targets/python/vector_runner.py $(VECTORS) $(if $(PYTHON_PACKAGE),--package $(PYTHON_PACKAGE))

BENCH_PYTHON_FRAMES ?= 1000000
# Also the fixture with floats (motorola_fd_float) and the second benchmark spec (bench/motorola_fd, mk/bench.mk)
BENCH_PYTHON_FLOATS ?= tests/fixtures/valid/motorola_fd_float.yaml
bench-python:  ## generated Python vs cantools (µs/frame) on the shipped spec, the second benchmark spec and $(BENCH_PYTHON_FLOATS); canspec decode vs cantools decode on a candump log
	$(PYTHON) tests/targets/python/bench.py --log-frames $(BENCH_PYTHON_FRAMES)
	$(MAKE) --no-print-directory bench-python-spec2
	$(PYTHON) tests/targets/python/bench.py --log-frames 0 --spec $(BENCH_PYTHON_FLOATS)
