"""Frame decoding straight from the IR, for `canspec decode`: no generated package needed.

Each message becomes a tuple of per-signal plans (shift, mask, sign bit, factor, offset,
labels), computed once; decoding a frame is then one int.from_bytes and a loop of shifts."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction

from canspec import ir


@dataclass(frozen=True, slots=True)
class SignalPlan:
    name: str
    shift: int
    mask: int
    sign_bit: int  # 0 for unsigned signals
    factor: float | int
    offset: float | int
    decimals: int  # places that show every value exactly (0 for integer signals)
    unit: str
    labels: dict[int, str]  # value-table entries and special values by raw


@dataclass(frozen=True, slots=True)
class MessagePlan:
    name: str
    frame_id: int
    dlc: int
    signals: tuple[SignalPlan, ...]
    checksum_shift: int  # -1 without a checksum
    checksum_cover: int


def value_text(s: SignalPlan, physical: float, label: str | None) -> str:
    """A value as printed: its label, or the number in the signal's precision."""
    if label is not None:
        return label
    return f"{physical:.{s.decimals}f}" if s.decimals else str(physical)


def _decimals(value: Fraction) -> int:
    places = 0
    while value.denominator != 1 and places < 12:
        value *= 10
        places += 1
    return places


def plan_message(msg: ir.Message) -> MessagePlan:
    signals = []
    for sig in msg.data_signals:
        labels: dict[int, str] = {}
        if sig.value_table is not None:
            labels.update((e.raw, e.name) for e in sig.value_table.entries)
        labels.update((s.raw, s.name) for s in sig.specials)
        as_int = sig.is_integer
        signals.append(SignalPlan(
            sig.name, sig.start, sig.mask, 1 << (sig.length - 1) if sig.signed else 0,
            int(sig.factor) if as_int else float(sig.factor), int(sig.offset) if as_int else float(sig.offset),
            0 if as_int else max(_decimals(sig.factor), _decimals(sig.offset)), sig.unit, labels,
        ))
    shift, cover = -1, 0
    if msg.checksum is not None:
        shift = msg.checksum.byte * 8
        cover = sum(0xFF << (8 * b) for b in msg.checksum.covers)
    return MessagePlan(msg.name, msg.frame_id, msg.dlc, tuple(signals), shift, cover)


def plans(can: ir.CanProtocol) -> dict[int, MessagePlan]:
    return {m.frame_id: plan_message(m) for m in can.messages}


def checksum_ok(plan: MessagePlan, v: int) -> bool:
    if plan.checksum_shift < 0:
        return True
    c = v & plan.checksum_cover
    x = 0
    while c:
        x ^= c & 0xFF
        c >>= 8
    return x == (v >> plan.checksum_shift) & 0xFF


def decode_values(plan: MessagePlan, v: int) -> list[tuple[SignalPlan, int, float | int, str | None]]:
    """(signal, raw, physical, label) of every data signal of a frame given as one little-endian integer."""
    out = []
    for s in plan.signals:
        raw = (v >> s.shift) & s.mask
        if s.sign_bit:
            raw = (raw ^ s.sign_bit) - s.sign_bit
        out.append((s, raw, raw * s.factor + s.offset, s.labels.get(raw)))
    return out


def signal_text(s: SignalPlan, raw: int) -> str:
    """`name=value[ unit]` as the text output prints it."""
    label = s.labels.get(raw)
    if label is not None:
        return f"{s.name}={label}"
    text = value_text(s, raw * s.factor + s.offset, None)
    return f"{s.name}={text} {s.unit}" if s.unit else f"{s.name}={text}"


TABLE_BITS = 10  # fields up to this wide get every text precomputed


def text_formatter(plan: MessagePlan) -> Callable[[int], str]:
    """A function from the frame integer to the text line's fields, compiled once per message:
    straight-line code with a precomputed text per raw value for narrow fields."""
    env: dict[str, object] = {"signal_text": signal_text}
    pieces = []
    for i, s in enumerate(plan.signals):
        raw = f"((v >> {s.shift}) & {s.mask})"
        if s.sign_bit:
            raw = f"(({raw} ^ {s.sign_bit}) - {s.sign_bit})"
        if not s.sign_bit and s.mask < (1 << TABLE_BITS):
            env[f"T{i}"] = tuple(signal_text(s, r) for r in range(s.mask + 1))
            pieces.append(f"T{i}[{raw}]")
        elif s.labels:
            env[f"S{i}"] = s
            pieces.append(f"signal_text(S{i}, {raw})")
        else:
            unit = f" {s.unit}" if s.unit else ""
            spec = f".{s.decimals}f" if s.decimals else "d"
            pattern = f"{s.name}=%{spec}{unit}".replace("%", "%%").replace(f"%%{spec}", f"%{spec}", 1)
            pieces.append(f"{pattern!r} % ({raw} * {s.factor!r} + {s.offset!r})")
    body = f"', '.join(({', '.join(pieces)},))" if pieces else "''"
    namespace: dict[str, object] = {}
    exec(f"def fields(v):\n    return {body}\n", env, namespace)  # noqa: S102 - source built from the IR's numbers and identifiers
    return namespace["fields"]  # type: ignore[return-value]
