"""Shared test vectors (`vectors/can.json`): the one file every language's round-trip tests read;
and the sequence vectors (`vectors/sequences.json`, sequences.py and texts.py) for the receive
monitors and multi-frame text reassembly.

Per message: the all-zero frame, the minimum and maximum of every signal, every allowed
value-table entry and special value, rounding ties, and 50 seeded pseudo-random cases.
Every case's physical values are encodable under the shared rules (values the documented
range excludes — e.g. reserved enum codes — are not physical-encodable and appear only as
raw bytes in the `raw_only` cases), and counters and checksums are filled in. A frame's data is
its `dlc` bytes (up to 64 in CAN FD). IEEE float fields get their own cases (floats.py): range
ends, ±0, subnormals, NaN (quiet and with a payload), ±Inf and random finite values.
"""

from __future__ import annotations

import functools
import random
import zlib
from fractions import Fraction
from typing import Any

from canspec import ir
from canspec.ir.encoding import fits_runtime, float_of_bits, to_physical_runtime, to_raw_exact, to_raw_runtime
from canspec.ir.model import runtime_quotient
from canspec.reference import codec
from canspec.render import jsontext
from canspec.render.jsontext import Streamed
from canspec.targets import Target
from canspec.targets.vectors import floats, sequences, texts

RANDOM_CASES = 50
VECTOR_FORMAT = 1
SAMPLE_VIN = "LKLA6G1H8LA000205"
MONITOR_RULES = (
    "Each sequence runs on a fresh monitor of every message (timeout = timeout_cycles x cycle, its params). Steps: start "
    "(supervise the messages' timeouts from t), frame (received at t: its faults, state, counter delta, checksum, recovery "
    "and the fault codes after it), check (the messages that time out at t). Times are ms modulo 2^32. "
    "The rules: generator/canspec/runtime/monitor.py."
)
TEXT_RULES = (
    "Frames of one multi-frame message fed in order to a fresh reassembly: result ok/length/checksum/index/inconsistent, "
    "text: the text when complete and valid, null while incomplete, false when complete but invalid. "
    "The rules: generator/canspec/reference/textframes.py."
)

FLOAT_RULES = (
    "An IEEE 754 field's raw value is its bit pattern, its physical value the float those bits hold: a JSON number (-0 as -0.0) or "
    '"NaN", "Infinity", "-Infinity". Encode rounds to nearest (binary32); NaN and +-Inf encode only where no range is documented (else '
    "the case is raw_only), NaN to the format's quiet NaN. float_special cases (+0, -0, the smallest subnormals, the quiet NaN, +-Inf) "
    "are physical-encodable; nan_payload cases (a NaN with another payload) decode to NaN and pack at raw level, their physical encode "
    "is not checked."
)


Scales = tuple[tuple[str, int, int, int], ...]


def _scales(msg: ir.Message) -> Scales:
    """Per data signal (name, a, b, d) with raw * factor + offset == (raw * a + b) / d in integers:
    the same numbers as sig.physical(...) as a JSON number (int when exact, else the correctly
    rounded double of the quotient), without Fraction arithmetic for each of many cases."""
    return tuple(
        (s.name, s.factor.numerator * s.offset.denominator, s.offset.numerator * s.factor.denominator, s.factor.denominator * s.offset.denominator)
        for s in msg.data_signals
        if not s.is_float
    )


def _case(
    msg: ir.Message, raw: dict[str, int], kind: str, physical: dict[str, Any] | None = None, note: str = "", *, scales: Scales | None = None
) -> dict[str, Any]:
    raw = dict(raw)
    data = codec.pack(msg, raw)
    if msg.checksum is not None:
        raw[msg.checksum.signal] = data[msg.checksum.byte]
    phys: dict[str, Any] = {}
    for name, a, b, d in scales if scales is not None else _scales(msg):
        n = raw[name] * a + b
        phys[name] = n // d if n % d == 0 else n / d
    for s in msg.data_signals:
        if s.is_float:
            phys[s.name] = floats.json_value(float_of_bits(raw[s.name], s.length))
    if physical:
        phys.update(physical)
    refused = {s.name: floats.encodes_to(s, raw[s.name]) for s in msg.data_signals if s.is_float}
    if kind != "raw_only" and any(refused.values()):
        kind = "raw_only" if "raw_only" in refused.values() else "nan_payload"
        why = {"raw_only": "a physical encode refuses it (documented range)", "nan_payload": "a physical encode gives the quiet NaN"}
        note = f"{note}; " * bool(note) + ", ".join(f"{n}: {why[k]}" for n, k in refused.items() if k)
    if kind not in ("raw_only", "nan_payload"):
        # a decoded case's values must encode back whatever the accepted range says: no range check here
        lost = [s.name for s in msg.data_signals
                if not s.is_identity and not s.is_float and not _survives_doubles(s, raw[s.name], phys[s.name], kind != "decoded")]
        if lost:
            kind, note = "beyond_double", f"{note}; " * bool(note) + f"the physical value of {', '.join(lost)} does not encode back in doubles"
    return case_record(msg, data, raw, phys, kind, note)


