"""cantools reading a canspec DBC under the spec's names. With `dbc_signal_names: unique` the DBC
writes a signal whose spec name has different definitions in different messages as
`<name>_<frame ID>` and states its spec name in the SpecSignalName attribute
(generator/canspec/targets/dbc/naming.py); a spec's `dbc_name` (what `canspec import` records) is
what the DBC writes for a message or signal; tests that compare cantools with the generated code
signal by signal read the DBC this way. (tests/targets/dbc reads it as is.)

A DBC name may start with a digit where a source's did (`0_COUNTER`): cantools' grammar refuses
those, so they are read under a prefix outside quoted text (a digit-run-underscore word is never a
DBC number) and renamed back."""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

_DIGIT_NAME = re.compile(r"(?<![\w.+-])(\d+_\w*)")
PREFIX = "DIGIT__"


def _readable(text: str) -> str:
    parts = text.split('"')
    return '"'.join(_DIGIT_NAME.sub(PREFIX + r"\1", p) if k % 2 == 0 else p for k, p in enumerate(parts))


def load_with_spec_names(path: Path | str, strict: bool = True, can: Any = None) -> Any:
    """`can`: the spec's IR (`ir.CanProtocol`), to read `dbc_name`s back as spec names."""
    import cantools

    db = cantools.database.load_string(_readable(Path(path).read_text(encoding="utf-8")), database_format="dbc", strict=strict)
    for msg in db.messages:
        msg.name = msg.name.removeprefix(PREFIX)
        names = {}
        for sig in msg.signals:
            spec_name = (sig.dbc.attributes if sig.dbc is not None else {}).get("SpecSignalName")
            names[sig.name] = spec_name.value if spec_name is not None else sig.name.removeprefix(PREFIX)
        _rename(msg, names)
    if can is not None:
        for m in can.messages:
            msg = next((x for x in db.messages if x.frame_id == m.frame_id and bool(x.is_extended_frame) == m.is_extended), None)
            if msg is None:
                continue
            msg.name = m.name
            _rename(msg, {s.dbc_name: s.name for s in m.data_signals})
    db.refresh()  # rebuild the lookups by name
    return db


def _rename(msg: Any, names: dict[str, str]) -> None:
    """The message's signals renamed (old → new, all at once), and the multiplexer each page names."""
    for sig in msg.signals:
        sig.name = names.get(sig.name, sig.name)
        if sig.multiplexer_signal is not None:
            sig.multiplexer_signal = names.get(sig.multiplexer_signal, sig.multiplexer_signal)
