"""Write a generated tree atomically: every file is staged next to its target first, and
only when all are staged are they renamed into place. A failure while staging (a full disk,
a killed process) leaves every existing file as it was. Unchanged files are not touched, and
files a previous run generated but this one does not are removed (tracked in a manifest)."""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import tempfile
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath

MANIFEST = ".canspec-manifest.json"
TMP_PREFIX = ".canspec-tmp-"


@dataclass
class Plan:
    write: dict[str, bytes] = field(default_factory=dict)  # new or changed
    unchanged: list[str] = field(default_factory=list)
    remove: list[str] = field(default_factory=list)  # generated before, not now
    notes: list[str] = field(default_factory=list)  # what the user should know (an unreadable manifest)

    @property
    def stale(self) -> list[str]:
        return sorted([*self.write, *self.remove])


def _read_manifest(out: Path, notes: list[str]) -> dict[str, dict[str, str]]:
    """The files an earlier run wrote, by relative path. Only paths that stay inside `out` count:
    the manifest is a file anyone can edit, and gen removes what it lists."""
    try:
        data = json.loads((out / MANIFEST).read_text(encoding="utf-8"))
        files = {k: dict(v) for k, v in data.get("files", {}).items()}
    except FileNotFoundError:
        return {}
    except (OSError, ValueError, AttributeError, TypeError):
        notes.append(f"{out / MANIFEST} cannot be read as canspec's manifest: files an earlier run wrote and this one does not are left in place")
        return {}
    return {rel: info for rel, info in files.items() if _inside(out, rel)}


def _inside(out: Path, rel: str) -> bool:
    """`rel` is a relative path without `..` whose file, symbolic links followed, lies under `out`."""
    parts = PurePosixPath(rel).parts
    if not parts or PurePosixPath(rel).is_absolute() or ".." in parts or "\\" in rel or ":" in parts[0]:
        return False
    try:
        return (out / rel).resolve().is_relative_to(out.resolve())
    except (OSError, RuntimeError):  # a symbolic link loop
        return False


def plan(out: Path, outputs: dict[str, dict[str, bytes]]) -> Plan:
    """What writing `outputs` (target name → relative path → bytes) into `out` would change.
    Files an earlier run generated for one of these targets, and this run does not, are stale."""
    notes: list[str] = []
    owned = _read_manifest(out, notes)
    targets = set(outputs)
    manifest = {k: v for k, v in owned.items() if v.get("target") not in targets}
    files: dict[str, bytes] = {}
    for target, produced in outputs.items():
        for rel, data in produced.items():
            files[rel] = data
            manifest[rel] = {"sha256": hashlib.sha256(data).hexdigest(), "target": target}
    everything = dict(files)
    everything[MANIFEST] = (json.dumps({"generator": "canspec", "files": dict(sorted(manifest.items()))}, indent=1, sort_keys=True) + "\n").encode()
    p = Plan(notes=notes)
    for rel, data in sorted(everything.items()):
        try:
            same = (out / rel).read_bytes() == data
        except OSError:
            same = False
        if same:
            p.unchanged.append(rel)
        else:
            p.write[rel] = data
    for rel, info in sorted(owned.items()):
        if info.get("target") in targets and rel not in files and (out / rel).exists():
            p.remove.append(rel)
    return p


# Staging threads: fsyncs issued together share the file system's journal commits (ext4: 800
# files one after another 3 s, together 0.1 s).
STAGING_THREADS = 32


def apply(out: Path, p: Plan) -> None:
    staged: dict[str, Path] = {}
    created: list[Path] = []  # folders this run made: removed again when staging fails
    try:
        _make_dirs(out, created)
        for rel in p.write:
            _make_dirs((out / rel).parent, created)
        _stage_all(out, p.write, staged)
    except BaseException:
        for tmp in staged.values():
            tmp.unlink(missing_ok=True)
        for folder in reversed(created):
            with contextlib.suppress(OSError):
                folder.rmdir()
        raise
    # The manifest goes last so it never describes files that are not in place yet.
    for rel in sorted(staged, key=lambda rel: rel == MANIFEST):
        os.replace(staged[rel], out / rel)
    for rel in p.remove:
        (out / rel).unlink(missing_ok=True)


def _stage_all(out: Path, files: dict[str, bytes], staged: dict[str, Path]) -> None:
    """Every file written and synced to a temporary next to its target (noted in `staged` as soon
    as it exists); the first failure stops the files not yet started and is raised."""
    if not files:
        return
    with ThreadPoolExecutor(max_workers=min(STAGING_THREADS, len(files))) as pool:
        futures = [pool.submit(_stage, out / rel, data, rel, staged) for rel, data in files.items()]
        try:
            for future in futures:
                future.result()
        except BaseException:
            pool.shutdown(cancel_futures=True)
            raise


def _stage(target: Path, data: bytes, rel: str, staged: dict[str, Path]) -> None:
    fd, tmp = tempfile.mkstemp(prefix=TMP_PREFIX, dir=target.parent)
    staged[rel] = Path(tmp)
    with os.fdopen(fd, "wb") as fh:
        fh.write(data)
        fh.flush()
        os.fsync(fh.fileno())
    os.chmod(tmp, 0o644)


def _make_dirs(folder: Path, created: list[Path]) -> None:
    """mkdir -p, noting in `created` each folder it made, outermost first."""
    missing = []
    while not folder.is_dir() and folder != folder.parent:
        missing.append(folder)
        folder = folder.parent
    for new in reversed(missing):
        new.mkdir()
        created.append(new)


def clean_stale_temporaries(out: Path) -> None:
    """Remove staging files a killed earlier run left behind."""
    if out.is_dir():
        for tmp in out.rglob(f"{TMP_PREFIX}*"):
            tmp.unlink(missing_ok=True)
