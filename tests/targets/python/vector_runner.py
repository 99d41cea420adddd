"""The Python vector runner: every case of a vectors file (the shared format) through a
generated package, both ways — any spec's package, not only the shipped one.

    python3 tests/targets/python/vector_runner.py [VECTORS.json] [--package DIR]

VECTORS defaults to generated/vectors/can.json, DIR (the package directory, e.g.
generated/python/kaiwo_gateway) to the shipped package. Exit 0 when every case agrees, 1
otherwise (each mismatch printed)."""

from __future__ import annotations

import argparse
import dataclasses
import importlib
import importlib.util
import json
import math
import sys
from pathlib import Path
from types import ModuleType
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
import pkgpath

PHYSICAL_KINDS = {"zero", "base", "min", "max", "enum", "special", "tie", "random", "decoded", "float_special"}
# Cases whose physical values do not encode back to their raw values: decode and raw pack only
# (beyond_double: not through doubles; nan_payload: a NaN's payload, which a physical encode drops).
DECODE_ONLY_KINDS = {"beyond_double", "nan_payload"}
NON_FINITE = {"NaN", "Infinity", "-Infinity"}  # what JSON has no number for, as the vectors name it


def physical_values(case: dict[str, Any]) -> dict[str, Any]:
    """A case's physical values as numbers: the names of NaN and ±Inf read as floats."""
    return {k: float(v) if v in NON_FINITE else v for k, v in case["physical"].items()}


def same_value(got: Any, expected: Any) -> bool:
    """Equal as the vectors mean it: NaN is NaN, -0.0 is not 0.0, scaled values to the double."""
    if isinstance(expected, float) and math.isnan(expected):
        return isinstance(got, float) and math.isnan(got)
    if isinstance(expected, float) and expected == 0 and got == 0:
        return math.copysign(1, got) == math.copysign(1, expected)
    return bool(got == expected or (isinstance(got, float) and math.isclose(got, expected, rel_tol=1e-12, abs_tol=1e-12)))


def load_package(package_dir: Path) -> ModuleType:
    """Import the generated package in `package_dir` under its own name."""
    name = package_dir.name
    if name in sys.modules:
        return sys.modules[name]
    spec = importlib.util.spec_from_file_location(name, package_dir / "__init__.py", submodule_search_locations=[str(package_dir)])
    if spec is None or spec.loader is None:
        raise ImportError(f"no Python package in {package_dir}")
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module


def shipped_package() -> ModuleType:
    return importlib.import_module("kaiwo_gateway")  # pkgpath put it on sys.path


def attr_names(cls: type) -> dict[str, str]:
    """Spec signal name → attribute name."""
    return dict(zip(cls.SIGNALS, (f.name for f in dataclasses.fields(cls))))


def check_case(gw: ModuleType, case: dict[str, Any]) -> list[str]:
    errors = []
    frame_id, data = case["frame_id"], bytes.fromhex(case["data"])
    cls = gw.BY_ID.get(frame_id)
    if cls is None or cls.NAME != case["message"]:
        return [f"frame ID 0x{frame_id:X} is not {case['message']}"]
    names = attr_names(cls)
    # decode: raw values exactly, physical values to the double (ties: within half a step)
    if gw.decode_raw(frame_id, data) != case["raw"]:
        errors.append(f"decode_raw gives {gw.decode_raw(frame_id, data)}, expected {case['raw']}")
    message = gw.decode(frame_id, data)
    physical = physical_values(case)
    for sig, expected in physical.items():
        got = getattr(message, names[sig])
        if case["kind"] == "tie" and case.get("note", "").startswith(f"{sig} tie "):
            # `expected` is the tie input: the decoded value is the raw step it rounded to, half a step
            # away (up to the doubles' own spacing there, in the step's measurement and in the decode)
            slack = 4 * math.ulp(max(abs(got), abs(expected)))
            ok = abs(got - expected) <= 0.5 * _step(gw, cls, sig, case["raw"]) * (1 + 1e-9) + slack
        else:
            ok = same_value(got, expected)
        if not ok:
            errors.append(f"decode: {sig} = {got!r}, expected {expected!r}")
    errors += check_pages(gw, cls, case, message)
    # encode
    if gw.encode_raw(frame_id, case["raw"]) != data:
        errors.append(f"encode_raw gives {gw.encode_raw(frame_id, case['raw']).hex().upper()}, expected {case['data']}")
    if case["kind"] in DECODE_ONLY_KINDS:
        return errors
    # a page the frame does not hold: its fields hold a sentinel that encode must neither check nor write
    built = cls(**{names[s]: v for s, v in physical.items()}, **dict.fromkeys((names[s] for s in absent_signals(cls, case)), SENTINEL))
    if case["kind"] in PHYSICAL_KINDS:
        try:
            encoded = gw.encode(built)
        except gw.EncodeError as exc:
            errors.append(f"encode raised {exc}")
        else:
            if encoded != data:
                errors.append(f"encode gives {encoded.hex().upper()}, expected {case['data']}")
    elif case["kind"] == "raw_only":  # the documented range excludes a value: a physical encode must refuse it
        try:
            gw.encode(built)
            errors.append("encode accepted a value outside the documented range (raw_only case)")
        except gw.RangeError:
            pass
    return errors


