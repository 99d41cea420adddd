"""Read a DBC the way a good tool would: what cantools cannot parse is repaired line by line where
one reading is sensible — each repair a warning with `file:line` and what was decided — and
refused with `file:line` and a hint where none is. Repairs (the corpus of real files forced each):

- a frame ID above 0x7FF without the extended flag: taken as 29-bit;
- a number written `.25`: read as 0.25;
- a name starting with a digit (`0_COUNTER`): kept as the DBC's name, parsed under a placeholder;
- a statement (`CM_`, `VAL_`, `BA_`, …) without its closing `;`: closed; `CM_ 145 "…"` (no object
  type): a message comment; `CM_ SG_ 304 "…"` (no signal name): dropped;
- `VAL_` for a signal that does not exist: dropped;
- a frame ID that does not fit 29 bits: that message left out (no reading of it is sensible);
- an SG_ line repeated word for word in its message: the repeat dropped;
- a `BA_` value of an ENUM attribute that is not an index of its values: dropped (cantools fails
  on it or gives no value).

Two different SG_ lines of one name in one message are refused: CM_, VAL_ and BA_ name a signal by
its name, so which of the two they mean has no sensible reading. So are two BO_ lines of one frame
ID: they name a message by its ID, and a DBC is one bus, where an ID is one message (cantools keeps
the later in its lookup by ID, silently but for a log line).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from fractions import Fraction

from canspec.ir.ids import DBC_EXTENDED_FLAG, MAX_EXTENDED_ID, MAX_STANDARD_ID

MAX_REPAIRS = 10_000
PLACEHOLDER = "CANSPEC_DIGIT_"  # prefix of a digit-first name while cantools parses it

_SYNTAX = re.compile(r"Invalid syntax at line (\d+), column (\d+)")
_STANDARD_TOO_BIG = re.compile(r"Standard frame id 0x([0-9a-fA-F]+) is more than 11 bits in message (\S+?)\.")
_EXTENDED_TOO_BIG = re.compile(r"Extended frame id 0x([0-9a-fA-F]+) is more than 29 bits in message (\S+?)\.")
_STATEMENT = re.compile(r"^\s*(CM_|VAL_|BA_|BA_DEF_|BA_DEF_DEF_|VAL_TABLE_|SIG_VALTYPE_|SG_MUL_VAL_)\s")
_UNUSED_VAL = re.compile(r"unused VAL_ entries in DBC")
_BO = re.compile(r"^(\s*BO_\s+)(\d+)(\s+)(\w+)(\s*:)")
BO_LINE = _BO
MAX_DBC_ID = 0xFFFF_FFFF  # a BO_ ID is 32 bits (flag and 29-bit ID); cantools wraps a larger one
ECHO = 200  # characters of source text an error or warning repeats
_DOT_NUMBER = re.compile(r"(?<![\w.])\.(\d)")
_CM_BARE = re.compile(r"^(\s*CM_\s+)(\d+)(\s+\")")
_CM_SG_NO_NAME = re.compile(r"^\s*CM_\s+SG_\s+\d+\s+\"")
_VAL = re.compile(r"^\s*VAL_\s+(\d+)\s+(\w+)\s")
_SG = re.compile(r"^\s*SG_\s+(\w+)")
# SG_ name [multiplexing] : start|length@order sign (factor,offset) [minimum|maximum]
_SG_NUMBERS = re.compile(r"^\s*SG_\s+(\w+)[^:]*:\s*\d+\|\d+@[01][+-]\s*\(([^,()]+),([^,()]+)\)\s*\[([^|\]]+)\|([^\]]+)\]")
_BO_ID = re.compile(r"^\s*BO_\s+(\d+)\s")
_ENUM_DEF = re.compile(r'^\s*BA_DEF_\s+(?:(?:BU_|BO_|SG_|EV_)\s+)?"(\w+)"\s+ENUM\s+(.*)$')
_BA_INDEX = re.compile(r'^\s*BA_\s+"(\w+)"\s+(?:[^;"]*?\s)?(-?\d+)\s*;\s*$')

Numbers = tuple[Fraction, Fraction, Fraction, Fraction]  # factor, offset, minimum, maximum


class DbcError(Exception):
    """A DBC no repair makes readable: `file:line: what` and a hint."""


def clip(text: str, limit: int = ECHO) -> str:
    """Source text as a message repeats it: a line of a damaged file can be megabytes long."""
    return text if len(text) <= limit else f"{text[:limit]}... ({len(text) - limit} more characters)"


def written_numbers(text: str) -> dict[tuple[int, str], Numbers]:
    """(BO_ ID as written, signal name) → the SG_ line's factor, offset and range, exactly as
    written: cantools reads doubles, which cannot hold 0.1 or a 64-bit field's 18446744073709551615."""
    out: dict[tuple[int, str], Numbers] = {}
    frame = None
    for line in text.splitlines():
        if (bo := _BO_ID.match(line)) is not None:
            frame = int(bo.group(1))
        elif frame is not None and (sg := _SG_NUMBERS.match(line)) is not None:
            try:
                f, o, lo, hi = (Fraction(g.strip()) for g in sg.groups()[1:])
            except (ValueError, ZeroDivisionError):
                continue  # cantools' reading stands
            out[(frame, sg.group(1))] = (f, o, lo, hi)
    return out


