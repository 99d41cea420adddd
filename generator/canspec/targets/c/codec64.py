"""Pack and unpack of one message for the cores with 64-bit registers and unaligned loads and
stores (x86-64, AArch64): the headers' <PREFIX>_STRATEGY 3, where it differs from the byte
form of codec.py, which every other core runs.

The byte form pays there for what small cores need: a branch per byte's range check (so that
few fields are held in registers at once) and, for a field that crosses bytes, a reload, shifts
and an OR per byte it touches (a store to dst may alias src). Per message the generator picks
(by the instruction estimates below, x86-64 gcc -O2; tests/targets/c/bench.py measures them):

- pack, frame word: each field placed at its start bit in a uint64_t `w` (the frame read as a
  little-endian integer: byte k is bits 8k..8k+7), the checksum byte the XOR fold of the others,
  then the bytes stored from `w` (compilers merge the byte stores into one word store, as they
  merge the byte loads of unpack's `w` into one load: the C itself is byte order independent);
- pack, byte sum: each byte once as the sum of its fields' pieces (disjoint bits once the fields
  fit, so the sum is their OR; x86 folds a shift by 1-3 and an add into one `lea`);
- otherwise the byte form's pack.
Either byte form zeroes the frame with one memset first where its bytes without a field, in runs
apart, would take more stores than the memset (memset_stores: gcc zeroes 3-15 bytes with two
overlapping stores), and then leaves them out; the frame word's pack does so for the bytes outside
its span at a tie too. Both new forms check the ranges once (ERR_RANGE leaves dst unspecified): the
fields of a bit count shared by several are OR'd into `ored<n>`, a lone field compared in the check
itself. The frame word's pack checks before its stores where the checked fields fit the free
registers (FREE_REGS: they are loaded once for the check and the word; after the stores a lone
check became a branch-free select of the status when inlined), else after its stores, like the byte
sum form after the last byte: the fields are read again there (a memory operand on x86), cheaper
than spilling them.

Unpack reads a field that crosses bytes off byte boundaries (and every 64-bit field) from `w` by
its start bit and mask, every field from `w` where all of them cross bytes, the others from their
byte as codec.py does; with `w` loaded the XOR checksum is folded from it. A classic frame without
such a field and without a checksum takes codec.py's unpack with each field reading its bytes from
src, not from byte locals (reread: gcc keeps the fields' stores apart). `w` holds the bytes it
covers from bit 0 (word_base: gcc merges byte loads into one wider load only there).

The frame word's byte order is its fields' (ir.Signal.word_order): read big-endian (byte 0 its
most significant) where most fields are Motorola, in which each of them is contiguous at its
word_shift; a field of the other order is taken from its bytes as codec.py does, and pack uses
the word only where every field shares its order. A frame longer than 8 bytes (CAN FD) packs in
the byte form, which zeroes the frame with one memset first where most bytes carry no field
(x86-64 stores 16 bytes at a time; byte stores of 0 split at each field byte), and without a
checksum unpacks in windows of up to 8 bytes (_windows), each a frame word of its fields, and
packs the runs of 2, 4 or 8 bytes that carry fields of one order in every byte, and no other
field, from a word each (pack_windows: one (byte-swapped) store, where the estimate says fewer
instructions; a byte without a field inside would be known 0 to gcc, which then splits the store).
"""

from __future__ import annotations

import re

from canspec import ir
from canspec.render.literals import C
from canspec.targets.c.codec import CCodec, _range_check, byte_pieces, float_copies, float_locals, negate64, pack_bytes, paren, shl, shr, store, store_bits
from canspec.targets.c.signals import CSignal

FOLD = ("x = w ^ (w >> 32u);", "x ^= x >> 16u;", "x ^= x >> 8u;")  # XOR of the word's 8 bytes, in x's low byte
FOLD_COST = 14  # x86-64 instructions to fold the word and merge the checksum byte into it
FREE_REGS = 7  # x86-64 registers a leaf function may use without saving them, beside dst and src
MARGIN = 2  # the word form where its estimate is at least this much lower (near ties go either way)


def _checked(sigs: tuple[CSignal, ...]) -> list[CSignal]:
    """The unsigned fields narrower than their type (their OR exceeds their bit count's maximum
    exactly when one of them does)."""
    return [s for s in sigs if not s.sig.signed and s.checked]


