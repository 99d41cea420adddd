"""One node's view (`canspec gen --node NAME`): the messages it keeps are exactly those cantools,
reading the generated DBC, lists with that node as sender or as a receiver of a signal; the value
and fault tables are the ones those messages use; an unknown node is refused."""

from __future__ import annotations

import pytest
from canspec.ir.nodeview import for_node, node_names
from canspec.render.environment import header_lines


def test_every_node_keeps_exactly_its_messages_per_the_dbc(spec, db):
    """A DBC names receivers per signal: a message without signals (vehicle_state_5, its layout
    undefined) is judged by its sender and the spec's receivers."""
    assert node_names(spec) == tuple(n.name for n in db.nodes)
    bare = {m.frame_id: m for m in spec.can.messages if not m.data_signals}
    assert bare, "the shipped spec has a message without signals"
    for node in node_names(spec):
        view = for_node(spec, node)
        want = {m.frame_id for m in db.messages if node in m.senders or any(node in s.receivers for s in m.signals)}
        want |= {i for i, m in bare.items() if node in m.receivers}
        assert {m.frame_id for m in view.can.messages} == want, node
        assert view.node == node and view.sha256 == spec.sha256


def test_tables_are_the_ones_its_messages_use(spec):
    for node in node_names(spec):
        can = for_node(spec, node).can
        used = {s.value_table.name for m in can.messages for s in m.signals if s.value_table is not None}
        assert {t.name for t in can.value_tables} == used, node
        kept = {m.name for m in can.messages}
        for fault in can.fault_tables:
            assert fault.table in used and {name for name, _ in fault.checksum} <= kept


def test_a_node_view_says_so_in_every_header(spec):
    node = node_names(spec)[0]
    assert not any(node in line for line in header_lines(spec, "c"))
    assert f"Node {node}: only the messages it sends or receives" in "\n".join(header_lines(for_node(spec, node), "c"))


def test_unknown_node_is_refused(spec):
    with pytest.raises(ValueError, match="no node 'NOPE' in the spec"):
        for_node(spec, "NOPE")