def _survives_doubles(sig: ir.Signal, raw: int, physical: float | int, ranged: bool = True) -> bool:
    """Whether the runtime rule (ir/encoding.py), given this physical value as a double, encodes
    it back to `raw`: always within a field's first 2^52 steps, not always beyond (a 63-bit
    field's maximum has no double of its own). Every language encodes an identity field
    (raw = physical) in integers; scaled ones are asked, integer-scaled too: a wide one's physical
    value may be an integer no double holds, and C's and Rust's encode of it takes a double."""
    x, (f, o) = float(physical), sig.runtime_scale
    if not fits_runtime(runtime_quotient(x, f, o), sig.raw_type_min, sig.raw_type_max) or to_raw_runtime(x, f, o) != raw:
        return False
    return not ranged or any(s.raw == raw for s in sig.specials) or float(sig.accept_min) <= x <= float(sig.accept_max)


def case_record(msg: ir.Message, data: bytes, raw: dict[str, int], physical: dict[str, Any], kind: str, note: str = "") -> dict[str, Any]:
    """One case as the vectors file holds it (also written by tools/big_vectors.py)."""
    case = {"message": msg.name, "frame_id": msg.frame_id, "data": data.hex().upper(), "raw": raw, "physical": physical, "kind": kind}
    if note:
        case["note"] = note
    return case


