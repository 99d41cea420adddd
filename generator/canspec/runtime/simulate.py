"""A rest-bus simulator: sends every message a node transmits at its cycle time on a python-can bus,
with live rolling counters and checksums, values settable while it runs, and deliberate faults
(drop a message, corrupt its checksum, freeze its counter) for testing receivers.

    with can.Bus(interface="virtual", channel="bench") as bus, RestBus(spec.can, "AUTOCAR", bus) as sim:
        sim.set("autocar_speed_command", accel_cmd=-1.5, gear_cmd=1)
        sim.inject("autocar_eps_command", SimFault.CORRUPT_CHECKSUM)
        time.sleep(5)

Frames are built by the reference codec from raw values (physical values go through the shared
encoding rules, range-checked); each cyclic message is scheduled on its own grid of absolute
deadlines (no drift). A CAN FD message goes out as an FD frame, with bit-rate switching where the
spec asks for it. Event-driven messages are sent when `set` changes them or on `send`. A multiplexed
message keeps the values of every page and sends the pages its multiplexers select (set the
multiplexer to send another page).
Needs python-can (`pip install python-can`).
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from enum import Enum
from typing import Any

from canspec import ir
from canspec.reference import codec


class SimFault(str, Enum):
    DROP = "drop"  # the message is not sent
    CORRUPT_CHECKSUM = "corrupt_checksum"  # its checksum byte is wrong
    FREEZE_COUNTER = "freeze_counter"  # its rolling counter stops


class SimulationError(ValueError):
    pass



@dataclass
class _Sent:
    msg: ir.Message
    raw: dict[str, int]
    due: float = 0.0  # next deadline (monotonic seconds), cyclic messages
    fault: SimFault | None = None
    frames: int = 0
    counter: int = field(default=0)


class RestBus:
    """Simulates `node` on `bus` (anything with python-can's `send(can.Message)`)."""

    def __init__(
        self,
        can: ir.CanProtocol,
        node: str,
        bus: Any,
        *,
        messages: Iterable[str] = (),
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        if node not in {n.name for n in can.nodes}:
            raise SimulationError(f"no node {node!r}: one of {', '.join(n.name for n in can.nodes)}")
        extra = set(messages)
        unknown = extra - {m.name for m in can.messages}
        if unknown:
            raise SimulationError(f"no message {', '.join(sorted(unknown))}")
        chosen = [m for m in can.messages if m.sender == node or m.name in extra]
        self.can, self.node, self.bus, self.clock = can, node, bus, clock
        self._sent = {m.name: _Sent(m, {s.name: s.base_raw for s in m.data_signals if s.role != "checksum"}) for m in chosen}
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None

    @property
    def messages(self) -> list[str]:
        return list(self._sent)

    def frames_sent(self, message: str) -> int:
        return self._entry(message).frames

    def _entry(self, message: str) -> _Sent:
        try:
            return self._sent[message]
        except KeyError:
            raise SimulationError(f"{self.node} does not send {message!r}: it sends {', '.join(self._sent) or 'nothing'}") from None

    # --- values and faults --------------------------------------------------------------------

    def set(self, message: str, /, **physical: float | int | str) -> None:
        """Physical values of a message's signals (range-checked by the shared rules)."""
        entry = self._entry(message)
        raw = {}
        for name, value in physical.items():
            sig = self._signal(entry.msg, name)
            if isinstance(value, str):  # a value name of the signal's table or its special values
                raw[name] = _named_raw(message, sig, value)
                continue
            try:
                raw[name] = codec.to_raw(sig, value)
            except codec.CodecError as exc:
                raise SimulationError(f"{message}.{exc}") from None
        self._update(entry, raw)

    def set_raw(self, message: str, /, **raw: int) -> None:
        """Raw values of a message's signals (any that fits the field)."""
        entry = self._entry(message)
        for name, value in raw.items():
            sig = self._signal(entry.msg, name)
            if not sig.raw_type_min <= value <= sig.raw_type_max:
                raise SimulationError(f"{message}.{name}: raw {value} does not fit {sig.length} bits")
        self._update(entry, dict(raw))

    def _signal(self, msg: ir.Message, name: str) -> ir.Signal:
        sig = next((s for s in msg.data_signals if s.name == name), None)
        if sig is None or sig.role == "checksum":
            raise SimulationError(f"{msg.name}: no settable signal {name!r} (the checksum is computed)")
        return sig

    def _update(self, entry: _Sent, raw: dict[str, int]) -> None:
        with self._lock:
            changed = any(entry.raw.get(k) != v for k, v in raw.items())
            entry.raw.update(raw)
        if changed and not entry.msg.is_cyclic and self.running:
            self.send(entry.msg.name)

    def inject(self, message: str, fault: SimFault | str) -> None:
        """Start sending a message faulty (until `clear`)."""
        entry, kind = self._entry(message), SimFault(fault)
        if kind is SimFault.CORRUPT_CHECKSUM and entry.msg.checksum is None:
            raise SimulationError(f"{message} has no checksum to corrupt")
        if kind is SimFault.FREEZE_COUNTER and entry.msg.counter is None:
            raise SimulationError(f"{message} has no counter to freeze")
        with self._lock:
            entry.fault = kind

    def clear(self, message: str) -> None:
        with self._lock:
            self._entry(message).fault = None

    # --- sending ------------------------------------------------------------------------------

    def frame(self, message: str) -> bytes:
        """The next frame of a message as it would be sent now (counter advanced)."""
        entry = self._entry(message)
        with self._lock:
            return self._next_frame(entry)

    def _next_frame(self, entry: _Sent) -> bytes:
        msg, raw = entry.msg, dict(entry.raw)
        if msg.counter is not None:
            if entry.fault is not SimFault.FREEZE_COUNTER:
                entry.counter = (entry.counter + 1) % msg.counter.modulo
            raw[msg.counter.signal] = entry.counter
        if msg.is_multiplexed:  # every page's values are kept; a frame sends the pages its multiplexers select
            raw = {s.name: raw[s.name] for s in msg.present(raw) if s.name in raw}
        data = bytearray(codec.pack(msg, raw))
        if entry.fault is SimFault.CORRUPT_CHECKSUM and msg.checksum is not None:
            data[msg.checksum.byte] ^= 0xFF
        return bytes(data)

    def send(self, message: str) -> bool:
        """Send one frame of a message now (unless it is dropped); whether it was sent."""
        entry = self._entry(message)
        with self._lock:
            if entry.fault is SimFault.DROP:
                return False
            data = self._next_frame(entry)
            entry.frames += 1
        import can  # python-can, only when frames go out

        msg = entry.msg
        self.bus.send(can.Message(arbitration_id=msg.frame_id, is_extended_id=msg.is_extended, data=data, is_fd=msg.is_fd, bitrate_switch=msg.brs, check=True))
        return True

    # --- the schedule -------------------------------------------------------------------------

    @property
    def running(self) -> bool:
        return self._thread is not None and self._thread.is_alive()

    def start(self) -> None:
        if self.running:
            return
        now = self.clock()
        for entry in self._sent.values():
            entry.due = now
        self._stop.clear()
        self._thread = threading.Thread(target=self._loop, name=f"canspec-simulate-{self.node}", daemon=True)
        self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join()
            self._thread = None

    def run(self, duration: float | None = None) -> None:
        """Send until `duration` seconds have passed (None: until stopped)."""
        self.start()
        self._stop.wait(duration)
        self.stop()

    def __enter__(self) -> RestBus:
        self.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self.stop()

    def _loop(self) -> None:
        cyclic = [e for e in self._sent.values() if e.msg.cycle_ms is not None]
        while not self._stop.is_set():
            now = self.clock()
            for entry in cyclic:
                if entry.due <= now:
                    self.send(entry.msg.name)
                    period = entry.msg.cycle_ms / 1000  # type: ignore[operator]
                    entry.due += period
                    if entry.due < now - period:  # far behind (a stalled host): resume the grid from now
                        entry.due = now + period
            wait = min((e.due for e in cyclic), default=now + 1.0) - self.clock()
            if wait > 0:
                self._stop.wait(wait)


def _named_raw(message: str, sig: ir.Signal, name: str) -> int:
    """The raw value a signal's value table or special values give `name`."""
    named = {e.name: e.raw for e in (sig.value_table.entries if sig.value_table is not None else ())}
    named.update({sp.name: sp.raw for sp in sig.specials})
    if name in named:
        return named[name]
    known = f"its value names: {', '.join(sorted(named))}" if named else "it has no value names"
    raise SimulationError(f"{message}.{sig.name}: {name!r} is neither a number nor a value name ({known})")
