"""The log health report (`canspec decode --report`): the receive monitor's semantics applied to
a recording. Per message: frames, measured period against the spec's cycle, counter jumps and
repeats, checksum errors, gaps longer than the monitor's timeout; plus unknown IDs, bad lines,
remote and error frames.

Every per-frame judgement comes from a monitor, through `MonitorAdapter` — the one place that
talks to it. The runtime issue's monitor (reference/monitor.py) is not written yet:
`MinimalMonitor` below is a STAND-IN with the same per-frame interface, to be replaced by it."""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from canspec import ir
from canspec.reference import codec


@dataclass(frozen=True)
class FrameEvent:
    """What the report needs from the monitor for one received frame."""

    counter: str | None  # "ok" | "repeat" | "jump"; None: no counter, or nothing to compare with yet
    checksum_ok: bool | None  # None: the message has no checksum
    gap: float | None  # seconds since the previous frame when longer than the timeout (a timeout), else None


class MinimalMonitor:
    """STAND-IN for reference/monitor.py (runtime issue), per message, caller-supplied time:
    counter must step by one modulo 2^length (same value: repeat, else jump; no tolerance),
    checksum from the reference codec, timeout = Message.timeout_ms (None: event-driven)."""

    def __init__(self, msg: ir.Message) -> None:
        self.msg = msg
        self.last_time: float | None = None
        self.last_counter: int | None = None

    def on_frame(self, time: float, word: int) -> FrameEvent:
        msg, counter, gap = self.msg, None, None
        if msg.counter is not None:
            value = (word & msg.counter.word_mask) >> msg.counter.start
            if self.last_counter is not None:
                counter = "repeat" if value == self.last_counter else "ok" if value == (self.last_counter + 1) % msg.counter.modulo else "jump"
            self.last_counter = value
        if msg.timeout_ms is not None and self.last_time is not None and time - self.last_time > msg.timeout_ms / 1000:
            gap = time - self.last_time
        if not math.isnan(time):
            self.last_time = time
        checksum = None if msg.checksum is None else ((word >> 8 * msg.checksum.byte) & 0xFF) == codec.xor_checksum(msg, word)
        return FrameEvent(counter, checksum, gap)


class MonitorAdapter:
    """Feeds one message's frames, in time order, to its monitor and yields its events."""

    def __init__(self, msg: ir.Message) -> None:
        self.monitor = MinimalMonitor(msg)

    def events(self, times: list[float], words: list[int]) -> list[FrameEvent]:
        on_frame = self.monitor.on_frame
        return [on_frame(t, w) for t, w in zip(times, words)]


@dataclass
class MessageHealth:
    msg: ir.Message
    adapter: MonitorAdapter
    frames: int = 0
    first: float = math.nan
    last: float = math.nan
    min_period: float = math.inf
    max_period: float = 0.0
    counter: Counter[str] = field(default_factory=Counter)
    checksum_errors: int = 0
    gaps: int = 0
    longest_gap: float = 0.0

    def feed(self, times: np.ndarray, words: np.ndarray) -> None:
        self.frames += len(times)
        valid = times[~np.isnan(times)]
        if len(valid):
            steps = np.diff(np.concatenate(([self.last], valid)) if not math.isnan(self.last) else valid)
            if len(steps):
                self.min_period, self.max_period = min(self.min_period, float(steps.min())), max(self.max_period, float(steps.max()))
            self.first = self.first if not math.isnan(self.first) else float(valid[0])
            self.last = float(valid[-1])
        for ev in self.adapter.events(times.tolist(), words.tolist()):
            if ev.counter is not None:
                self.counter[ev.counter] += 1
            self.checksum_errors += ev.checksum_ok is False
            if ev.gap is not None:
                self.gaps += 1
                self.longest_gap = max(self.longest_gap, ev.gap)

    def record(self) -> dict[str, Any]:
        span = self.last - self.first
        period = span / (self.frames - 1) * 1000 if self.frames > 1 and not math.isnan(span) else None
        return {
            "message": self.msg.name, "id": self.msg.id_text, "frames": self.frames,
            "cycle_ms": self.msg.cycle_ms, "timeout_ms": self.msg.timeout_ms,
            "period_ms": None if period is None else round(period, 3),
            "min_period_ms": None if self.min_period == math.inf else round(self.min_period * 1000, 3),
            "max_period_ms": None if self.min_period == math.inf else round(self.max_period * 1000, 3),
            "counter_jumps": self.counter["jump"], "counter_repeats": self.counter["repeat"],
            "checksum_errors": self.checksum_errors, "gaps": self.gaps,
            "longest_gap_ms": round(self.longest_gap * 1000, 3) if self.gaps else None,
        }


class HealthReport:
    def __init__(self, messages: tuple[ir.Message, ...]) -> None:
        self.health = {m.name: MessageHealth(m, MonitorAdapter(m)) for m in messages}
        self.unknown: Counter[str] = Counter()

    def feed_message(self, msg: ir.Message, times: np.ndarray, words: np.ndarray) -> None:
        self.health[msg.name].feed(times, words)

    def feed_unknown(self, frame_ids: np.ndarray, extended: np.ndarray) -> None:
        for fid, ext in zip(frame_ids.tolist(), extended.tolist()):
            self.unknown[f"0x{fid:08X}" if ext else f"0x{fid:03X}"] += 1

    def result(self, counts: dict[str, int]) -> dict[str, Any]:
        return {
            "messages": [h.record() for h in self.health.values()],
            "unknown_ids": dict(self.unknown.most_common()),
            "counts": counts,
        }


def format_text(report: dict[str, Any]) -> str:
    head = f"{'message':28} {'id':>10} {'frames':>9} {'period ms':>10} {'spec ms':>8} {'min..max ms':>19} {'jumps':>6} {'repeats':>7} {'checksum':>8} {'gaps':>5} {'longest':>9}"
    lines = [head, "-" * len(head)]
    for r in report["messages"]:
        if not r["frames"]:
            lines.append(f"{r['message']:28} {r['id']:>10} {0:>9}  (not in the log)")
            continue
        span = f"{r['min_period_ms']}..{r['max_period_ms']}" if r["min_period_ms"] is not None else "-"
        period = "-" if r["period_ms"] is None else f"{r['period_ms']:.3f}"
        spec = "event" if r["cycle_ms"] is None else str(r["cycle_ms"])
        longest = "-" if r["longest_gap_ms"] is None else f"{r['longest_gap_ms']:.1f}"
        lines.append(f"{r['message']:28} {r['id']:>10} {r['frames']:>9,} {period:>10} {spec:>8} {span:>19} {r['counter_jumps']:>6} "
                     f"{r['counter_repeats']:>7} {r['checksum_errors']:>8} {r['gaps']:>5} {longest:>9}")
    unknown = ", ".join(f"{k} ×{v}" for k, v in report["unknown_ids"].items()) or "none"
    lines.append(f"unknown IDs: {unknown}")
    lines.append("; ".join(f"{k.replace('_', ' ')}: {v:,}" for k, v in report["counts"].items()))
    return "\n".join(lines) + "\n"
