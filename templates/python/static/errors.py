"""Errors raised by this package: every one names the message, and where it applies the
signal, the value and what was expected."""

from __future__ import annotations


class Error(Exception):
    """Base class of every error this package raises."""


class DecodeError(Error, ValueError):
    """A frame could not be decoded."""


class UnknownFrameError(DecodeError):
    """The frame ID belongs to no message of the protocol (or a 29-bit ID to an 11-bit message, or
    the other way round: `is_extended` is the frame's flag when it is known)."""

    def __init__(self, frame_id: int, is_extended: bool | None = None) -> None:
        digits = 8 if is_extended or frame_id > 0x7FF else 3
        kind = "" if is_extended is None else f" ({'29' if is_extended else '11'}-bit)"
        super().__init__(f"unknown frame ID 0x{frame_id:0{digits}X}{kind}: no message of {__package__} has this ID")
        self.frame_id = frame_id
        self.is_extended = is_extended


class FrameLengthError(DecodeError):
    """The frame has a different number of data bytes than the message's DLC."""

    def __init__(self, message: str, frame_id: int, expected: int, actual: int, *, id_text: str) -> None:
        super().__init__(f"{message} ({id_text}): frame has {actual} data bytes, expected {expected}")
        self.message = message
        self.frame_id = frame_id
        self.id_text = id_text
        self.expected = expected
        self.actual = actual


class ChecksumError(DecodeError):
    """The frame's checksum byte does not match the checksum of its other bytes."""

    def __init__(self, message: str, frame_id: int, expected: int, actual: int, *, id_text: str) -> None:
        super().__init__(f"{message} ({id_text}): checksum mismatch: frame carries 0x{actual:02X}, bytes give 0x{expected:02X}")
        self.message = message
        self.frame_id = frame_id
        self.id_text = id_text
        self.expected = expected
        self.actual = actual


class TextError(DecodeError):
    """A multi-frame text (e.g. the VIN) could not be reassembled."""

    def __init__(self, message: str, frame_id: int, problem: str, *, id_text: str) -> None:
        super().__init__(f"{message} ({id_text}): {problem}")
        self.message = message
        self.frame_id = frame_id
        self.id_text = id_text


class TextIndexError(TextError):
    """A frame's index is outside the text's frames: the frame is refused."""


class InconsistentTextError(TextError):
    """A frame contradicts the frames taken (another sender, or another text at the same index):
    they are dropped and reassembly restarts from this frame."""


class InvalidTextError(TextError):
    """Every frame has arrived but the bytes are not a text: a character that is not printable
    ASCII, or text after the padding."""


class EncodeError(Error, ValueError):
    """A message could not be encoded."""


class RangeError(EncodeError):
    """A physical value is outside the signal's allowed range (nothing is clamped or wrapped)."""

    def __init__(self, message: str, signal: str, value: object, allowed: str, raw: tuple[int, int, int] | None = None) -> None:
        # raw: (the raw value it rounds to, the range's first and last raw value), for a value whose
        # double lies in the range but whose raw does not (the range's end is not a raw step)
        why = f" (it is raw {raw[0]}, beyond the range's raw values {raw[1]}..{raw[2]})" if raw is not None else ""
        super().__init__(f"{message}.{signal}: {value!r} is outside the allowed range {allowed}{why}")
        self.message = message
        self.signal = signal
        self.value = value
        self.allowed = allowed


class RawRangeError(EncodeError):
    """A raw value does not fit the signal's bits."""

    def __init__(self, message: str, signal: str, value: object, minimum: int, maximum: int) -> None:
        super().__init__(f"{message}.{signal}: raw value {value!r} does not fit the field (an integer in {minimum}..{maximum})")
        self.message = message
        self.signal = signal
        self.value = value
        self.minimum = minimum
        self.maximum = maximum


class UnknownSignalError(EncodeError):
    """A raw mapping names signals the message does not have."""

    def __init__(self, message: str, names: list[str]) -> None:
        super().__init__(f"{message}: no signal named {', '.join(repr(n) for n in names)}")
        self.message = message
        self.names = names