def _ored(sigs: tuple[CSignal, ...]) -> dict[int, list[str]]:
    """The checked fields by bit count."""
    out: dict[int, list[str]] = {}
    for s in _checked(sigs):
        out.setdefault(s.length, []).append(f"src->{s.field}")
    return out


def _shared(sigs: tuple[CSignal, ...]) -> set[int]:
    """The bit counts of two or more checked fields: OR'd into a local `ored<n>` as the bytes go."""
    return {n for n, fields in _ored(sigs).items() if len(fields) > 1}


def _check(sigs: tuple[CSignal, ...], err: str) -> list[str]:
    """The message's one range check: per bit count the OR of its fields (`ored<n>`, or the one
    field) against the count's maximum, two compares per signed field narrower than its type."""
    shared = _shared(sigs)
    terms = [f"({f'ored{n}' if n in shared else f[0]} > {C.unsigned((1 << n) - 1)})" for n, f in sorted(_ored(sigs).items())]
    for s in sigs:
        if s.sig.signed and s.checked:
            bits, field = s.sig.storage_bits, f"src->{s.field}"
            terms += [f"({field} < {C.integer(s.sig.raw_type_min, bits)})", f"({field} > {C.integer(s.sig.raw_type_max, bits)})"]
    return [f"if ({' || '.join(terms)}) {{", f"return {err};", "}"] if terms else []


def _check_locals(sigs: tuple[CSignal, ...]) -> list[str]:
    """`ored<n>` in the type of the checked n-bit fields (a signed field of n bits has another)."""
    types = {s.length: s.type for s in _checked(sigs)}
    return [f"{types[n]} ored{n};" for n in sorted(_shared(sigs))]


def _accumulate(sigs: tuple[CSignal, ...], shared: set[int], seen: set[int]) -> list[str]:
    """`ored<n> |= ...` for these fields of the shared bit counts (`=` for a count's first)."""
    out = []
    for n, fields in _ored(sigs).items():
        if n in shared:
            out.append(f"ored{n} {'|=' if n in seen else '='} {' | '.join(fields)};")
            seen.add(n)
    return out


def byte_at(k: int, dlc: int, order: str) -> int:
    """Where frame byte k lies in the frame word of that order: its lowest bit."""
    return 8 * k if order == "little" else 8 * (dlc - 1 - k)


def word_order(sigs: tuple[CSignal, ...]) -> str:
    """The frame word's order: the order of most fields (little where as many are Intel)."""
    big = sum(s.sig.is_big_endian for s in sigs)
    return "big" if 2 * big > len(sigs) else "little"


def _pack_bytes(sigs: tuple[CSignal, ...], dlc: int, checksum: int | None, err: str, zeroed: bool = False) -> list[str]:
    pieces, starting = byte_pieces(sigs)
    out: list[str] = float_copies(sigs, "&{local}", "&src->{field}")
    seen: set[int] = set()
    shared = _shared(sigs)
    for k in range(dlc):
        if k == checksum:
            others = [f"dst[{b}]" for b in range(dlc) if b != k]
            out.append(f"dst[{k}] = (uint8_t)({' ^ '.join(others)});" if len(others) > 1 else f"dst[{k}] = {others[0]};")
        elif k in pieces:
            terms = pieces[k]
            out.append(f"dst[{k}] = (uint8_t){paren(terms[0] if len(terms) == 1 else '(' + ' + '.join(terms) + ')')};")
        elif not zeroed:
            out.append(f"dst[{k}] = 0u;")
        out += _accumulate(tuple(starting.get(k, ())), shared, seen)
    return out + _check(sigs, err)


def _placed(s: CSignal, base: int = 0) -> str:
    """The field's bits at their place in the frame word: a signed field cut to its bits, and in a
    big-endian word an unsigned one of several bytes at a byte boundary (unmasked, gcc traces the
    word's bytes back to the struct's and, finding no byte swap of one load, stores them one by one,
    shifted and OR'd, instead of the word's byte-swapped store)."""
    v = f"(uint64_t){s.value}"
    swapped = s.sig.word_order == "big" and 8 < s.length < s.sig.storage_bits and s.word_shift % 8 == 0
    if (s.sig.signed and s.length < 64) or swapped:
        v = f"({v} & {C.hex(s.sig.mask, bits=64)})"
    return v if s.word_shift == base else f"({v} << {s.word_shift - base}u)"


