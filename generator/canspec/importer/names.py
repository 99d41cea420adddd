"""Spec identifiers for the names a source file uses. The spec's names are lower_snake identifiers
(every target derives its own from them); a source name that is not one keeps its own spelling as
the DBC's name (`dbc_name`), so the DBC generated from the imported spec says what the source said."""

from __future__ import annotations

import re
from collections.abc import Callable

_NOT_IDENT = re.compile(r"[^a-z0-9]+")
_NOT_DBC = re.compile(r"[^A-Za-z0-9_]")


def identifier(text: str, fallback: str) -> str:
    """lower_snake: letters and digits kept, every other run one `_`; a digit first gets `n`."""
    ident = _NOT_IDENT.sub("_", text.lower()).strip("_")
    if not ident:
        return fallback
    return ident if ident[0].isalpha() else f"n{ident}"


class Namer:
    """Unique identifiers within one scope (a message's signals, a spec's messages, a table's labels),
    and the DBC's spellings of the scope's source names (`sources`)."""

    def __init__(self, sources: tuple[str, ...] = ()) -> None:
        self.taken: set[str] = set()
        self.spelt = {n for n in sources if not _NOT_DBC.search(n)}

    def dbc(self, text: str, warn: Callable[[str], None]) -> str:
        """The source's name as a DBC can write it: itself, or (a KCD, SYM or ARXML name with spaces
        or signs, `Switch Outputs`) each other character as `_`, made unique in the scope, with a warning."""
        if not _NOT_DBC.search(text):
            return text
        base = _NOT_DBC.sub("_", text)
        fixed, n = base, 2
        while fixed in self.spelt:
            fixed, n = f"{base}_{n}", n + 1
        self.spelt.add(fixed)
        warn(f"name {text!r} is not a DBC identifier: the DBC writes {fixed}")
        return fixed

    def name(self, text: str, fallback: str) -> str:
        base = identifier(text, fallback)
        ident, n = base, 2
        while ident in self.taken:
            ident, n = f"{base}_{n}", n + 1
        self.taken.add(ident)
        return ident
