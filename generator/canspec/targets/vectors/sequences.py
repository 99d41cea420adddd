"""Sequence vectors (`vectors/sequences.json`): timed frame sequences with what the receive monitor
must report after every step, and multi-frame texts fed frame by frame with what reassembly must
give. The expected values come from the reference monitor (runtime/monitor.py, configured by
runtime/supervision.py) and the reference reassembly (reference/textframes.py); the C, Python and
Rust runners replay every step and compare.

Steps: `start` (supervise the listed messages' timeouts from t), `frame` (a frame received at t:
ID, ID format, data), `check` (timeouts at t). Each category is built for up to
MESSAGES_PER_CATEGORY messages of distinct shapes (counter width, checksum, cyclic, DLC) that
have what it needs, so any spec gets what applies to it: a spec without counters gets no
counter sequences, one without multi-frame text no text sequences.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from typing import Any

from canspec import ir
from canspec.ir.fd import FD_LENGTHS, dlc_code
from canspec.ir.ids import MAX_EXTENDED_ID, MAX_STANDARD_ID
from canspec.reference import codec
from canspec.runtime import supervision
from canspec.runtime.monitor import FrameEvent, Monitor

MESSAGES_PER_CATEGORY = 3
EVENT_GAP_MS = 1000  # between frames of an event-driven message
STATS = ("frames", "accepted", "length_errors", "checksum_errors", "counter_repeats", "counter_jumps", "lost_frames", "timeouts")
TICK_WRAP = 1 << 32



def frame(msg: ir.Message, counter: int = 0, **raw: int) -> bytes:
    base = {m.name: m.base_raw for m in msg.multiplexers}  # a multiplexed message: the page its multiplexers' base values select
    values = {s.name: s.base_raw for s in msg.present(base) if s.role != "checksum"}
    if msg.counter is not None:
        values[msg.counter.signal] = counter % msg.counter.modulo
    values.update(raw)
    return codec.pack(msg, values)


def corrupt(msg: ir.Message, data: bytes) -> bytes:
    assert msg.checksum is not None
    out = bytearray(data)
    out[msg.checksum.byte] ^= 0x01
    return bytes(out)


class Sequence:
    """One sequence under construction: a fresh monitor, its steps and their expected results."""

    def __init__(self, can: ir.CanProtocol, category: str, note: str, messages: list[ir.Message], **params: int) -> None:
        self.can, self.messages = can, messages
        self.params = {"counter_tolerance": ir.MONITOR_COUNTER_TOLERANCE, "valid_after": ir.MONITOR_VALID_AFTER, **params}
        self.mon: Monitor = supervision.new_monitor(can, **self.params)
        self.record: dict[str, Any] = {"category": category, "note": note, "messages": [m.name for m in messages], "params": self.params, "steps": []}

    def start(self, t: int) -> None:
        self.mon.start(t, [m.name for m in self.messages])
        self.record["steps"].append({"t": t, "action": "start", "messages": [m.name for m in self.messages]})

    def frame(self, t: int, msg: ir.Message, data: bytes, *, frame_id: int | None = None, extended: bool | None = None) -> FrameEvent:
        fid = msg.frame_id if frame_id is None else frame_id
        ext = msg.is_extended if extended is None else extended
        ev = self.mon.feed(t % TICK_WRAP, fid, ext, data)
        expect = {
            "message": ev.message, "faults": [f.value for f in ev.faults], "accepted": ev.accepted,
            "state": ev.state.value if ev.state is not None else None, "counter_delta": ev.counter_delta, "checksum_ok": ev.checksum_ok,
            "recovered": ev.recovered, "codes": dict(ev.fault_codes),
        }
        self.record["steps"].append({"t": t % TICK_WRAP, "action": "frame", "frame_id": fid, "extended": ext, "data": data.hex().upper(), "expect": expect})
        return ev

    def check(self, t: int) -> None:
        timeouts = [e.message for e in self.mon.check(t % TICK_WRAP)]
        expect = {"timeouts": timeouts, "states": {m.name: self.mon.state(m.name).value for m in self.messages}, "codes": self.mon.fault_codes()}
        self.record["steps"].append({"t": t % TICK_WRAP, "action": "check", "expect": expect})

    def done(self) -> dict[str, Any]:
        stats = {m.name: {k: getattr(self.mon.stats(m.name), k) for k in STATS} for m in self.messages}
        self.record["end"] = {"stats": stats, "unknown_frames": self.mon.unknown_frames}
        return self.record


def _shape(msg: ir.Message) -> tuple[Any, ...]:
    return (msg.counter.length if msg.counter else None, msg.checksum is not None, msg.is_cyclic, msg.dlc)


def pick(can: ir.CanProtocol, want: Callable[[ir.Message], bool]) -> list[ir.Message]:
    """Up to MESSAGES_PER_CATEGORY messages that `want`, of distinct shapes, in document order."""
    out: dict[tuple[Any, ...], ir.Message] = {}
    for m in can.messages:
        if want(m) and _shape(m) not in out and len(out) < MESSAGES_PER_CATEGORY:
            out[_shape(m)] = m
    return list(out.values())


def period(msg: ir.Message) -> int:
    return msg.cycle_ms if msg.cycle_ms is not None else EVENT_GAP_MS


def _run(seq: Sequence, msg: ir.Message, t: int, counters: list[int]) -> int:
    """Frames with these counters, one period apart from t on; the time of the last."""
    for i, c in enumerate(counters):
        seq.frame(t + i * period(msg), msg, frame(msg, c))
    return t + (len(counters) - 1) * period(msg)


def in_order(can: ir.CanProtocol) -> Iterator[dict[str, Any]]:
    for msg in pick(can, lambda m: True):
        seq = Sequence(can, "in_order", f"{msg.name}: frames every period, counter +1", [msg])
        seq.start(0)
        last = _run(seq, msg, period(msg), list(range(5)))
        seq.check(last + period(msg))
        yield seq.done()


def counters(can: ir.CanProtocol) -> Iterator[dict[str, Any]]:
    """Wrap, repeats, jumps within and beyond the tolerance, a counter going back (stale)."""
    for msg in pick(can, lambda m: m.counter is not None):
        assert msg.counter is not None
        mod, p = msg.counter.modulo, period(msg)
        cases = [
            ("counter_wrap", "the counter wraps modulo 2^length", [mod - 3, mod - 2, mod - 1, 0, 1, 2]),
            ("repeated", "a frame's counter repeats, then the sequence goes on", [0, 1, 1, 2, 3, 4]),
            ("counter_jump", "a step of 2 (one frame lost: within the default tolerance)", [0, 1, 3, 4, 5]),
            ("counter_jump", "a step of 3 (beyond the default tolerance), then recovery", [0, 1, 4, 5, 6, 7]),
            ("stale", "a counter that goes back one step (a stale frame), then recovery", [0, 1, 2, 1, 2, 3, 4]),
        ]
        for category, note, values in cases:
            seq = Sequence(can, category, f"{msg.name}: {note}", [msg])
            _run(seq, msg, p, values)
            yield seq.done()
        for tolerance in (0, 2):
            seq = Sequence(can, "counter_jump", f"{msg.name}: steps of 2 and 3 with counter_tolerance {tolerance}", [msg], counter_tolerance=tolerance)
            _run(seq, msg, p, [0, 2, 5, 6, 7])
            yield seq.done()


def checksums(can: ir.CanProtocol) -> Iterator[dict[str, Any]]:
    for msg in pick(can, lambda m: m.checksum is not None):
        p = period(msg)
        seq = Sequence(can, "checksum", f"{msg.name}: a corrupted checksum, then good frames (recovery)", [msg])
        seq.start(0)
        _run(seq, msg, p, [0, 1])
        seq.frame(3 * p, msg, corrupt(msg, frame(msg, 2)))
        _run(seq, msg, 4 * p, [2, 3, 4])
        yield seq.done()
        seq = Sequence(can, "checksum", f"{msg.name}: every checksum wrong until the timeout", [msg])
        seq.start(0)
        for i in range(1, 6):
            seq.frame(i * p, msg, corrupt(msg, frame(msg, i)))
            seq.check(i * p + 1)
        yield seq.done()


def fault_codes(can: ir.CanProtocol) -> Iterator[dict[str, Any]]:
    """The fault-code tables: checksum failures of messages with different codes and a timeout at
    once give the lowest code; each clears with an accepted frame of its message."""
    seen = set()
    for table in can.fault_tables:
        by_code: dict[int, ir.Message] = {}
        for name, code in table.checksum:
            by_code.setdefault(code, can.message(name))
        msgs = [by_code[c] for c in sorted(by_code)]
        if not msgs or (table.checksum, table.timeout) in seen:
            continue
        seen.add((table.checksum, table.timeout))
        names = ", ".join(m.name for m in msgs)
        seq = Sequence(can, "fault_codes", f"{table.table}: checksum failures of {names}, then a timeout as well, then recovery", msgs)
        seq.start(0)
        t = 0
        for m in reversed(msgs):
            t += 1
            seq.frame(t, m, corrupt(m, frame(m, 0)))
        t += 1
        seq.frame(t, msgs[0], frame(msgs[0], 1))
        t += max(m.timeout_ms or 0 for m in msgs) + 1
        seq.check(t)
        for c in (5, 6):
            for m in msgs:
                t += 1
                seq.frame(t, m, frame(m, c))
        seq.check(t)
        yield seq.done()


def timeouts(can: ir.CanProtocol) -> Iterator[dict[str, Any]]:
    """A check and a frame exactly at the limit and just past it; recovery; timeout from start."""
    for msg in pick(can, lambda m: m.timeout_ms is not None):
        assert msg.timeout_ms is not None
        p, limit = period(msg), msg.timeout_ms
        seq = Sequence(can, "timeout", f"{msg.name}: checks at exactly the timeout and 1 ms past it, then recovery", [msg])
        seq.start(0)
        last = _run(seq, msg, p, [0, 1])
        seq.check(last + limit)
        seq.check(last + limit + 1)
        seq.check(last + limit + 2)
        _run(seq, msg, last + limit + p, [5, 6, 7])
        yield seq.done()
        seq = Sequence(can, "timeout", f"{msg.name}: frames arriving exactly at the timeout and 1 ms past it", [msg])
        last = _run(seq, msg, p, [0, 1])
        seq.frame(last + limit, msg, frame(msg, 2))
        seq.frame(last + 2 * limit + 1, msg, frame(msg, 3))
        _run(seq, msg, last + 2 * limit + 1 + p, [4, 5])
        yield seq.done()
        seq = Sequence(can, "timeout", f"{msg.name}: nothing received after start", [msg])
        seq.start(0)
        seq.check(limit)
        seq.check(limit + 1)
        _run(seq, msg, limit + p, [0, 1, 2])
        yield seq.done()
        seq = Sequence(can, "timeout", f"{msg.name}: the millisecond tick wraps around 2^32", [msg])
        seq.start(TICK_WRAP - p)
        last = _run(seq, msg, TICK_WRAP - p // 2, [0, 1, 2])
        seq.check(last + limit)
        seq.check(last + limit + 1)
        yield seq.done()
    for msg in pick(can, lambda m: m.timeout_ms is not None and m.counter is not None):
        assert msg.timeout_ms is not None
        seq = Sequence(can, "repeated", f"{msg.name}: a frozen counter is no new data: it times out and stays out", [msg])
        seq.start(0)
        for i in range(1, 8):
            seq.frame(i * period(msg), msg, frame(msg, 1))
            seq.check(i * period(msg) + 1)
        yield seq.done()


def event_driven(can: ir.CanProtocol) -> Iterator[dict[str, Any]]:
    for msg in pick(can, lambda m: not m.is_cyclic):
        seq = Sequence(can, "event_driven", f"{msg.name}: irregular frames, no timeout however long the silence", [msg])
        seq.start(0)
        for t, c in ((5, 0), (7, 1), (60_000, 2), (60_001, 3)):
            seq.frame(t, msg, frame(msg, c))
        seq.check(10_000_000)
        yield seq.done()


def frames_refused(can: ir.CanProtocol) -> Iterator[dict[str, Any]]:
    """Wrong lengths, unknown IDs, an ID in the other ID format; parameters valid_after 1 and 3."""
    for msg in pick(can, lambda m: True):
        seq = Sequence(can, "length", f"{msg.name}: a frame {'one length' if msg.dlc > 8 else 'one byte'} short (or long), then good frames", [msg])
        _run(seq, msg, period(msg), [0])
        seq.frame(2 * period(msg), msg, short_frame(frame(msg, 0)))
        _run(seq, msg, 3 * period(msg), [1, 2, 3])
        yield seq.done()
        for valid_after in (1, 3):
            seq = Sequence(can, "in_order", f"{msg.name}: valid after {valid_after} good frame(s)", [msg], valid_after=valid_after)
            _run(seq, msg, period(msg), [0, 1, 2, 3])
            yield seq.done()
    if can.messages:
        msg = can.messages[0]
        seq = Sequence(can, "unknown_id", "IDs of no message, and a message's ID in the other ID format", [msg])
        for t, (fid, ext) in enumerate(unknown_ids(can)):
            seq.frame(t, msg, frame(msg, 0), frame_id=fid, extended=ext)
        yield seq.done()


def short_frame(data: bytes) -> bytes:
    """A frame of the wrong length: one byte short (one FD length short above 8 bytes, as no frame
    of 9..11 bytes exists), or one byte long for a 0-byte message."""
    if not data:
        return b"\x00"
    return data[: FD_LENGTHS[dlc_code(len(data)) - 1]]


def unknown_ids(can: ir.CanProtocol) -> list[tuple[int, bool]]:
    used = {(m.frame_id, m.is_extended) for m in can.messages}
    out = [next((i, ext) for i in range(top, 0, -1) if (i, ext) not in used) for top, ext in ((MAX_EXTENDED_ID, True), (MAX_STANDARD_ID, False))]
    msg = can.messages[0]
    if msg.frame_id <= MAX_STANDARD_ID and (msg.frame_id, not msg.is_extended) not in used:
        out.append((msg.frame_id, not msg.is_extended))
    return out


def interleaved(can: ir.CanProtocol) -> Iterator[dict[str, Any]]:
    """Two messages interleaved: each supervised on its own; one falls silent and times out."""
    both = [m for m in can.messages if m.timeout_ms is not None][:2]
    if len(both) < 2:
        return
    a, b = both
    seq = Sequence(can, "interleaved", f"{a.name} and {b.name} interleaved; then only {a.name}", [a, b])
    seq.start(0)
    for i in range(4):
        seq.frame(i * 10 + 1, a, frame(a, i))
        seq.frame(i * 10 + 2, b, frame(b, i))
    assert b.timeout_ms is not None
    for i in range(4, 4 + b.timeout_ms // 10 + 2):
        seq.frame(i * 10 + 1, a, frame(a, i))
        seq.check(i * 10 + 3)
    yield seq.done()


MONITOR_BUILDERS = (in_order, counters, checksums, fault_codes, timeouts, event_driven, frames_refused, interleaved)


def monitor_sequences(can: ir.CanProtocol) -> list[dict[str, Any]]:
    out = [s for build in MONITOR_BUILDERS for s in build(can)]
    for i, s in enumerate(out):
        s["id"] = i
    return out
