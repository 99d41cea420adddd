"""Multiplexed messages in the Rust crate: when a field is present, as a condition over its
multiplexers' raw values (Message.mux_chain), on the message type (the frame's bits) and on its
values struct (the physical values; a multiplexer is an unsigned unscaled integer or an enum).

The message type holds one frame, so fields of different pages may share bits: it keeps only the
present fields' bits, its getters of a multiplexed field return an `Option`, and its multiplexers
and multiplexed fields are set only through `new`/`from_raw`/`from_values`, which encode the
present fields and ignore the others. The values struct is flat (every field of every page).
"""

from __future__ import annotations

from dataclasses import dataclass

from canspec import ir
from canspec.ir.mux import Ranges
from canspec.render.literals import RUST
from canspec.targets.rust.naming import field_names


@dataclass(frozen=True)
class RustMuxField:
    """A field of a multiplexed message (every field of it, not only the multiplexed ones)."""

    depth: int  # multiplexers on its chain: `new` sets a multiplexer before the fields it selects
    frame_cond: str  # Rust bool on `self` (the message type): the field is present; "" when in every frame
    values_cond: str  # the same on `self` (its values struct)


def _matches(expr: str, ranges: Ranges) -> str:
    if len(ranges) == 1 and ranges[0][0] == ranges[0][1]:
        return f"{expr} == {RUST.integer(ranges[0][0])}"
    patterns = " | ".join(RUST.integer(lo) if lo == hi else f"{RUST.integer(lo)}..={RUST.integer(hi)}" for lo, hi in ranges)
    return f"matches!({expr}, {patterns})"


def mux_field(msg: ir.Message, sig: ir.Signal) -> RustMuxField | None:
    """None for a message without multiplexing."""
    if not msg.is_multiplexed:
        return None
    chain = msg.mux_chain(sig)
    frame, values = [], []
    for cond in chain:
        by = msg.signal(cond.by)
        names = field_names(by)
        frame.append(_matches(f"self.{names.load}()", cond.ranges))
        values.append(_matches(f"self.{names.field}.wire()" if by.decodes_to_enum else f"self.{names.field}", cond.ranges))
    return RustMuxField(len(chain), " && ".join(frame), " && ".join(values))
