"""What a DBC cannot express, refused by `canspec check` with the spec's line and column."""

from __future__ import annotations

from collections.abc import Iterator

from canspec import ir
from canspec.spec.problems import Problem, error
from canspec.targets.dbc.model import UNKNOWN_NODE

# Words a DBC reads as keywords wherever they stand (cantools' DBC grammar, Vector's DBC format).
KEYWORDS = frozenset({
    "BA_", "BA_DEF_", "BA_DEF_DEF_", "BA_DEF_DEF_REL_", "BA_DEF_REL_", "BA_DEF_SGTYPE_", "BA_REL_", "BA_SGTYPE_", "BO_",
    "BO_TX_BU_", "BS_", "BU_", "BU_BO_REL_", "BU_EV_REL_", "BU_SG_REL_", "CAT_", "CAT_DEF_", "CM_", "ENVVAR_DATA_", "EV_",
    "EV_DATA_", "FILTER", "NS_", "NS_DESC_", "SG_", "SG_MUL_VAL_", "SGTYPE_", "SGTYPE_VAL_", "SIG_GROUP_", "SIG_TYPE_REF_",
    "SIG_VALTYPE_", "SIGTYPE_VALTYPE_", "VAL_", "VAL_TABLE_", "VERSION",
})


def problems(spec: ir.Spec) -> Iterator[Problem]:
    """Node names are the only spec names a DBC keyword can be (messages and signals are lower case)."""
    for node in spec.can.nodes if spec.can is not None else ():
        if node.name in KEYWORDS or node.name == UNKNOWN_NODE:
            meaning = "its 'no node'" if node.name == UNKNOWN_NODE else "a keyword"
            yield error(f"node name {node.name!r} cannot be written in a DBC: the DBC format reads it as {meaning}", node.loc,
                        "rename the node (its `label` may keep the printed name)", "dbc-node-name")
