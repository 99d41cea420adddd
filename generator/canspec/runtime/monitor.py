"""Receive monitor: per message, timeouts, rolling-counter repeats and jumps, checksum and length
faults, a state in the spirit of AUTOSAR E2E's state machine, statistics, and the protocol's own
fault codes. Standard library only, and independent of any spec: it is configured with plain
rules, so the same file serves canspec (rules from its IR) and a generated package (rules from its
message classes), which ships it verbatim. The caller supplies every time (milliseconds, any
epoch; differences are taken modulo 2^32 like a wrapping 32-bit tick), so it runs the same on a
bench, in a test and on recorded logs.

    rules = [MessageRule("eps_command", 0x1801B0A0, True, 8, timeout_ms=60,
                         counter=CounterRule(start=8, length=8), checksum=ChecksumRule(byte=7, cover_mask=0xFFFFFFFFFFFFFF))]
    mon = Monitor(rules, fault_tables=(), counter_tolerance=1, valid_after=2)
    mon.start(now_ms)                                    # optional: supervise timeouts from now on
    event = mon.feed(now_ms, frame_id, extended, data)   # FrameEvent, for every frame
    for timeout in mon.check(now_ms):                    # TimeoutEvent per message newly timed out
        ...
    mon.state("eps_command"), mon.stats("eps_command"), mon.fault_codes(), mon.unknown_ids()

Semantics (the C, Rust and Python monitors implement exactly these; the shared sequence vectors
test them):

- A frame is looked up by its ID *and* ID format. An unknown one gives Fault.UNKNOWN_ID and is
  counted; it touches no message.
- Timeout: a message with `timeout_ms` is supervised from `start()` or from its first accepted
  frame. It times out when more than `timeout_ms` have passed since its last accepted frame (at
  exactly `timeout_ms` it has not): found by `check(now)`, or by `feed` for the message's own frame
  before the frame is judged (so the result does not depend on how often `check` runs). A
  message without `timeout_ms` (event-driven) never times out.
- A frame whose length differs from the DLC (Fault.LENGTH), or whose checksum byte is not the
  XOR of the bytes it covers (Fault.CHECKSUM), is rejected.
- Counter: delta = (counter - stored counter) mod 2^length. delta 0: Fault.COUNTER_REPEAT, the
  frame is rejected (stale or replayed data). 1 <= delta <= 1 + counter_tolerance: in sequence
  (delta - 1 frames lost, counted). A larger delta (including a counter that went back):
  Fault.COUNTER_JUMP; the frame is accepted and the sequence restarts from it (as E2E profile 4
  stores the counter on a wrong sequence). The first frame of a message, and the first after a
  timeout, are not compared (except that a repeat of the stored counter after a timeout is still
  a repeat: a frozen counter stays timed out).
- A rejected frame changes neither the stored counter nor the timeout's reference time. An
  accepted frame (intact, not a repeat) ends a timeout and a checksum fault.
- State: NO_DATA until the first frame; every fault (a timeout too) makes it INVALID; a message
  turns VALID after `valid_after` consecutive accepted frames without a fault (INIT until then
  when it was NO_DATA). Use a frame's values when its event's state is VALID.
- Fault codes: for each FaultTable, the lowest code among the checksum codes of messages whose
  last frame failed the checksum (until an accepted frame) and the timeout code when any message
  is timed out; the table's `none` code otherwise.
- Counts saturate at 2^32 - 1.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from enum import Enum

__all__ = [
    "ChecksumRule",
    "CounterRule",
    "Fault",
    "FaultTable",
    "FrameEvent",
    "MessageRule",
    "MessageStats",
    "Monitor",
    "State",
    "TimeoutEvent",
]

TICK_MODULO = 1 << 32  # times wrap like a 32-bit millisecond tick
COUNT_MAX = (1 << 32) - 1  # counts saturate here
UNKNOWN_IDS_KEPT = 256  # distinct unknown IDs counted one by one (all of them in the total)


class State(str, Enum):
    """A message's receive state."""

    NO_DATA = "no_data"  # nothing received yet
    INIT = "init"  # receiving, not yet `valid_after` good frames in a row
    VALID = "valid"
    INVALID = "invalid"  # a fault; valid again after `valid_after` good frames in a row


