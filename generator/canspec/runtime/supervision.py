"""The receive monitor (runtime/monitor.py) configured from the IR: one rule per message, the
protocol's fault-code tables, and the IR's default parameters. `canspec decode --report`, the
sequence vectors and the simulator's tests use it; a generated Python package builds the same
rules from its message classes."""

from __future__ import annotations

from canspec import ir
from canspec.runtime.monitor import ChecksumRule, CounterRule, FaultTable, MessageRule, Monitor


def message_rule(msg: ir.Message, timeout_cycles: int = ir.MONITOR_TIMEOUT_CYCLES) -> MessageRule:
    return MessageRule(
        name=msg.name,
        frame_id=msg.frame_id,
        extended=msg.is_extended,
        dlc=msg.dlc,
        timeout_ms=msg.cycle_ms * timeout_cycles if msg.cycle_ms is not None else None,
        counter=CounterRule(msg.counter.start, msg.counter.length, msg.counter.word_order) if msg.counter is not None else None,
        checksum=ChecksumRule(msg.checksum.byte, msg.checksum.cover_mask) if msg.checksum is not None else None,
    )


def fault_tables(can: ir.CanProtocol) -> tuple[FaultTable, ...]:
    return tuple(FaultTable(t.table, t.none, t.timeout, dict(t.checksum)) for t in can.fault_tables)


def new_monitor(
    can: ir.CanProtocol,
    *,
    timeout_cycles: int = ir.MONITOR_TIMEOUT_CYCLES,
    counter_tolerance: int = ir.MONITOR_COUNTER_TOLERANCE,
    valid_after: int = ir.MONITOR_VALID_AFTER,
) -> Monitor:
    """A monitor of every message of the protocol, reporting in its fault-code tables."""
    return Monitor(
        (message_rule(m, timeout_cycles) for m in can.messages),
        fault_tables=fault_tables(can),
        counter_tolerance=counter_tolerance,
        valid_after=valid_after,
    )
