"""Random traffic in the sequence-vector format (vectors/sequences.json), its expectations from the
independent model (model.py): what the C and Rust sequence runners replay to be checked against
the model on traffic no one wrote by hand.

Monitor sequences interleave the frames of a few messages with drops, repeats, counter jumps and
stale counters, corrupted checksums, wrong lengths, unknown IDs (and IDs of the other format),
timing jitter and times landing exactly around the timeout, timeout checks, (re)starts of the
supervision, and tick wrap-around.
Text sequences interleave the frames of several senders' texts (valid, too long, with control
characters) with drops, repeats, short frames, bad indexes and corrupted checksums.

Everything follows from one seed: `build(can, seed, ...)` gives the same file every time.
"""

from __future__ import annotations

import random
from typing import Any

from canspec.reference import codec
from canspec.targets.vectors.texts import frames_of

from runtime.model import ModelMonitor, ModelText

WRAP = 1 << 32
TIMEOUT_CYCLES = 3
EVENT_GAP_MS = 1000  # typical gap between frames of an event-driven message
PRINTABLE = bytes(range(32, 127))


def _frame(rng: random.Random, msg, counter: int) -> bytes:
    """Random bytes with the message's counter set and the checksum byte the XOR of the others."""
    data = bytearray(rng.randbytes(msg.dlc))
    if msg.counter is not None:
        sig = msg.signal(msg.counter.signal)
        word = int.from_bytes(data, "little") & ~(((1 << sig.length) - 1) << sig.start)
        data = bytearray((word | (counter % (1 << sig.length)) << sig.start).to_bytes(msg.dlc, "little"))
    if msg.checksum is not None:
        data[msg.checksum.byte] = 0
        for i, b in enumerate(data):
            data[msg.checksum.byte] ^= b if i != msg.checksum.byte else 0
    return bytes(data)


