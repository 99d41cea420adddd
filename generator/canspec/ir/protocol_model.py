"""The IR of a CAN protocol as a whole: its bus, its nodes, its messages and its fault codes."""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

from canspec.ir.dbc_attributes import Attributes, DbcAttributeDef
from canspec.ir.labels import ValueTable
from canspec.ir.model import Message
from canspec.spec.problems import Loc

# Receive monitors time a cyclic message out after this many cycle times without a frame,
# accept a counter step of up to 1 + MONITOR_COUNTER_TOLERANCE (frames lost in between) and hold a
# message valid after MONITOR_VALID_AFTER good frames in a row (runtime/monitor.py states the rules).
MONITOR_TIMEOUT_CYCLES = 3
MONITOR_COUNTER_TOLERANCE = 1
MONITOR_VALID_AFTER = 2
# The value-table entries that make a table a receive-fault code table: `message_timeout` (with a
# raw-0 "no fault" entry) and `<layout>_xor_error` for a checksum failure of a message of that layout.
FAULT_TIMEOUT_ENTRY = "message_timeout"
FAULT_XOR_ERROR_SUFFIX = "_xor_error"


@dataclass(frozen=True)
class Node:
    name: str
    label: str
    sa: int | None  # J1939 source address (None on a bus without J1939 addressing)
    zh: str
    desc: str
    aliases: tuple[str, ...]
    loc: Loc | None = field(default=None, compare=False, hash=False)
    dbc_name: str = ""  # the name the DBC writes: the spec's `dbc_name`, else `name`
    dbc_attributes: Attributes = ()  # a source DBC's own attribute values (ir/dbc_attributes.py)


@dataclass(frozen=True)
class Bus:
    bitrate: int
    id_format: str  # "extended" | "standard": the messages' default
    addressing: str  # "j1939" | "none"
    byte_order: str  # the signals' default: "little_endian" | "big_endian"
    data_bitrate: int | None = None  # CAN FD data phase (frames with bit-rate switching)

    @property
    def is_j1939(self) -> bool:
        return self.addressing == "j1939"

    @property
    def kbit(self) -> int | float:
        return self.bitrate // 1000 if self.bitrate % 1000 == 0 else self.bitrate / 1000


@dataclass(frozen=True)
class FaultTable:
    """A value table of receive-fault codes (the shipped spec's unmanned_entry_fault of 0x1813A0B0):
    its entry `message_timeout` is the code for a message timeout, `<layout>_xor_error` the code for
    a checksum failure of the messages of that layout, raw 0 no fault. Receive monitors report in it."""

    table: str
    none: int  # 0
    timeout: int
    checksum: tuple[tuple[str, int], ...]  # (message name, code), messages with a checksum, in document order


@dataclass(frozen=True)
class CanProtocol:
    name: str
    title: str
    title_zh: str
    version: str
    document: str
    bus: Bus
    nodes: tuple[Node, ...]
    messages: tuple[Message, ...]  # in document order
    value_tables: tuple[ValueTable, ...]
    fault_tables: tuple[FaultTable, ...] = ()
    loc: Loc | None = field(default=None, compare=False, hash=False)  # of the protocol's name
    dbc_signal_names: str = "per_message"  # or "unique" (targets/dbc/naming.py)
    dbc_as_imported: bool = False  # the DBC says what the imported source said (protocol.dbc_as_imported)
    dbc_attribute_defs: tuple[DbcAttributeDef, ...] = ()  # a source DBC's own attributes (ir/dbc_attributes.py)

    def message(self, name: str) -> Message:
        return next(m for m in self.messages if m.name == name)

    # What the protocol uses at all: targets leave out the helpers of what it does not. Cached:
    # templates read them per row.
    @cached_property
    def has_standard(self) -> bool:
        return any(not m.is_extended for m in self.messages)

    @cached_property
    def has_counters(self) -> bool:
        return any(m.counter is not None for m in self.messages)

    @cached_property
    def has_checksums(self) -> bool:
        return any(m.checksum is not None for m in self.messages)

    @cached_property
    def has_fd(self) -> bool:
        return any(m.is_fd for m in self.messages)

    @cached_property
    def has_big_endian(self) -> bool:
        return any(m.has_big_endian for m in self.messages)

    @cached_property
    def has_float(self) -> bool:
        return any(m.has_float for m in self.messages)

    @cached_property
    def max_dlc(self) -> int:
        return max((m.dlc for m in self.messages), default=0)

    @cached_property
    def has_multiplexing(self) -> bool:
        return any(m.is_multiplexed for m in self.messages)

    @cached_property
    def has_multiframe(self) -> bool:
        return any(m.multiframe is not None for m in self.messages)

    @cached_property
    def has_cyclic(self) -> bool:
        return any(m.is_cyclic for m in self.messages)

    def by_id(self, frame_id: int) -> Message | None:
        return next((m for m in self.messages if m.frame_id == frame_id), None)
