"""C identifiers: every name the headers declare, derived once from the spec's names.

Every global C name is the protocol prefix followed by the words of spec names and a fixed
suffix (`kaiwo_gateway_eps_state_pack`, `KAIWO_GATEWAY_EPS_STATE_FRAME_ID`). A message whose
names would meet the runtime's own (a message `status`: `<prefix>_status_t`) is named
`<message>_msg` instead, and a value table whose names would meet the runtime's or a message's
`<table>_values`. Other spec names can still meet (a message `a` with a signal `b_c` and a
message `a_b` with a signal `c`): `declared()` lists every name with the spec element it comes
from, so the target's `check` refuses such a spec at the element's line instead of the
compiler failing on the header. A test holds the lists below to what the generated headers
declare.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from functools import lru_cache

from canspec import ir
from canspec.ir.names import c_ident, snake, upper_snake
from canspec.spec.problems import Loc

# (template, file suffix after the prefix): one header per concern, each compiles alone.
HEADERS = (
    ("c/common.h.j2", "_common.h"),
    ("c/enums.h.j2", "_enums.h"),
    ("c/messages.h.j2", "_messages.h"),
    ("c/dispatch.h.j2", "_dispatch.h"),
    ("c/text.h.j2", "_text.h"),
    ("c/monitor.h.j2", "_monitor.h"),
    ("c/umbrella.h.j2", ".h"),
)
# The names the runtime declares whatever the spec holds (common.h, messages.h, dispatch.h, monitor.h).
RUNTIME_FUNCTIONS = (
    "status_t", "round_abs", "round_half_away", "mul_hi32", "div_round_mul", "div_round_mulhi", "div_round_mulrem",
    "mul_wide", "mul64_u", "mul64", "mul_hi64", "shr64", "div_round_u64_mulhi", "div_round_u64_mulrem", "div_round64_mulhi", "div_round64_mulrem",
    "phys_t", "phys_q", "phys_round", "phys_encode", "copy_bits", "bits_differ",
    *(f"zero_{n}" for n in (12, 16, 20, 24, 32, 48, 64)),  # messages.h: a CAN FD frame's zeroing (codec.zero_fill)
    *(f"phys_encode_{s}{bits}" for s in "ui" for bits in (8, 16, 32, 64)),
    "j1939_id_t", "j1939_decompose", "j1939_compose",
    "msg_t", "msg_info_t", "msg_info", "lookup_id", "lookup_id_any_priority", "lookup_pgn", "any_t", "unpack_any", "pack_any", "any_counter",
    "rx_state_t", "monitor_t", "monitor_init", "monitor_expect", "monitor_on_frame", "monitor_check", "monitor_timed_out", "monitor_state",
    "monitor_count_up", "monitor_invalidate", "monitor_expire", "monitor_counter_fault",  # the monitor's helpers
)
RUNTIME_MACROS = (
    "SPEC_NAME", "SPEC_VERSION", "SPEC_SHA256", "BITRATE", "DATA_BITRATE", "STRATEGY", "PHYS_NOINLINE",
    "OK", "ERR_LENGTH", "ERR_CHECKSUM", "ERR_RANGE", "ERR_UNKNOWN_ID", "ERR_INDEX", "ERR_INCOMPLETE", "ERR_INCONSISTENT",
    "J1939_PDU2_MIN_PF", "J1939_GLOBAL_ADDRESS", "J1939_ID_MASK", "J1939_PRIORITY_MASK", "MSG_NONE", "MSG_COUNT",
    "MONITOR_TIMEOUT_CYCLES", "MONITOR_COUNTER_TOLERANCE", "MONITOR_VALID_AFTER", "RX_NO_DATA", "RX_INIT", "RX_VALID", "RX_INVALID",
    "RX_UNKNOWN_ID", "RX_LENGTH", "RX_CHECKSUM", "RX_COUNTER_JUMP", "RX_COUNTER_REPEAT", "RX_TIMEOUT", "RX_RECOVERED",
    "H", "COMMON_H", "ENUMS_H", "MESSAGES_H", "DISPATCH_H", "TEXT_H", "MONITOR_H",
)
# Per message (after <prefix>_<message>_ / <PREFIX>_<MESSAGE>_), per signal, per multi-frame text.
MESSAGE_FUNCTIONS = ("t", "pack", "unpack", "init", "counter_next")
MESSAGE_MACROS = ("FRAME_ID", "IS_EXTENDED", "DLC", "IS_FD", "BRS", "CYCLE_MS", "PRIORITY", "PGN", "SA", "DA", "FINGERPRINT")
SIGNAL_FUNCTIONS = ("decode", "encode", "decode_fixed", "encode_fixed", "phys")  # `phys`: its encoder's descriptor
SIGNAL_MACROS = ("FACTOR", "OFFSET", "MIN", "MAX", "FIXED_SCALE")
TEXT_FUNCTIONS = ("split", "rx_t", "rx_init", "rx_complete", "rx_feed", "rx_get")
TEXT_MACROS = ("LENGTH", "FRAMES", "BYTES_PER_FRAME", "PADDING")
# A fault-code table (ir.FaultTable: a value table with a `message_timeout` entry) gets a monitor
# function `<prefix>_monitor_<table>`.


# Spec names recur in every name derived from them: convert each once (a 30000-signal spec
# derives about a million names).
_snake = lru_cache(maxsize=None)(snake)
_upper_snake = lru_cache(maxsize=None)(upper_snake)

MESSAGE_SUFFIX = "msg"  # appended to a message's C name that meets the runtime's
TABLE_SUFFIX = "values"  # appended to a value table's that meets the runtime's or a message's

Origin = tuple[str, Loc | None]  # what declares a name, and where the spec says so


@dataclass(frozen=True)
class CNames:
    """How a protocol's spec names become C names."""

    prefix: str  # lower_snake: functions and types
    macro: str  # UPPER_SNAKE: macros and enum constants
    bases: Mapping[tuple[str, str], str] = field(default_factory=dict)  # ("message" | "table", name) → C base

    @classmethod
    def of(cls, can: ir.CanProtocol) -> CNames:
        return named(can)[0]

    @classmethod
    def plain(cls, can: ir.CanProtocol) -> CNames:
        """The protocol's prefixes alone (what every C name starts with), no name checked."""
        return cls(snake(can.name), upper_snake(can.name))

    def fn(self, *words: str) -> str:
        return "_".join([self.prefix, *map(_snake, words)])

    def const(self, *words: str) -> str:
        return "_".join([self.macro, *map(_upper_snake, words)])

    def message(self, name: str) -> str:
        """The words a message's C names start with."""
        return self.bases.get(("message", name), name)

    def table(self, name: str) -> str:
        return self.bases.get(("table", name), name)

    def special(self, base: str, signal: str, name: str) -> str:
        """A special value's constant; `<name>_value` where the name is one of the signal's own
        macros (a special value `max` beside `<SIGNAL>_MAX`)."""
        words = (base, signal, name, "value") if _upper_snake(name) in SIGNAL_MACROS else (base, signal, name)
        return self.const(*words)

    @staticmethod
    def member(name: str) -> str:
        """A struct field or union member: the bare name, a keyword escaped."""
        return c_ident(snake(name))

    def runtime(self) -> list[tuple[str, Origin]]:
        origin: Origin = ("the C target's runtime", None)
        return [(self.fn(w), origin) for w in RUNTIME_FUNCTIONS] + [(self.const(w), origin) for w in RUNTIME_MACROS]


