"""Test data every target derives from a multi-frame text message the same way: a sample text that
round-trips, and a second valid value of a key signal (another sender's frames). The Rust crate's
tests and the sequence vectors both use them, so they are computed here once."""

from __future__ import annotations

from canspec.ir.model import Message, MultiFrame


def sample_text(mf: MultiFrame, text: str) -> str:
    """`text` repeated or cut to the text length, without the padding byte: a text that round-trips."""
    chars = "".join(c for c in text if ord(c) != mf.padding) or "A"
    return (chars * (mf.text_length // len(chars) + 1))[: mf.text_length]


def other_key(msg: Message) -> tuple[str, int] | None:
    """A key signal of a multi-frame message and a valid raw value of it besides its base value
    (the nearest to 0 in range): what tells another sender's frames apart."""
    assert msg.multiframe is not None
    for name in msg.multiframe.key_signals:
        sig = msg.signal(name)
        base = min(max(0, sig.raw_min), sig.raw_max)
        other = next((r for r in (base + 1, base - 1) if sig.raw_min <= r <= sig.raw_max), None)
        if other is not None:
            return name, other
    return None
