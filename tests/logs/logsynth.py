"""The same frames written in every log format, as a tool would write them: python-can's writers
for candump `-L`, Vector ASC and BLF, PEAK TRC and ASAM MF4; candump's screen forms (default,
`-ta`, `-tA`, `-x`) as can-utils prints them (candump.c / lib.c). Used by tests/logs and
bench/bench_decode.py.

    python3 tests/logs/logsynth.py OUT_DIR --frames N [--formats candump,asc,...]"""

from __future__ import annotations

import argparse
import gzip
import shutil
import sys
from collections.abc import Iterable, Iterator
from datetime import datetime
from pathlib import Path
from typing import NamedTuple

T0 = 1700000000.0
STEP = 0.0005  # seconds between frames
# format name → file name; the candump screen forms are written by hand below
FORMATS = {
    "candump": "bus.log", "candump_gz": "bus.log.gz", "candump_default": "bus_default.log", "candump_ta": "bus_ta.log",
    "candump_tA": "bus_tA.log", "candump_x": "bus_x.log", "asc": "bus.asc", "blf": "bus.blf", "trc": "bus.trc", "mf4": "bus.mf4",
}
HAS_SPECIAL_FRAMES = {
    "candump", "candump_gz", "candump_default", "candump_ta", "candump_tA", "candump_x", "asc", "blf", "mf4"}  # TRC: python-can writes neither
HAS_TIME = {"candump", "candump_gz", "candump_ta", "candump_tA", "candump_x", "asc", "blf", "trc", "mf4"}


class Frame(NamedTuple):
    timestamp: float
    frame_id: int
    extended: bool
    data: bytes
    kind: str = "data"  # data | remote | error
    fd: bool = False  # a CAN FD frame (up to 64 bytes)
    brs: bool = False  # with bit-rate switching
    esi: bool = False  # error state indicator (the sender is error passive)


