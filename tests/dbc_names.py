"""cantools reading a canspec DBC under the spec's signal names. The DBC writes a signal whose spec
name has different definitions in different messages as `<name>_<frame ID>` and states its spec
name in the SpecSignalName attribute (generator/canspec/targets/dbc/naming.py); tests that compare
cantools with the generated code signal by signal read the DBC this way. (tests/targets/dbc reads it as is.)"""

from __future__ import annotations

from pathlib import Path
from typing import Any


def load_with_spec_names(path: Path | str, strict: bool = True) -> Any:
    import cantools

    db = cantools.database.load_file(str(path), encoding="utf-8", strict=strict)
    for msg in db.messages:
        for sig in msg.signals:
            spec_name = (sig.dbc.attributes if sig.dbc is not None else {}).get("SpecSignalName")
            if spec_name is not None:
                sig.name = spec_name.value
    db.refresh()  # rebuild the lookups by name
    return db