def span(sigs: tuple[CSignal, ...], dlc: int, checksum: bool, unpack: bool = False) -> range:
    """The frame bytes the word covers: every byte, or first to last byte of these fields where
    that takes fewer loads and stores (a run of n bytes is one access per set bit of n: 8 bytes
    one, 7 bytes three). Bytes outside are 0 on pack and never read on unpack, so a 7-byte frame
    whose fields lie in bytes 1-3 moves 3 bytes, not 7. A checksum folds every byte. Unpack takes
    the fewer bytes at a tie too (2 of 8: a 16-bit load and rotate, as few instructions as the
    8-byte load and swap, and the byte loads and stores of the other fields are left as they are:
    gcc merges them with the 8-byte load's value into one shifted and OR'd struct store)."""
    touched = [seg.byte for s in sigs for seg in s.sig.segments]
    if checksum or not touched:
        return range(dlc)
    inner = range(min(touched), max(touched) + 1)
    fewer, same = bin(len(inner)).count("1"), bin(dlc).count("1")
    return inner if fewer < same or (unpack and fewer == same) else range(dlc)


def _pack_word(sigs: tuple[CSignal, ...], dlc: int, checksum: int | None, err: str, order: str) -> list[str]:
    check = [*_accumulate(sigs, _shared(sigs), set()), *_check(sigs, err)]
    first = sum(s.checked for s in sigs) <= FREE_REGS
    out = [*float_copies(sigs, "&{local}", "&src->{field}"), *(check if first else ()), "w = " + " | ".join(_placed(s) for s in sigs) + ";"]
    if checksum is not None:
        at = byte_at(checksum, dlc, order)
        out += [*FOLD, f"w |= (x & 0xFFu) << {at}u;" if at else "w |= x & 0xFFu;"]
    covered = span(sigs, dlc, checksum is not None)
    zero = _zero_first(set(covered), dlc, ties=True)
    out += [f"(void)memset(dst, 0, {dlc}u);"] if zero else []
    out += [f"dst[{k}] = (uint8_t){shr('w', byte_at(k, dlc, order))};" if k in covered else f"dst[{k}] = 0u;" for k in range(dlc) if k in covered or not zero]
    return out if first else [*out, *check]


def _unswapped(sigs: tuple[CSignal, ...], dlc: int, checksum: int | None, order: str) -> bool:
    """Whether gcc stores a big-endian word's bytes one by one, each with its shift, instead of
    one byte-swapped store: where a byte it covers carries no field (stored as a constant 0) or
    it covers no 2, 4 or 8 bytes (a little-endian word it stores whole)."""
    if order != "big":
        return False
    used = {seg.byte for s in sigs for seg in s.sig.segments} | ({checksum} if checksum is not None else set())
    covered = span(sigs, dlc, checksum is not None)
    return len(covered) not in (2, 4, 8) or any(k not in used for k in covered)


def _cost_bytes(sigs: tuple[CSignal, ...], dlc: int, checksum: int | None) -> int:
    """Estimated x86-64 instructions of the byte sum form without the range check: per piece a
    load, a shift of the value and one into the byte (none into bits 1-3 after the first piece:
    `lea`), an add; a store per byte; the checksum an XOR per other byte."""
    cost = dlc + (dlc - 1 if checksum is not None else 0)
    for s in sigs:
        for seg in s.sig.segments:
            cost += 2 + (seg.value_shift > 0) + (seg.byte_shift > 3 or (seg.byte_shift > 0 and seg.value_shift > 0))
    return cost - len({seg.byte for s in sigs for seg in s.sig.segments})  # the first piece of a byte adds nothing


def _cost_word(sigs: tuple[CSignal, ...], checksum: int | None) -> int:
    """Per field a load, a shift (but at bit 0), an OR (but the first), a mask (signed fields);
    one store; the checksum's fold."""
    cost = sum(2 + (s.word_shift > 0) + (s.sig.signed and s.length < 64) for s in sigs)
    return cost + (FOLD_COST if checksum is not None else 0)


# ---- unpack ----------------------------------------------------------------------------------