def frames_from_cases(cases: list[tuple[int, bool, bytes]], n: int, specials_every: int = 0) -> list[Frame]:
    """n frames cycling through (id, extended, data) cases; every `specials_every`-th frame a remote
    or error frame instead (0: none)."""
    out = []
    for i in range(n):
        t = round(T0 + i * STEP, 6)
        if specials_every and i % specials_every == specials_every - 1:
            fid, ext, _ = cases[i % len(cases)]
            out.append(Frame(t, fid, ext, b"", "remote") if (i // specials_every) % 2 else Frame(t, 0x4, True, bytes(8), "error"))
        else:
            fid, ext, data = cases[i % len(cases)]
            out.append(Frame(t, fid, ext, data))
    return out


def _can_messages(frames: Iterable[Frame]) -> Iterator[object]:
    import can

    for f in frames:
        if f.kind == "error":
            yield can.Message(timestamp=f.timestamp, is_error_frame=True, arbitration_id=f.frame_id, data=f.data, channel=0)
        else:
            yield can.Message(timestamp=f.timestamp, arbitration_id=f.frame_id, is_extended_id=f.extended, is_remote_frame=f.kind == "remote",
                              dlc=len(f.data) if f.kind == "data" else 2, data=f.data if f.kind == "data" else None, channel=0,
                              is_fd=f.fd, bitrate_switch=f.brs, error_state_indicator=f.esi)


def _hex_id(f: Frame) -> str:
    if f.kind == "error":
        return f"{f.frame_id | 0x20000000:08X}"
    return f"{f.frame_id:08X}" if f.extended else f"{f.frame_id:03X}"


def _screen_line(f: Frame, lead: str) -> str:
    """candump's screen form (lib.c sprint_long_canframe): `  can0  1806A0B0   [8]  00 11 ...`; a CAN
    FD frame's length with two digits (`[12]`, `[08]`)."""
    size = len(f.data) if f.kind != "remote" else 2
    head = f"{lead} can0  {_hex_id(f):>8}   [{size:02d}]  " if f.fd else f"{lead} can0  {_hex_id(f):>8}   [{size}]  "
    if f.kind == "remote":
        return head + "remote request\n"
    body = " ".join(f"{b:02X}" for b in f.data)
    return head + body + ("   ERRORFRAME\n" if f.kind == "error" else "\n")


def _screen(frames: Iterable[Frame], path: Path, form: str) -> None:
    with path.open("w", encoding="ascii") as out:
        for f in frames:
            if form == "default":
                lead = " "
            elif form == "tA":
                lead = f"({datetime.fromtimestamp(f.timestamp).strftime('%Y-%m-%d %H:%M:%S.%f')}) "
            else:
                lead = f"({f.timestamp:.6f}) "
            line = _screen_line(f, lead)
            out.write(line.replace(" can0  ", f" can0  RX {'B' if f.brs else '-'} {'E' if f.esi else '-'}  ", 1) if form == "x" else line)


def write(fmt: str, path: Path, frames: list[Frame]) -> Path:
    """Writes the frames as `fmt` (a FORMATS key) to path; returns it."""
    import can

    if fmt.startswith("candump_") and fmt != "candump_gz":
        _screen(frames, path, fmt.removeprefix("candump_"))
    elif fmt == "candump_gz":
        plain = path.with_name(path.name + ".tmp")
        write("candump", plain, frames)
        with plain.open("rb") as src, gzip.open(path, "wb", compresslevel=1) as dst:
            shutil.copyfileobj(src, dst)
        plain.unlink()
    else:
        writer = {"candump": can.CanutilsLogWriter, "asc": can.ASCWriter, "blf": can.BLFWriter, "blf64": _blf64_writer(), "trc": _trc_writer(),
                  "mf4": can.MF4Writer}[fmt]
        with writer(str(path)) as w:
            for msg in _can_messages(f for f in frames if fmt != "trc" or f.kind == "data"):
                w.on_message_received(msg)
    return path


def _trc_writer():  # type: ignore[no-untyped-def]
    """python-can's TRC writer (file version 2.1), which drops CAN FD frames, taught PEAK's FD records:
    type FD, FB (bit-rate switching), FE (BRS and ESI) or BI (ESI), and the length's DLC code in the L column."""
    import can
    from can.util import len2dlc

    class TrcFdWriter(can.TRCWriter):
        def on_message_received(self, msg):  # type: ignore[no-untyped-def]
            if not msg.is_fd:
                return super().on_message_received(msg)
            if self.first_timestamp is None:
                self.first_timestamp = msg.timestamp
            coded = can.Message(timestamp=msg.timestamp, arbitration_id=msg.arbitration_id, is_extended_id=msg.is_extended_id, is_fd=True,
                                dlc=len2dlc(len(msg.data)), data=msg.data, check=False)
            kind = {(False, False): "FD", (True, False): "FB", (True, True): "FE", (False, True): "BI"}[msg.bitrate_switch, msg.error_state_indicator]
            plain, self._msg_fmt_string = self._msg_fmt_string, self.FORMAT_MESSAGE.replace(" DT ", f" {kind} ")
            try:
                line = self._format_message_by_format(coded, (msg.channel or 0) + 1)
            finally:
                self._msg_fmt_string = plain
            self.msgnr += 1
            self.log_event(line, msg.timestamp)
            return None

    return TrcFdWriter


def _blf64_writer():  # type: ignore[no-untyped-def]
    """python-can's BLF writer with CAN FD frames as CAN_FD_MESSAGE_64 objects (as CANoe writes them;
    python-can itself writes CAN_FD_MESSAGE), through its own object writer."""
    import can
    from can.io import blf
    from can.util import len2dlc

    class Blf64Writer(can.BLFWriter):
        def on_message_received(self, msg):  # type: ignore[no-untyped-def]
            if not msg.is_fd:
                return super().on_message_received(msg)
            can_id = msg.arbitration_id | (blf.CAN_MSG_EXT if msg.is_extended_id else 0)
            flags = 0x1000 | (0x2000 if msg.bitrate_switch else 0) | (0x4000 if msg.error_state_indicator else 0)
            head = blf.CAN_FD_MSG_64_STRUCT.pack((msg.channel or 0) + 1, len2dlc(len(msg.data)), len(msg.data), 0, can_id, 0, flags, 0, 0, 0, 0, 0, 0, 0, 0)
            self._add_object(blf.CAN_FD_MESSAGE_64, head + bytes(msg.data), msg.timestamp)
            return None

    return Blf64Writer


def vector_cases(vectors: dict) -> list[tuple[int, bool, bytes]]:  # type: ignore[type-arg]
    return [(c["frame_id"], True, bytes.fromhex(c["data"])) for c in vectors["cases"] if c["kind"] != "raw_only"]


def main() -> int:
    import json

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out", type=Path)
    ap.add_argument("--frames", type=int, default=20000)
    ap.add_argument("--formats", default=",".join(FORMATS))
    ap.add_argument("--vectors", type=Path, default=Path(__file__).resolve().parents[2] / "generated" / "vectors" / "can.json")
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    frames = frames_from_cases(vector_cases(json.loads(args.vectors.read_text(encoding="utf-8"))), args.frames)
    for fmt in args.formats.split(","):
        print(write(fmt, args.out / FORMATS[fmt], frames))
    return 0


if __name__ == "__main__":
    sys.exit(main())


def drive_frames(can, seconds: float, t0: float = T0) -> list[Frame]:  # type: ignore[no-untyped-def]
    """A plausible drive: every cyclic message at its cycle, counters stepping, checksums filled
    by the reference codec; accel_cmd a sine, steering a slow sweep, gear_cmd stepping through
    its values. Raw values of other signals stay 0."""
    import math

    from canspec.reference import codec

    frames = []
    for msg in can.messages:
        if msg.cycle_ms is None:
            continue
        for k in range(int(seconds * 1000 / msg.cycle_ms)):
            t = t0 + k * msg.cycle_ms / 1000
            raw = {}
            for sig in msg.data_signals:
                if sig.name == "accel_cmd":
                    raw[sig.name] = codec.to_raw(sig, round(2 * math.sin(t - t0), 2))
                elif sig.name == "steering_angle_cmd":
                    raw[sig.name] = codec.to_raw(sig, round(300 * math.sin((t - t0) / 3), 1))
                elif sig.name == "gear_cmd":
                    raw[sig.name] = int((t - t0) // 2) % 3
            if msg.counter is not None:
                raw[msg.counter.signal] = k % msg.counter.modulo
            frames.append(Frame(round(t, 6), msg.frame_id, msg.is_extended, codec.pack(msg, raw)))
    return sorted(frames, key=lambda f: f.timestamp)
