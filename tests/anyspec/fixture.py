"""Turn a (shrunk) failing spec into a valid fixture: tests/fixtures/valid/<name>.yaml with the
`# expect: ok` header line the other valid fixtures carry.

    python3 tests/anyspec/fixture.py SPEC NAME [--why TEXT] [--dir tests/fixtures/valid]

SPEC is a single `kind: can_protocol` file, or a bundle whose only other file is a
`value_tables` file (its tables are folded into the CAN file). Bundles with a JSON protocol
or a changelog cannot be one-file fixtures: the tool says so.
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[2]


def single_file_text(spec: Path) -> str:
    path = spec / "canspec.yaml" if spec.is_dir() else spec
    text = path.read_text(encoding="utf-8")
    kind = yaml.safe_load(text).get("kind")
    if kind == "can_protocol":
        return text
    if kind != "bundle":
        raise ValueError(f"{path}: kind {kind!r}; a fixture is a can_protocol file (or a bundle of one)")
    files = [path.parent / f for f in yaml.safe_load(text)["files"]]
    kinds = {f: yaml.safe_load(f.read_text(encoding="utf-8"))["kind"] for f in files}
    others = sorted(k for k in kinds.values() if k not in ("can_protocol", "value_tables"))
    if others:
        raise ValueError(f"{path}: the bundle also has {', '.join(others)}; keep it as a bundle (tests/fixtures/valid holds single files)")
    (can,) = [f for f, k in kinds.items() if k == "can_protocol"]
    out = can.read_text(encoding="utf-8")
    for f, k in kinds.items():
        if k == "value_tables":
            body = f.read_text(encoding="utf-8")
            tables = body[body.index("value_tables:"):]
            out = out.replace("\nmessages:\n", "\n" + tables.rstrip() + "\nmessages:\n", 1)
    return out


def write_fixture(spec: Path, name: str, why: str, directory: Path = ROOT / "tests" / "fixtures" / "valid") -> Path:
    if not re.fullmatch(r"[a-z0-9][a-z0-9_-]*", name):
        raise ValueError(f"fixture name {name!r}: use lower-case letters, digits, - and _")
    body = single_file_text(spec)
    body = "\n".join(ln for ln in body.splitlines() if not ln.startswith("# A spec drawn by")) + "\n"
    head = f"# {why.strip()}\n# expect: ok\n"
    dest = directory / f"{name}.yaml"
    dest.write_text(head + body, encoding="utf-8")
    return dest


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("spec", type=Path)
    ap.add_argument("name")
    ap.add_argument("--why", default="A valid spec found by the anyspec harness (tests/anyspec/) that a canspec target once failed on.")
    ap.add_argument("--dir", type=Path, default=ROOT / "tests" / "fixtures" / "valid")
    args = ap.parse_args(argv)
    try:
        dest = write_fixture(args.spec, args.name, args.why, args.dir)
    except (OSError, ValueError, KeyError) as exc:
        print(f"fixture: {exc}", file=sys.stderr)
        return 1
    print(dest)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
