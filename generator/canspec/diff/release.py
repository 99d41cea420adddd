"""A release's declared change record beside the computed diff: for every item the new revision's
change record declares between the two versions, the computed changes it accounts for and what it
declares that the diff does not show; and the computed changes no item declares. (`canspec
check` enforces the same agreement for the newest version, history.py; this shows it.)

An item matches by its `changes` entries (kind, message, signal), or, without them, by the
message IDs it names. Docs-class changes need no item."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from canspec import ir
from canspec.diff.compare import Change, declared_frame_id

UNRECONSTRUCTED = "unreconstructed"  # a declared change the reconstructed revisions cannot show


def declares(entry: Mapping[str, Any], change: Change) -> bool:
    """Whether a declared `changes` entry is this computed change."""
    same_place = change.frame_id == declared_frame_id(entry["message"]) and ("signal" not in entry or change.signal == entry["signal"])
    return change.kind == entry["kind"] and same_place


@dataclass(frozen=True)
class ItemCheck:
    version: ir.ChangeVersion
    item: ir.ChangeItem
    changes: tuple[int, ...]  # indices of the computed changes the item accounts for
    missing: tuple[str, ...]  # what the item declares that the diff does not show
    unreconstructed: tuple[str, ...]  # declared changes no revision can show, with the record's reason


@dataclass(frozen=True)
class Release:
    versions: tuple[ir.ChangeVersion, ...]  # the record's versions after the old revision, up to the new one
    items: tuple[ItemCheck, ...]
    undeclared: tuple[int, ...]  # computed changes (docs excepted) no item accounts for

    def declared_in(self, index: int) -> list[str]:
        """`V2.0.5 #2` for every item that accounts for computed change `index`."""
        return [f"V{c.version.version} #{c.item.number}" for c in self.items if index in c.changes]


def released(log: ir.Changelog, old_version: str | None, new_version: str | None) -> tuple[ir.ChangeVersion, ...]:
    names = [v.version for v in log.versions]
    if new_version not in names:
        return ()
    end = names.index(new_version)
    start = names.index(old_version) + 1 if old_version in names and names.index(old_version) < end else end
    return log.versions[start : end + 1]


def _check(version: ir.ChangeVersion, item: ir.ChangeItem, changes: list[Change]) -> ItemCheck:
    unknown = tuple(f"0x{e['message']:08X}: {e.get('reason', 'not reconstructed')}" for e in item.changes if e["kind"] == UNRECONSTRUCTED)
    if item.changes:
        entries = [e for e in item.changes if e["kind"] != UNRECONSTRUCTED]
        hits = [i for i, c in enumerate(changes) if any(declares(e, c) for e in entries)]
        missing = [
            f"{e['kind']} 0x{e['message']:08X}" + (f" {e['signal']}" if "signal" in e else "") for e in entries if not any(declares(e, c) for c in changes)
        ]
    else:
        hits = [i for i, c in enumerate(changes) if c.frame_id in item.ids]
        missing = [f"0x{fid:08X}: no change" for fid in item.ids if not any(c.frame_id == fid for c in changes)]
    return ItemCheck(version, item, tuple(hits), tuple(missing), unknown)


def release(log: ir.Changelog | None, old_version: str | None, new_version: str | None, changes: list[Change]) -> Release | None:
    """None when the new revision has no change record (a DBC, or a spec without one)."""
    if log is None:
        return None
    versions = released(log, old_version, new_version)
    items = tuple(_check(v, item, changes) for v in versions for item in v.items)
    covered = {i for check in items for i in check.changes}
    return Release(versions, items, tuple(i for i, c in enumerate(changes) if c.cls != "docs" and i not in covered))