def word_fields(sigs: tuple[CSignal, ...], order: str) -> tuple[CSignal, ...]:
    """The fields unpack reads from the frame word (of their order): the 64-bit ones and those that
    cross bytes off byte boundaries; all of them where every field crosses bytes (the compiler then
    merges their stores too). A byte-aligned field of whole bytes among others is read from its
    bytes, whose reads the compiler merges into one load itself."""
    crossing = [len(s.sig.segments) > 1 for s in sigs]
    if sigs and all(crossing) and all(s.sig.word_order == order for s in sigs):
        return tuple(sigs)
    return tuple(s for s, crosses in zip(sigs, crossing)
                 if s.sig.word_order == order and (s.sig.storage_bits == 64 or (crosses and (s.word_shift % 8 or s.length % 8))))


def _word_store(s: CSignal, base: int, w: str = "w") -> list[str]:
    """The field from `w`, the frame word shifted right by `base` bits."""
    field, n, t = f"dst->{s.field}", s.length, s.type
    shift = s.word_shift - base
    at = w if shift == 0 else f"({w} >> {shift}u)"
    exact = n == 64 or (n == s.sig.storage_bits and not s.sig.signed)  # the store's conversion cuts the rest
    bits = at if exact else f"({at} & {C.hex(s.sig.mask, bits=64)})"
    if s.float is not None:
        return store_bits(s, at if n == 64 else f"(uint32_t){paren(at)}")
    if not s.sig.signed:
        return [f"{field} = ({t}){bits};"]
    if n == 64:
        return [f"t64 = {w};", negate64("t64", "t64", field)]  # t64 at the function's scope, as codec.store's (cppcheck: variableScope)
    sign = s.sig.sign_bit
    if n < 32:  # bits ^ sign is below 2^n: an int32_t holds it and the subtraction
        return [f"t = (uint32_t){paren(bits)} ^ {C.hex(sign)};", f"{field} = ({t})((int32_t)t - {C.integer(sign)});"]
    return [f"t64 = {bits} ^ {C.hex(sign, bits=64)};", f"{field} = ({t})((int64_t)t64 - {C.integer(sign, 64)});"]


def _chunk_locals(covered: range) -> list[str]:
    """The uint32_t locals `w<bits>` of _load_word's chunks of 4 and 2 bytes (a composite
    expression is not cast wider: MISRA C:2012 rule 10.8)."""
    return [] if len(covered) in (1, 2, 4, 8) else [f"uint32_t w{8 * n};" for n in (4, 2) if len(covered) & n]


def word_base(covered: range, dlc: int, order: str) -> int:
    """The frame word bit of the covered bytes' least significant one: `w` holds the frame word
    shifted right by it (gcc merges byte loads into one wider load only at bit 0)."""
    return min(byte_at(k, dlc, order) for k in covered)


def _load_word(covered: range, dlc: int, order: str, w: str = "w") -> list[str]:
    """The statements reading the covered bytes into `w`, from bit 0 (word_base). gcc merges byte
    loads into one (byte-swapped) load of 2, 4 or 8 bytes only: a run of another length is read in
    runs of 4, 2 and 1 bytes (6 bytes: 4 and 2), each placed at the word bit of its least
    significant byte."""
    base = word_base(covered, dlc, order)
    if len(covered) in (1, 2, 4, 8):
        return [f"{w} = " + " | ".join(shl(f"(uint64_t)src[{k}]", byte_at(k, dlc, order) - base) for k in covered) + ";"]
    body, parts, at = [], [], covered.start
    for n in (4, 2, 1):
        if covered.stop - at < n:
            continue
        chunk, at = range(at, at + n), at + n
        low = byte_at(chunk[-1] if order == "big" else chunk[0], dlc, order) - base
        if n == 1:
            parts.append(shl(f"(uint64_t)src[{chunk[0]}]", low))
            continue
        body.append(f"w{8 * n} = " + " | ".join(shl(f"(uint32_t)src[{k}]", byte_at(k, dlc, order) - base - low) for k in chunk) + ";")
        parts.append(shl(f"(uint64_t)w{8 * n}", low))
    return [*body, f"{w} = " + " | ".join(parts) + ";"]


