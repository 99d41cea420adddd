#!/usr/bin/env bash
# C target: clang-format formats the generated headers (generation fails without it); gcc and
# clang build the compile matrix; clang + compiler-rt give ASan/UBSan and libFuzzer; binutils
# (nm, size) measure code size in `make bench-c` and valgrind (callgrind) its x86-64 instruction
# counts; make drives the mock firmware project; cmake with Ninja and Make builds the CMake package's
# scratch projects (tests/cmake/) and the example ECU (examples/ecu/).
set -euo pipefail
apt_install clang-format clang libclang-rt-14-dev gcc g++ make binutils valgrind cmake ninja-build
