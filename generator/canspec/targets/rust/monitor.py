"""The Rust view of the receive monitor's configuration (`src/supervision.rs`): one rule per
message — from the message type's constants where it has them — and the protocol's fault-code
tables, with the rules' indexes. The monitor itself is the static `src/monitor.rs`."""

from __future__ import annotations

from dataclasses import dataclass

from canspec import ir
from canspec.render.literals import RUST
from canspec.targets.rust.model import RustCrate


@dataclass(frozen=True)
class RustRule:
    type: str
    timeout: str  # the rule's `timeout_ms`
    counter: str
    checksum: str


@dataclass(frozen=True)
class RustFaultTable:
    name: str
    none: str
    timeout: str
    checksum: str  # the `&[(rule index, code)]` slice


@dataclass(frozen=True)
class RustSupervision:
    rules: tuple[RustRule, ...]
    tables: tuple[RustFaultTable, ...]
    uses_counter: bool
    uses_checksum: bool
    uses_cycles: bool  # a cyclic message: monitor_rules reads its timeout_cycles


def _rule(name: str, msg: ir.Message) -> RustRule:
    c, k = msg.counter, msg.checksum
    return RustRule(
        type=name,
        timeout=f"Some(crate::messages::{name}::CYCLE_TIME_MS * timeout_cycles)" if msg.is_cyclic else "None",
        counter=f"Some(CounterRule {{ start: {c.start}, length: {c.length}, big_endian: {str(c.word_order == 'big').lower()} }})" if c is not None else "None",
        checksum=f"Some(ChecksumRule {{ byte: {k.byte}, covers: {RUST.integer(sum(1 << b for b in k.covers))} }})" if k is not None else "None",
    )


def build_supervision(can: ir.CanProtocol, crate: RustCrate) -> RustSupervision:
    index = {m.msg.name: i for i, m in enumerate(crate.messages)}
    tables = tuple(
        RustFaultTable(t.table, str(t.none), str(t.timeout), "&[" + ", ".join(f"({index[n]}, {code})" for n, code in t.checksum) + "]")
        for t in can.fault_tables
    )
    return RustSupervision(
        rules=tuple(_rule(m.name, m.msg) for m in crate.messages), tables=tables, uses_counter=can.has_counters, uses_checksum=can.has_checksums,
        uses_cycles=can.has_cyclic,
    )
