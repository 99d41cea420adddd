# canspec in a firmware project: the example ECU (examples/ecu/) built with CMake and canspec's CMake
# package for Cortex-M0+ and Cortex-M4 (tests/examples/, tests/cmake/; its footprint is in bench-c).
ECU_BUILD ?= build/ecu
.PHONY: ecu test-firmware

ecu:  ## the example ECU image (examples/ecu, node Wire_Car_ECU) for Cortex-M0+/M4 into $(ECU_BUILD)
	cmake -S examples/ecu -B $(ECU_BUILD) -G Ninja --toolchain=$(CURDIR)/examples/ecu/cmake/arm-none-eabi.cmake \
		-Dcanspec_DIR="$$($(CANSPEC) --cmake-dir)" -DCANSPEC_COMMAND="$(PYTHON);-m;canspec"
	cmake --build $(ECU_BUILD)

test-firmware:  ## the CMake package (Ninja, Makefiles) and the example ECU under qemu against the sequence vectors
	$(PYTHON) -m pytest -q tests/cmake tests/examples