def named(can: ir.CanProtocol) -> tuple[CNames, list[tuple[str, Origin]]]:
    """The protocol's C names, and every global name the headers declare (some only where the
    spec uses the feature) with the element it comes from. The last protocol's are kept: the
    check asks twice and the model once (0.1 s each at 1,000 messages); the IR is immutable."""
    if _NAMED and _NAMED[0][0] is can:
        return _NAMED[0][1]
    result = _named(can)
    _NAMED[:] = [(can, result)]
    return result


_NAMED: list[tuple[ir.CanProtocol, tuple[CNames, list[tuple[str, Origin]]]]] = []


def _named(can: ir.CanProtocol) -> tuple[CNames, list[tuple[str, Origin]]]:
    plain = CNames.plain(can)
    runtime = plain.runtime()
    taken = {name for name, _ in runtime}
    bases: dict[tuple[str, str], str] = {}
    for msg in can.messages:
        meets = _may_meet(plain, msg.c_name, taken) and any(name in taken for name, _ in _message_names(plain, msg, msg.c_name))
        bases["message", msg.name] = f"{msg.c_name}_{MESSAGE_SUFFIX}" if meets else msg.c_name
    names = CNames(plain.prefix, plain.macro, bases)
    found = runtime + [item for msg in can.messages for item in _message_names(names, msg, names.message(msg.name))]
    taken |= {name for name, _ in found}
    for table in can.value_tables:
        meets = any(name in taken for name, _ in _table_names(plain, table, table.name))
        bases["table", table.name] = f"{table.name}_{TABLE_SUFFIX}" if meets else table.name
    return names, found + [item for table in can.value_tables for item in _table_names(names, table, names.table(table.name))]


