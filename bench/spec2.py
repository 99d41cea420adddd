"""The second benchmark spec (bench/motorola_fd, issue 24 item 4) ready for the benches: its C headers,
DBC and vectors generated into build/bench-spec2/<variant>/.

    python3 bench/spec2.py [--no-pages] [--out DIR]   → prints the generated directory

`--no-pages` benchmarks the spec without its multiplexed messages (every target carries pages now;
the variant stays for comparing with earlier figures).
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parent.parent
SPEC2 = ROOT / "bench" / "motorola_fd"


def without_pages(src: Path, dst: Path) -> None:
    """A copy of the bundle whose protocol file lists no multiplexed message."""
    dst.mkdir(parents=True, exist_ok=True)
    for f in src.glob("*.yaml"):
        doc = yaml.safe_load(f.read_text())
        if doc.get("kind") == "can_protocol":
            doc["messages"] = [m for m in doc["messages"] if not any("mux" in s for s in m["signals"])]
        (dst / f.name).write_text(yaml.safe_dump(doc, sort_keys=False))


def prepare(no_pages: bool, out: Path) -> Path | None:
    """The spec generated into `out`; None when `canspec gen` refused it (its message is on stderr)."""
    spec = SPEC2
    if no_pages:
        spec = out / "spec"
        without_pages(SPEC2, spec)
    gen = out / "generated"
    done = subprocess.run([sys.executable, "-m", "canspec", "gen", str(spec), "-o", str(gen), "--target", "c", "--target", "dbc",
                           "--target", "vectors", "--target", "python", "--target", "rust"], check=False, stdout=subprocess.DEVNULL)
    return spec if done.returncode == 0 else None


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--no-pages", action="store_true", help="leave the multiplexed messages out")
    ap.add_argument("--out", type=Path, default=None)
    args = ap.parse_args()
    out = args.out or ROOT / "build" / "bench-spec2" / ("no-pages" if args.no_pages else "pages")
    spec = prepare(args.no_pages, out)
    if spec is None:
        print("bench-spec2: canspec gen failed on the second benchmark spec (see above)", file=sys.stderr)
        return 1
    print(spec)
    return 0


if __name__ == "__main__":
    sys.exit(main())
