"""Stage 2 — the intermediate representation: frozen dataclasses (model), built in one place
(build) from a validated spec, with the bit layout (bits), J1939 fields (j1939), fingerprints
and the encoding rules every language shares (encoding). Targets read it; they never recompute it.

`from canspec import ir` gives the model's classes (`ir.Spec`, `ir.Message`, ...): they are public API (a
compiled spec is made of them); the modules of ir/ that compute them are internal."""

from canspec.ir.json_model import JsonEnumValue, JsonField, JsonMessage, JsonParty, JsonProtocol
from canspec.ir.labels import Label, SpecialValue, ValueEntry, ValueTable
from canspec.ir.model import (
    EXACT_LIMIT,
    EXACT_LIMIT_TEXT,
    TIE_EPSILON,
    TIE_EPSILON_TEXT,
    Checksum,
    Counter,
    J1939Id,
    Message,
    MultiFrame,
    Segment,
    Signal,
    runtime_quotient,
    to_physical,
)
from canspec.ir.mux import MuxCondition, MuxGroup
from canspec.ir.protocol_model import (
    FAULT_TIMEOUT_ENTRY,
    FAULT_XOR_ERROR_SUFFIX,
    MONITOR_COUNTER_TOLERANCE,
    MONITOR_TIMEOUT_CYCLES,
    MONITOR_VALID_AFTER,
    Bus,
    CanProtocol,
    FaultTable,
    Node,
)
from canspec.ir.spec_model import ChangeItem, Changelog, ChangeVersion, Spec

__all__ = [
    "EXACT_LIMIT",
    "EXACT_LIMIT_TEXT",
    "FAULT_TIMEOUT_ENTRY",
    "FAULT_XOR_ERROR_SUFFIX",
    "MONITOR_COUNTER_TOLERANCE",
    "MONITOR_TIMEOUT_CYCLES",
    "MONITOR_VALID_AFTER",
    "TIE_EPSILON",
    "TIE_EPSILON_TEXT",
    "Bus",
    "CanProtocol",
    "ChangeItem",
    "ChangeVersion",
    "Changelog",
    "Checksum",
    "Counter",
    "FaultTable",
    "J1939Id",
    "JsonEnumValue",
    "JsonField",
    "JsonMessage",
    "JsonParty",
    "JsonProtocol",
    "Label",
    "Message",
    "MultiFrame",
    "MuxCondition",
    "MuxGroup",
    "Node",
    "Segment",
    "Signal",
    "Spec",
    "SpecialValue",
    "ValueEntry",
    "ValueTable",
    "runtime_quotient",
    "to_physical",
]
