#!/usr/bin/env python3
"""Write a large, seeded vectors file in the shared format (generated/vectors/can.json's format)
for the cross-language agreement check (issue 9): `make roundtrip VECTORS=<file>` runs every
language's runner on it, and tests/targets/vectors/test_big_vectors.py checks a sample with cantools.

  tools/big_vectors.py [SPEC] -o build/big.json [--cases 100000] [--seed 1] [--encoder MODULE:ATTR]

The file holds every case of the regular vectors (all-zero, min/max of every signal, every value,
special values, rounding ties, ...) and then seeded cases over all messages, round-robin, until
--cases: random values biased towards the boundaries (raw_min, raw_min+1, raw_max-1, raw_max) and
special values, random rounding ties (physical input exactly halfway between two raw steps), and
raw-only cases (values the field holds but the documented range excludes).

The frame bytes and physical values come from an *encoder*: by default the reference codec
(canspec.codec). Pass `--encoder module:attr` to produce them with another implementation — e.g.
the generated Python binding once it exists — given an object with
    pack(msg: canspec.ir.Message, raw: dict[str, int]) -> bytes      (checksum filled in)
    physical(sig: canspec.ir.Signal, raw: int) -> int | float        (raw * factor + offset)
The expected raw value of a tie always comes from the shared rule (canspec.encoding).
"""

from __future__ import annotations

import argparse
import importlib
import json
import random
import sys
from fractions import Fraction
from pathlib import Path
from typing import Any, Protocol

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "generator"))

from canspec import ir
from canspec.ir.encoding import to_raw_exact, to_raw_runtime
from canspec.pipeline import compile_spec
from canspec.reference import codec
from canspec.targets.vectors import build_vectors, case_record


class Encoder(Protocol):
    def pack(self, msg: ir.Message, raw: dict[str, int]) -> bytes: ...
    def physical(self, sig: ir.Signal, raw: int) -> int | float: ...


class ReferenceEncoder:
    """canspec.codec, the reference the generated languages must match."""

    def pack(self, msg: ir.Message, raw: dict[str, int]) -> bytes:
        return codec.pack(msg, raw)

    def physical(self, sig: ir.Signal, raw: int) -> int | float:
        value = sig.physical(raw)
        return value.numerator if value.denominator == 1 else float(value)


def load_encoder(spec: str | None) -> Encoder:
    if not spec:
        return ReferenceEncoder()
    module, _, attr = spec.partition(":")
    obj = getattr(importlib.import_module(module), attr or "ENCODER")
    return obj() if isinstance(obj, type) else obj


def _tie(sig: ir.Signal, rng: random.Random) -> tuple[float, int] | None:
    """A random physical input exactly halfway between two raw steps, and the raw it must give."""
    if sig.is_identity or sig.raw_max - sig.raw_min < 2:
        return None
    lower = rng.randint(sig.raw_min, sig.raw_max - 1)
    tie = Fraction(2 * lower + 1, 2) * sig.factor + sig.offset
    expected = to_raw_exact(tie, sig.factor, sig.offset)
    if not (sig.check_min <= tie <= sig.check_max and sig.raw_min <= expected <= sig.raw_max):
        return None
    # Only ties the double-precision runtime rule resolves like the exact rule are portable vectors.
    if to_raw_runtime(float(tie), float(sig.factor), float(sig.offset)) != expected:
        return None
    return float(tie), expected


def _random_raw(sig: ir.Signal, rng: random.Random) -> int:
    r = rng.random()
    if sig.specials and r < 0.1:
        return rng.choice(sig.specials).raw
    if r < 0.3:
        return rng.choice([sig.raw_min, min(sig.raw_min + 1, sig.raw_max), max(sig.raw_max - 1, sig.raw_min), sig.raw_max])
    return rng.randint(sig.raw_min, sig.raw_max)