def _windows(sigs: tuple[CSignal, ...], dlc: int, checksum: bool, order: str) -> list[tuple[tuple[CSignal, ...], range]]:
    """The words unpack loads: (the fields read from it, the bytes it covers). A classic frame has
    one, over span(). A CAN FD frame has one per window of at most 8 bytes: its fields grouped in
    frame order while they fit 8 bytes from the first one's first byte, each group's word fields
    (word_fields, as in a classic frame) read from a load of their bytes (widened to 8 where that
    takes fewer loads and the frame has them); a field over more than 8 bytes from its bytes."""
    if dlc <= 8:
        words = word_fields(sigs, order)
        return [(words, span(words, dlc, checksum, unpack=True))] if words else []
    groups: list[list[CSignal]] = []
    for s in sorted(sigs, key=lambda s: min(seg.byte for seg in s.sig.segments)):
        lo, hi = min(seg.byte for seg in s.sig.segments), max(seg.byte for seg in s.sig.segments)
        if hi - lo >= 8:
            continue
        first = min(seg.byte for seg in groups[-1][0].sig.segments) if groups else -8
        groups.append([s]) if hi - first >= 8 else groups[-1].append(s)
    out = []
    for group in groups:
        words = word_fields(tuple(group), order)
        if not words:
            continue
        touched = [seg.byte for s in words for seg in s.sig.segments]
        inner = range(min(touched), max(touched) + 1)
        if bin(len(inner)).count("1") > 1:
            start = min(inner.start, dlc - 8)
            inner = range(start, start + 8)
        out.append((words, inner))
    return out


def unpack_parts64(sigs: tuple[CSignal, ...], dlc: int, checksum: bool, order: str) -> tuple[tuple[str, ...], tuple[str, ...]] | None:
    """None where no field is read from a word (the byte form of codec.py then)."""
    windows = _windows(sigs, dlc, checksum, order)
    if not windows:
        return None
    names = ["w" if i == 0 else f"w{i}" for i in range(len(windows))]  # w1..w7: apart from the chunks' w16, w32
    where = {id(s): i for i, (words, _) in enumerate(windows) for s in words}  # by identity: comparing CSignals compares their whole IR
    held: list[int] = []
    body = _load_word(windows[0][1], dlc, order)  # first (gcc: byte loads before it may merge into its value); the others before their first field
    loaded = {0}
    for s in sigs:
        if id(s) in where:
            i = where[id(s)]
            if i not in loaded:
                body += _load_word(windows[i][1], dlc, order, names[i])
                loaded.add(i)
            body += _word_store(s, word_base(windows[i][1], dlc, order), names[i])
            continue
        for k in sorted({seg.byte for seg in s.sig.segments} - set(held)):
            body.append(f"b{k} = src[{k}];")
            held.append(k)
        body += store(s)
    if checksum:
        body += [*FOLD, "x &= 0xFFu;"]
    chunks = sorted({line for _, covered in windows for line in _chunk_locals(covered)}, reverse=True)
    local = [f"uint32_t b{k};" for k in sorted(held)]
    local += [*chunks, *(f"uint64_t {n};" for n in names), *(["uint64_t x;"] if checksum else [])]
    local += ["uint32_t lo;", "uint32_t hi;"] if any(s.sig.storage_bits == 64 for s in sigs if id(s) not in where) else []  # codec.store's halves
    # the temporaries of signed fields: from the word, t below 32 bits; from bytes (codec.store), up to 32
    narrow = {s.sig.name: (32 if id(s) in where else 33) for s in sigs if s.sig.signed}
    local += ["uint32_t t;"] if any(s.length < narrow[s.sig.name] for s in sigs if s.sig.signed) else []
    local += ["uint64_t t64;"] if any(s.length >= narrow[s.sig.name] for s in sigs if s.sig.signed) else []
    return (*local, *float_locals(sigs)), tuple(body)


def _struct_run(fields: tuple[CSignal, ...]) -> bool:
    """Whether a field that fills its type is followed, in the struct (no padding between) and in
    the frame, by the next field, while not every field fills its type. The frame word's OR of
    the two would then be one wider load of the struct to the compiler (gcc merges it), which
    stalls on the separate stores that wrote the fields (unpack's, when every field fills its
    type, are merged alike)."""
    if all(f.length == f.sig.storage_bits for f in fields):
        return False
    offset = 0
    ends: dict[int, tuple[int, int]] = {}  # struct offset just past a field that fills its type -> its frame word bits
    for f in fields:
        size = f.sig.storage_bits // 8
        offset += -offset % size  # natural alignment
        lo, hi = ends.get(offset, (-1, -1))
        if f.word_shift == hi or f.word_shift + f.length == lo:  # next to it in the word, above or below
            return True
        offset += size
        if f.length == f.sig.storage_bits:
            ends[offset] = (f.word_shift, f.word_shift + f.length)
    return False


