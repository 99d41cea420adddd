#!/usr/bin/env bash
# C on other machines (tests/targets/c/cross/): arm-none-eabi-gcc + newlib for the exact Cortex-M0+/M4
# cores, user-mode qemu (qemu-arm, qemu-ppc) to run them and big-endian PowerPC
# (powerpc-linux-gnu-gcc + its libc), cppcheck with its MISRA C:2012 addon.
set -euo pipefail
apt_install gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-user gcc-powerpc-linux-gnu libc6-dev-powerpc-cross cppcheck
