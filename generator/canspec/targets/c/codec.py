"""Pack and unpack of one message as C statements, byte by byte.

The IR gives each signal's share of each frame byte (its segments: value bits [value_shift,
value_shift + width) at byte bits [byte_shift, ...)), in either byte order: a Motorola field's
segments run from its last byte (least significant) back to its first. The C follows those
segments literally, so a reviewer reads each field's byte, shift and mask next to its name, and
every core runs it well: only 32-bit arithmetic (a 64-bit field is two 32-bit halves), no
unaligned access, no helper calls, the same arithmetic on either host byte order, any frame
length (CAN FD's 64 bytes too). A float field's bit pattern goes through a local of its width
(floats.py).

Pack writes each frame byte once, as the OR of its fields' pieces (reserved bits 0, no memset,
no read-modify-write), with the check that the fields starting in it fit their bits. Two variants
zero the bytes without a field otherwise (the header picks by <PREFIX>_STRATEGY and -Os):
word_zeros (unaligned word stores, level 2) and zero_first (a long CAN FD frame zeroed first). Unpack reads each frame
byte once into a local when its first field needs it (stores to *dst may alias src, so reading
it again later would cost a load each time), and folds it into the XOR the checksum needs.

Cores with 64-bit registers (x86-64, AArch64: <PREFIX>_STRATEGY 3) run codec64.py's forms where the
generator estimates them cheaper there.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from canspec import ir
from canspec.render.literals import C
from canspec.targets.c.signals import CSignal


@dataclass(frozen=True)
class CCodec:
    pack: tuple[str, ...]  # statements writing dst[0 .. dlc-1], returning `err` if a field does not fit
    unpack_locals: tuple[str, ...]
    unpack: tuple[str, ...]  # statements filling *dst from src (and, with a checksum, x)
    pack_locals: tuple[str, ...] = ()  # codec64.py's forms declare some


_OPERAND = re.compile(r"(\(uint32_t\))?\w+(\[\d+\]|->\w+)?")  # b3, src[5], src->f, (uint32_t)src->f


def paren(expr: str) -> str:
    """`expr` as an operand: parenthesised unless it is a name, an access, a cast of one, or
    already one parenthesis."""
    if _OPERAND.fullmatch(expr):
        return expr
    if expr.startswith("(") and _closing(expr) == len(expr) - 1:
        return expr
    return f"({expr})"


def _closing(expr: str) -> int:
    """The index of the parenthesis that closes the one `expr` starts with (-1: none)."""
    depth = 0
    for i, ch in enumerate(expr):
        if ch == "(":
            depth += 1
        elif ch == ")":
            depth -= 1
            if depth == 0:
                return i
    return -1


def shr(expr: str, n: int) -> str:
    return expr if n == 0 else f"({paren(expr)} >> {n}u)"


def shl(expr: str, n: int) -> str:
    return expr if n == 0 else f"({paren(expr)} << {n}u)"


def masked(expr: str, width: int) -> str:
    return f"({paren(expr)} & {C.hex((1 << width) - 1)})"


def ored(terms: list[str]) -> str:
    return terms[0] if len(terms) == 1 else "(" + " | ".join(terms) + ")"


# ---- pack ------------------------------------------------------------------------------------

def _halves(s: CSignal, wide: bool) -> tuple[str, str]:
    """The field's value: its low 32 bits (the field itself where it is unsigned and `wide` is
    not asked for) and, for 64-bit fields, its high 32 bits (as uint32_t)."""
    field, bits = s.value, s.sig.storage_bits
    cast = s.sig.signed or bits == 64 or (wide and bits < 32)  # two's complement bits / the low half / no int promotion
    high = f"((uint64_t){field} >> 32u)" if s.sig.signed else f"({field} >> 32u)"  # no shift of a signed value (MISRA 10.1)
    return (f"(uint32_t){field}" if cast else field), (f"(uint32_t){high}" if bits == 64 else "")


def piece(s: CSignal, seg: ir.Segment) -> str:
    """Pack: the segment's value bits, placed at its bits of the byte (bits above the byte are
    cut by the store). Only a signed field's top piece needs a mask: below the top the field
    goes on into the next byte, and an unsigned field is checked to fit its bits. A left shift
    works on a uint32_t (never on a promoted int)."""
    lo, hi = _halves(s, seg.byte_shift > 0)
    vs = seg.value_shift
    if vs >= 32:
        e = shr(hi, vs - 32)
    elif hi and vs + seg.width > 32:
        e = f"({shr(lo, vs)} | ({paren(hi)} << {32 - vs}u))"
    else:
        e = shr(lo, vs)
    top = vs + seg.width == s.length
    if s.sig.signed and top and seg.byte_shift + seg.width < 8:
        e = masked(e, seg.width)
    return shl(e, seg.byte_shift)


def _range_check(sigs: tuple[CSignal, ...]) -> str:
    """One compare per width of the unsigned fields narrower than their type (their OR exceeds
    the width's maximum exactly when one of them does), two per signed such field."""
    groups: dict[tuple[int, int], list[str]] = {}
    signed = []
    for s in sigs:
        bits, field = s.sig.storage_bits, f"src->{s.field}"
        if not s.checked:
            continue
        if s.sig.signed:
            signed += [f"({field} < {C.integer(s.sig.raw_type_min, bits)})", f"({field} > {C.integer(s.sig.raw_type_max, bits)})"]
        else:
            groups.setdefault((s.length, bits), []).append(field)
    terms = [f"({ored(fields)} > {C.unsigned((1 << n) - 1, bits)})" for (n, bits), fields in sorted(groups.items())]
    return " || ".join(terms + signed)


HELD_FIELDS = 4  # checked fields a byte's check may keep in registers for the byte (Cortex-M0+: 8 low registers)


def first_byte(s: CSignal) -> int:
    """The frame byte a field starts in: its least significant (Intel) or most significant (Motorola) one."""
    return min(seg.byte for seg in s.sig.segments)


def byte_pieces(sigs: tuple[CSignal, ...]) -> tuple[dict[int, list[str]], dict[int, list[CSignal]]]:
    """Per frame byte: its fields' pieces (pack), and the fields that start in it."""
    pieces: dict[int, list[str]] = {}
    starting: dict[int, list[CSignal]] = {}
    for s in sigs:
        starting.setdefault(first_byte(s), []).append(s)
        for seg in s.sig.segments:
            pieces.setdefault(seg.byte, []).append(piece(s, seg))
    return pieces, starting


WORD_PIECE = 8  # bytes: a run of bytes without a field is zeroed in pieces of at most this many, aligned in the frame


def zero_pieces(a: int, b: int) -> list[tuple[int, int]]:
    """(first byte, count): the run of bytes [a, b) without a field cut at each multiple of
    WORD_PIECE, each piece one memset that compilers turn into at most two word stores and a
    halfword and byte store (unaligned word stores: <PREFIX>_STRATEGY 2)."""
    out, k = [], a
    while k < b:
        end = min(b, (k // WORD_PIECE + 1) * WORD_PIECE)
        out.append((k, end - k))
        k = end
    return out


def pack_bytes(sigs: tuple[CSignal, ...], dlc: int, checksum: int | None, err: str, zeroed: bool = False,
               words: bool = False) -> tuple[str, ...]:
    """Each byte stored as soon as it is computed (holding them all would spill on small cores),
    with the check of the checked fields that start in it: before the byte where it checks at
    most HELD_FIELDS of them (the values stay in registers for the byte), after it otherwise
    (the fields are read again: a store to dst may alias src; cheaper than spilling them). On
    ERR_RANGE the frame's bytes are unspecified. `zeroed`: the frame is already 0, the bytes
    without fields are not stored."""
    pieces, starting = byte_pieces(sigs)
    out = float_copies(sigs, "&{local}", "&src->{field}")
    for k in range(dlc):
        checked = tuple(s for s in starting.get(k, ()) if s.checked)
        check = [f"if ({_range_check(checked)}) {{", f"return {err};", "}"] if checked else []
        before = len(checked) <= HELD_FIELDS
        out += check if before else []
        if k == checksum:
            others = [f"dst[{b}]" for b in range(dlc) if b != k]
            out.append(f"dst[{k}] = (uint8_t)({' ^ '.join(others)});" if len(others) > 1 else f"dst[{k}] = {others[0]};" if others else f"dst[{k}] = 0u;")
        elif k in pieces:
            out.append(f"dst[{k}] = (uint8_t){paren(ored(pieces[k]))};")
        elif words:
            if k == 0 or (k - 1) in pieces or k - 1 == checksum:  # the run starts here
                end = next((j for j in range(k, dlc) if j in pieces or j == checksum), dlc)
                out += [f"(void)memset(&dst[{a}], 0, {n}u);" if n > 1 else f"dst[{a}] = 0u;" for a, n in zero_pieces(k, end)]
        elif not zeroed:
            out.append(f"dst[{k}] = 0u;")
        out += [] if before else check
    return tuple(out)


# ---- unpack ----------------------------------------------------------------------------------

def _bits(seg: ir.Segment) -> str:
    """Unpack: the segment's bits of its byte local, at bit 0 (uint32_t)."""
    e = shr(f"b{seg.byte}", seg.byte_shift)
    return e if seg.byte_shift + seg.width == 8 else masked(e, seg.width)


def _assemble(s: CSignal) -> tuple[list[str], str]:
    """(statements, expression): the field's raw bits, uint32_t (fields up to 32 bits) or
    uint64_t from the halves `lo` and `hi`."""
    if s.sig.storage_bits < 64:
        return [], ored([shl(_bits(seg), seg.value_shift) for seg in s.sig.segments])
    low, high = [], []
    for seg in s.sig.segments:
        vs, e = seg.value_shift, _bits(seg)
        if vs >= 32:
            high.append(shl(e, vs - 32))
            continue
        low.append(shl(e, vs))
        if vs + seg.width > 32:
            high.append(shr(e, 32 - vs))
    stmts = [f"lo = {ored(low)};", f"hi = {ored(high)};"]
    return stmts, "(((uint64_t)hi << 32u) | (uint64_t)lo)"


def negate64(bits: str, temp: str, field: str) -> str:
    """A 64-bit two's complement value into an int64_t without an implementation-defined
    conversion: a negative one through its complement, which an int64_t holds (cast as a
    variable, not as a composite expression: MISRA C:2012 rule 10.8)."""
    return (f"if ({bits} <= (uint64_t)INT64_MAX) {{ {field} = (int64_t){bits}; }} "
            f"else {{ {temp} = ~{bits}; {field} = -(int64_t){temp} - 1; }}")


def float_copies(sigs: tuple[CSignal, ...], to: str, source: str) -> list[str]:
    """The statements copying the float fields' bit patterns (`to`, `source`: formats of `local`
    and `field`): pack's, from each field into its local."""
    return [f"{s.float.copy_fn}({to.format(local=s.float.local, field=s.field)}, {source.format(local=s.float.local, field=s.field)}, sizeof {s.float.local});"
            for s in sigs if s.float is not None]


def float_locals(sigs: tuple[CSignal, ...]) -> list[str]:
    return [f"{s.float.bits_type} {s.float.local};" for s in sigs if s.float is not None]


def store_bits(s: CSignal, bits: str) -> list[str]:
    """Unpack: the float field's bit pattern `bits` into its local, then into the field."""
    assert s.float is not None
    return [f"{s.float.local} = {bits};", *float_copies((s,), "&dst->{field}", "&{local}")]


def store(s: CSignal) -> list[str]:
    stmts, bits = _assemble(s)
    field, n, t = f"dst->{s.field}", s.length, s.type
    if s.float is not None:
        return [*stmts, *store_bits(s, bits)]
    if not s.sig.signed:
        return [*stmts, f"{field} = ({t}){paren(bits)};"]
    if n == 64:
        return [*stmts, f"t64 = {bits};", negate64("t64", "t64", field)]
    sign = s.sig.sign_bit
    if n < 32:  # bits ^ sign is below 2^n: an int32_t holds it and the subtraction
        return [*stmts, f"t = {bits} ^ {C.hex(sign)};", f"{field} = ({t})((int32_t)t - {C.integer(sign)});"]
    wide = "t64" if n > 32 else "t"
    return [*stmts, f"{wide} = {bits} ^ {C.hex(sign, bits=64 if n > 32 else 32)};", f"{field} = ({t})((int64_t){wide} - {C.integer(sign, 64)});"]


def unpack_parts(sigs: tuple[CSignal, ...], dlc: int, checksum: bool) -> tuple[tuple[str, ...], tuple[str, ...]]:
    held: list[int] = []  # frame bytes read into locals, in the order read
    body: list[str] = []
    for s in sigs:
        for k in sorted({seg.byte for seg in s.sig.segments} - set(held)):
            body.append(f"b{k} = src[{k}];")
            if checksum:
                body.append(f"x {'^=' if held else '='} b{k};")
            held.append(k)
        body += store(s)
    if checksum:  # the bytes no field reads (reserved) are covered too
        rest = [k for k in range(dlc) if k not in held]
        body += [f"x {'^=' if held or i else '='} src[{k}];" for i, k in enumerate(rest)]
    local = [f"uint32_t b{k};" for k in sorted(held)]
    local += ["uint32_t x;"] if checksum else []
    local += ["uint32_t lo;", "uint32_t hi;"] if any(s.sig.storage_bits == 64 for s in sigs) else []
    local += ["uint32_t t;"] if any(s.sig.signed and s.length <= 32 for s in sigs) else []
    local += ["uint64_t t64;"] if any(s.sig.signed and s.length > 32 for s in sigs) else []
    return (*local, *float_locals(sigs)), tuple(body)


def build_codec(msg: ir.Message, sigs: tuple[CSignal, ...], err: str, words: bool = False) -> CCodec:
    """`sigs`: the struct's fields (the checksum's too: unpack stores it, pack computes it).
    `words`: pack zeroes the runs of bytes without a field a word at a time (zero_pieces)."""
    ck = msg.checksum.byte if msg.checksum is not None else None
    packed = tuple(s for s in sigs if s.sig.role != "checksum")
    locals_, unpack = unpack_parts(sigs, msg.dlc, ck is not None)
    return CCodec(pack_bytes(packed, msg.dlc, ck, err, words=words) if packed else (), locals_, unpack, tuple(float_locals(packed)))


ZERO_FIRST_BYTES = 32  # a CAN FD frame with at least this many bytes without a field is zeroed first (zero_first)


def zero_first(msg: ir.Message, sigs: tuple[CSignal, ...], err: str, bytewise: CCodec, fill: str) -> CCodec | None:
    """A CAN FD frame with at least ZERO_FIRST_BYTES bytes without a field: zeroed whole by the
    statement `fill` first (a memset call, or the shared word stores of zero_fill), then only the
    bytes that carry fields are stored; None for any other frame."""
    ck = msg.checksum.byte if msg.checksum is not None else None
    packed = tuple(s for s in sigs if s.sig.role != "checksum")
    used = {seg.byte for s in packed for seg in s.sig.segments} | ({ck} if ck is not None else set())
    if msg.is_classic_length or msg.is_multiplexed or not packed or msg.dlc - len(used) < ZERO_FIRST_BYTES:
        return None
    pack = (fill, *pack_bytes(packed, msg.dlc, ck, err, zeroed=True))
    return CCodec(pack, bytewise.unpack_locals, bytewise.unpack, bytewise.pack_locals)


def zero_fill(dlc: int) -> tuple[str, ...]:
    """The body of the shared function that zeroes a frame of `dlc` bytes with word stores
    (<PREFIX>_STRATEGY 2): out of line in a build for size, one copy for every message."""
    return tuple(f"(void)memset(&dst[{a}], 0, {n}u);" for a, n in zero_pieces(0, dlc))


def word_zeros(msg: ir.Message, sigs: tuple[CSignal, ...], err: str, bytewise: CCodec) -> CCodec | None:
    """The pack of <PREFIX>_STRATEGY 2 (unaligned word stores): the byte form's, each run of bytes
    without a field zeroed a word at a time (zero_pieces); None where it is the byte form's."""
    words = build_codec(msg, sigs, err, words=True)
    return None if words.pack == bytewise.pack else words