SENTINEL = object()  # no field's value: any use of it by encode raises
OUT_OF_RANGE_RAW = -(2**70)  # no field's raw value


def absent_signals(cls: type, case: dict[str, Any]) -> list[str]:
    """The fields of the pages the case's frame does not hold (none for a message without multiplexing)."""
    return [s for s in cls.SIGNALS if s not in case["raw"]]


def check_pages(gw: ModuleType, cls: type, case: dict[str, Any], message: Any) -> list[str]:
    """Multiplexing: decode gives None for the other pages' fields, `update` leaves them alone, the presence
    query names the case's fields, and the raw packer ignores the other pages' values."""
    absent, names, errors = absent_signals(cls, case), attr_names(cls), []
    if [getattr(message, names[s]) for s in absent] != [None] * len(absent):
        errors.append(f"decode: the absent fields {absent} are not all None")
    present = [s for s in cls.SIGNALS if s in case["raw"]]
    if list(message.present_signals()) != present or not all(message.is_present(s) for s in present) or any(message.is_present(s) for s in absent):
        errors.append(f"present_signals() = {message.present_signals()}, expected {present}")
    held = cls(**dict.fromkeys(names.values(), SENTINEL))
    if held.update(bytes.fromhex(case["data"])) is not held:
        errors.append("update does not return the message it updates")
    kept = [s for s in absent if getattr(held, names[s]) is not SENTINEL]
    if kept or not all(same_value(getattr(held, names[s]), getattr(message, names[s])) for s in present):
        errors.append(f"update: the absent fields {kept} lost their values, or a present one differs from decode")
    extra = dict.fromkeys(absent, OUT_OF_RANGE_RAW)
    if absent and gw.encode_raw(case["frame_id"], {**case["raw"], **extra}) != bytes.fromhex(case["data"]):
        errors.append("encode_raw wrote or checked an absent page's raw value")
    return errors


def _step(gw: ModuleType, cls: type, sig: str, raws: dict[str, int]) -> float:
    """The physical size of one raw step of a signal at the case's raw values, measured through the package itself."""
    name, raw = attr_names(cls)[sig], raws[sig]
    here = float(getattr(cls.from_raw({**raws, sig: raw}), name))
    try:
        there = float(getattr(cls.from_raw({**raws, sig: raw - 1}), name))
    except gw.RawRangeError:
        there = float(getattr(cls.from_raw({**raws, sig: raw + 1}), name))
    return abs(here - there)


def check_multiframe(gw: ModuleType, entry: dict[str, Any]) -> list[str]:
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


def run(path: Path, gw: ModuleType | None = None) -> tuple[int, list[str]]:
    """Every case of the vectors file at `path` through `gw` (default: the shipped package)."""
    gw = gw if gw is not None else shipped_package()
    vectors = json.loads(path.read_text(encoding="utf-8"))
    failures = []
    count = 0
    for case in vectors["cases"]:
        count += 1
        try:
            errors = check_case(gw, case)
        except (gw.Error, ValueError, TypeError, KeyError) as exc:
            errors = [f"{type(exc).__name__}: {exc}"]
        for err in errors:
            failures.append(f"case {count} ({case['message']}, {case['kind']}{', ' + case['note'] if case.get('note') else ''}): {err}")
    for entry in vectors.get("multiframe", []):
        count += 1
        failures += [f"multiframe {entry['text']!r}: {e}" for e in check_multiframe(gw, entry)]
    return count, failures


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(prog=Path(argv[0]).name, description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("vectors", nargs="?", type=Path, default=pkgpath.DEFAULT_VECTORS)
    ap.add_argument("--package", type=Path, default=None, help="the generated package's directory (default: the shipped one)")
    args = ap.parse_args(argv[1:])
    gw = load_package(args.package.resolve()) if args.package is not None else shipped_package()
    count, failures = run(args.vectors, gw)
    for f in failures:
        print(f)
    print(f"python vector runner: {count} cases, {len(failures)} mismatches ({args.vectors}; package {Path(gw.__file__).parent})")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
