"""The IR of a whole spec: its CAN protocol, its JSON protocols and its change record."""

from __future__ import annotations

from dataclasses import dataclass

from canspec.ir.json_model import JsonProtocol
from canspec.ir.protocol_model import CanProtocol

# --- change record -----------------------------------------------------------------------


@dataclass(frozen=True)
class ChangeItem:
    number: int
    zh: str
    en: str
    ids: tuple[int, ...]
    errata: tuple[str, ...]
    changes: tuple[dict, ...]  # type: ignore[type-arg]


@dataclass(frozen=True)
class ChangeVersion:
    version: str
    date: str | None
    authors: tuple[str, ...]
    label: str
    label_zh: str
    items: tuple[ChangeItem, ...]
    errata: tuple[str, ...]


@dataclass(frozen=True)
class Changelog:
    protocol: str
    versions: tuple[ChangeVersion, ...]  # oldest first

    def date_of(self, version: str) -> str | None:
        """The date the record gives a version (its release date), if any."""
        return next((v.date for v in self.versions if v.version == version and v.date), None)


# --- the whole spec ----------------------------------------------------------------------


@dataclass(frozen=True)
class Spec:
    name: str  # bundle name (or the CAN protocol's)
    version: str  # the CAN protocol version (or the JSON one when there is no CAN protocol)
    sha256: str  # hash of the spec files' bytes
    can: CanProtocol | None
    json: tuple[JsonProtocol, ...]
    changelog: Changelog | None
    generator_version: str
    errata_md: str | None = None  # text of ERRATA.md beside the bundle, if any (rendered by the docs)
    node: str | None = None  # set in one node's view (ir/nodeview.py): only its messages
