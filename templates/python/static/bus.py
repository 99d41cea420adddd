"""python-can integration (needs `pip install python-can`): messages to and from `can.Message`.
A frame belongs to a message when both its ID and its ID format (29-bit or 11-bit) match."""

from __future__ import annotations

import can

from .errors import UnknownFrameError
from .messages import BY_ID, Message

__all__ = ["from_can_message", "receive", "send", "to_can_message"]


def to_can_message(message: Message, *, channel: str | int | None = None) -> can.Message:
    """A python-can frame carrying the encoded message, with the message's ID format."""
    return can.Message(arbitration_id=message.FRAME_ID, is_extended_id=message.IS_EXTENDED, data=message.encode(), channel=channel)


def from_can_message(frame: can.Message, *, verify_checksum: bool = True) -> Message:
    """The message in a python-can frame (UnknownFrameError, FrameLengthError, ChecksumError)."""
    cls = BY_ID.get(frame.arbitration_id)
    if cls is None or frame.is_extended_id != cls.IS_EXTENDED:
        raise UnknownFrameError(frame.arbitration_id, frame.is_extended_id)
    return cls.decode(frame.data, verify_checksum=verify_checksum)


def send(bus: can.BusABC, message: Message, timeout: float | None = None) -> None:
    """Encode and send a message."""
    bus.send(to_can_message(message), timeout=timeout)


def receive(bus: can.BusABC, timeout: float | None = None) -> Message | None:
    """The next frame of this protocol on the bus, decoded; None on timeout. Other frames are skipped."""
    while True:
        frame = bus.recv(timeout)
        if frame is None:
            return None
        cls = BY_ID.get(frame.arbitration_id)
        if cls is not None and frame.is_extended_id == cls.IS_EXTENDED:
            return cls.decode(frame.data)