def _ties(sig: ir.Signal) -> list[tuple[float, int, str]]:
    """Physical inputs halfway between two raw steps (at both ends of the range and in its
    middle, so wide fields get their extremes), with the raw value the shared runtime rule gives
    for that double input (ir/encoding.py). Within the rule's tie guarantee that is the exact
    decimal rule's result (tested); beyond it the note says so."""
    if sig.is_identity or sig.is_float or sig.raw_max - sig.raw_min < 2:
        return []
    out = []
    for lower in sorted({sig.raw_min, (sig.raw_min + sig.raw_max) // 2, sig.raw_max - 1}):
        tie = sig.physical(Fraction(2 * lower + 1, 2))
        x = float(tie)
        expected = to_raw_runtime(x, float(sig.factor), float(sig.offset))
        if not (sig.check_min <= tie <= sig.check_max and sig.raw_min <= expected <= sig.raw_max):
            continue
        beyond = "" if expected == to_raw_exact(tie, sig.factor, sig.offset) else " (beyond the tie guarantee: the double quotient rounds)"
        out.append((x, expected, beyond))
    return out


def _decoded(sig: ir.Signal) -> list[tuple[int, float]]:
    """The raw ends of a field and their neighbours with the double every decoder returns for them
    (raw × factor + offset, each step in doubles) where that is not the nearest double of the exact
    value (those the min/max cases hold) and the runtime rule carries it back (its quotient inside
    the field, rounding to the raw value): each must encode back to its raw value."""
    if sig.is_integer or sig.is_float:  # integer physical values: exact in doubles wherever they survive at all
        return []
    f, o = float(sig.factor), float(sig.offset)
    out = []
    for raw in sorted({sig.raw_min, sig.raw_min + 1, sig.raw_max - 1, sig.raw_max}):
        x = to_physical_runtime(raw, f, o)
        if not sig.raw_min <= raw <= sig.raw_max or x == float(sig.physical(raw)):
            continue
        if fits_runtime(sig.runtime_quotient(x), sig.raw_type_min, sig.raw_type_max) and to_raw_runtime(x, f, o) == raw:
            out.append((raw, x))
    return out


def message_cases(msg: ir.Message) -> list[dict[str, Any]]:
    """The message's cases; a multiplexed message's, page by page (ir.Message.page_selections):
    each page's cases as a plain message's, those with its multiplexer values (a value-table
    entry of a multiplexer selects another page)."""
    if not msg.is_multiplexed:
        return _cases(msg)
    return [c for values in msg.page_selections for c in _cases(msg.page(values)) if all(c["raw"][k] == v for k, v in values.items())]


def _cases(msg: ir.Message) -> list[dict[str, Any]]:
    sigs = [s for s in msg.data_signals if s.role != "checksum"]
    case = functools.partial(_case, msg, scales=_scales(msg))
    base = {s.name: s.base_raw for s in sigs}
    cases = []
    zero = {s.name: 0 for s in sigs}
    if all(s.raw_allowed(0) for s in sigs):
        cases.append(case(zero, "zero"))
    else:
        cases.append(case(zero, "raw_only", note="all-zero frame; some zero raw values lie outside the documented range"))
    cases.append(case(base, "base"))
    for sig in sigs:
        if sig.is_float:
            cases += [case({**base, sig.name: raw}, kind, note=note) for raw, kind, note in floats.edge_cases(sig)]
            continue
        cases.append(case({**base, sig.name: sig.raw_min}, "min", note=sig.name))
        cases.append(case({**base, sig.name: sig.raw_max}, "max", note=sig.name))
        if sig.value_table is not None:
            for entry in sig.value_table.entries:
                kind = "enum" if sig.raw_allowed(entry.raw) else "raw_only"
                cases.append(case({**base, sig.name: entry.raw}, kind, note=f"{sig.name}={entry.name}"))
        for special in sig.specials:
            cases.append(case({**base, sig.name: special.raw}, "special", note=f"{sig.name}={special.name}"))
        for tie, expected, beyond in _ties(sig):
            cases.append(case({**base, sig.name: expected}, "tie", {sig.name: tie}, note=f"{sig.name} tie {tie!r} -> raw {expected}{beyond}"))
        for raw, x in _decoded(sig):
            cases.append(case({**base, sig.name: raw}, "decoded", {sig.name: x}, note=f"{sig.name} raw {raw} decodes to {x!r}"))
    rng = random.Random(zlib.crc32(msg.name.encode()))
    cases += [case({s.name: _random_raw(s, rng) for s in sigs}, "random") for _ in range(RANDOM_CASES if sigs else 0)]
    return cases


def _random_raw(sig: ir.Signal, rng: random.Random) -> int:
    """A random raw value of the field: a special value now and then, else any in its range."""
    if sig.is_float:
        return floats.random_raw(sig, rng)
    if sig.specials and rng.random() < 0.1:
        return rng.choice(sig.specials).raw
    return rng.randint(sig.raw_min, sig.raw_max)


def vin_cases(can: ir.CanProtocol) -> list[dict[str, Any]]:
    out = []
    for msg in can.messages:
        mf = msg.multiframe
        if mf is None:
            continue
        sample = (SAMPLE_VIN * (mf.text_length // len(SAMPLE_VIN) + 1))[: mf.text_length]  # the VIN, fitted to the text's length
        for vin in (sample, "0" * mf.text_length):
            text = vin.encode("ascii")
            frames = []
            for i in range(mf.frames):
                chunk = text[i * mf.bytes_per_frame : (i + 1) * mf.bytes_per_frame].ljust(mf.bytes_per_frame, bytes([mf.padding]))
                raw = {mf.index_signal: i, mf.payload_signal: int.from_bytes(chunk, "little")}
                for s in msg.data_signals:
                    raw.setdefault(s.name, s.base_raw)
                frames.append(codec.pack(msg, raw).hex().upper())
            out.append({"message": msg.name, "frame_id": msg.frame_id, "text": vin, "frames": frames})
    return out


def _about(spec: ir.Spec) -> dict[str, Any]:
    """What every vectors file says about itself: its format and the spec it comes from."""
    return {"format": VECTOR_FORMAT, "spec": spec.name, "version": spec.version, "sha256": spec.sha256, "generated_by": f"canspec {spec.generator_version}"}


def build_vectors(spec: ir.Spec, *, stream: bool = False) -> dict[str, Any]:
    """The vectors file's data; `stream`: its cases as a jsontext.Streamed list, produced message by
    message while the text is written (a large spec's cases never all exist at once)."""
    assert spec.can is not None
    can = spec.can
    cases = Streamed(c for m in can.messages for c in message_cases(m)) if stream else [c for m in can.messages for c in message_cases(m)]
    return {
        **_about(spec),
        "rules": {
            "physical_to_raw": "q = (physical - offset) / factor in doubles; raw = sign(q) * (|q| >= 2^52 ? |q| : floor(|q| + 0.5 + "
            + ir.TIE_EPSILON_TEXT
            + ")) (round half away from zero)",
            "range": "physical outside the documented range, or a raw value that does not fit, is an error unless the raw value is a special value",
            "reserved_bits": 0,
            "checksum": "XOR of every other byte of the frame, in its checksum byte",
            "kinds": (
                "zero/base/min/max/enum/special/tie/random/decoded cases are physical-encodable (a decoded case's physical value is the double a "
                "decoder returns for its raw value: raw x factor + offset, each step in doubles); raw_only cases decode and pack at raw level and a"
                " physical encode must refuse them; beyond_double cases (physical values a double cannot carry back to their raw value, on fields "
                "wider than 2^52 steps) decode and pack at raw level only"
            ),
            **({"float": FLOAT_RULES} if spec.can.has_float else {}),
        },
        "cases": cases,
        "multiframe": vin_cases(spec.can),
    }


def build_sequences(spec: ir.Spec) -> dict[str, Any]:
    assert spec.can is not None
    return {
        **_about(spec),
        "rules": {
            "monitor": MONITOR_RULES,
            "timeout_cycles": ir.MONITOR_TIMEOUT_CYCLES,
            "texts": TEXT_RULES,
        },
        "monitor": sequences.monitor_sequences(spec.can),
        "texts": texts.all_text_sequences(spec.can),
    }


def _json(data: dict[str, Any]) -> bytes:
    return (jsontext.dumps(data, indent=1) + "\n").encode("utf-8")


def render_vectors(spec: ir.Spec) -> dict[str, bytes]:
    if spec.can is None:
        return {}
    return {"vectors/can.json": _json(build_vectors(spec, stream=True)), "vectors/sequences.json": _json(build_sequences(spec))}


TARGET = Target("vectors", "shared CAN test vectors (JSON)", "vectors/", render_vectors, order=20, cost=2)
