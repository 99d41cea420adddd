"""The example ECU image's footprint per core (`make bench-c`): .text/.data/.bss as
arm-none-eabi-size reports them and the stack's high-water mark, measured by the image itself
(startup paints its stack; after a run over every sequence vector it feeds, the untouched part is
left) — the code size and the stack an ECU built on canspec's headers needs.

    python3 tests/examples/ecu_bench.py [--build DIR]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import ecu_image
import ecu_script


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", type=Path, default=ecu_image.ROOT / "build" / "ecu")
    args = ap.parse_args(argv[1:])
    missing = ecu_image.missing_tools()
    if missing:
        print(f"ecu_bench: missing {', '.join(missing)} (make setup)", file=sys.stderr)
        return 1
    try:
        elves = ecu_image.build(args.build)
        spec = ecu_script.node_spec(ecu_image.NODE)
        script = ecu_script.script(ecu_script.sequences(spec, ecu_image.NODE))
        rows = [(core, ecu_image.sizes(elf), ecu_image.stack(ecu_image.run(elf, script))) for core, elf in elves.items()]
    except ecu_image.ImageError as exc:
        print(f"ecu_bench: {exc}", file=sys.stderr)
        return 1
    print(f"examples/ecu (node {ecu_image.NODE}, -Os, every sequence vector it receives): bytes")
    print(f"{'core':<15} {'.text':>7} {'.data':>6} {'.bss':>6} {'stack used':>11} {'of':>6}")
    for core, size, (used, total) in rows:
        print(f"{core:<15} {size['text']:>7} {size['data']:>6} {size['bss']:>6} {used:>11} {total:>6}")
    print("(.bss holds the painted stack; the high-water mark includes the receive path's deepest call)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
