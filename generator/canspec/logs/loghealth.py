"""The log health report (`canspec decode --report`): the receive monitor (runtime/monitor.py,
configured from the IR by runtime/supervision.py; the same rules as the generated C, Python and
Rust monitors) applied to a recording. Per message: frames, measured period against the spec's
cycle, counter jumps (beyond the monitor's tolerance), lost frames (counter steps within it) and
repeats, checksum errors, timeouts (gaps since the last accepted frame longer than the monitor's
timeout); plus unknown IDs, bad lines, remote and error frames.

The monitor runs on whole milliseconds, like the C monitor's tick; a frame without a timestamp, or
stamped before its message's previous frame, counts as no time passing."""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from canspec import ir
from canspec.ir.ids import id_text
from canspec.runtime.monitor import Fault, FrameEvent, MessageStats, Monitor
from canspec.runtime.supervision import message_rule


class MonitorAdapter:
    """Feeds each message's frames, in its time order, to one monitor of the protocol (messages are
    judged independently, so per-message batches need no global order)."""

    def __init__(self, messages: tuple[ir.Message, ...]) -> None:
        self.monitor = Monitor((message_rule(m) for m in messages), counter_tolerance=ir.MONITOR_COUNTER_TOLERANCE,
                               valid_after=ir.MONITOR_VALID_AFTER)
        self.now_ms: dict[str, int] = {}

    def events(self, msg: ir.Message, times: list[float], payloads: list[bytes]) -> Iterator[tuple[float, FrameEvent]]:
        """(time in seconds, the monitor's event) per frame."""
        feed = self.monitor.feed
        now = self.now_ms.get(msg.name)
        if now is None:  # frames before the first timestamp take it
            now = next((round(t * 1000) for t in times if not math.isnan(t)), 0)
        for t, data in zip(times, payloads):
            if not math.isnan(t):
                now = max(now, round(t * 1000))
            yield t, feed(now, msg.frame_id, msg.is_extended, data)
        self.now_ms[msg.name] = now

    def stats(self, msg: ir.Message) -> MessageStats:
        return self.monitor.stats(msg.name)


@dataclass
class MessageHealth:
    msg: ir.Message
    adapter: MonitorAdapter
    frames: int = 0
    first: float = math.nan
    last: float = math.nan
    min_period: float = math.inf
    max_period: float = 0.0
    previous: float = math.nan  # time of the message's previous frame
    longest_gap: float = 0.0  # seconds before a frame that found its message timed out
    stats: MessageStats = field(default_factory=MessageStats)

    def feed(self, times: np.ndarray, payloads: list[bytes]) -> None:
        self.frames += len(times)
        valid = times[~np.isnan(times)]
        if len(valid):
            steps = np.diff(np.concatenate(([self.last], valid)) if not math.isnan(self.last) else valid)
            if len(steps):
                self.min_period, self.max_period = min(self.min_period, float(steps.min())), max(self.max_period, float(steps.max()))
            self.first = self.first if not math.isnan(self.first) else float(valid[0])
            self.last = float(valid[-1])
        for t, ev in self.adapter.events(self.msg, times.tolist(), payloads):
            if Fault.TIMEOUT in ev.faults and not math.isnan(t - self.previous):
                self.longest_gap = max(self.longest_gap, t - self.previous)
            self.previous = t if not math.isnan(t) else self.previous
        self.stats = self.adapter.stats(self.msg)

    def record(self) -> dict[str, Any]:
        span = self.last - self.first
        period = span / (self.frames - 1) * 1000 if self.frames > 1 and not math.isnan(span) else None
        st = self.stats
        return {
            "message": self.msg.name, "id": self.msg.id_text, "frames": self.frames,
            "cycle_ms": self.msg.cycle_ms, "timeout_ms": self.msg.timeout_ms,
            "period_ms": None if period is None else round(period, 3),
            "min_period_ms": None if self.min_period == math.inf else round(self.min_period * 1000, 3),
            "max_period_ms": None if self.min_period == math.inf else round(self.max_period * 1000, 3),
            "counter_jumps": st.counter_jumps, "counter_repeats": st.counter_repeats, "lost_frames": st.lost_frames,
            "checksum_errors": st.checksum_errors, "gaps": st.timeouts,
            "longest_gap_ms": round(self.longest_gap * 1000, 3) if self.longest_gap else None,
        }


class HealthReport:
    def __init__(self, messages: tuple[ir.Message, ...]) -> None:
        adapter = MonitorAdapter(messages)
        self.health = {m.name: MessageHealth(m, adapter) for m in messages}
        self.unknown: Counter[str] = Counter()

    def feed_message(self, msg: ir.Message, times: np.ndarray, payloads: list[bytes]) -> None:
        """One message's frames: their times and data bytes (fields.MessageFrames.payloads)."""
        self.health[msg.name].feed(times, payloads)

    def feed_unknown(self, frame_ids: np.ndarray, extended: np.ndarray) -> None:
        for fid, ext in zip(frame_ids.tolist(), extended.tolist()):
            self.unknown[id_text(fid, ext)] += 1

    def result(self, counts: dict[str, int]) -> dict[str, Any]:
        return {
            "messages": [h.record() for h in self.health.values()],
            "unknown_ids": dict(self.unknown.most_common()),
            "counts": counts,
        }


def format_text(report: dict[str, Any]) -> str:
    head = (f"{'message':28} {'id':>10} {'frames':>9} {'period ms':>10} {'spec ms':>8} {'min..max ms':>19} "
            f"{'jumps':>6} {'lost':>6} {'repeats':>7} {'checksum':>8} {'gaps':>5} {'longest':>9}")
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
                     f"{r['lost_frames']:>6} {r['counter_repeats']:>7} {r['checksum_errors']:>8} {r['gaps']:>5} {longest:>9}")
    unknown = ", ".join(f"{k} ×{v}" for k, v in report["unknown_ids"].items()) or "none"
    lines.append(f"unknown IDs: {unknown}")
    lines.append("; ".join(f"{k.replace('_', ' ')}: {v:,}" for k, v in report["counts"].items()))
    return "\n".join(lines) + "\n"
