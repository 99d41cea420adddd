# Python bindings (generated/python): vector runner and benchmark.
ROUNDTRIP_TARGETS += roundtrip-python
BENCH_TARGETS += bench-python

.PHONY: roundtrip-python bench-python

roundtrip-python:  ## the generated Python package on $(VECTORS); fails on any mismatch
	$(PYTHON) tests/python/vector_runner.py $(VECTORS)

BENCH_PYTHON_FRAMES ?= 1000000
bench-python:  ## generated Python vs cantools (µs/frame), canspec decode vs cantools decode on a candump log
	$(PYTHON) tests/python/bench.py --log-frames $(BENCH_PYTHON_FRAMES)
