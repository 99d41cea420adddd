#!/usr/bin/env python3
"""Write a synthetic canspec spec for scale tests and benchmarks.

  tools/synth_spec.py OUT --copies K
      The shipped spec with its 25 CAN messages repeated K times (K=1 is the shipped spec):
      every feature (shared layouts and variants, value tables, specials, counters, checksums,
      the multiframe VIN) scales with it. Copies get new names and new, unique J1939 IDs
      (PDU1, PF/PS counting up) from the same senders.
  tools/synth_spec.py OUT --messages 2000 --signals 30000 [--seed N]
      A generated CAN protocol of that many messages and signals (counters, checksums, value
      tables, signed/scaled fields, specials), deterministic for a seed.

OUT becomes a spec directory (OUT/canspec.yaml + files) for `canspec check|gen OUT`.
"""

from __future__ import annotations

import argparse
import random
import re
import shutil
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SHIPPED = ROOT / "spec"

_MESSAGE_START = re.compile(r"^  - name: ([a-z0-9_]+)\s*$", re.MULTILINE)
_ID = re.compile(r"^    id: 0x([0-9A-Fa-f]+)\s*$", re.MULTILINE)
_J1939 = re.compile(r"^(    j1939: \{.*?)pf: 0x[0-9A-Fa-f]+, ps: 0x[0-9A-Fa-f]+(.*)$", re.MULTILINE)


def _copy_message(block: str, suffix: str, index: int) -> str:
    """One message block of gateway.yaml renamed and moved to a unique PDU1 ID."""
    pf, ps = index % 240, index // 240
    assert ps < 0x20, "the shipped IDs use PS >= 0x20 or PF >= 0xF0; stay clear of them"
    old_id = int(_ID.search(block)[1], 16)
    new_id = (old_id & 0x1C0000FF) | pf << 16 | ps << 8
    block = _MESSAGE_START.sub(lambda m: f"  - name: {m[1]}{suffix}", block, count=1)
    block = re.sub(r"^(    c_name: \w+)", lambda m: f"{m[1]}{suffix}", block, count=1, flags=re.MULTILINE)  # the C name too
    block = _ID.sub(f"    id: 0x{new_id:08X}", block, count=1)
    return _J1939.sub(lambda m: f"{m[1]}pf: 0x{pf:02X}, ps: 0x{ps:02X}{m[2]}", block, count=1)


def replicate(out: Path, copies: int) -> tuple[int, int]:
    """The shipped spec with its messages repeated `copies` times; returns (messages, copies)."""
    if out.exists():
        shutil.rmtree(out)
    shutil.copytree(SHIPPED, out, ignore=shutil.ignore_patterns("ERRATA.md", "*.md", "v[0-9]*"))
    # The revisions are not copied (a replicated spec is no revision of V2.0.4): drop `previous:`.
    log = out / "history" / "changelog.yaml"
    log.write_text(re.sub(r"^previous: .*\n", "", log.read_text(encoding="utf-8"), flags=re.MULTILINE), encoding="utf-8")
    can = out / "can" / "gateway.yaml"
    text = can.read_text(encoding="utf-8")
    head, body = text.split("\nmessages:\n", 1)
    starts = [m.start() for m in _MESSAGE_START.finditer(body)]
    # Each block runs from its `- name:` line to the next one (comments before a message go with the previous one: harmless).
    blocks = [body[a:b] for a, b in zip(starts, starts[1:] + [len(body)])]
    prefix = body[: starts[0]]
    parts = [prefix, *blocks]
    for k in range(1, copies):
        for i, block in enumerate(blocks):
            copy = _copy_message(block, f"_c{k}", (k - 1) * len(blocks) + i)
            parts.append(copy if copy.endswith("\n") else copy + "\n")
    can.write_text(head + "\nmessages:\n" + "".join(parts), encoding="utf-8")
    return len(blocks) * copies, copies


_HEADER = """# Synthetic CAN protocol written by tools/synth_spec.py ({messages} messages, {signals} signals, seed {seed}).
schema_version: 1
kind: can_protocol
protocol: {{name: synthetic, version: 1.0.0}}
bus: {{bitrate: 250000, id_format: extended, addressing: j1939, byte_order: little_endian}}
nodes:
  - {{name: ECU, sa: 0xB0}}
  - {{name: CTRL, sa: 0xA0}}
value_tables:
  state:
    0: [off, 关]
    1: [on, 开]
    2: [error, 故障]
    3: [not_available, 不可用]
  level:
    0: [none, 无]
    1: [low, 低]
    2: [mid, 中]
    3: [high, 高]
    7: [invalid, 无效]
messages:
"""