def declared(can: ir.CanProtocol) -> list[tuple[str, Origin]]:
    return named(can)[1]


def header_names(can: ir.CanProtocol) -> list[str]:
    return [f"{snake(can.name)}{suffix}" for _, suffix in HEADERS]


def _may_meet(n: CNames, base: str, taken: set[str]) -> bool:
    """Whether a message's names can meet these (runtime) names: every one of them starts with
    its function or macro stem, or is its enumerator."""
    stems = (n.fn(base) + "_", n.const(base) + "_")
    return n.const("msg", base) in taken or any(name.startswith(stems) for name in taken)


def _table_names(n: CNames, table: ir.ValueTable, base: str) -> Iterator[tuple[str, Origin]]:
    origin: Origin = (f"value table {table.name!r}", table.loc)
    yield n.fn(base, "t"), origin
    yield n.fn(base, "name"), origin
    if any(e.name == ir.FAULT_TIMEOUT_ENTRY for e in table.entries):
        yield n.fn("monitor", base), origin
    yield from ((n.const(base, e.name), (f"value {e.name!r} of table {table.name!r}", e.loc)) for e in table.entries)


def _message_names(n: CNames, msg: ir.Message, base: str) -> Iterator[tuple[str, Origin]]:
    """(The suffixes are snake / UPPER words already: they are joined as they are.)"""
    origin: Origin = (f"message {msg.name!r}", msg.loc)
    fn, const = n.fn(base), n.const(base)
    yield n.const("msg", base), origin
    yield from ((f"{fn}_{w}", origin) for w in MESSAGE_FUNCTIONS)
    yield from ((f"{const}_{w}", origin) for w in MESSAGE_MACROS)
    if msg.multiframe is not None:
        yield from ((f"{fn}_text_{w}", origin) for w in TEXT_FUNCTIONS)
        yield from ((f"{const}_TEXT_{w}", origin) for w in TEXT_MACROS)
    for sig in msg.data_signals:
        where: Origin = (f"signal {sig.name!r} of message {msg.name!r}", sig.loc)
        sig_fn, sig_const = f"{fn}_{_snake(sig.c_name)}", f"{const}_{_upper_snake(sig.c_name)}"
        if sig.role == "data":  # counters and checksums have no physical functions
            yield from ((f"{sig_fn}_{w}", where) for w in SIGNAL_FUNCTIONS)
            yield from ((f"{sig_const}_{w}", where) for w in SIGNAL_MACROS)
        if sig.mux is not None:  # a field some multiplexer selects (targets/c/mux.py)
            yield f"{sig_fn}_is_present", where
        yield from ((n.special(base, sig.c_name, sp.name), (f"special value {sp.name!r} of signal {sig.name!r}", sig.loc)) for sp in sig.specials)


def members(msg: ir.Message) -> Iterator[tuple[str, Origin]]:
    """The message struct's fields, which share one scope."""
    for sig in msg.data_signals:
        yield CNames.member(sig.c_name), (f"signal {sig.name!r} of message {msg.name!r}", sig.loc)
