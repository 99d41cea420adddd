"""The Python vector runner: every case of a vectors file (the shared format, default
generated/vectors/can.json) through the generated package, both ways.

    python3 tests/python/vector_runner.py [VECTORS.json]

Exit 0 when every case agrees, 1 otherwise (each mismatch printed)."""

from __future__ import annotations

import dataclasses
import importlib
import json
import math
import sys
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
import pkgpath

gw = importlib.import_module("kaiwo_gateway")

PHYSICAL_KINDS = {"zero", "base", "min", "max", "enum", "special", "tie", "random"}


def attr_names(cls: type) -> dict[str, str]:
    """Spec signal name → attribute name."""
    return dict(zip(cls.SIGNALS, (f.name for f in dataclasses.fields(cls))))


def check_case(case: dict[str, Any]) -> list[str]:
    errors = []
    frame_id, data = case["frame_id"], bytes.fromhex(case["data"])
    cls = gw.BY_ID.get(frame_id)
    if cls is None or cls.NAME != case["message"]:
        return [f"frame ID 0x{frame_id:08X} is not {case['message']}"]
    names = attr_names(cls)
    # decode: raw values exactly, physical values to the double (ties: within half a step)
    if gw.decode_raw(frame_id, data) != case["raw"]:
        errors.append(f"decode_raw gives {gw.decode_raw(frame_id, data)}, expected {case['raw']}")
    message = gw.decode(frame_id, data)
    for sig, expected in case["physical"].items():
        got = getattr(message, names[sig])
        if case["kind"] == "tie" and case.get("note", "").startswith(f"{sig} tie "):
            # `expected` is the tie input: the decoded value is the raw step it rounded to, half a step away
            ok = abs(got - expected) <= 0.5 * _step(cls, sig, case["raw"][sig]) * (1 + 1e-9)
        else:
            ok = got == expected or (isinstance(got, float) and math.isclose(got, expected, rel_tol=1e-12, abs_tol=1e-12))
        if not ok:
            errors.append(f"decode: {sig} = {got!r}, expected {expected!r}")
    # encode
    if gw.encode_raw(frame_id, case["raw"]) != data:
        errors.append(f"encode_raw gives {gw.encode_raw(frame_id, case['raw']).hex().upper()}, expected {case['data']}")
    built = cls(**{names[s]: v for s, v in case["physical"].items()})
    if case["kind"] in PHYSICAL_KINDS:
        try:
            encoded = gw.encode(built)
        except gw.EncodeError as exc:
            errors.append(f"encode raised {exc}")
        else:
            if encoded != data:
                errors.append(f"encode gives {encoded.hex().upper()}, expected {case['data']}")
    else:  # raw_only: the documented range excludes a value, so a physical encode must refuse it
        try:
            gw.encode(built)
            errors.append("encode accepted a value outside the documented range (raw_only case)")
        except gw.RangeError:
            pass
    return errors


def _step(cls: type, sig: str, raw: int) -> float:
    """The physical size of one raw step of a signal, measured through the package itself."""
    name = attr_names(cls)[sig]
    here = float(getattr(cls.from_raw({sig: raw}), name))
    try:
        there = float(getattr(cls.from_raw({sig: raw - 1}), name))
    except gw.RawRangeError:
        there = float(getattr(cls.from_raw({sig: raw + 1}), name))
    return abs(here - there)


def check_multiframe(entry: dict[str, Any]) -> list[str]:
    cls = gw.BY_ID[entry["frame_id"]]
    split = getattr(gw, f"split_{cls.NAME}_text")
    join = getattr(gw, f"join_{cls.NAME}_text")
    frames = [m.encode().hex().upper() for m in split(entry["text"])]
    errors = []
    if frames != entry["frames"]:
        errors.append(f"split {entry['text']!r} gives {frames}, expected {entry['frames']}")
    text = join(cls.decode(bytes.fromhex(f)) for f in entry["frames"])
    if text != entry["text"].rstrip("\0"):
        errors.append(f"join gives {text!r}, expected {entry['text']!r}")
    return errors


def run(path: Path) -> tuple[int, list[str]]:
    vectors = json.loads(path.read_text(encoding="utf-8"))
    failures = []
    count = 0
    for case in vectors["cases"]:
        count += 1
        try:
            errors = check_case(case)
        except (gw.Error, ValueError, TypeError, KeyError) as exc:
            errors = [f"{type(exc).__name__}: {exc}"]
        for err in errors:
            failures.append(f"case {count} ({case['message']}, {case['kind']}{', ' + case['note'] if case.get('note') else ''}): {err}")
    for entry in vectors.get("multiframe", []):
        count += 1
        failures += [f"multiframe {entry['text']!r}: {e}" for e in check_multiframe(entry)]
    return count, failures


def main(argv: list[str]) -> int:
    path = Path(argv[1]) if len(argv) > 1 else pkgpath.DEFAULT_VECTORS
    count, failures = run(path)
    for f in failures:
        print(f)
    print(f"python vector runner: {count} cases, {len(failures)} mismatches ({path}; package {Path(gw.__file__).parent})")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
