"""Vector's attributes as the DBC writes them. The enumerations are Vector's J1939 database
template's, value for value and in its order (the index is what a `BA_` line stores), so CANalyzer,
CANoe and CANdb++ show the same names as for a database made from that template."""

from __future__ import annotations

from canspec import ir

# BA_DEF_ SG_ "SigType": what a signal is, for J1939 tools (ASCII text, counters, checksums).
SIG_TYPES = ("Default", "Range", "RangeSigned", "ASCII", "Discrete", "Control", "ReferencePGN", "DTC",
             "StringDelimiter", "StringLength", "StringLengthControl", "MessageCounter", "MessageChecksum")
# BA_DEF_ BO_ "VFrameFormat": how a message goes on the bus; a bus with CAN FD frames gets the values
# up to Vector's FD ones (14, 15), as CANdb++ writes them.
VFRAME_FORMATS = ("StandardCAN", "ExtendedCAN", "reserved", "J1939PG")
VFRAME_FORMATS_FD = VFRAME_FORMATS + ("reserved",) * 10 + ("StandardCAN_FD", "ExtendedCAN_FD")
# SIG_VALTYPE_: 1 for an IEEE float32 signal, 2 for a float64 (0, an integer, is not written).
SIG_VALTYPES = {32: 1, 64: 2}
# BA_DEF_ BO_ "GenMsgSendType", spelt as the J1939 template spells it ("cyclic", "noMsgSendType").
MSG_SEND_TYPES = ("cyclic", "NotUsed", "NotUsed", "NotUsed", "NotUsed", "NotUsed", "NotUsed", "IfActive", "noMsgSendType")
CYCLIC = MSG_SEND_TYPES.index("cyclic")
NOT_CYCLIC = MSG_SEND_TYPES.index("noMsgSendType")  # event-driven: sent on change or on request
# The largest GenMsgCycleTime the template allows (an hour).
MAX_CYCLE_MS = 3_600_000


def sig_type(msg: ir.Message, sig: ir.Signal) -> int:
    if sig.role == "counter":
        return SIG_TYPES.index("MessageCounter")
    if sig.role == "checksum":
        return SIG_TYPES.index("MessageChecksum")
    if msg.multiframe is not None and sig.name == msg.multiframe.payload_signal:
        return SIG_TYPES.index("ASCII")
    if sig.value_table is not None:
        return SIG_TYPES.index("Discrete")
    return SIG_TYPES.index("RangeSigned" if sig.signed else "Range")


def vframe_format(bus: ir.Bus, msg: ir.Message) -> int:
    """A CAN FD frame; a J1939 parameter group on a J1939 bus; else a plain standard or extended frame."""
    if msg.is_fd:
        return VFRAME_FORMATS_FD.index("ExtendedCAN_FD" if msg.is_extended else "StandardCAN_FD")
    if bus.is_j1939:
        return VFRAME_FORMATS.index("J1939PG")
    return VFRAME_FORMATS.index("ExtendedCAN" if msg.is_extended else "StandardCAN")


def send_type(msg: ir.Message) -> int:
    return CYCLIC if msg.is_cyclic else NOT_CYCLIC
