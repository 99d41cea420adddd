"""The anyspec harness from the command line (see tests/anyspec/README.md).

    python3 tests/anyspec/run.py -n 1000 [--base-seed S]     # a batch (make test-any-spec N=1000)
    python3 tests/anyspec/run.py --seed S                    # reproduce one spec of a batch
    python3 tests/anyspec/run.py --spec DIR_OR_FILE          # run an existing spec
    python3 tests/anyspec/run.py --seed S --shrink           # shrink each failure of seed S
    python3 tests/anyspec/run.py --seed S --print            # just print the spec of seed S

`--features current` draws only what the current checker accepts; the default `all` uses the
relaxed format of this issue. Exit status 0 when every check passed, 1 otherwise.
"""

from __future__ import annotations

import argparse
import json
import os
import random
import shutil
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "generator"))  # the reproduce line works outside make too
from anyspec import harness, strategy


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("-n", type=int, default=100, help="specs in the batch (default 100)")
    ap.add_argument("--base-seed", type=int, default=None, help="seed of the first spec (default: random, printed)")
    ap.add_argument("--seed", type=int, default=None, help="run only the spec of this seed")
    ap.add_argument("--spec", type=Path, default=None, help="run only this spec (file, bundle or directory)")
    ap.add_argument("--features", default="all", help="all (default) | current | comma list of " + ", ".join(sorted(strategy.ALL)))
    ap.add_argument("--rust", type=int, default=12, help="specs whose crates go through cargo clippy + test (default 12)")
    ap.add_argument("--mypy-every", type=int, default=10, help="mypy --strict on every k-th spec (default 10; 0: never)")
    ap.add_argument("--cross-every", type=int, default=10, help="the C runner on PowerPC/Cortex-M (qemu) on every k-th spec (default 10; 0: never)")
    ap.add_argument("--jobs", type=int, default=None, help="worker processes (default: CPU count)")
    ap.add_argument("--shrink", action="store_true", help="with --seed: shrink each distinct failure")
    ap.add_argument("--shrink-seconds", type=float, default=900)
    ap.add_argument("--shrink-batch", type=Path, default=None, help="shrink the first spec of each distinct failure of a --json results file")
    ap.add_argument("--print", action="store_true", help="with --seed: print the spec and stop")
    ap.add_argument("--run-dir", type=Path, default=None, help="work directory of the batch (default build/anyspec/run)")
    ap.add_argument("--json", type=Path, default=None, help="write every result to this file")
    args = ap.parse_args(argv)
    features = strategy.parse_features(args.features)
    missing = harness.missing_tools()
    if missing and not args.print:
        print("anyspec: missing toolchain(s), nothing checked: " + "; ".join(missing), file=sys.stderr)
        return 1
    if args.spec is not None:
        return run_spec_path(args.spec)
    if args.shrink_batch is not None:
        from anyspec import shrink as shrinker

        shrinker.shrink_batch(args.shrink_batch, args.shrink_seconds, args.jobs or 2)
        return 0
    if args.seed is not None:
        spec = strategy.example(args.seed, features)
        if args.print:
            print(spec.text(), end="")
            return 0
        batch = harness.run_batch(1, args.seed, features, rust=1, mypy_every=1, cross_every=1, jobs=1, run_dir=harness.BUILD / "one")
        print(harness.report(batch, verbose_specs=1))
        if args.shrink and batch.failures:
            return shrink(spec, features, batch, args.shrink_seconds)
        return 1 if batch.failures else 0
    base = args.base_seed if args.base_seed is not None else random.randrange(1_000_000_000)
    batch = harness.run_batch(args.n, base, features, rust=args.rust, mypy_every=args.mypy_every, cross_every=args.cross_every, jobs=args.jobs,
                              run_dir=args.run_dir)
    print(harness.report(batch))
    if args.json:
        args.json.write_text(json.dumps(harness.to_json(batch), indent=1, default=str), encoding="utf-8")
    return 1 if batch.failures else 0


def run_spec_path(path: Path) -> int:
    path = path.resolve()
    spec_dir = path if path.is_dir() else path.parent
    entry = "canspec.yaml" if path.is_dir() else path.name
    import yaml

    text = (spec_dir / entry).read_text(encoding="utf-8")
    facts = {"has_json": False}
    try:
        doc = yaml.safe_load(text)
        if doc.get("kind") == "bundle":
            kinds = [yaml.safe_load((spec_dir / f).read_text(encoding="utf-8")).get("kind") for f in doc.get("files", [])]
            facts["has_json"] = "json_protocol" in kinds
            can = next((spec_dir / f for f, k in zip(doc["files"], kinds) if k == "can_protocol"), None)
            facts["messages"] = len(yaml.safe_load(can.read_text(encoding="utf-8"))["messages"]) if can else 0
        else:
            facts["messages"] = len(doc.get("messages", []))
    except Exception:  # noqa: BLE001 — canspec check will report a broken file
        pass
    root = harness.BUILD / "one" / f"p{os.getpid()}"  # several --spec runs may share the machine
    work = root / "s0000"
    job = harness.Job("s0000", None, str(spec_dir), entry, str(work / "out"), [], facts, mypy=True, cross=True)
    res = harness.run_spec(job)
    if res.accepted and "rust" in res.generated and (Path(res.out_dir) / "vectors" / "can.json").is_file():
        harness.stage_rust([res], root)
    if res.accepted and res.facts.get("has_json"):
        harness.stage_typescript([res], root)
    batch = harness.Batch(0, 1, strategy.ALL, [res], res.seconds, {})
    print(harness.report(batch, verbose_specs=0))
    shutil.rmtree(root, ignore_errors=True)
    return 1 if res.failures else 0


def shrink(spec: strategy.GeneratedSpec, features: frozenset[str], batch: harness.Batch, seconds: float) -> int:
    from anyspec import shrink as shrinker

    seen = set()
    for f in batch.failures:
        if f.signature in seen or f.target == "check":
            continue
        seen.add(f.signature)
        small, failure = shrinker.shrink_failure(spec.seed, spec.choices, features, f, seconds)
        if small is None or failure is None:
            continue
        path = shrinker.save(small, failure, f"seed-{spec.seed}-{f.target.replace(':', '-')}")
        print(f"\nshrunk ({f.signature}) → {path}\n{small.text()}")
        print(f"error: {failure.message[:1500]}")
    return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
