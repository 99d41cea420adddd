"""A small, independent model of the receive monitor and of multi-frame text reassembly, written
from the rules as README.md states them (not from canspec's runtime/monitor.py): the oracle the
sequence vectors and the property tests are checked against.

It reads only what the spec says of a message: ID and format, DLC, cycle time, the counter's bits,
whether the last byte is an XOR checksum of the others, and the fault-code value tables by their
entry names.
"""

from __future__ import annotations

from dataclasses import dataclass, field

WRAP = 2**32
SATURATE = 2**32 - 1


def field_bits(data: bytes, sig) -> int:
    """A field's unsigned value, bit by bit in the DBC numbering (bit 8 × byte + b): an Intel field
    rises from its LSB `start`; a Motorola field falls from its MSB `start` to bit 0 of the byte and
    goes on from bit 7 of the next."""
    value, pos = 0, sig.start
    for i in range(sig.length):
        bit = (data[pos // 8] >> (pos % 8)) & 1
        if sig.byte_order == "big_endian":
            value = value << 1 | bit
            pos = pos - 1 if pos % 8 else pos + 15
        else:
            value |= bit << i
            pos += 1
    return value


def xor_ok(data: bytes, byte: int) -> bool:
    """The checksum byte is the XOR of every other byte of the frame."""
    x = 0
    for i, b in enumerate(data):
        x ^= b if i != byte else 0
    return x == data[byte]


@dataclass
class Msg:
    """Per-message memory: the few facts the rules need."""

    state: str = "no_data"
    run: int = 0  # accepted frames in a row since the last fault
    since: int | None = None  # reference time of the timeout (None: not supervised yet)
    silent: bool = False  # timed out, no accepted frame since
    bad_checksum: bool = False  # last judged frame failed the checksum, no accepted frame since
    last_counter: int | None = None
    stats: dict[str, int] = field(default_factory=lambda: dict.fromkeys(
        ("frames", "accepted", "length_errors", "checksum_errors", "counter_repeats", "counter_jumps", "lost_frames", "timeouts"), 0))

    def bump(self, key: str, n: int = 1) -> None:
        self.stats[key] = min(SATURATE, self.stats[key] + n)


class ModelMonitor:
    def __init__(self, can, *, counter_tolerance: int, valid_after: int, timeout_cycles: int = 3) -> None:
        self.can, self.tol, self.need, self.cycles = can, counter_tolerance, valid_after, timeout_cycles
        self.msgs = {m.name: Msg() for m in can.messages}
        self.unknown = 0

    def _limit(self, m) -> int | None:
        return None if m.cycle_ms is None else m.cycle_ms * self.cycles

    def _fault(self, s: Msg) -> None:
        s.state, s.run = "invalid", 0

    def _maybe_timeout(self, m, now: int) -> bool:
        s, limit = self.msgs[m.name], self._limit(m)
        if limit is None or s.since is None or s.silent or (now - s.since) % WRAP <= limit:
            return False
        s.silent = True
        s.bump("timeouts")
        self._fault(s)
        return True

    def codes(self) -> dict[str, int]:
        out = {}
        for table in self.can.value_tables:
            names = {e.name: e.raw for e in table.entries}
            if "message_timeout" not in names or table.by_raw(0) is None:
                continue
            active = [names[f"{m.layout}_xor_error"] for m in self.can.messages
                      if m.checksum and m.layout and f"{m.layout}_xor_error" in names and self.msgs[m.name].bad_checksum]
            if any(s.silent for s in self.msgs.values()):
                active.append(names["message_timeout"])
            out[table.name] = min(active) if active else 0
        return out

    def start(self, now: int, names: list[str]) -> None:
        for n in names:
            self.msgs[n].since, self.msgs[n].silent = now, False

    def check(self, now: int) -> list[str]:
        return [m.name for m in self.can.messages if self._maybe_timeout(m, now)]

    def frame(self, now: int, frame_id: int, extended: bool, data: bytes) -> dict:
        m = next((m for m in self.can.messages if m.frame_id == frame_id and m.is_extended == extended), None)
        if m is None:
            self.unknown += 1
            return {"message": None, "faults": ["unknown_id"], "accepted": False, "state": None, "counter_delta": None,
                    "checksum_ok": None, "recovered": False, "codes": self.codes()}
        s = self.msgs[m.name]
        before = s.state
        s.bump("frames")
        faults = ["timeout"] if self._maybe_timeout(m, now) else []
        own, ck, delta = self._judge(m, s, data)
        faults += [own] if own else []
        accepted = own in (None, "counter_jump")
        if accepted:
            s.bump("accepted")
            s.since, s.silent, s.bad_checksum = now, False, False
            if own:
                self._fault(s)
            else:
                s.run = min(s.run + 1, self.need)
                s.state = "valid" if s.run >= self.need else ("init" if s.state == "no_data" else s.state)
        return {"message": m.name, "faults": faults, "accepted": accepted, "state": s.state, "counter_delta": delta, "checksum_ok": ck,
                "recovered": before == "invalid" and s.state == "valid", "codes": self.codes()}

    def _judge(self, m, s: Msg, data: bytes):
        """(own fault, checksum ok, counter delta); updates the stored counter."""
        if len(data) != m.dlc:
            s.bump("length_errors")
            self._fault(s)
            return "length", None, None
        ck = None
        if m.checksum:
            ck = xor_ok(data, m.checksum.byte)
            if not ck:
                s.bump("checksum_errors")
                s.bad_checksum = True
                self._fault(s)
                return "checksum", False, None
        if not m.counter:
            return None, ck, None
        sig = m.signal(m.counter.signal)
        value = field_bits(data, sig)
        previous, s.last_counter = s.last_counter, value
        if previous is None:
            return None, ck, None
        delta = (value - previous) % (1 << sig.length)
        if delta == 0:
            s.bump("counter_repeats")
            self._fault(s)
            return "counter_repeat", ck, 0
        if not s.silent and delta > 1 + self.tol:
            s.bump("counter_jumps")
            return "counter_jump", ck, delta
        if not s.silent:
            s.bump("lost_frames", delta - 1)
        return None, ck, delta


class ModelText:
    """Reassembly of one multi-frame message, from the frames' raw values."""

    def __init__(self, msg) -> None:
        self.msg, self.mf = msg, msg.multiframe
        self.parts: dict[int, bytes] = {}
        self.owner: tuple | None = None

    def feed(self, data: bytes) -> str:
        m, mf = self.msg, self.mf
        if len(data) != m.dlc:
            return "length"
        if m.checksum and not xor_ok(data, m.checksum.byte):
            return "checksum"
        raw = {}
        for s in m.data_signals:
            v = field_bits(data, s)
            raw[s.name] = v - (1 << s.length) if s.signed and v >> (s.length - 1) else v
        index = raw[mf.index_signal]
        if index < 0 or index >= mf.frames:
            return "index"
        part = data[mf.payload_byte : mf.payload_byte + mf.bytes_per_frame]
        owner = tuple(v for k, v in sorted(raw.items()) if k not in (mf.index_signal, mf.payload_signal) and m.signal(k).role == "data")
        clash = bool(self.parts) and (owner != self.owner or (index in self.parts and self.parts[index] != part))
        if clash:
            self.parts = {}
        if not self.parts:
            self.owner = owner
        self.parts[index] = part
        return "inconsistent" if clash else "ok"

    def text(self) -> str | bool | None:
        if len(self.parts) < self.mf.frames:
            return None
        data = b"".join(self.parts[i] for i in range(self.mf.frames))
        text = data.split(bytes([self.mf.padding]), 1)[0]
        rest = data[len(text):]
        if len(text) > self.mf.text_length or rest.strip(bytes([self.mf.padding])) or any(c < 32 or c > 126 for c in text):
            return False
        return text.decode("ascii")