class CaseMaker:
    def __init__(self, encoder: Encoder) -> None:
        self.encoder = encoder

    def case(self, msg: ir.Message, raw: dict[str, int], kind: str, physical: dict[str, Any] | None = None, note: str = "") -> dict[str, Any]:
        raw = dict(raw)
        data = self.encoder.pack(msg, raw)
        if msg.checksum is not None:
            raw[msg.checksum.signal] = data[msg.checksum.byte]
        phys = {s.name: self.encoder.physical(s, raw[s.name]) for s in msg.data_signals}
        if physical:
            phys.update(physical)
        return case_record(msg, data, raw, phys, kind, note)

    def seeded(self, msg: ir.Message, rng: random.Random) -> dict[str, Any]:
        sigs = [s for s in msg.data_signals if s.role != "checksum"]
        choice = rng.random()
        if choice < 0.15:  # a rounding tie on one signal, the others random
            sig = rng.choice(sigs)
            tie = _tie(sig, rng)
            if tie is not None:
                raw = {s.name: _random_raw(s, rng) for s in sigs}
                raw[sig.name] = tie[1]
                return self.case(msg, raw, "tie", {sig.name: tie[0]}, note=f"{sig.name} tie {tie[0]!r} -> raw {tie[1]}")
        if choice < 0.25:  # a value the field holds but the documented range excludes
            sig = rng.choice(sigs)
            outside = [
                v
                for v in (sig.raw_type_min, sig.raw_min - 1, sig.raw_max + 1, sig.raw_type_max)
                if sig.raw_type_min <= v <= sig.raw_type_max and not sig.raw_allowed(v)
            ]
            if outside:
                raw = {s.name: s.base_raw for s in sigs}
                raw[sig.name] = rng.choice(outside)
                return self.case(msg, raw, "raw_only", note=f"{sig.name}={raw[sig.name]} outside the documented range")
        return self.case(msg, {s.name: _random_raw(s, rng) for s in sigs}, "random")


def build(spec: ir.Spec, cases: int, seed: int, encoder: Encoder) -> dict[str, Any]:
    assert spec.can is not None, "the spec has no CAN protocol"
    doc = build_vectors(spec)  # header, the regular cases, the multiframe texts
    maker = CaseMaker(encoder)
    by_name = {m.name: m for m in spec.can.messages}
    if not isinstance(encoder, ReferenceEncoder):  # the regular cases' bytes and physicals from this encoder too

        def again(c: dict[str, Any]) -> dict[str, Any]:
            msg = by_name[c["message"]]
            raw = {k: v for k, v in c["raw"].items() if msg.checksum is None or k != msg.checksum.signal}
            return maker.case(msg, raw, c["kind"], c["physical"] if c["kind"] in ("tie", "decoded") else None, c.get("note", ""))

        doc["cases"] = [again(c) for c in doc["cases"]]
    rng = random.Random(seed)
    # Messages without signals (layout_undefined) have one frame, already in the regular cases.
    messages = [m for m in spec.can.messages if any(s.role != "checksum" for s in m.data_signals)]
    i = 0
    while len(doc["cases"]) < cases:
        doc["cases"].append(maker.seeded(messages[i % len(messages)], rng))
        i += 1
    doc["generated_by"] = f"tools/big_vectors.py seed {seed} ({type(encoder).__name__}), from {doc['generated_by']}"
    return doc


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("spec", nargs="?", default=None, help="spec (default: the shipped one)")
    ap.add_argument("-o", "--output", type=Path, required=True)
    ap.add_argument("--cases", type=int, default=100_000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--encoder", help="module:attr of an encoder object (default: the reference codec)")
    args = ap.parse_args(argv)
    compiled = compile_spec(args.spec)
    if compiled.spec is None:
        for p in compiled.errors:
            print(p.format(), file=sys.stderr)
        return 1
    doc = build(compiled.spec, args.cases, args.seed, load_encoder(args.encoder))
    args.output.parent.mkdir(parents=True, exist_ok=True)
    tmp = args.output.with_name(args.output.name + ".tmp")
    tmp.write_text(json.dumps(doc, sort_keys=True, ensure_ascii=False, separators=(",", ":")) + "\n", encoding="utf-8")
    tmp.replace(args.output)
    kinds: dict[str, int] = {}
    for c in doc["cases"]:
        kinds[c["kind"]] = kinds.get(c["kind"], 0) + 1
    print(
        f"big_vectors: {len(doc['cases'])} cases over {len(compiled.spec.can.messages)} messages -> {args.output} "
        f"({', '.join(f'{k} {n}' for k, n in sorted(kinds.items()))})",
        file=sys.stderr,
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