def _pack(msg: ir.Message, sigs: tuple[CSignal, ...], err: str, bytewise: CCodec, fields: tuple[CSignal, ...]) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """(locals, statements): the frame word where its estimate is lower (and no struct run, no
    byte-swapped store lost), the byte sum form where fields share a bit count (their one check
    saves a branch per byte), else the byte form."""
    ck = msg.checksum.byte if msg.checksum is not None else None
    locals_ = _check_locals(sigs)
    order = word_order(sigs)
    one_order = all(s.sig.word_order == order for s in sigs)
    word = _cost_word(sigs, ck) + MARGIN <= _cost_bytes(sigs, msg.dlc, ck) and not _struct_run(fields) and not _unswapped(sigs, msg.dlc, ck, order)
    if sigs and one_order and word:
        locals_ += ["uint64_t w;", *(["uint64_t x;"] if ck is not None else []), *float_locals(sigs)]
        return tuple(locals_), tuple(_pack_word(sigs, msg.dlc, ck, err, order))
    zero = bool(sigs) and _zero_first(_used(sigs, ck), msg.dlc)  # without fields: the byte form's, which says `(void)src`
    fill = (f"(void)memset(dst, 0, {msg.dlc}u);",) if zero else ()
    if _shared(sigs):
        return (*locals_, *float_locals(sigs)), (*fill, *_pack_bytes(sigs, msg.dlc, ck, err, zeroed=zero))
    return bytewise.pack_locals, (*fill, *pack_bytes(sigs, msg.dlc, ck, err, zeroed=True)) if zero else bytewise.pack


