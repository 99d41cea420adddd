"""The log health report (`canspec decode --report`): the receive monitor (runtime/monitor.py,
configured from the IR by runtime/supervision.py; the same rules as the generated C, Python and
Rust monitors) applied to a recording. Per message: frames, measured period against the spec's
cycle, counter jumps (beyond the monitor's tolerance), lost frames (counter steps within it) and
repeats, checksum errors, timeouts (gaps since the last accepted frame longer than the monitor's
timeout); plus unknown IDs, bad lines, remote and error frames.

The monitor runs on whole milliseconds, like the C monitor's tick; a frame without a timestamp, or
stamped before its message's previous frame, counts as no time passing. Such a step back in time is
not a period: the periods (mean, min, max) are measured over the steps forward, and the steps back
are counted per message and reported with the first place (`decode` warns on stderr too)."""

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
    last: float = math.nan  # time of the message's last frame with one
    step_sum: float = 0.0  # seconds between frames, over the steps forward in time
    steps: int = 0
    min_period: float = math.inf
    max_period: float = 0.0
    backwards: int = 0  # steps back in time: not periods, left out of them
    first_back: int | None = None  # the line of the first frame stamped before the one before it
    back_from: tuple[float, float] = (math.nan, math.nan)  # its time and the time before it
    previous: float = math.nan  # time of the message's previous frame
    longest_gap: float = 0.0  # seconds before a frame that found its message timed out
    stats: MessageStats = field(default_factory=MessageStats)

    def feed(self, times: np.ndarray, payloads: list[bytes], lines: np.ndarray | None = None) -> None:
        self.frames += len(times)
        timed = ~np.isnan(times)
        valid = times[timed]
        if len(valid):
            before = np.concatenate(([self.last], valid[:-1]))
            steps = valid - before
            back = steps < 0
            if back.any() and self.first_back is None:
                i = int(np.argmax(back))
                self.first_back = None if lines is None else int(lines[timed][i])
                self.back_from = (float(valid[i]), float(before[i]))
            forward = steps[~back & ~np.isnan(steps)]
            self.backwards += int(back.sum())
            if len(forward):
                self.step_sum, self.steps = self.step_sum + float(forward.sum()), self.steps + len(forward)
                self.min_period, self.max_period = min(self.min_period, float(forward.min())), max(self.max_period, float(forward.max()))
            self.last = float(valid[-1])
        for t, ev in self.adapter.events(self.msg, times.tolist(), payloads):
            if Fault.TIMEOUT in ev.faults and not math.isnan(t - self.previous):
                self.longest_gap = max(self.longest_gap, t - self.previous)
            self.previous = t if not math.isnan(t) else self.previous
        self.stats = self.adapter.stats(self.msg)

    def record(self) -> dict[str, Any]:
        period = self.step_sum / self.steps * 1000 if self.steps else None
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
            "time_backwards": self.backwards,
        }


class HealthReport:
    def __init__(self, messages: tuple[ir.Message, ...]) -> None:
        adapter = MonitorAdapter(messages)
        self.health = {m.name: MessageHealth(m, adapter) for m in messages}
        self.unknown: Counter[str] = Counter()

    def feed_message(self, msg: ir.Message, times: np.ndarray, payloads: list[bytes], lines: np.ndarray | None = None) -> None:
        """One message's frames: their times, data bytes (fields.MessageFrames.payloads) and lines."""
        self.health[msg.name].feed(times, payloads, lines)

    def feed_unknown(self, frame_ids: np.ndarray, extended: np.ndarray) -> None:
        for fid, ext in zip(frame_ids.tolist(), extended.tolist()):
            self.unknown[id_text(fid, ext)] += 1

    def time_backwards(self) -> dict[str, Any]:
        """How often a message's frame is stamped before the one before it, and the first such place
        (the earliest line): a merged, reordered or damaged log, whose periods are not to be trusted."""
        back = [h for h in self.health.values() if h.backwards]
        first = min(back, key=lambda h: h.first_back if h.first_back is not None else math.inf, default=None)
        return {"count": sum(h.backwards for h in back), "first_line": None if first is None else first.first_back,
                "first_time": None if first is None else first.back_from[0], "time_before": None if first is None else first.back_from[1]}

    def result(self, counts: dict[str, int]) -> dict[str, Any]:
        return {
            "messages": [h.record() for h in self.health.values()],
            "unknown_ids": dict(self.unknown.most_common()),
            "time_backwards": self.time_backwards(),
            "counts": counts,
        }


def backwards_warning(report: dict[str, Any]) -> str | None:
    """`LINE: warning: ...` when a message's time goes backwards in the report's log (None when not)."""
    back = report["time_backwards"]
    if not back["count"]:
        return None
    return (f"{back['first_line']}: warning: time goes backwards ({back['first_time']:.6f} s after {back['time_before']:.6f} s); "
            f"{back['count']:,} step{'s' * (back['count'] != 1)} back in this log, left out of the measured periods")


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
    if report["time_backwards"]["count"]:
        which = ", ".join(f"{r['message']} ×{r['time_backwards']}" for r in report["messages"] if r["time_backwards"])
        lines.append(f"time goes backwards: {which} (first at line {report['time_backwards']['first_line']}); "
                     "periods are measured over the steps forward only")
    lines.append("; ".join(f"{k.replace('_', ' ')}: {v:,}" for k, v in report["counts"].items()))
    return "\n".join(lines) + "\n"
