# Bus logs (canspec decode / plot): the decode benchmark against cantools, a cantools+pandas
# reference script and asammdf, on every log format; the tests live in tests/logs (part of make test).
.PHONY: bench-decode

BENCH_DECODE_FRAMES ?= 1000000
BENCH_DECODE_MEMORY_FRAMES ?= 0
bench-decode:  ## canspec decode on $(BENCH_DECODE_FRAMES) frames in every format vs cantools, a cantools+pandas script and asammdf (ratios, peak memory)
	$(PYTHON) bench/bench_decode.py --frames $(BENCH_DECODE_FRAMES) --memory-frames $(BENCH_DECODE_MEMORY_FRAMES)
