"""The statements of each message's encode, pack, decode checks and checksum test, as lines of
Python (indented relative to the function body; the template places them).

Encode computes the shared rounding rule (ir/encoding.py, `to_raw_runtime`) inline for values
inside the range check, step for step in doubles; everything else — out of range, NaN, a float
for an integer signal, not a number — goes to the runtime's slow path, which applies the full
rule and raises the documented errors.
"""

from __future__ import annotations

from dataclasses import dataclass

from canspec import ir
from canspec.render.literals import PYTHON
from canspec.targets.python.fields import PySignal

TIE = ir.TIE_EPSILON_TEXT
EXACT = ir.EXACT_LIMIT_TEXT
IND = "    "


@dataclass(frozen=True)
class PyChecksum:
    shift: int  # bit position of the checksum byte in the frame integer
    cover_mask: str  # hex literal: the bytes the XOR covers, in the frame integer
    folds: tuple[int, ...]  # shifts that XOR-fold the frame's bytes into its lowest byte


@dataclass(frozen=True)
class Frame:
    """What the statements need to know about the message."""

    name: str
    id_lit: str  # the frame ID as the protocol writes it (a valid Python literal)
    dlc: int
    signals: tuple[PySignal, ...]
    checksum: PyChecksum | None

    @property
    def values(self) -> tuple[PySignal, ...]:
        """The signals encode takes from the caller (the checksum it computes)."""
        return tuple(s for s in self.signals if not s.is_checksum)


def xor_folds(nbytes: int) -> tuple[int, ...]:
    """Shifts that XOR-fold `nbytes` bytes of an integer into its lowest byte."""
    out = []
    span = 1
    while span < nbytes:
        span *= 2
    while span > 1:
        span //= 2
        out.append(span * 8)
    return tuple(out)


def _xor(checksum: PyChecksum) -> list[str]:
    """`c & 0xFF` = the XOR of the bytes of the frame integer `v` that the checksum covers."""
    return [f"c = v & {checksum.cover_mask}", *(f"c ^= c >> {f}" for f in checksum.folds)]


def frame_checks(f: Frame) -> tuple[str, ...]:
    """Length check, frame integer `v`, checksum check: the start of decode and unpack."""
    lines = [f"if len(data) != {f.dlc}:", f'{IND}raise FrameLengthError("{f.name}", {f.id_lit}, {f.dlc}, len(data), id_text="{f.id_lit}")']
    if f.signals or f.checksum:
        lines.append('v = _from_bytes(data, "little")')
    if f.checksum is not None:
        byte = f"(v >> {f.checksum.shift}) & 0xFF"
        lines += ["if verify_checksum:", *(IND + s for s in _xor(f.checksum)), f"{IND}if (c & 0xFF) != {byte}:"]
        lines.append(f'{IND * 2}raise ChecksumError("{f.name}", {f.id_lit}, c & 0xFF, {byte}, id_text="{f.id_lit}")')
    return tuple(lines)


def checksum_ok(f: Frame) -> tuple[str, ...]:
    """The body of `checksum_ok(data)`: never raises."""
    if f.checksum is None:
        return ("return True",)
    byte = f"(v >> {f.checksum.shift}) & 0xFF"
    return (f"if len(data) != {f.dlc}:", f"{IND}return False", 'v = _from_bytes(data, "little")', *_xor(f.checksum), f"return (c & 0xFF) == {byte}")


def pack_tail(f: Frame) -> tuple[str, ...]:
    """The raw values in `r0`, `r1`, ... (each fits its field) into the frame bytes, checksum filled."""
    if not f.values:
        return (f"return bytes({f.dlc})",)  # reserved bits 0; a checksum of zero bytes is 0
    terms = [(f"({s.raw_var} & {PYTHON.hex(s.sig.mask)})" if s.sig.signed else s.raw_var) + (f" << {s.sig.start}" if s.sig.start else "") for s in f.values]
    lines = ["v = " + " | ".join(terms)]
    if f.checksum is not None:
        lines += [*_xor(f.checksum), f"v |= (c & 0xFF) << {f.checksum.shift}"]
    return (*lines, f'return v.to_bytes({f.dlc}, "little")')


def pack(f: Frame, names_var: str) -> tuple[str, ...]:
    """The body of the raw packer: unknown names refused, every raw value checked against its field."""
    lines = [f"if not raw.keys() <= {names_var}:", f'{IND}raise UnknownSignalError("{f.name}", sorted(raw.keys() - {names_var}))']
    lines += [f'{s.raw_var} = _check_raw(raw.get("{s.name}", 0), {s.descriptor})' for s in f.values]
    return (*lines, *pack_tail(f))


def _rounded(s: PySignal, q: str) -> list[str]:
    """`raw_var` = the rule applied to the quotient expression `q` (a value inside the range check)."""
    r = s.raw_var
    if s.q_nonneg and not s.exact_branch:
        return [f"{r} = int({q} + 0.5 + {TIE})"]
    if s.q_nonneg:
        return [f"q = {q}", f"{r} = int(q) if q >= {EXACT} else int(q + 0.5 + {TIE})"]
    if not s.exact_branch:
        return [f"q = {q}", f"{r} = int(q + 0.5 + {TIE}) if q >= 0 else -int(-q + 0.5 + {TIE})"]
    return [f"q = {q}", "a = abs(q)", f"{r} = int(a) if a >= {EXACT} else int(a + 0.5 + {TIE})", "if q < 0:", f"{IND}{r} = -{r}"]


def _to_raw(s: PySignal) -> list[str]:
    """`raw_var` from the attribute: inline inside the range, the runtime's full rule otherwise."""
    r, slow = s.raw_var, f"_to_raw({s.var}, {s.descriptor})"
    if s.direct:  # integers convert exactly: the raw range check is the whole check
        return [f"{r} = {s.q_expr}", f"if not {s.sig.raw_min} <= {r} <= {s.sig.raw_max}:", f"{IND}{r} = _to_raw(m.{s.attr}, {s.descriptor})"]
    in_range = f"{s.lo_lit} <= {s.var} <= {s.hi_lit}"
    if s.q_nonneg and not s.exact_branch and not s.raw_check:
        return [f"{s.var} = m.{s.attr}", f"{r} = int({s.q_expr} + 0.5 + {TIE}) if {in_range} else {slow}"]
    lines = [f"{s.var} = m.{s.attr}", f"if {in_range}:", *(IND + line for line in _rounded(s, s.q_expr))]
    if s.raw_check:
        lines += [f"{IND}if not {s.sig.raw_min} <= {r} <= {s.sig.raw_max}:", f"{IND * 2}{r} = {slow}"]
    return [*lines, "else:", f"{IND}{r} = {slow}"]


def encode(f: Frame, pack_func: str) -> tuple[str, ...]:
    """The body of the encoder: every value through `_to_raw`, then the frame; a value the inline
    code cannot take (a float for an integer signal, not a number) re-runs through the slow path."""
    if not f.values:
        return pack_tail(f)
    body = [line for s in f.values for line in _to_raw(s)] + list(pack_tail(f))
    retry = ", ".join(f'"{s.name}": _to_raw(m.{s.attr}, {s.descriptor})' for s in f.values)
    return (
        "try:",
        *(IND + line for line in body),
        "except (TypeError, AttributeError):  # a float for an integer signal (rounded by the rule), or not a number at all",
        f"{IND}return {pack_func}({{{retry}}})",
    )