class Fault(str, Enum):
    """What can be wrong with a frame or a message."""

    UNKNOWN_ID = "unknown_id"
    LENGTH = "length"
    CHECKSUM = "checksum"
    COUNTER_REPEAT = "counter_repeat"
    COUNTER_JUMP = "counter_jump"
    TIMEOUT = "timeout"


@dataclass(frozen=True)
class CounterRule:
    """A rolling counter: `length` bits from bit `start` of the frame read as one integer, little-endian
    (an Intel counter) or big-endian (a Motorola one: `word_order` "big")."""

    start: int
    length: int
    word_order: str = "little"


@dataclass(frozen=True)
class ChecksumRule:
    """An XOR checksum in byte `byte`: the XOR of the bytes set in `cover_mask` (the frame read as
    a little-endian integer)."""

    byte: int
    cover_mask: int


@dataclass(frozen=True)
class MessageRule:
    """What the monitor checks of one message. `timeout_ms` None: not supervised (event-driven)."""

    name: str
    frame_id: int
    extended: bool
    dlc: int
    timeout_ms: int | None = None
    counter: CounterRule | None = None
    checksum: ChecksumRule | None = None


@dataclass(frozen=True)
class FaultTable:
    """A value table of fault codes: `none` when nothing is wrong, `timeout` for a timed-out
    message, `checksum[name]` for a checksum failure of that message."""

    name: str
    none: int
    timeout: int
    checksum: Mapping[str, int] = field(default_factory=dict)


@dataclass(frozen=True)
class FrameEvent:
    """What one frame did. `faults`: TIMEOUT first when the message's timeout ran out before the
    frame, then the frame's own fault, if any."""

    time_ms: int
    frame_id: int
    extended: bool
    message: str | None  # None: unknown ID
    faults: tuple[Fault, ...]
    accepted: bool  # intact and new: its data count (see the state)
    state: State | None  # the message's state after the frame (None: unknown ID)
    previous_state: State | None
    counter: int | None  # the frame's counter (None: none, or the frame is not intact)
    counter_delta: int | None  # against the stored counter (None: not compared)
    checksum_ok: bool | None  # None: no checksum, or the length is wrong
    gap_ms: int | None  # since the message's previous frame (None: its first)
    recovered: bool  # INVALID -> VALID with this frame
    fault_codes: Mapping[str, int]  # each fault table's code after the frame

    @property
    def ok(self) -> bool:
        return not self.faults


@dataclass(frozen=True)
class TimeoutEvent:
    """A message timed out: `silent_ms` since its last accepted frame (or since `start`)."""

    time_ms: int
    message: str
    silent_ms: int
    fault_codes: Mapping[str, int]


@dataclass
class MessageStats:
    """Per-message counts (saturating) and the gaps between its frames."""

    frames: int = 0
    accepted: int = 0
    length_errors: int = 0
    checksum_errors: int = 0
    counter_repeats: int = 0
    counter_jumps: int = 0  # beyond the tolerance
    lost_frames: int = 0  # missing in counter steps within the tolerance
    timeouts: int = 0
    min_gap_ms: int | None = None
    max_gap_ms: int | None = None
    gap_total_ms: int = 0
    gaps: int = 0

    @property
    def mean_gap_ms(self) -> float | None:
        return self.gap_total_ms / self.gaps if self.gaps else None


def _add(count: int, n: int = 1) -> int:
    return min(count + n, COUNT_MAX)


@dataclass
class _Track:
    """One message's receive state."""

    state: State = State.NO_DATA
    good_run: int = 0  # accepted frames in a row without a fault
    armed: bool = False  # timeout supervised (reference time set)
    reference_ms: int = 0  # last accepted frame, or start()
    timed_out: bool = False
    checksum_failed: bool = False
    counter: int | None = None  # of the last accepted frame
    last_frame_ms: int | None = None
    stats: MessageStats = field(default_factory=MessageStats)


