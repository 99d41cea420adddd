"""Signal names in the DBC.

By default (`protocol: {dbc_signal_names: per_message}`) the DBC names every signal as the spec
does (its `dbc_name`, else its name), per message, as every DBC tool does: a cantools user types
`counter`, whatever other messages call their counters.

The formats a DBC is converted to, and the converters (canmatrix and cantools: SYM, KCD, ARXML),
keep one definition per signal *name*: the value table a SYM enum is named after, the ARXML system
signal, I-signal, compu method and unit, cantools' SYM signal list. Two messages with an 8-bit and
a 4-bit `counter` come back as two 8-bit counters, and value tables are swapped. For those,
`dbc_signal_names: unique` writes a name that carries different definitions in different messages
(anything the DBC says about the signal apart from where it sits in the frame: length, sign,
scaling, range, unit, value labels, SigType, comment, receivers) as `<name>_<frame ID>`
(`counter_1805B0A0`, `mode_123`) in every message that has it; a name with one definition
everywhere keeps its name. A renamed name keeps to the 32 characters Vector's tools want (the name
is shortened, never the ID) and says the spec's name in the signal's comment and in its
`SpecSignalName` attribute, which `canspec diff` reads. Only the DBC is renamed: the C, Python and
Rust APIs keep the spec's names.
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Hashable, Iterator

from canspec import ir
from canspec.targets.dbc.attributes import sig_type
from canspec.targets.dbc.comments import signal_comment

MAX_NAME = 32
SPEC_NAME_ATTRIBUTE = "SpecSignalName"


def definition(msg: ir.Message, sig: ir.Signal) -> Hashable:
    """What the DBC says about a signal apart from its place in the frame."""
    labels = tuple((lb.raw, lb.name) for lb in sig.labels)
    return (sig.length, sig.signed, sig.factor, sig.offset, sig.phys_min, sig.phys_max, sig.unit, labels,
            sig_type(msg, sig), signal_comment(sig, None), msg.receivers)


def _data_signals(can: ir.CanProtocol) -> Iterator[tuple[ir.Message, ir.Signal]]:
    return ((msg, sig) for msg in can.messages for sig in msg.data_signals)


def signal_names(can: ir.CanProtocol) -> dict[tuple[str, str], str]:
    """(message name, spec signal name) → the signal's name in the DBC, for every data signal."""
    if can.dbc_signal_names != "unique":
        return {(msg.name, sig.name): sig.dbc_name for msg, sig in _data_signals(can)}
    definitions: dict[str, set[Hashable]] = defaultdict(set)
    for msg, sig in _data_signals(can):
        definitions[sig.dbc_name].add(definition(msg, sig))
    ambiguous = {name for name, defs in definitions.items() if len(defs) > 1}
    taken = set(definitions) - ambiguous
    names = {}
    for msg, sig in _data_signals(can):
        if sig.dbc_name in ambiguous:
            names[(msg.name, sig.name)] = _unique(sig.dbc_name, msg.id_text[2:], taken)
            taken.add(names[(msg.name, sig.name)])
        else:
            names[(msg.name, sig.name)] = sig.dbc_name
    return names


def _unique(name: str, frame_id: str, taken: set[str]) -> str:
    """`name_<frame ID>`, within MAX_NAME characters, not yet taken (a `_2`, `_3` … after the ID
    only when a spec name already looks like a renamed one, or two long names shorten alike)."""
    n = 1
    while True:
        suffix = f"_{frame_id}" + (f"_{n}" if n > 1 else "")
        candidate = name[: max(1, MAX_NAME - len(suffix))] + suffix
        if candidate not in taken:
            return candidate
        n += 1