def memset_stores(n: int) -> int:
    """The stores x86-64 gcc -O2 zeroes n bytes with: one where n is a power of 2 up to 16, else
    two overlapping ones up to 16 (7 bytes: 4 at 0 and 4 at 3), then one per 16 bytes."""
    return 1 if n in (1, 2, 4, 8, 16) else 2 if n < 16 else -(-n // 16)


def _zero_first(written: set[int], dlc: int, ties: bool = False) -> bool:
    """Whether a pack zeroes the frame first (one memset) rather than store its runs of bytes
    that it does not otherwise write (`written`): an access per set bit of a run's length, each
    run apart; the memset's stores where they are fewer."""
    runs, run = [], 0
    for k in range(dlc + 1):
        if k < dlc and k not in written:
            run += 1
        elif run:
            runs.append(run)
            run = 0
    stores = sum(bin(n).count("1") for n in runs)
    return stores > memset_stores(dlc) or (ties and stores == memset_stores(dlc))


def _used(sigs: tuple[CSignal, ...], checksum: int | None) -> set[int]:
    """The frame bytes that carry a field or the checksum."""
    return {seg.byte for s in sigs for seg in s.sig.segments} | ({checksum} if checksum is not None else set())


def _fd_clusters(sigs: tuple[CSignal, ...]) -> list[tuple[range, list[CSignal]]]:
    """The fields grouped by shared frame bytes (a byte is stored whole: its fields go in one
    store), each group with its first to last byte, in frame order."""
    groups: list[tuple[set[int], list[CSignal]]] = []
    for s in sigs:
        own = {seg.byte for seg in s.sig.segments}
        hit = [g for g in groups if g[0] & own]
        for g in hit:
            groups.remove(g)
            own |= g[0]
        groups.append((own, [f for g in hit for f in g[1]] + [s]))
    return sorted(((range(min(b), max(b) + 1), fs) for b, fs in groups), key=lambda g: g[0].start)


def _window_run(group: list[CSignal], fields: tuple[CSignal, ...]) -> bool:
    """_struct_run for the fields of one pack window: two fields that fill their types, next to
    each other in the struct and in the word (gcc would load both at once); a narrower field's
    bits are not its type's bytes, and gcc loads it alone."""
    if all(f.length == f.sig.storage_bits for f in group):
        return False
    inside = {id(f) for f in group}
    offset = 0
    ends: dict[int, tuple[int, int]] = {}  # struct offset just past a field of the window that fills its type -> its word bits
    for f in fields:
        size = f.sig.storage_bits // 8
        offset += -offset % size
        lo, hi = ends.get(offset, (-1, -1))
        if id(f) in inside and f.length == f.sig.storage_bits and (f.word_shift == hi or f.word_shift + f.length == lo):
            return True
        offset += size
        if f.length == f.sig.storage_bits and id(f) in inside:
            ends[offset] = (f.word_shift, f.word_shift + f.length)
    return False


def _cost_window(group: list[CSignal], base: int) -> int:
    """_cost_word for a window whose word starts at frame word bit `base`, and the mask of a
    Motorola field _placed masks."""
    swapped = sum(1 for s in group if s.sig.word_order == "big" and 8 < s.length < s.sig.storage_bits and s.word_shift % 8 == 0)
    return swapped + sum(2 + (s.word_shift > base) + (s.sig.signed and s.length < 64) for s in group)


def _cost_window_bytes(group: list[CSignal]) -> int:
    """_cost_bytes for a window's fields, but a field alone in its bytes from bit 0 of its least
    significant one: a load and store of its first byte, then per byte a load again (the store
    to dst may alias src), a shift and a store."""
    count: dict[int, int] = {}
    for s in group:
        for b in {seg.byte for seg in s.sig.segments}:
            count[b] = count.get(b, 0) + 1
    own: list[CSignal] = []
    others: list[CSignal] = []
    for s in group:
        nbytes = {seg.byte for seg in s.sig.segments}
        alone = all(count[b] == 1 for b in nbytes) and s.word_shift % 8 == 0
        (own if alone else others).append(s)
    shared = {seg.byte for s in others for seg in s.sig.segments}
    cost = sum(3 * len({seg.byte for seg in s.sig.segments}) - 1 for s in own)
    return cost + (_cost_bytes(tuple(others), len(shared), None) if others else 0)


def pack_windows(sigs: tuple[CSignal, ...], dlc: int, fields: tuple[CSignal, ...]) -> list[tuple[list[CSignal], range, str]]:
    """The windows a CAN FD frame packs from a word: (its fields, its bytes, their order). A window
    is a run of 2, 4 or 8 bytes every one of which carries a field of it, and no other field's
    (its store writes them whole, and gcc splits a byte-swapped store at a byte it knows is 0),
    its fields of one byte order, taken where its estimate is at least MARGIN below the byte
    form's (_cost_window_bytes) and no two of its fields load as one (_window_run). Runs of fields
    are tried from the frame's start, 8 bytes first."""
    clusters = _fd_clusters(sigs)
    out: list[tuple[list[CSignal], range, str]] = []
    i = 0
    while i < len(clusters):
        taken = None
        for n in (8, 4, 2):
            group: list[CSignal] = []
            j, end = i, clusters[i][0].start
            while j < len(clusters) and clusters[j][0].start == end and clusters[j][0].stop - clusters[i][0].start <= n:
                group += clusters[j][1]
                end = clusters[j][0].stop
                j += 1
            covered = range(clusters[i][0].start, end)
            orders = {s.sig.word_order for s in group}
            if len(covered) != n or len(orders) != 1:
                continue
            order = orders.pop()
            base = word_base(covered, dlc, order)
            if _cost_window(group, base) + MARGIN <= _cost_window_bytes(group) and not _window_run(group, fields):
                taken = (group, covered, order, j)
                break
        if taken is None:
            i += 1
            continue
        out.append(taken[:3])
        i = taken[3]
    return out


def _pack_fd(msg: ir.Message, sigs: tuple[CSignal, ...], err: str, bytewise: CCodec, fields: tuple[CSignal, ...]) -> CCodec | None:
    """A CAN FD frame without a checksum whose pack_windows are some: the frame zeroed as the
    byte form does (one memset where most bytes carry no field, else a store per run), the other
    fields' bytes as the byte form's, then per window its check, its word and one store of it
    (byte-swapped for a Motorola window); None without windows."""
    windows = pack_windows(sigs, msg.dlc, fields)
    if not windows:
        return None
    inside = {id(s) for group, _, _ in windows for s in group}
    rest = tuple(s for s in sigs if id(s) not in inside)
    used = _used(sigs, None)
    names = ["w" if i == 0 else f"w{i}" for i in range(len(windows))]
    out: list[str] = []
    if 2 * len(used) < msg.dlc:
        out.append(f"(void)memset(dst, 0, {msg.dlc}u);")
    else:
        out += [f"dst[{k}] = 0u;" for k in range(msg.dlc) if k not in used]
    out += pack_bytes(rest, msg.dlc, None, err, zeroed=True) if rest else ()
    for (group, covered, order), w in zip(windows, names):
        base = word_base(covered, msg.dlc, order)
        checked = tuple(s for s in group if s.checked)
        check = [f"if ({_range_check(checked)}) {{", f"return {err};", "}"] if checked else []
        first = len(checked) <= FREE_REGS
        out += [*float_copies(tuple(group), "&{local}", "&src->{field}"), *(check if first else ())]
        out.append(f"{w} = " + " | ".join(_placed(s, base) for s in group) + ";")
        out += [f"dst[{k}] = (uint8_t){shr(w, byte_at(k, msg.dlc, order) - base)};" for k in covered]
        out += [] if first else check
    locals_ = (*bytewise.pack_locals, *(f"uint64_t {w};" for w in names))
    return CCodec(tuple(out), bytewise.unpack_locals, bytewise.unpack, locals_)


def _zeroed(msg: ir.Message, sigs: tuple[CSignal, ...], err: str, bytewise: CCodec) -> CCodec | None:
    """A CAN FD frame most of whose bytes are reserved: zeroed by one memset (a few 16-byte
    stores), then the byte form's stores of the bytes that carry fields; None where most carry one."""
    used = {seg.byte for s in sigs for seg in s.sig.segments} | ({msg.checksum.byte} if msg.checksum is not None else set())
    if not sigs or 2 * len(used) >= msg.dlc:
        return None
    pack = (f"(void)memset(dst, 0, {msg.dlc}u);", *pack_bytes(sigs, msg.dlc, msg.checksum.byte if msg.checksum else None, err, zeroed=True))
    return CCodec(pack, bytewise.unpack_locals, bytewise.unpack, bytewise.pack_locals)


def build_codec64(msg: ir.Message, sigs: tuple[CSignal, ...], err: str, bytewise: CCodec) -> CCodec | None:
    """The message's pack/unpack under <PREFIX>_STRATEGY 3, or None where it is the byte form.
    `sigs`: the struct's fields (the checksum's too: unpack stores it, pack computes it)."""
    if not msg.dlc:
        return None
    if not msg.is_classic_length:  # CAN FD: the byte form's pack (zeroed first where most bytes are reserved), unpack by windows
        data = tuple(s for s in sigs if s.sig.role != "checksum")
        zeroed = (_pack_fd(msg, data, err, bytewise, sigs) if msg.checksum is None else None) or _zeroed(msg, data, err, bytewise) or bytewise
        windows = unpack_parts64(sigs, msg.dlc, False, word_order(sigs)) if msg.checksum is None else None
        out = CCodec(zeroed.pack, *(windows or (bytewise.unpack_locals, bytewise.unpack)), zeroed.pack_locals)
        return None if out == bytewise else out
    pack_locals, pack = _pack(msg, tuple(s for s in sigs if s.sig.role != "checksum"), err, bytewise, sigs)
    unpack_locals, unpack = unpack_parts64(sigs, msg.dlc, msg.checksum is not None, word_order(sigs)) or reread(msg, bytewise)
    out = CCodec(pack, unpack_locals, unpack, pack_locals)
    return None if out == bytewise else out



def reread(msg: ir.Message, bytewise: CCodec) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """The byte form's unpack with each field reading its bytes from src (`b<k>` -> `src[k]`), not
    from byte locals: a store to dst may alias src, so gcc loads the byte again per field and keeps
    the fields' stores apart. From the locals it merges the stores of a byte's fields into one wider
    store built with a shift and an OR per field (gcc 12 store merging; a byte of 4 fields: 17
    instructions, 15 when read again). Not for a checksum (its XOR reads every byte once), nor where
    the byte form's statements are not of that shape (then unchanged)."""
    loads = [line for line in bytewise.unpack if re.fullmatch(r"b(\d+) = src\[\1\];", line)]
    if msg.checksum is not None or not loads:
        return bytewise.unpack_locals, bytewise.unpack
    body = [re.sub(r"\bb(\d+)\b", r"(uint32_t)src[\1]", line) for line in bytewise.unpack if line not in loads]
    body = [line.replace("(uint8_t)(uint32_t)src[", "(uint8_t)src[") for line in body]
    locals_ = tuple(line for line in bytewise.unpack_locals if not re.fullmatch(r"uint32_t b\d+;", line))
    if len(locals_) + len(loads) != len(bytewise.unpack_locals) or any(re.search(r"\bb\d+\b", line) for line in body):
        return bytewise.unpack_locals, bytewise.unpack
    return locals_, tuple(body)
