"""`canspec simulate [SPEC] --node NAME`: a rest-bus simulator on a python-can bus.

Sends every message the node transmits at its cycle time, with live counters and checksums,
until --duration seconds have passed or Ctrl-C. Values and faults are set on the command line
and, while it runs, by lines on stdin:

    set MESSAGE SIGNAL=VALUE [SIGNAL=VALUE ...]     physical values (range-checked)
    fault MESSAGE drop|corrupt_checksum|freeze_counter
    clear MESSAGE                                   back to good frames
    send MESSAGE                                    one frame now (event-driven messages)
"""

from __future__ import annotations

import argparse
import sys
import threading
import time
from collections.abc import Iterable

from canspec.commands.common import add_spec_argument, compile_or_report, number_in
from canspec.runtime.simulate import RestBus, SimulationError

MAX_DURATION = 365 * 24 * 3600  # a year; without --duration it runs until Ctrl-C
MAX_BITRATE = 20_000_000  # CAN XL's fastest data phase; no CAN controller runs faster


def register(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    p = sub.add_parser("simulate", help="rest-bus simulation of a node on a python-can bus", description=__doc__,
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    add_spec_argument(p)
    p.add_argument("--node", required=True, help="the node to simulate (its messages are sent)")
    p.add_argument("--interface", default="virtual", help="python-can interface: virtual, socketcan, pcan, ... (default virtual)")
    p.add_argument("--channel", default="canspec", help="python-can channel, e.g. vcan0 (default canspec)")
    p.add_argument("--bitrate", type=number_in(int, 1, MAX_BITRATE, "bit/s"), help="bitrate for interfaces that set it (default: the spec's)")
    p.add_argument("--duration", type=number_in(float, 0, MAX_DURATION, "seconds; without --duration it runs until Ctrl-C"),
                   help="seconds to run, 0 sends each message once (default: until Ctrl-C)")
    p.add_argument("--message", action="append", default=[], metavar="NAME", help="also send this message (e.g. one whose sender is ALL)")
    p.add_argument("--set", action="append", default=[], metavar="MESSAGE.SIGNAL=VALUE", help="a physical value at start")
    p.add_argument("--fault", action="append", default=[], metavar="MESSAGE=KIND", help="a fault at start: drop, corrupt_checksum, freeze_counter")
    p.set_defaults(func=run)


def command(sim: RestBus, line: str) -> str:
    """Apply one command line; what it did."""
    words = line.split()
    if not words:
        return ""
    verb, args = words[0], words[1:]
    if verb == "set" and len(args) >= 2 and all("=" in a for a in args[1:]):
        values = dict(a.split("=", 1) for a in args[1:] if "=" in a)
        sim.set(args[0], **{k: _number(v) for k, v in values.items()})
        return f"set {args[0]} {values}"
    if verb == "fault" and len(args) == 2:
        sim.inject(args[0], args[1])
        return f"fault {args[0]} {args[1]}"
    if verb == "clear" and len(args) == 1:
        sim.clear(args[0])
        return f"cleared {args[0]}"
    if verb == "send" and len(args) == 1:
        return f"sent {args[0]}" if sim.send(args[0]) else f"{args[0]} is dropped"
    usage = {"set": "set MESSAGE SIGNAL=VALUE...", "fault": "fault MESSAGE KIND", "clear": "clear MESSAGE", "send": "send MESSAGE"}
    if verb in usage:
        raise SimulationError(f"{line.strip()!r}: expected `{usage[verb]}`")
    raise SimulationError(f"unknown command {line.strip()!r}: set, fault, clear or send")


def _number(text: str) -> float | int | str:
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def _start_values(sim: RestBus, sets: Iterable[str], faults: Iterable[str]) -> None:
    for item in sets:
        target, _, value = item.partition("=")
        message, _, signal = target.partition(".")
        if not (value and signal):
            raise SimulationError(f"--set {item!r}: expected MESSAGE.SIGNAL=VALUE")
        sim.set(message, **{signal: _number(value)})
    for item in faults:
        message, _, kind = item.partition("=")
        try:
            sim.inject(message, kind)
        except ValueError as exc:
            raise SimulationError(f"--fault {item!r}: {exc}") from None


def _read_commands(sim: RestBus) -> None:
    try:
        for line in iter(sys.stdin.readline, ""):
            try:
                said = command(sim, line)
            except (SimulationError, ValueError) as exc:
                said = f"error: {exc}"
            if said:
                print(said, file=sys.stderr, flush=True)
    except (OSError, ValueError):  # no readable stdin
        return


def run(args: argparse.Namespace) -> int:
    compiled = compile_or_report(args.spec, quiet_warnings=True, cached=True)
    if compiled.spec is None or compiled.spec.can is None:
        print("canspec simulate: the spec has no CAN protocol" if compiled.spec is not None else "canspec simulate: the spec has errors", file=sys.stderr)
        return 1
    import can  # python-can: canspec[logs] (cli.main names the extra when it is missing)

    can_ir = compiled.spec.can
    try:
        bus = can.Bus(interface=args.interface, channel=args.channel, bitrate=args.bitrate or can_ir.bus.bitrate)
    except (can.CanError, ValueError, OSError, ImportError) as exc:
        print(f"canspec simulate: cannot open {args.interface} channel {args.channel}: {exc}", file=sys.stderr)
        return 1
    with bus:
        try:
            sim = RestBus(can_ir, args.node, bus, messages=args.message)
            _start_values(sim, args.set, args.fault)
        except (SimulationError, ValueError) as exc:
            print(f"canspec simulate: {exc}", file=sys.stderr)
            return 1
        print(f"canspec simulate: {args.node} on {args.interface} {args.channel}: {', '.join(sim.messages) or 'no messages'}", file=sys.stderr)
        threading.Thread(target=_read_commands, args=(sim,), daemon=True).start()
        started = time.monotonic()
        try:
            sim.run(args.duration)
        except KeyboardInterrupt:
            sim.stop()
        took = time.monotonic() - started
        sent = ", ".join(f"{m} {sim.frames_sent(m)}" for m in sim.messages)
        print(f"canspec simulate: {took:.1f} s, frames sent: {sent or 'none'}", file=sys.stderr)
    return 0