def _signal_lines(rng: random.Random, count: int) -> list[str]:
    """`count` signals filling a 64-bit frame: a counter first, a checksum byte last, data between."""
    lines = []
    data = count - 2
    bits = 56 - 4  # counter: bits 0..3, checksum: byte 7
    widths = [bits // data + (1 if j < bits % data else 0) for j in range(data)]
    start = 4
    lines.append("      - {name: counter, zh: 心跳, start: 0, len: 4, range: [0, 15], role: counter}")
    for j, width in enumerate(widths):
        name = f"s{j:02d}"
        kind = rng.choice(["plain", "scaled", "signed", "enum", "special"] if width >= 3 else ["plain", "enum2"])
        if kind == "scaled":
            factor = rng.choice(["0.1", "0.5", "0.02", "2", "0.05"])
            extra = f", factor: {factor}, offset: -{rng.randint(0, 3) * 10}, unit: x"
        elif kind == "signed":
            extra = ", signed: true, factor: 0.25"
        elif kind == "enum":
            extra = ", values: level" if width >= 3 else ", values: state"
        elif kind == "enum2":
            extra = ", values: state" if width >= 2 else ""
        elif kind == "special":
            extra = f", special: {{{(1 << width) - 1}: [invalid, 无效]}}"
        else:
            extra = ""
        lines.append(f"      - {{name: {name}, zh: 信号{j}, start: {start}, len: {width}{extra}}}")
        start += width
    lines.append("      - {name: checksum, zh: 校验, start: 56, len: 8, range: [0, 255], role: checksum}")
    return lines


def synthesize(out: Path, messages: int, signals: int, seed: int) -> tuple[int, int]:
    if out.exists():
        shutil.rmtree(out)
    (out / "can").mkdir(parents=True)
    rng = random.Random(seed)
    per = [signals // messages + (1 if i < signals % messages else 0) for i in range(messages)]
    if min(per) < 3 or max(per) > 2 + 52:
        raise SystemExit("synth_spec: need 3..54 signals per message")
    parts = [_HEADER.format(messages=messages, signals=signals, seed=seed)]
    for i, count in enumerate(per):
        sender, sa, ps = ("CTRL", 0xA0, 0xB0) if i % 2 == 0 else ("ECU", 0xB0, 0xA0)
        pf, ps = i % 240, i // 240
        frame_id = 0x18000000 | pf << 16 | ps << 8 | sa
        parts.append(
            f"  - name: msg_{i:05d}\n    id: 0x{frame_id:08X}\n"
            f"    j1939: {{priority: 6, pf: 0x{pf:02X}, ps: 0x{ps:02X}, sa: 0x{sa:02X}}}\n"
            f"    sender: {sender}\n    receivers: ALL\n    cycle_ms: {rng.choice([10, 20, 50, 100, 1000])}\n    signals:\n"
            + "\n".join(_signal_lines(rng, count))
            + "\n"
        )
    (out / "can" / "synthetic.yaml").write_text("".join(parts), encoding="utf-8")
    (out / "canspec.yaml").write_text("schema_version: 1\nkind: bundle\nname: synthetic\nfiles:\n  - can/synthetic.yaml\n", encoding="utf-8")
    return messages, signals


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("out", type=Path)
    p.add_argument("--copies", type=int, help="repeat the shipped spec's messages this many times")
    p.add_argument("--messages", type=int, help="generate this many messages")
    p.add_argument("--signals", type=int, help="... holding this many signals in all")
    p.add_argument("--seed", type=int, default=1)
    args = p.parse_args(argv)
    if args.copies is not None:
        n, _ = replicate(args.out, args.copies)
        print(f"synth_spec: {args.out}: shipped spec x{args.copies} = {n} CAN messages", file=sys.stderr)
    elif args.messages and args.signals:
        synthesize(args.out, args.messages, args.signals, args.seed)
        print(f"synth_spec: {args.out}: {args.messages} messages, {args.signals} signals", file=sys.stderr)
    else:
        p.error("give --copies K, or --messages M --signals S")
    return 0


if __name__ == "__main__":
    sys.exit(main())
