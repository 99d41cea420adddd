"""Helpers of the DBC tests: a spec's DBC and vectors rendered in memory and written out, the DBC
read by cantools (strict) and canmatrix, the spec's names of the DBC's signals (as the DBC itself
states them, in its SpecSignalName attribute), and the cantools oracle over a vectors file."""

from __future__ import annotations

import functools
import json
import logging
import math
import struct
from pathlib import Path
from typing import Any

import canmatrix.formats
import cantools
from canspec import ir
from canspec.ir.encoding import float_of_bits
from canspec.pipeline import compile_spec
from canspec.targets import registry
from repo_paths import ROOT

VALID = ROOT / "tests" / "fixtures" / "valid"
ENCODINGS = {"dbcImportEncoding": "utf-8", "dbcImportCommentEncoding": "utf-8", "dbcExportEncoding": "utf-8",
             "dbcExportCommentEncoding": "utf-8", "symImportEncoding": "utf-8", "symExportEncoding": "utf-8"}


def valid_fixtures() -> list[Path]:
    return sorted(VALID.glob("*.yaml"))


@functools.cache
def compiled(path: Path) -> ir.Spec:
    result = compile_spec(path)
    assert result.spec is not None and not result.errors, "\n".join(p.format() for p in result.problems)
    return result.spec


def can_fixtures() -> list[Path]:
    return [p for p in valid_fixtures() if compiled(p).can is not None]


def write_dbc(spec: ir.Spec, directory: Path) -> Path:
    (rel, data), = registry()["dbc"].render(spec).items()
    path = directory / Path(rel).name
    path.write_bytes(data)
    return path


def vectors(spec: ir.Spec) -> dict[str, Any]:
    return json.loads(registry()["vectors"].render(spec)["vectors/can.json"])


def load_cantools(path: Path, strict: bool = True) -> Any:
    return cantools.database.load_file(str(path), encoding="utf-8", strict=strict)


def load_canmatrix(path: Path) -> Any:
    logging.getLogger("canmatrix").setLevel(logging.ERROR)
    return canmatrix.formats.loadp(str(path), **ENCODINGS)[""]


def attribute(obj: Any, name: str) -> Any:
    attr = (getattr(getattr(obj, "dbc", None), "attributes", None) or {}).get(name)
    return None if attr is None else attr.value


def spec_names(message: Any) -> dict[str, str]:
    """DBC signal name → the spec's name, from the DBC's SpecSignalName attributes."""
    return {s.name: attribute(s, "SpecSignalName") or s.name for s in message.signals}


def check_oracle(db: Any, vectors_: dict[str, Any]) -> int:
    """cantools decodes every case's bytes to its raw values and encodes its raw values to its
    bytes; physical values agree (within half a step on ties, where cantools rounds otherwise)."""
    for case in vectors_["cases"]:
        msg = db.get_message_by_name(case["message"])  # by name: frame IDs repeat across 11 and 29 bits
        to_dbc = {v: k for k, v in spec_names(msg).items()}
        # cantools' raw value of an IEEE float signal is the float itself: the bits the vectors hold, as a float
        raw = {to_dbc[k]: float_of_bits(v, msg.get_signal_by_name(to_dbc[k]).length) if msg.get_signal_by_name(to_dbc[k]).is_float else v
               for k, v in case["raw"].items()}
        data = bytes.fromhex(case["data"])
        assert same_values(msg.decode(data, decode_choices=False, scaling=False), raw), case
        assert msg.encode(raw, scaling=False, strict=False) == data, case
        phys = msg.decode(data, decode_choices=False, scaling=True)
        for sig in msg.signals:
            if sig.name not in phys:  # another page's field: the raw comparison above holds the frame's fields exactly
                continue
            expected = case["physical"][spec_names(msg)[sig.name]]
            if sig.is_float:  # a number, -0.0 with its sign, or "NaN" / "Infinity" / "-Infinity"
                assert math.isnan(phys[sig.name]) if expected == "NaN" else same_values({0: phys[sig.name]}, {0: float(expected)}), (case, sig.name)
                continue
            tolerance = abs(sig.scale) / 2 * (1 + 1e-9) if case["kind"] == "tie" else 1e-9 * max(1.0, abs(expected))
            tolerance += 4 * math.ulp(float(expected))  # the double arithmetic of both sides (a tie 0.05 from 1838860.7000000002)
            assert math.isclose(phys[sig.name], expected, abs_tol=tolerance), (case, sig.name)
    return len(vectors_["cases"])


def same_values(a: dict[Any, Any], b: dict[Any, Any]) -> bool:
    """Equal values, floats bit for bit (NaN equals NaN of the same bits; -0.0 differs from 0.0)."""
    def key(v: Any) -> Any:
        return ("float", struct.pack("<d", v)) if isinstance(v, float) else v

    return a.keys() == b.keys() and all(key(a[k]) == key(b[k]) for k in a)