class MonitorRun:
    """One random monitor sequence: the model fed step by step, every step recorded with its result."""

    def __init__(self, can, rng: random.Random, index: int) -> None:
        self.can, self.rng = can, rng
        k = rng.randint(1, min(4, len(can.messages)))
        self.messages = rng.sample(list(can.messages), k)
        params = {"counter_tolerance": rng.randint(0, 3), "valid_after": rng.randint(1, 4)}
        self.model = ModelMonitor(can, **params, timeout_cycles=TIMEOUT_CYCLES)
        self.t = rng.choice([0, rng.randrange(WRAP), WRAP - rng.randint(1, 3000)])
        self.counters = {m.name: rng.randrange(256) for m in self.messages}
        self.last: dict[str, bytes] = {}
        self.steps: list[dict[str, Any]] = []
        names = [m.name for m in self.messages]
        self.record = {"id": index, "category": "random", "note": "", "messages": names, "params": params, "steps": self.steps}

    def period(self, msg) -> int:
        return msg.cycle_ms if msg.cycle_ms is not None else EVENT_GAP_MS

    def advance(self, msg) -> None:
        """The next step's time: jitter around the period, or exactly around the timeout limit."""
        rng, p = self.rng, self.period(msg)
        since = self.model.msgs[msg.name].since
        if msg.cycle_ms is not None and since is not None and rng.random() < 0.2:
            target = since + msg.cycle_ms * TIMEOUT_CYCLES + rng.choice([-1, 0, 0, 1])
            self.t = max(self.t, target)  # the clock never goes back
        else:
            gaps = [p + rng.randint(-(p // 4), p // 4), rng.randint(0, p // 2), p * rng.randint(2, 6), 0]
            self.t += rng.choices(gaps, [10, 3, 1, 1])[0]

    def now(self) -> int:
        return self.t % WRAP

    def start(self) -> None:
        names = [m.name for m in self.messages]
        self.model.start(self.now(), names)
        self.steps.append({"t": self.now(), "action": "start", "messages": names})

    def send(self, frame_id: int, extended: bool, data: bytes) -> None:
        expect = self.model.frame(self.now(), frame_id, extended, data)
        self.steps.append({"t": self.now(), "action": "frame", "frame_id": frame_id, "extended": extended, "data": data.hex().upper(), "expect": expect})

    def check(self) -> None:
        expect = {"timeouts": self.model.check(self.now()), "states": {m.name: self.model.msgs[m.name].state for m in self.messages},
                  "codes": self.model.codes()}
        self.steps.append({"t": self.now(), "action": "check", "expect": expect})

    def counter_step(self, msg) -> int:
        rng = self.rng
        steps = [1] * 10 + [0, 2, 3, 4, -1, rng.randint(5, 300)]
        return rng.choice(steps) if msg.counter is not None else 1

    def event(self) -> str:
        rng = self.rng
        msg = rng.choice(self.messages)
        self.advance(msg)
        kind = rng.choices(["ok", "drop", "repeat", "corrupt", "length", "unknown", "check", "start"], [12, 2, 1, 2, 1, 1, 3, 1])[0]
        if kind == "check":
            self.check()
            return kind
        if kind == "start":
            self.start()
            return kind
        if kind == "unknown":
            self.send(*self.unknown_id(), rng.randbytes(rng.randint(0, 8)))
            return kind
        if kind == "repeat" and msg.name in self.last:
            self.send(msg.frame_id, msg.is_extended, self.last[msg.name])
            return kind
        self.counters[msg.name] += self.counter_step(msg)
        data = _frame(rng, msg, self.counters[msg.name])
        if kind == "drop":
            return kind
        if kind == "corrupt" and msg.dlc > 0:
            wrong = bytearray(data)
            wrong[rng.randrange(msg.dlc)] ^= rng.randint(1, 255)
            data = bytes(wrong)
        elif kind == "length":
            n = rng.choice([n for n in range(9) if n != msg.dlc])
            data = (data + rng.randbytes(8))[:n]
        self.last[msg.name] = data
        self.send(msg.frame_id, msg.is_extended, data)
        return kind

    def unknown_id(self) -> tuple[int, bool]:
        """An ID no message has: a random one, or a message's ID in the other format."""
        rng = self.rng
        known = {(m.frame_id, m.is_extended) for m in self.can.messages}
        msg = rng.choice(self.messages)
        if rng.random() < 0.5 and (msg.frame_id, not msg.is_extended) not in known and (msg.is_extended or msg.frame_id < 0x800):
            return msg.frame_id, not msg.is_extended
        while True:
            ext = rng.random() < 0.5
            fid = rng.randrange(1 << 29 if ext else 1 << 11)
            if (fid, ext) not in known:
                return fid, ext

    def done(self, kinds: list[str]) -> dict[str, Any]:
        self.record["end"] = {"stats": {m.name: dict(self.model.msgs[m.name].stats) for m in self.messages}, "unknown_frames": self.model.unknown}
        self.record["note"] = f"{len(kinds)} events: " + " ".join(kinds)
        return self.record


def monitor_sequence(can, rng: random.Random, index: int) -> dict[str, Any]:
    run = MonitorRun(can, rng, index)
    if rng.random() < 0.6:
        run.start()
    kinds = [run.event() for _ in range(rng.randint(5, 60))]
    run.advance(rng.choice(run.messages))
    run.check()
    return run.done(kinds)


def _text(rng: random.Random, mf) -> bytes:
    """A text to send: mostly a valid one, sometimes with a control character or too long."""
    room = mf.frames * mf.bytes_per_frame
    chars = bytes(c for c in PRINTABLE if c != mf.padding)
    n = rng.randint(1, mf.text_length)
    text = bytes(rng.choice(chars) for _ in range(n))
    flaw = rng.choices(["none", "control", "long"], [8, 1, 1])[0]
    if flaw == "control":
        i = rng.randrange(n)
        text = text[:i] + bytes([rng.choice([c for c in range(1, 32) if c != mf.padding])]) + text[i + 1 :]
    elif flaw == "long" and room > mf.text_length:
        text = bytes(rng.choice(chars) for _ in range(rng.randint(mf.text_length + 1, room)))
    return text


def _sender(rng: random.Random, msg) -> dict[str, int]:
    """Random key values (what tells senders apart), within their ranges."""
    return {k: rng.randint(msg.signal(k).raw_min, msg.signal(k).raw_max) for k in msg.multiframe.key_signals}


def _bad_index(rng: random.Random, msg, data: bytes) -> bytes | None:
    mf = msg.multiframe
    sig = msg.signal(mf.index_signal)
    bad = [v for v in (mf.frames, sig.raw_type_max, sig.raw_type_min, -1) if sig.raw_type_min <= v <= sig.raw_type_max and not 0 <= v < mf.frames]
    if not bad:
        return None
    return codec.pack(msg, {**codec.unpack(msg, data), mf.index_signal: rng.choice(bad)})


def text_sequence(msg, rng: random.Random, index: int) -> dict[str, Any]:
    """Frames of 1..3 senders' texts (1..2 each), shuffled, dropped, repeated, broken."""
    mf, model = msg.multiframe, ModelText(msg)
    sets = []
    for _ in range(rng.randint(1, 3)):
        keys = _sender(rng, msg)
        if msg.counter is not None:
            keys[msg.counter.signal] = rng.randrange(msg.counter.modulo)
        sets += [frames_of(msg, _text(rng, mf), **keys) for _ in range(rng.randint(1, 2))]
    pool = [f for s in sets for f in s]
    order = list(range(len(pool)))
    if rng.random() < 0.5:  # else in sending order, so that texts complete
        rng.shuffle(order)
    steps, kinds = [], []
    for i in order:
        data = pool[i]
        kind = rng.choices(["ok", "drop", "twice", "short", "long", "index", "corrupt"], [14, 2, 2, 1, 1, 1, 1])[0]
        if kind == "short":
            data = data[: rng.randrange(len(data))] if data else b"\x00"
        elif kind == "long":  # a padded frame: no part of a text in any language
            data = data + bytes(rng.randint(1, 4))
        elif kind == "index":
            data = _bad_index(rng, msg, data) or data
        elif kind == "corrupt" and msg.checksum is not None:
            wrong = bytearray(data)
            wrong[rng.randrange(msg.dlc)] ^= rng.randint(1, 255)
            data = bytes(wrong)
        kinds.append(kind)
        for _ in range({"drop": 0, "twice": 2}.get(kind, 1)):
            result = model.feed(data)
            steps.append({"data": data.hex().upper(), "expect": {"result": result, "text": model.text()}})
    note = f"{len(sets)} texts, {len(pool)} frames: " + " ".join(kinds)
    return {"id": index, "category": "random", "note": note, "message": msg.name, "frame_id": msg.frame_id, "steps": steps}


def build(can, seed: int, monitor_count: int, text_count: int) -> dict[str, Any]:
    """A sequence-vector document of random sequences: `monitor_count` monitor sequences and
    `text_count` text sequences spread over the multi-frame messages, numbered on from the
    monitor sequences (a runner's report names one sequence unambiguously)."""
    rng = random.Random(seed)
    texts = [m for m in can.messages if m.multiframe is not None]
    monitor = monitor_count if can.messages else 0
    return {
        "format": 1,
        "seed": seed,
        "monitor": [monitor_sequence(can, rng, i) for i in range(monitor)],
        "texts": [text_sequence(texts[i % len(texts)], rng, monitor + i) for i in range(text_count if texts else 0)],
    }
