"""Spec identifiers for the names a source file uses. The spec's names are lower_snake identifiers
(every target derives its own from them); a source name that is not one keeps its own spelling as
the DBC's name (`dbc_name`), so the DBC generated from the imported spec says what the source said."""

from __future__ import annotations

import re

_NOT_IDENT = re.compile(r"[^a-z0-9]+")


def identifier(text: str, fallback: str) -> str:
    """lower_snake: letters and digits kept, every other run one `_`; a digit first gets `n`."""
    ident = _NOT_IDENT.sub("_", text.lower()).strip("_")
    if not ident:
        return fallback
    return ident if ident[0].isalpha() else f"n{ident}"


class Namer:
    """Unique identifiers within one scope (a message's signals, a spec's messages, a table's labels)."""

    def __init__(self) -> None:
        self.taken: set[str] = set()

    def name(self, text: str, fallback: str) -> str:
        base = identifier(text, fallback)
        ident, n = base, 2
        while ident in self.taken:
            ident, n = f"{base}_{n}", n + 1
        self.taken.add(ident)
        return ident
