"""What the Rust target cannot express, refused by `canspec check` (Target.check): spec names
that meet as Rust names, a value table no Rust integer type can hold, and multi-frame text
over more frames than its reassembler tracks or whose frame index, payload or key fields are
multiplexed (the reassembler reads them from every frame)."""

from __future__ import annotations

from collections.abc import Iterator

from canspec import ir
from canspec.spec.problems import Problem, error
from canspec.targets.rust import naming, values
from canspec.targets.rust.encode import has_range_consts
from canspec.targets.rust.text import MAX_TEXT_FRAMES


def problems(spec: ir.Spec) -> Iterator[Problem]:
    if spec.can is None:
        return
    users = values.enum_users(spec.can)
    yield from values.problems(users)
    yield from naming.problems(spec.can, users, has_range_consts)
    for msg in spec.can.messages:
        if msg.multiframe and msg.multiframe.frames > MAX_TEXT_FRAMES:
            yield error(f"multi-frame text of {msg.name!r} takes {msg.multiframe.frames} frames; the Rust reassembler tracks at most {MAX_TEXT_FRAMES}",
                        msg.loc, f"carry the text in at most {MAX_TEXT_FRAMES} frames (longer payloads need fewer)", "rust-text-frames")
        for name in msg.text_fields_in_pages:
            yield error(f"multi-frame text of {msg.name!r} reads {name!r}, which only some pages hold; the Rust reassembler reads it from every frame",
                        msg.signal(name).loc or msg.loc, "take the text's index, payload and keys from fields in every frame", "rust-text-mux")