@dataclass
class Repairs:
    source: str
    lines: list[str]
    warnings: list[tuple[int, str]] = field(default_factory=list)  # (1-based line, text)
    renamed: dict[str, str] = field(default_factory=dict)  # placeholder → the DBC's own name

    @property
    def text(self) -> str:
        return "\n".join(self.lines) + "\n"

    def warn(self, index: int, text: str) -> None:
        self.warnings.append((index + 1, text))


_SG_OR_BO_NAME = re.compile(r"^\s*(?:SG_|BO_\s+\d+)\s+(\w+)")
_BO_SIZE = re.compile(r"^\s*BO_\s+\d+\s+(\w+)\s*:\s*(\d+)")
_SG_BITS = re.compile(r"^\s*SG_\s+(\w+)[^:]*:\s*(\d+)\|(\d+)@")
MAX_FRAME_BYTES = 64  # a CAN FD frame


def _check_sizes(rep: Repairs) -> None:
    """Refuse lengths and bit positions no CAN frame has before cantools reads them: it builds its
    codec bit by bit and byte by byte (a signal of 10^10 bits took 24 GB and was killed)."""
    bits = 8 * MAX_FRAME_BYTES
    for i, line in enumerate(rep.lines):
        if (m := _BO_SIZE.match(line)) is not None and int(m.group(2)) > MAX_FRAME_BYTES:
            raise DbcError(f"{rep.source}:{i + 1}: message {m.group(1)} is {m.group(2)} bytes long; a CAN frame holds at most "
                           f"{MAX_FRAME_BYTES} (hint: correct the length on its BO_ line)")
        if (m := _SG_BITS.match(line)) is not None and (int(m.group(2)) >= bits or not 0 < int(m.group(3)) <= bits):
            raise DbcError(f"{rep.source}:{i + 1}: signal {m.group(1)}: start bit {m.group(2)}, {m.group(3)} bits: no CAN frame has "
                           f"these bits (at most {bits}, numbered 0..{bits - 1}; hint: correct the SG_ line's start|length)")


def _check_signal_names(rep: Repairs) -> None:
    """One SG_ name per message: a word-for-word repeat is dropped, two definitions are refused."""
    message, seen = "", {}
    for i, line in enumerate(rep.lines):
        if (bo := _BO.match(line)) is not None:
            message, seen = bo.group(4), {}
        elif (sg := _SG.match(line)) is not None and message:
            first = seen.setdefault(sg.group(1), i)
            if first == i:
                continue
            if rep.lines[first].strip() == line.strip():
                rep.warn(i, f"SG_ line of signal {sg.group(1)} repeats line {first + 1} of message {message} word for word: dropped")
                rep.lines[i] = ""
                continue
            raise DbcError(f"{rep.source}:{i + 1}: message {message} has two signals named {sg.group(1)} (lines {first + 1} and {i + 1}): "
                           "CM_, VAL_ and BA_ lines could mean either (hint: rename one of them, and the lines naming it)")


def prepass(rep: Repairs) -> None:
    """The repairs a scan of the lines finds, made before cantools first parses the text: each
    would otherwise cost a parse of the whole file to discover (a large DBC takes seconds)."""
    _check_sizes(rep)
    _check_signal_names(rep)
    for i, line in enumerate(rep.lines):
        if (m := _SG_OR_BO_NAME.match(line)) is not None and m.group(1)[0].isdigit() and not m.group(1).isdigit():
            _rename_digit_name(rep, i, m.group(1))
        elif re.match(r"\s*SG_", line) and _DOT_NUMBER.search(line.partition('"')[0]):
            rep.lines[i] = _DOT_NUMBER.sub(r"0.\1", line.partition('"')[0]) + line[len(line.partition('"')[0]):]
            rep.warn(i, "number written without a leading 0 (e.g. '.25'): read as 0.25")
        elif (m := _CM_BARE.match(line)) is not None:
            rep.lines[i] = f"{m.group(1)}BO_ {m.group(2)}{line[m.end(2):]}"
            rep.warn(i, f"CM_ without an object type before ID {m.group(2)}: taken as the comment of message {m.group(2)}")
    for line in list(rep.lines):
        if (m := _BO.match(line)) is not None and MAX_STANDARD_ID < int(m.group(2)) < DBC_EXTENDED_FLAG:
            _extend_id(rep, int(m.group(2)), m.group(4))
        elif m is not None and int(m.group(2)) > MAX_DBC_ID:  # before cantools wraps it to 32 bits
            _drop_message(rep, int(m.group(2)), m.group(4))
    _drop_unused_vals(rep)
    _drop_bad_enum_indices(rep)
    _check_frame_ids(rep)


