"""The C view of one signal: its struct field and the physical conversions.

Two physical paths, both following the shared rules (ir/encoding.py):
- double: `*_decode` / `*_encode`, for every field whose raw values are all exact in a double,
  and for any field the integer path cannot hold;
- fixed point: `*_decode_fixed` / `*_encode_fixed` in integers only, physical × 10^k, k the
  fewest decimals that express every raw step, both range bounds and (for scaled signals) every
  half step, so each rounding tie is an integer input. It exists when every value it computes
  fits a 32- or 64-bit integer (signed, or unsigned for wide unsigned fields without offset).
An IEEE float field is a `float` / `double` in the struct (pack and unpack copy its bit pattern,
see CFloat) with the float path of floats.py instead of both.
"""

from __future__ import annotations

from dataclasses import dataclass

from canspec import ir
from canspec.ir.bits import describe
from canspec.render.literals import C
from canspec.targets.c.floats import CFloat, float_path
from canspec.targets.c.names import CNames
from canspec.targets.c.physical import CDouble, CFixed, double_path, fixed_path, int_lit


def ctype(bits: int, signed: bool) -> str:
    return f"{'int' if signed else 'uint'}{bits}_t"


@dataclass(frozen=True)
class CSpecial:
    macro: str
    value: str  # literal in the field's type
    raw: int
    label: str


@dataclass(frozen=True)
class CSignal:
    sig: ir.Signal
    field: str
    macro: str  # <PREFIX>_<MESSAGE>_<SIGNAL>
    fn: str  # <prefix>_<message>_<signal>
    type: str  # the struct field's type
    length: int
    word_shift: int  # the field's LSB in the frame word of its byte order (ir.Signal.word_shift)
    where: str  # its bits, for the struct's comment
    value: str  # pack: its raw value (the field, or for a float the local holding its bit pattern)
    range_check: str  # C condition true when a signed src->field does not fit its bits ("" if it always does)
    needs_check: bool  # unsigned field whose type is wider than its bits
    specials: tuple[CSpecial, ...]
    factor: str  # the *_FACTOR macro's value (a negative one in parentheses)
    offset: str  # double literals of the offset and the documented (else encodable) range
    check_min: str
    check_max: str
    enum_type: str  # C type of its value table ("" if none)
    is_data: bool  # has physical encode/decode (not counter/checksum)
    double: CDouble | None  # the double path (None: use the fixed one)
    fixed: CFixed | None  # the integer path (None: its values do not fit 64-bit integers)
    float: CFloat | None  # an IEEE float field: its bit pattern's type and its decode/encode
    unit: str
    comment: str  # its Chinese name (or English description) and unit
    range_known: bool = False  # a multiplexer inside a branch on its values (mux.py): pack need not check it

    @property
    def checked(self) -> bool:
        """Pack checks that it fits its bits: narrower than its type, its value not known to fit."""
        return self.length != self.sig.storage_bits and not self.range_known


def build_signal(names: CNames, msg: ir.Message, sig: ir.Signal, enum_types: dict[str, str]) -> CSignal:
    bits = sig.storage_bits
    field = CNames.member(sig.c_name)
    fits_type = sig.length == bits
    range_check = ""
    if sig.signed and not fits_type:
        range_check = f"(src->{field} < {C.integer(sig.raw_type_min, bits)}) | (src->{field} > {C.integer(sig.raw_type_max, bits)})"
    base = names.message(msg.name)
    macro = names.const(base, sig.c_name)
    specials = tuple(CSpecial(names.special(base, sig.c_name, sp.name), int_lit(sp.raw, bits, sig.signed), sp.raw, sp.label) for sp in sig.specials)
    is_data = sig.role == "data"
    flt = float_path(names, sig, field) if sig.is_float else None
    fixed = fixed_path(names, sig) if is_data and flt is None else None
    fn = names.fn(base, sig.c_name)
    double = double_path(names, sig, fn, macro, force=fixed is None) if is_data and flt is None else None
    renamed = f"spec name {sig.name}" if sig.c_name != sig.name else ""  # the reviewer's key into the protocol table
    comment = " ".join(t for t in (sig.zh or sig.desc, f"[{sig.unit}]" if sig.unit else "", renamed) if t)
    return CSignal(
        sig=sig,
        field=field,
        macro=macro,
        fn=fn,
        type=flt.type if flt is not None else ctype(bits, sig.signed),
        length=sig.length,
        word_shift=sig.word_shift,
        where=_where(sig),
        value=flt.local if flt is not None else f"src->{field}",
        range_check=range_check,
        needs_check=not fits_type and not sig.signed,
        specials=specials,
        factor=C.double(sig.factor) if sig.factor > 0 else f"({C.double(sig.factor)})",
        offset=C.double(sig.offset),
        check_min=flt.check_min if flt is not None else C.double(sig.check_min),
        check_max=flt.check_max if flt is not None else C.double(sig.check_max),
        enum_type=enum_types.get(sig.value_table.name, "") if sig.value_table else "",
        is_data=is_data,
        double=double,
        fixed=fixed,
        float=flt,
        unit=sig.unit,
        comment=comment,
    )



def _where(sig: ir.Signal) -> str:
    """An Intel field's bit range; a Motorola field's start bit (its MSB) and its bits byte by byte."""
    if not sig.is_big_endian:
        return f"bits {sig.start}..{sig.last_bit}"
    return f"Motorola, start bit {sig.start}: {describe(sig.start, sig.length, sig.byte_order)}"
