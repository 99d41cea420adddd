"""The statements of each message's encode, pack, decode checks and checksum test, as lines of
Python (indented relative to the function body; the template places them).

Encode computes the shared rounding rule (ir/encoding.py, `to_raw_runtime`) inline for values
inside the range check, step for step in doubles; everything else — out of range, NaN, a float
for an integer signal, not a number — goes to the runtime's slow path, which applies the full
rule and raises the documented errors.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from canspec import ir
from canspec.render.literals import PYTHON
from canspec.targets.python import pages
from canspec.targets.python.fields import PySignal
from canspec.targets.python.reads import checksums_every_byte

TIE = ir.TIE_EPSILON_TEXT
CLASSIC_BYTES = 8
EXACT = ir.EXACT_LIMIT_TEXT
IND = "    "


@dataclass(frozen=True)
class PyChecksum:
    word: str  # the frame word it is computed on: "v" (little-endian) or "b" (big-endian, a frame of Motorola fields only)
    shift: int  # bit position of the checksum byte in that word
    cover_mask: str  # hex literal: the bytes the XOR covers, in that word
    folds: tuple[int, ...]  # shifts that XOR-fold the covered bytes into the word's lowest byte
    # The checksum covers every other byte of the frame: then the XOR of the whole word is 0 for an
    # intact frame, and (with the checksum byte still 0) the checksum itself while encoding — no mask.
    whole: bool = False


@dataclass(frozen=True)
class Frame:
    """What the statements need to know about the message."""

    name: str
    id_lit: str  # the frame ID as the protocol writes it (a valid Python literal)
    dlc: int
    signals: tuple[PySignal, ...]
    checksum: PyChecksum | None
    byte_struct: str = ""  # the module's struct.Struct that unpacks the bytes and 16-bit words decode reads (struct_format)
    pair_order: str = "<"  # the byte order of its 16-bit words (fields.word_pairs)

    @property
    def values(self) -> tuple[PySignal, ...]:
        """The signals encode takes from the caller (the checksum it computes)."""
        return tuple(s for s in self.signals if not s.is_checksum)

    def reads(self, physical: bool) -> set[str | None]:
        """What decode (`physical`) or unpack reads its fields from: "d" (the frame's bytes or 16-bit words), "v", "b" (its words)."""
        return {s.decode_word if physical else s.read for s in self.signals}

    def _readers(self, physical: bool) -> list[PySignal]:
        return [s for s in self.signals if (s.decode_word if physical else s.read) == "d"]

    def bytes_used(self, physical: bool) -> set[int]:
        return {i for s in self._readers(physical) if s.pair is None and s.frame_bytes is not None for i, _ in s.frame_bytes}

    def pairs_used(self, physical: bool) -> set[int]:
        return {s.pair for s in self._readers(physical) if s.pair is not None}


def read_bytes(f: Frame, physical: bool) -> tuple[int, ...]:
    """The frame bytes decode (`physical`) or unpack reads as `dN`: every byte where decode XORs them for the checksum."""
    if "d" not in f.reads(physical):
        return ()
    if f.checksum is not None and f.checksum.whole:
        return tuple(range(f.dlc))
    return tuple(sorted(f.bytes_used(physical)))


def by_index(f: Frame, physical: bool) -> bool:
    """Whether decode (`physical`) or unpack reads its bytes by a length check and one index each, not in one unpack.
    Measured on CPython 3.11 (ns, k bytes read of n): unpacking the data as a tuple costs 31 + 4.8 n, a struct of
    the k bytes 34 + 6.8 k, the length check and indexes 15 + 12 k; indexing must win by 10 ns (here in fifths of
    a ns, to stay in integers). Never where a 16-bit word is read (a struct reads it whole)."""
    k = len(read_bytes(f, physical))
    if not k or f.pairs_used(physical):
        return False
    unpack = 155 + 24 * f.dlc if f.dlc <= CLASSIC_BYTES else 170 + 34 * k
    return 125 + 60 * k < unpack


def struct_items(f: Frame) -> tuple[tuple[int, str], ...]:
    """What a struct unpacks for decode and unpack, where they do not index the bytes (by_index): (frame byte, `B`) for
    a byte read as `dN`, (first byte, `H`) for a 16-bit word read as `hN`. Only for a CAN FD frame, or one with such
    words: tuple-unpacking a classic frame's bytes is faster than a struct call."""
    pairs = f.pairs_used(True) | f.pairs_used(False)
    if f.dlc <= CLASSIC_BYTES and not pairs:
        return ()
    bytes_ = {i for physical in (True, False) if not by_index(f, physical) for i in read_bytes(f, physical)}
    return tuple(sorted([(i, "B") for i in bytes_] + [(p, "H") for p in pairs]))


def struct_format(f: Frame) -> str:
    """The struct format of struct_items: `B`, `H`, and `x` (counted) for the bytes between."""
    out, at = [f.pair_order if any(code == "H" for _, code in struct_items(f)) else "<"], 0
    for i, code in struct_items(f):
        out.append(f"{i - at}x" if i - at > 1 else "x" * (i - at))
        out.append(code)
        at = i + (2 if code == "H" else 1)
    out.append(f"{f.dlc - at}x" if f.dlc - at > 1 else "x" * (f.dlc - at))
    return "".join(out)


def pack_word(values: tuple[PySignal, ...]) -> str:
    """The frame word encode builds the frame in: little-endian unless every field it sets is Motorola."""
    return "b" if values and all(s.word == "b" for s in values) else "v"


def make_checksum(msg: ir.Message, values: tuple[PySignal, ...]) -> PyChecksum | None:
    """The XOR checksum on the word encode builds (so encode folds the word it has)."""
    if msg.checksum is None:
        return None
    word, mask, byte = pack_word(values), msg.checksum.cover_mask, msg.checksum.byte
    if word == "b":  # the same bytes, numbered from the frame's end
        mask, byte = int.from_bytes(mask.to_bytes(msg.dlc, "little"), "big"), msg.dlc - 1 - byte
    whole = checksums_every_byte(msg)
    return PyChecksum(word, byte * 8, PYTHON.hex(mask), xor_folds(msg.dlc if whole else (mask.bit_length() + 7) // 8), whole)


ORDERS = {"v": "little", "b": "big"}


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
    """`c & 0xFF` = the XOR of the bytes of the frame word that the checksum covers (when it covers
    every other byte: of all bytes, the checksum byte included)."""
    w, folds = checksum.word, checksum.folds
    if checksum.whole:
        return [f"c = {w} ^ {w} >> {folds[0]}", *(f"c ^= c >> {f}" for f in folds[1:])] if folds else [f"c = {w}"]
    return [f"c = {w} & {checksum.cover_mask}", *(f"c ^= c >> {f}" for f in folds)]


def _checksum_byte(checksum: PyChecksum) -> str:
    return f"({checksum.word} >> {checksum.shift}) & 0xFF" if checksum.shift else f"{checksum.word} & 0xFF"


def _byte_names(f: Frame, physical: bool) -> str:
    """`d0, _, d2 = data`: the frame's bytes decode reads (every one where the checksum XORs them); with a struct,
    the bytes `dN` and 16-bit words `hN` it unpacks."""
    used, pairs = read_bytes(f, physical), f.pairs_used(physical)
    if f.byte_struct:
        names = [f"h{i}" if code == "H" and i in pairs else f"d{i}" if code == "B" and i in used else "_" for i, code in struct_items(f)]
        source = f"{f.byte_struct}.unpack(data)"
    else:
        names, source = [f"d{i}" if i in used else "_" for i in range(f.dlc)], "data"
    return f"({names[0]},) = {source}" if len(names) == 1 else f"{', '.join(names)} = {source}"


def frame_checks(f: Frame, physical: bool) -> tuple[str, ...]:
    """Length check, frame bytes `dN` / words `v` / `b`, checksum check: the start of decode (`physical`) and unpack.
    Where decode reads the bytes anyway, an XOR checksum of every other byte is their XOR (small ints)."""
    wrong = f'raise FrameLengthError("{f.name}", {f.id_lit}, {f.dlc}, len(data), id_text="{f.id_lit}")'
    reads, ck = f.reads(physical), f.checksum
    by_bytes = ck is not None and ck.whole and "d" in reads
    if "d" in reads and not by_index(f, physical):  # unpacking the bytes checks the length (a try costs nothing until it raises)
        error = "_StructError" if f.byte_struct else "ValueError"
        lines = ["try:", IND + _byte_names(f, physical), f"except {error}:  # not {f.dlc} bytes", f"{IND}{wrong} from None"]
    else:
        lines = [f"if len(data) != {f.dlc}:", IND + wrong, *(f"d{i} = data[{i}]" for i in read_bytes(f, physical))]
    words = reads | ({ck.word} if ck is not None and not by_bytes else set())
    lines += [f'{w} = _from_bytes(data, "{order}")' for w, order in ORDERS.items() if w in words]
    if ck is None:
        return tuple(lines)
    if by_bytes:
        own = f"d{f.dlc - 1 - ck.shift // 8 if ck.word == 'b' else ck.shift // 8}"
        check, test, computed, byte = [f"c = {' ^ '.join(f'd{i}' for i in range(f.dlc))}"], "c", f"c ^ {own}", own
    elif ck.whole:  # the XOR of every byte is 0; the one the frame should carry is that XOR with its own
        own = f"{ck.word} >> {ck.shift}" if ck.shift else ck.word
        check, test, computed, byte = _xor(ck), "c & 0xFF", f"(c ^ {own}) & 0xFF", _checksum_byte(ck)
    else:
        byte = _checksum_byte(ck)
        check, test, computed = _xor(ck), f"(c & 0xFF) != {byte}", "c & 0xFF"
    lines += ["if verify_checksum:", *(IND + s for s in check), f"{IND}if {test}:"]
    lines.append(f'{IND * 2}raise ChecksumError("{f.name}", {f.id_lit}, {computed}, {byte}, id_text="{f.id_lit}")')
    return tuple(lines)


def checksum_ok(f: Frame) -> tuple[str, ...]:
    """The body of `checksum_ok(data)`: never raises."""
    if f.checksum is None:
        return ("return True",)
    word = f'{f.checksum.word} = _from_bytes(data, "{ORDERS[f.checksum.word]}")'
    return (f"if len(data) != {f.dlc}:", f"{IND}return False", word, *_xor(f.checksum),
            "return not c & 0xFF" if f.checksum.whole else f"return (c & 0xFF) == {_checksum_byte(f.checksum)}")


def _terms(values: list[PySignal]) -> str:
    """The raw values ORed into their frame word (each fits its field; a signed one masked)."""
    terms = [(f"({s.raw_var} & {PYTHON.hex(s.sig.mask)})" if s.sig.signed else s.raw_var) + (f" << {s.sig.word_shift}" if s.sig.word_shift else "")
             for s in values]
    return " | ".join(terms)


def pack_tail(f: Frame) -> tuple[str, ...]:
    """The raw values in `r0`, `r1`, ... (each fits its field) into the frame bytes, checksum filled."""
    if not f.values:
        return (f"return bytes({f.dlc})",)  # reserved bits 0; a checksum of zero bytes is 0
    word = pack_word(f.values)
    lines = [f"{w} = {_terms(group)}" for w in ORDERS if (group := [s for s in f.values if s.word == w])]
    if len(lines) == 2:  # both orders: the Motorola fields join the little-endian word
        lines.append(f'v |= _from_bytes(b.to_bytes({f.dlc}, "big"), "little")')
    if f.checksum is not None:
        lines += [*_xor(f.checksum), f"{word} |= (c & 0xFF) << {f.checksum.shift}" if f.checksum.shift else f"{word} |= c & 0xFF"]
    return (*lines, f'return {word}.to_bytes({f.dlc}, "{ORDERS[word]}")')


def _paged(f: Frame, convert: Callable[[PySignal], list[str]]) -> list[str]:
    """`convert` of every value, a page's under its condition on the multiplexers' raw locals (0 where absent)."""
    by_name = {s.name: s for s in f.values}
    lines: list[str] = []
    for chain, group in pages.grouped(f.values):
        if chain:
            lines.append(" = ".join([*(s.raw_var for s in group), "0"]))
        lines += pages.under(chain, lambda n: by_name[n].raw_var, [line for s in group for line in convert(s)])
    return lines


def pack(f: Frame, names_var: str) -> tuple[str, ...]:
    """The body of the raw packer: unknown names refused, every raw value checked against its field (of a
    multiplexed message: every value of the pages its multiplexers select; the others are ignored)."""
    lines = [f"if not raw.keys() <= {names_var}:", f'{IND}raise UnknownSignalError("{f.name}", sorted(raw.keys() - {names_var}))']
    lines += _paged(f, lambda s: [f'{s.raw_var} = _check_raw(raw.get("{s.name}", 0), {s.descriptor})'])
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
    # a page's field is typed `T | None`; None is only for absent pages, and here raises TypeError (the slow path's error)
    read = f'{s.var} = cast("{s.py_type.removesuffix(" | None")}", m.{s.attr})' if s.chain else f"{s.var} = m.{s.attr}"
    if s.sig.is_float:  # the double's bit pattern in the format (NaN, ±Inf and what lies outside: the slow path)
        bits = f'_from_bytes(_pack_f{s.sig.length}({s.var}), "little")'
        return [read, f"{r} = {bits} if {s.lo_lit} <= {s.var} <= {s.hi_lit} else {slow}"]
    if s.direct:  # integers convert exactly: the raw range check is the whole check
        lines = [f"{r} = {s.q_expr}", f"if not {s.sig.raw_min} <= {r} <= {s.sig.raw_max}:", f"{IND}{r} = _to_raw(m.{s.attr}, {s.descriptor})"]
        return [read, *lines] if s.chain else lines
    in_range = f"{s.lo_lit} <= {s.var} <= {s.hi_lit}"
    if s.q_nonneg and not s.exact_branch and not s.raw_check:
        return [read, f"{r} = int({s.q_expr} + 0.5 + {TIE}) if {in_range} else {slow}"]
    lines = [read, f"if {in_range}:", *(IND + line for line in _rounded(s, s.q_expr))]
    if s.raw_check:
        lines += [f"{IND}if not {s.sig.raw_min} <= {r} <= {s.sig.raw_max}:", f"{IND * 2}{r} = {slow}"]
    return [*lines, "else:", f"{IND}{r} = {slow}"]


def encode(f: Frame, pack_func: str) -> tuple[str, ...]:
    """The body of the encoder: every value through `_to_raw`, then the frame; a value the inline
    code cannot take (a float for an integer signal, not a number) re-runs through the slow path."""
    if not f.values:
        return pack_tail(f)
    body = _paged(f, _to_raw) + list(pack_tail(f))
    return (
        "try:",
        *(IND + line for line in body),
        "except (TypeError, AttributeError):  # a float for an integer signal (rounded by the rule), or not a number at all",
        *(IND + line for line in _retry(f, pack_func)),
    )


def _retry(f: Frame, pack_func: str) -> list[str]:
    """Every value (of a multiplexed message: of the selected pages) through the slow path, then the raw packer."""
    groups = pages.grouped(f.values)
    first = ", ".join(f'"{s.name}": _to_raw(m.{s.attr}, {s.descriptor})' for s in (groups[0][1] if not groups[0][0] else []))
    if len(groups) == 1 and not groups[0][0]:
        return [f"return {pack_func}({{{first}}})"]
    lines = [f"raw: dict[str, int] = {{{first}}}"]
    for chain, group in groups[1:] if not groups[0][0] else groups:
        lines += pages.under(chain, lambda n: f'raw["{n}"]', [f'raw["{s.name}"] = _to_raw(m.{s.attr}, {s.descriptor})' for s in group])
    return [*lines, f"return {pack_func}(raw)"]
