"""python-can integration (needs `pip install python-can`): messages to and from `can.Message`,
receiving within a total deadline, an iterator that reports the frames it skips, and feeding
python-can frames to the receive monitor. A frame belongs to a message when both its ID and its ID
format (29-bit or 11-bit) match.

    for item in messages(bus, timeout=10.0):
        if isinstance(item, Skipped):
            print("skipped", item.reason, item.frame)
        else:
            print(item)
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from enum import Enum

import can

from .errors import ChecksumError, DecodeError, FrameLengthError, UnknownFrameError
from .messages import BY_ID, Message
from .monitor import FrameEvent, Monitor

__all__ = ["Skip", "Skipped", "decode_frame", "feed", "from_can_message", "messages", "receive", "send", "to_can_message"]

CLASSIC_MAX_DLC = 8
_FD_BUS = any(cls.IS_FD for cls in BY_ID.values())  # whether any message of this protocol is a CAN FD frame


class Skip(str, Enum):
    """Why a frame carries no message of this protocol."""

    ERROR_FRAME = "error_frame"
    REMOTE_FRAME = "remote_frame"
    FD_FRAME = "fd_frame"  # a frame format other than the message's (CAN FD for a classic message, or classic for an FD one)
    UNKNOWN_ID = "unknown_id"  # no message has this ID in this ID format
    LENGTH = "length"  # a message's ID with a different number of data bytes than its DLC
    CHECKSUM = "checksum"


@dataclass(frozen=True)
class Skipped:
    """A frame that was not decoded: why, the frame, and the decode error where there is one."""

    reason: Skip
    frame: can.Message
    error: DecodeError | None = None


def to_can_message(message: Message, *, channel: str | int | None = None) -> can.Message:
    """A data frame carrying the encoded message, with the message's ID format, DLC and frame format
    (classic, or CAN FD with its bit-rate switch)."""
    return can.Message(
        arbitration_id=message.FRAME_ID,
        is_extended_id=message.IS_EXTENDED,
        is_remote_frame=False,
        is_fd=message.IS_FD,
        bitrate_switch=message.BRS,
        data=message.encode(),
        channel=channel,
        check=True,
    )


def decode_frame(frame: can.Message, *, verify_checksum: bool = True) -> Message | Skipped:
    """The message in a python-can frame, or why there is none; never raises."""
    if frame.is_error_frame:
        return Skipped(Skip.ERROR_FRAME, frame)
    if frame.is_remote_frame:
        return Skipped(Skip.REMOTE_FRAME, frame)
    fd = frame.is_fd or len(frame.data) > CLASSIC_MAX_DLC
    cls = BY_ID.get(frame.arbitration_id)
    if cls is None or frame.is_extended_id != cls.IS_EXTENDED:
        if fd and not _FD_BUS:  # a classic protocol: an FD frame is none of its messages
            return Skipped(Skip.FD_FRAME, frame)
        return Skipped(Skip.UNKNOWN_ID, frame, UnknownFrameError(frame.arbitration_id, frame.is_extended_id))
    if fd != cls.IS_FD:
        return Skipped(Skip.FD_FRAME, frame)
    try:
        return cls.decode(frame.data, verify_checksum=verify_checksum)
    except FrameLengthError as exc:
        return Skipped(Skip.LENGTH, frame, exc)
    except ChecksumError as exc:
        return Skipped(Skip.CHECKSUM, frame, exc)


def from_can_message(frame: can.Message, *, verify_checksum: bool = True) -> Message:
    """The message in a python-can frame: DecodeError (UnknownFrameError, FrameLengthError,
    ChecksumError) when it carries none."""
    item = decode_frame(frame, verify_checksum=verify_checksum)
    if isinstance(item, Skipped):
        raise item.error if item.error is not None else DecodeError(f"{item.reason.value.replace('_', ' ')}: {frame}")
    return item


def send(bus: can.BusABC, message: Message, timeout: float | None = None) -> None:
    """Encode and send a message."""
    bus.send(to_can_message(message), timeout=timeout)


def messages(bus: can.BusABC, timeout: float | None = None) -> Iterator[Message | Skipped]:
    """Every frame from the bus, as its decoded message or as Skipped (never raises for a frame),
    until `timeout` seconds have passed in all (None: for ever)."""
    deadline = None if timeout is None else time.monotonic() + timeout
    while True:
        remaining = None if deadline is None else max(0.0, deadline - time.monotonic())
        frame = bus.recv(remaining)
        if frame is None:
            return
        yield decode_frame(frame)
        if deadline is not None and time.monotonic() >= deadline:
            return


def receive(bus: can.BusABC, timeout: float | None = None, *, on_skip: Callable[[Skipped], None] | None = None) -> Message | None:
    """The next message of this protocol, decoded; None when `timeout` seconds pass in all first
    (however many other frames arrive). Frames that carry none are passed to `on_skip`."""
    for item in messages(bus, timeout):
        if not isinstance(item, Skipped):
            return item
        if on_skip is not None:
            on_skip(item)
    return None


def feed(monitor: Monitor, frame: can.Message) -> FrameEvent | None:
    """Give a python-can frame to the receive monitor at its timestamp (ms); None for an error or
    remote frame, which carries no data to judge."""
    if frame.is_error_frame or frame.is_remote_frame:
        return None
    return monitor.feed(round(frame.timestamp * 1000), frame.arbitration_id, frame.is_extended_id, frame.data)