def _drop_bad_enum_indices(rep: Repairs) -> None:
    """A BA_ line stores an ENUM attribute's value as an index of its BA_DEF_ values: one past them
    names no value (cantools fails on VFrameFormat's with 'list index out of range')."""
    sizes = {m.group(1): len(re.findall(r'"[^"]*"', m.group(2))) for line in rep.lines if (m := _ENUM_DEF.match(line)) is not None}
    for i, line in enumerate(rep.lines):
        if (m := _BA_INDEX.match(line)) is not None and m.group(1) in sizes and not 0 <= int(m.group(2)) < sizes[m.group(1)]:
            _drop_statement(rep, i, f"BA_ {m.group(1)} value {m.group(2)} is not an index of its ENUM's {sizes[m.group(1)]} values "
                                    f"(0..{sizes[m.group(1)] - 1}): dropped")


def _check_frame_ids(rep: Repairs) -> None:
    """One message per frame ID (after the repairs above made every ID above 0x7FF extended)."""
    seen: dict[int, int] = {}
    for i, line in enumerate(rep.lines):
        if (m := _BO.match(line)) is None:
            continue
        first = seen.setdefault(int(m.group(2)), i)
        if first != i:
            other = _BO.match(rep.lines[first]).group(4)  # type: ignore[union-attr]
            names = [rep.renamed.get(n, n) for n in (other, m.group(4))]
            raise DbcError(f"{rep.source}:{i + 1}: messages {names[0]} (line {first + 1}) and {names[1]} (line {i + 1}) have one frame ID, "
                           f"0x{int(m.group(2)) & ~DBC_EXTENDED_FLAG:X}: a DBC describes one bus, where an ID is one message "
                           "(hint: renumber or remove one of them; CM_, BA_ and VAL_ lines name a message by its ID)")


def repair_step(rep: Repairs, error: str) -> bool:
    """Apply the repair cantools' `error` calls for; False when there is none."""
    if (m := _STANDARD_TOO_BIG.search(error)) is not None:
        return _extend_id(rep, int(m.group(1), 16), m.group(2))
    if (m := _EXTENDED_TOO_BIG.search(error)) is not None:
        return _drop_message(rep, int(m.group(1), 16) | DBC_EXTENDED_FLAG, m.group(2))
    if _UNUSED_VAL.search(error):
        return _drop_unused_vals(rep)
    if (m := _SYNTAX.search(error)) is not None:
        return _repair_syntax(rep, int(m.group(1)) - 1, int(m.group(2)) - 1)
    return False


def _extend_id(rep: Repairs, frame_id: int, name: str) -> bool:
    if frame_id > MAX_EXTENDED_ID:
        return _drop_message(rep, frame_id, name)
    for i, line in enumerate(rep.lines):
        m = _BO.match(line)
        if m and int(m.group(2)) == frame_id and m.group(4) == name:
            rep.lines[i] = f"{m.group(1)}{frame_id | DBC_EXTENDED_FLAG}{line[m.end(2):]}"
            rep.warn(i, f"ID 0x{frame_id:X} of {name} is above 0x7FF but has no extended flag: taken as 29-bit")
            # The message's other statements name it by the ID as written: with the BO_ line alone
            # rewritten, its comments, attributes (cycle time), value labels and float types were lost.
            ref = _references(frame_id)
            for k, other in enumerate(rep.lines):
                if (r := ref.match(other)) is not None:
                    rep.lines[k] = f"{other[:r.start('id')]}{frame_id | DBC_EXTENDED_FLAG}{other[r.end('id'):]}"
            return True
    return False


def _references(dbc_id: int) -> re.Pattern[str]:
    """The statements after the BO_ blocks that name message `dbc_id` (as written) by its ID."""
    return re.compile(rf"^\s*(?:CM_\s+(?:BO_|SG_)|BA_\s+\"\w+\"\s+(?:BO_|SG_)|VAL_|SIG_VALTYPE_|SG_MUL_VAL_|BO_TX_BU_)\s+(?P<id>{dbc_id})\s")


