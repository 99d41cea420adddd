"""The changelog that checks itself: the spec's changelog names its previous revision
(`previous:`, a path relative to the changelog file), and the items of its newest version must
agree with `canspec diff previous this-spec`. A computed change no item accounts for is a
missing entry; an item that names a change the diff does not show is an invented one. Docs-only
changes (names as printed, descriptions) are not required in the record."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from canspec import ir
from canspec.diff.compare import Change, compare, declared_frame_id, subject
from canspec.diff.model import from_spec
from canspec.diff.release import UNRECONSTRUCTED, declares
from canspec.pipeline import compile_spec
from canspec.spec.loader import display_name, load
from canspec.spec.problems import Problem, SpecError, error, warning


def _describe(c: Change) -> str:
    what = f"{c.message}.{c.signal}" if c.signal else c.message
    return f"{c.kind} {c.subject} {what} ({c.detail})"


def _item_problems(item: Any, item_label: str, changes: list[Change], old_version: str, covered: set[int]) -> list[Problem]:
    """One changelog item against the diff: what it names that the diff does not show; the changes it covers go into `covered`."""
    problems: list[Problem] = []
    declared = item.get("changes")
    if declared is None:
        ids = item.get("ids", [])
        if not ids:
            problems.append(warning(f"{item_label} names no message, so it cannot be checked against the diff", item.loc,
                                    "add `ids: [0x...]` or `changes: [...]`", "changelog-unchecked"))
        for fid in ids:
            hits = [i for i, c in enumerate(changes) if c.frame_id == fid]
            if not hits:
                problems.append(error(f"{item_label} names 0x{fid:08X}, but the diff from {old_version} shows no change there", item.loc_of("ids"),
                                      "remove the entry or make the spec change it describes", "changelog-invented"))
            covered.update(hits)
        return problems
    for j, d in enumerate(declared):
        if d["kind"] == UNRECONSTRUCTED:
            continue
        hits = [i for i, c in enumerate(changes) if declares(d, c)]
        if not hits:
            what = f" {d['signal']}" if "signal" in d else ""
            where = subject(declared_frame_id(d["message"]))
            problems.append(error(f"{item_label} declares {d['kind']}{what} in {where}, which the diff from {old_version} does not show",
                                  declared.loc_of(j), "remove the entry or make the spec change it describes", "changelog-invented"))
        covered.update(hits)
    return problems


def changelog_problems(spec_path: str | Path | None, spec: ir.Spec) -> list[Problem]:
    """Problems of the changelog-vs-diff rule for a spec that already compiled to `spec`."""
    try:
        loaded = load(spec_path)
    except SpecError:
        return []
    docs = loaded.of_kind("changelog")
    if not docs or "previous" not in docs[0].data or spec.can is None:
        return []
    doc = docs[0]
    data, versions = doc.data, doc.data["versions"]
    prev_loc = data.loc_of("previous")
    prev_path = doc.path.parent / data["previous"]
    compiled = compile_spec(prev_path)
    if compiled.spec is None or compiled.spec.can is None:
        first = compiled.errors[0].format().splitlines()[0] if compiled.errors else "it has no CAN protocol"
        return [error(f"`previous` revision {display_name(prev_path)} does not load: {first}", prev_loc,
                      "point `previous` at the previous revision's spec bundle (relative to this changelog file)", "changelog-previous")]
    old, new = from_spec(compiled.spec, str(prev_path)), from_spec(spec, str(spec_path or "spec"))
    newest = versions[-1]
    problems: list[Problem] = []
    expected_prev = str(versions[-2]["version"]) if len(versions) > 1 else None
    if old.version != expected_prev:
        problems.append(error(f"`previous` is version {old.version}, but the version before {newest['version']} in this changelog is {expected_prev}",
                              prev_loc, "point `previous` at the revision listed just before the newest one", "changelog-previous"))
        return problems
    changes = [c for c in compare(old, new) if c.cls != "docs"]
    covered: set[int] = set()
    label = f"V{newest['version']}"
    for n, item in enumerate(newest["items"], start=1):
        problems.extend(_item_problems(item, f"{label} item {n}", changes, old.version, covered))
    problems.extend(_since_problems(spec, changes, str(newest["version"]), old.version))
    for i, c in enumerate(changes):
        if i not in covered:
            problems.append(error(f"{label}: the diff from {old.version} shows a {c.cls} change that no item records: {_describe(c)}",
                                  versions.loc_of(len(versions) - 1),
                                  f"add an item (with `changes: [{{kind: {c.kind}, message: {c.subject}"
                                  + (f", signal: {c.signal}" if c.signal else "") + "}]`) or undo the change", "changelog-missing"))
    return problems


def _since_problems(spec: ir.Spec, changes: list[Change], newest: str, previous: str | None) -> list[Problem]:
    """A signal marked `since: <newest>` must be one the diff shows as added in that version."""
    added = {(c.frame_id, c.signal) for c in changes if c.kind == "signal_added"} | {(c.frame_id, None) for c in changes if c.kind == "message_added"}
    out = []
    for msg in spec.can.messages if spec.can is not None else ():
        for sig in msg.signals:
            if sig.since == newest and (msg.frame_id, sig.name) not in added and (msg.frame_id, None) not in added:
                out.append(error(f"signal {sig.name!r} of 0x{msg.frame_id:08X} says `since: {newest}`, but the diff from {previous} does not show it added",
                                 sig.loc, "fix `since` or the previous revision", "changelog-since"))
    return out
