"""DBC for the CAN protocol, with the attributes of Vector's J1939 template where the bus uses
J1939 addressing. Encoding: UTF-8 (see the README): identifiers are ASCII, Chinese text appears
only in CM_ comments and units. model.py decides every line's content, naming.py the signal names
(unique where a spec name has different definitions), attributes.py Vector's enumerations."""

from __future__ import annotations

from canspec import ir
from canspec.render.environment import render
from canspec.targets import Target
from canspec.targets.dbc import attributes, model, naming, refusals


def render_dbc(spec: ir.Spec) -> dict[str, bytes]:
    if spec.can is None:
        return {}
    text = render(
        "dbc/protocol.dbc.j2",
        spec,
        "dbc",
        dbc=model.build(spec, spec.can),
        unknown_node=model.UNKNOWN_NODE,
        sig_types=attributes.SIG_TYPES,
        send_types=attributes.MSG_SEND_TYPES,
        default_send_type=attributes.MSG_SEND_TYPES[attributes.NOT_CYCLIC],
        max_cycle_ms=attributes.MAX_CYCLE_MS,
        spec_name_attribute=naming.SPEC_NAME_ATTRIBUTE,
    )
    return {f"dbc/{spec.can.name}.dbc": text.encode("utf-8")}


TARGET = Target("dbc", "DBC database (Vector J1939 attributes, UTF-8)", "dbc/", render_dbc, order=10, check=refusals.problems)
