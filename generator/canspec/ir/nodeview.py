"""One node's view of a spec (`canspec gen --node NAME`): only the messages that node sends or
receives, with the value and fault tables they use, so an ECU's headers hold nothing else.
Targets render a view like any spec; `Spec.node` names the node in every file's header."""

from __future__ import annotations

from dataclasses import replace

from canspec.ir.model import Message
from canspec.ir.protocol_model import CanProtocol
from canspec.ir.spec_model import Spec


def node_names(spec: Spec) -> tuple[str, ...]:
    return tuple(n.name for n in spec.can.nodes) if spec.can is not None else ()


def involves(msg: Message, node: str) -> bool:
    """Whether `node` sends or receives `msg` (a message every node sends involves every node;
    receivers "ALL" are already spelled out in the IR)."""
    return msg.sender in (node, "ALL") or node in msg.receivers


def traffic(can: CanProtocol, node: str) -> tuple[int, int, int]:
    """(messages in the node's view, messages it sends, messages it receives); a message every
    node sends counts as both."""
    kept = sum(involves(m, node) for m in can.messages)
    sends = sum(m.sender in (node, "ALL") for m in can.messages)
    receives = sum(node in m.receivers and m.sender != node for m in can.messages)
    return kept, sends, receives


def for_node(spec: Spec, node: str) -> Spec:
    """The spec as `node` sees it. `node` must be one of `node_names(spec)`."""
    if node not in node_names(spec):
        raise ValueError(f"no node {node!r} in the spec (nodes: {', '.join(node_names(spec)) or 'none'})")
    assert spec.can is not None
    return replace(spec, can=_can_for_node(spec.can, node), node=node)


def _can_for_node(can: CanProtocol, node: str) -> CanProtocol:
    messages = tuple(m for m in can.messages if involves(m, node))
    kept = {m.name for m in messages}
    tables = {s.value_table.name for m in messages for s in m.signals if s.value_table is not None}
    faults = tuple(replace(f, checksum=tuple((name, code) for name, code in f.checksum if name in kept)) for f in can.fault_tables if f.table in tables)
    return replace(can, messages=messages, value_tables=tuple(t for t in can.value_tables if t.name in tables), fault_tables=faults)