def _drop_message(rep: Repairs, dbc_id: int, name: str) -> bool:
    for i, line in enumerate(rep.lines):
        m = _BO.match(line)
        if m and int(m.group(2)) in (dbc_id, dbc_id & ~DBC_EXTENDED_FLAG) and m.group(4) == name:
            dbc_id = int(m.group(2))
            written = f"{dbc_id} (0x{dbc_id:X})" if dbc_id > MAX_DBC_ID else f"0x{dbc_id & ~DBC_EXTENDED_FLAG:X}"
            rep.warn(i, f"ID {written} of {name} does not fit 29 bits: message left out")
            rep.lines[i] = ""
            j = i + 1
            while j < len(rep.lines) and _SG.match(rep.lines[j]):
                rep.lines[j] = ""
                j += 1
            ref = _references(dbc_id)
            for k, other in enumerate(rep.lines):
                if ref.match(other):
                    _drop_statement(rep, k, "", warn=False)
            return True
    return False


def signal_names(lines: list[str]) -> dict[int, set[str]]:
    """BO_ ID as written → the names of its SG_ lines."""
    out: dict[int, set[str]] = {}
    current = None
    for line in lines:
        if (m := _BO.match(line)) is not None:
            current = out.setdefault(int(m.group(2)), set())
        elif current is not None and (s := _SG.match(line)) is not None:
            current.add(s.group(1))
    return out


def _drop_unused_vals(rep: Repairs) -> bool:
    names = signal_names(rep.lines)
    dropped = False
    for i, line in enumerate(rep.lines):
        m = _VAL.match(line)
        if m and m.group(2) not in names.get(int(m.group(1)), set()):
            rep.warn(i, f"VAL_ for signal {m.group(2)} of message {m.group(1)}, which has no such signal: dropped")
            rep.lines[i] = ""
            dropped = True
    return dropped


def _repair_syntax(rep: Repairs, index: int, column: int) -> bool:
    if not 0 <= index < len(rep.lines):
        return False
    line = rep.lines[index]
    if _DOT_NUMBER.search(line) and re.match(r"\s*SG_", line):
        rep.lines[index] = _DOT_NUMBER.sub(r"0.\1", line)
        rep.warn(index, "number written without a leading 0 (e.g. '.25'): read as 0.25")
        return True
    token = re.match(r"\d\w*", line[column:]) if 0 <= column < len(line) else None
    if token is not None and not token.group(0).isdigit():  # a name where the grammar wants one: `0_COUNTER`
        return _rename_digit_name(rep, index, token.group(0))
    if (m := _CM_BARE.match(line)) is not None:
        rep.lines[index] = f"{m.group(1)}BO_ {m.group(2)}{line[m.end(2):]}"
        rep.warn(index, f"CM_ without an object type before ID {m.group(2)}: taken as the comment of message {m.group(2)}")
        return True
    if _CM_SG_NO_NAME.match(line):
        return _drop_statement(rep, index, "CM_ SG_ without a signal name: dropped")
    return _close_statement(rep, index if column > 0 else _previous_statement(rep.lines, index))


def _rename_digit_name(rep: Repairs, index: int, name: str) -> bool:
    placeholder = PLACEHOLDER + name
    pattern = re.compile(rf"(?<![\w]){re.escape(name)}(?![\w])")
    for i, line in enumerate(rep.lines):
        parts = line.split('"')  # a comment's or attribute's text (odd parts) is not a name
        rep.lines[i] = '"'.join(pattern.sub(placeholder, part) if k % 2 == 0 else part for k, part in enumerate(parts))
    rep.renamed[placeholder] = name
    rep.warn(index, f"name {name!r} starts with a digit: kept as the DBC's name, with an identifier of its own in the spec")
    return True


def _previous_statement(lines: list[str], index: int) -> int:
    i = index - 1
    while i >= 0 and not lines[i].strip():
        i -= 1
    return i


def _close_statement(rep: Repairs, index: int) -> bool:
    """A statement whose closing `;` is missing (cantools then fails on the next line)."""
    start = index
    while start >= 0 and not _STATEMENT.match(rep.lines[start]):
        start -= 1
    if start < 0 or index < 0 or rep.lines[index].rstrip().endswith(";"):
        return False
    if rep.lines[index].rstrip().count('"') % 2 == 1 and start == index:
        return False  # an unclosed quote: no sensible reading
    rep.lines[index] = rep.lines[index].rstrip() + ";"
    rep.warn(start, f"{rep.lines[start].split()[0]} without its closing ';': closed at the end of its line")
    return True


def _drop_statement(rep: Repairs, index: int, text: str, warn: bool = True) -> bool:
    end = index
    while end < len(rep.lines) and not rep.lines[end].rstrip().endswith(";"):
        end += 1
    for i in range(index, min(end + 1, len(rep.lines))):
        rep.lines[i] = ""
    if warn:
        rep.warn(index, text)
    return True