class Monitor:
    """Receive monitor over a set of message rules (see the module docstring)."""

    def __init__(
        self,
        rules: Iterable[MessageRule],
        *,
        fault_tables: Iterable[FaultTable] = (),
        counter_tolerance: int,
        valid_after: int,
    ) -> None:
        if counter_tolerance < 0 or valid_after < 1:
            raise ValueError("counter_tolerance must be >= 0 and valid_after >= 1")
        self.rules: tuple[MessageRule, ...] = tuple(rules)
        self.fault_tables: tuple[FaultTable, ...] = tuple(fault_tables)
        self.counter_tolerance = counter_tolerance
        self.valid_after = valid_after
        self._by_key = {(r.frame_id, r.extended): r for r in self.rules}
        if len(self._by_key) != len(self.rules) or len({r.name for r in self.rules}) != len(self.rules):
            raise ValueError("two rules share a name, or an ID and ID format")
        self._tracks = {r.name: _Track() for r in self.rules}
        self._tables = {t.name: t for t in self.fault_tables}
        self._unknown: dict[tuple[int, bool], int] = {}
        self._unknown_total = 0

    # --- queries ---------------------------------------------------------------------------

    def state(self, message: str) -> State:
        return self._tracks[message].state

    def timed_out(self, message: str) -> bool:
        return self._tracks[message].timed_out

    def stats(self, message: str) -> MessageStats:
        """A copy of the message's statistics."""
        return replace(self._tracks[message].stats)

    def unknown_ids(self) -> dict[tuple[int, bool], int]:
        """Frames of unknown (ID, extended) seen, per ID (the first distinct IDs only)."""
        return dict(self._unknown)

    @property
    def unknown_frames(self) -> int:
        return self._unknown_total

    def fault_code(self, table: str) -> int:
        ft = self._tables[table]
        codes = [
            ft.checksum[r.name] for r in self.rules if r.name in ft.checksum and self._tracks[r.name].checksum_failed
        ]
        if any(t.timed_out for t in self._tracks.values()):
            codes.append(ft.timeout)
        return min(codes, default=ft.none)

    def fault_codes(self) -> dict[str, int]:
        return {t.name: self.fault_code(t.name) for t in self.fault_tables}

    # --- time ------------------------------------------------------------------------------

    def start(self, now_ms: int, messages: Iterable[str] | None = None) -> None:
        """Supervise the timeouts of these messages (default: all with a timeout) from now on."""
        for name in self._tracks if messages is None else messages:
            track = self._tracks[name]
            track.armed, track.reference_ms, track.timed_out = True, now_ms, False

    def check(self, now_ms: int) -> list[TimeoutEvent]:
        """Messages that time out at `now_ms` (each reported once per timeout)."""
        expired = [r.name for r in self.rules if self._expire(r, self._tracks[r.name], now_ms)]
        codes = self.fault_codes()
        return [
            TimeoutEvent(now_ms, name, (now_ms - self._tracks[name].reference_ms) % TICK_MODULO, codes)
            for name in expired
        ]

    def _expire(self, rule: MessageRule, track: _Track, now_ms: int) -> bool:
        if rule.timeout_ms is None or not track.armed or track.timed_out:
            return False
        if (now_ms - track.reference_ms) % TICK_MODULO <= rule.timeout_ms:
            return False
        track.timed_out = True
        track.stats.timeouts = _add(track.stats.timeouts)
        self._fail(track)
        return True

    # --- frames ----------------------------------------------------------------------------

    def feed(self, now_ms: int, frame_id: int, extended: bool, data: bytes | bytearray | memoryview) -> FrameEvent:
        """Judge one received frame at `now_ms`."""
        rule = self._by_key.get((frame_id, bool(extended)))
        if rule is None:
            return self._unknown_frame(now_ms, frame_id, bool(extended))
        track = self._tracks[rule.name]
        previous = track.state
        gap = None if track.last_frame_ms is None else (now_ms - track.last_frame_ms) % TICK_MODULO
        self._count_frame(track.stats, gap)
        track.last_frame_ms = now_ms
        faults = [Fault.TIMEOUT] if self._expire(rule, track, now_ms) else []
        fault, checksum_ok, counter, delta = self._judge(rule, track, bytes(data))
        if fault is not None:
            faults.append(fault)
        accepted = fault in (None, Fault.COUNTER_JUMP)
        if accepted:
            self._accept(track, now_ms, counter, jumped=fault is not None)
        recovered = previous is State.INVALID and track.state is State.VALID
        return FrameEvent(
            now_ms,
            frame_id,
            bool(extended),
            rule.name,
            tuple(faults),
            accepted,
            track.state,
            previous,
            counter,
            delta,
            checksum_ok,
            gap,
            recovered,
            self.fault_codes(),
        )

    def _unknown_frame(self, now_ms: int, frame_id: int, extended: bool) -> FrameEvent:
        self._unknown_total = _add(self._unknown_total)
        key = (frame_id, extended)
        if key in self._unknown or len(self._unknown) < UNKNOWN_IDS_KEPT:
            self._unknown[key] = _add(self._unknown.get(key, 0))
        nothing = dict.fromkeys(("state", "previous_state", "counter", "counter_delta", "checksum_ok", "gap_ms"))
        return FrameEvent(
            now_ms,
            frame_id,
            extended,
            None,
            (Fault.UNKNOWN_ID,),
            False,
            **nothing,
            recovered=False,
            fault_codes=self.fault_codes(),
        )

    @staticmethod
    def _count_frame(stats: MessageStats, gap: int | None) -> None:
        stats.frames = _add(stats.frames)
        if gap is not None:
            stats.gaps = _add(stats.gaps)
            stats.gap_total_ms += gap
            stats.min_gap_ms = gap if stats.min_gap_ms is None else min(stats.min_gap_ms, gap)
            stats.max_gap_ms = gap if stats.max_gap_ms is None else max(stats.max_gap_ms, gap)

    def _judge(
        self, rule: MessageRule, track: _Track, data: bytes
    ) -> tuple[Fault | None, bool | None, int | None, int | None]:
        """(fault, checksum ok, counter, counter delta) of an intact-or-not frame; counts faults."""
        stats = track.stats
        if len(data) != rule.dlc:
            stats.length_errors = _add(stats.length_errors)
            self._fail(track)
            return Fault.LENGTH, None, None, None
        word = int.from_bytes(data, "little")
        checksum_ok = None
        if rule.checksum is not None:
            covered, xor = word & rule.checksum.cover_mask, 0
            while covered:
                xor ^= covered & 0xFF
                covered >>= 8
            checksum_ok = xor == data[rule.checksum.byte]
            if not checksum_ok:
                stats.checksum_errors = _add(stats.checksum_errors)
                track.checksum_failed = True
                self._fail(track)
                return Fault.CHECKSUM, False, None, None
        if rule.counter is None:
            return None, checksum_ok, None, None
        modulo = 1 << rule.counter.length
        counter_word = word if rule.counter.word_order == "little" else int.from_bytes(data, "big")
        counter = (counter_word >> rule.counter.start) % modulo
        if track.counter is None:
            return None, checksum_ok, counter, None
        delta = (counter - track.counter) % modulo
        if delta == 0:
            stats.counter_repeats = _add(stats.counter_repeats)
            self._fail(track)
            return Fault.COUNTER_REPEAT, checksum_ok, counter, delta
        if track.timed_out:  # the sequence restarts after a timeout
            return None, checksum_ok, counter, delta
        if delta > 1 + self.counter_tolerance:
            stats.counter_jumps = _add(stats.counter_jumps)
            return Fault.COUNTER_JUMP, checksum_ok, counter, delta
        stats.lost_frames = _add(stats.lost_frames, delta - 1)
        return None, checksum_ok, counter, delta

    def _accept(self, track: _Track, now_ms: int, counter: int | None, *, jumped: bool) -> None:
        track.stats.accepted = _add(track.stats.accepted)
        track.armed, track.reference_ms, track.timed_out, track.checksum_failed = True, now_ms, False, False
        if counter is not None:
            track.counter = counter
        if jumped:
            self._fail(track)
            return
        track.good_run = min(track.good_run + 1, self.valid_after)
        if track.good_run >= self.valid_after:
            track.state = State.VALID
        elif track.state is State.NO_DATA:
            track.state = State.INIT

    @staticmethod
    def _fail(track: _Track) -> None:
        track.state, track.good_run = State.INVALID, 0
