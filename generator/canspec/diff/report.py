"""Render a diff as text, Markdown or JSON (data built in Python, shaped here)."""

from __future__ import annotations

import json
from dataclasses import dataclass
from itertools import groupby

from canspec.diff.classes import LADDER, TITLES, bump_note, suggest_bump
from canspec.diff.compare import Change, subject
from canspec.diff.model import ProtocolModel


@dataclass(frozen=True)
class Summary:
    counts: dict[str, int]
    strictest: str | None
    bump: str
    suggested: str | None
    why: str
    note: str | None  # the new version bumps less than the changes suggest


def summarize(old: ProtocolModel, new: ProtocolModel, changes: list[Change]) -> Summary:
    counts = {c: sum(1 for ch in changes if ch.cls == c) for c in LADDER}
    classes = {ch.cls for ch in changes}
    bump, suggested, why = suggest_bump(old.version, classes)
    note = bump_note(old.version, new.version, bump) if changes else None
    return Summary(counts, next((c for c in LADDER if counts[c]), None), bump, suggested, why, note)


def _groups(changes: list[Change]):  # type: ignore[no-untyped-def]
    return groupby(changes, key=lambda ch: (ch.frame_id, ch.message))


def _summary_line(s: Summary, old: ProtocolModel) -> str:
    total = sum(s.counts.values())
    parts = ", ".join(f"{s.counts[c]} {TITLES[c]}" for c in LADDER)
    if s.bump == "none":
        bump = "none"
    else:
        bump = f"{s.bump}" + (f" ({old.version} → {s.suggested})" if s.suggested else "") + f": {s.why}"
    if s.note:
        bump += f"\nnote: {s.note}"
    return f"{total} change(s): {parts}\nsuggested version bump: {bump}"


def text(old: ProtocolModel, new: ProtocolModel, changes: list[Change]) -> str:
    lines = [f"canspec diff: {old.source} ({old.label}) → {new.source} ({new.label})", ""]
    width = max((len(TITLES[c]) for c in LADDER), default=10)
    for (frame_id, name), items in _groups(changes):
        lines.append(f"{subject(frame_id)} {name}")
        for ch in items:
            what = f"{ch.signal}: " if ch.signal and ch.kind not in ("signal_added", "signal_removed", "signal_renamed") else ""
            lines.append(f"  {TITLES[ch.cls]:<{width}}  {ch.kind:<28} {what}{ch.detail}")
        lines.append("")
    if not changes:
        lines += ["no differences", ""]
    lines.append(_summary_line(summarize(old, new, changes), old))
    return "\n".join(lines) + "\n"


def markdown(old: ProtocolModel, new: ProtocolModel, changes: list[Change]) -> str:
    s = summarize(old, new, changes)
    lines = [f"# Protocol diff: {old.label} → {new.label}", "", f"`{old.source}` → `{new.source}`", ""]
    lines += ["| Class | Changes |", "|---|---|"] + [f"| {TITLES[c]} | {s.counts[c]} |" for c in LADDER] + [""]
    if s.bump == "none":
        lines += ["**Suggested version bump:** none (no differences)", ""]
    else:
        target = f" ({old.version} → {s.suggested})" if s.suggested else ""
        lines += [f"**Suggested version bump:** {s.bump}{target} — {s.why}", ""]
    if s.note:
        lines += [f"> Note: {s.note}", ""]
    for (frame_id, name), items in _groups(changes):
        lines += [f"## `{subject(frame_id)}` {name}", "", "| Class | Kind | Signal | Change |", "|---|---|---|---|"]
        for ch in items:
            detail = ch.detail.replace("|", "\\|")
            lines.append(f"| {TITLES[ch.cls]} | `{ch.kind}` | {'`' + ch.signal + '`' if ch.signal else ''} | {detail} |")
        lines.append("")
    return "\n".join(lines)


def as_json(old: ProtocolModel, new: ProtocolModel, changes: list[Change]) -> str:
    s = summarize(old, new, changes)
    data = {
        "format": "canspec-diff/1",
        "old": {"source": old.source, "kind": old.kind, "name": old.name, "version": old.version},
        "new": {"source": new.source, "kind": new.kind, "name": new.name, "version": new.version},
        "summary": {"counts": s.counts, "strictest": s.strictest, "bump": s.bump, "suggested_version": s.suggested, "reason": s.why, "note": s.note},
        "changes": [ch.as_json() for ch in changes],
    }
    return json.dumps(data, indent=2, ensure_ascii=False, sort_keys=True) + "\n"


FORMATS = {"text": text, "markdown": markdown, "json": as_json}
