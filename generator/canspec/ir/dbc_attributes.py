"""A source DBC's own attributes, which canspec keeps without computing anything from them (the
spec's `dbc_attributes`, written by `canspec import`): definitions, defaults and values, written
back by the DBC target as they were. The attributes canspec computes from the spec itself (bit
rates, frame format, cycle time, signal type) are not among them (spec rule `dbc-attribute`)."""

from __future__ import annotations

from dataclasses import dataclass

AttributeValue = int | float | str
Attributes = tuple[tuple[str, AttributeValue], ...]  # (name, value) in the spec's order; an ENUM value by its text

# What the DBC target writes from the spec's own fields; a spec cannot define these again.
COMPUTED = ("BusType", "Baudrate", "BaudrateCANFD", "NmStationAddress", "VFrameFormat", "GenMsgCycleTime", "CANFD_BRS", "SigType",
            "SpecSignalName")
# Written by the DBC target unless the spec defines them itself: what the spec says does not decide them
# (cycle_ms says whether a message is cyclic, not how a source named its send types; a DBC's name and
# protocol type, "GMLAN", are the source's words).
REPLACEABLE = ("GenMsgSendType", "ProtocolType", "DBName")
OBJECTS = {"network": "", "node": "BU_", "message": "BO_", "signal": "SG_"}  # the object's keyword in BA_DEF_ / BA_


@dataclass(frozen=True)
class DbcAttributeDef:
    name: str
    object: str  # "network" | "node" | "message" | "signal"
    type: str  # "INT" | "HEX" | "FLOAT" | "STRING" | "ENUM"
    minimum: int | float | None
    maximum: int | float | None
    values: tuple[str, ...]  # an ENUM's texts, in index order
    default: AttributeValue | None
    value: AttributeValue | None  # a network attribute's value

    @property
    def keyword(self) -> str:
        return OBJECTS[self.object]
