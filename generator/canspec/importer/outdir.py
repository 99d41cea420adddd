"""Where `canspec import -o DIR` may write. The spec it writes is the user's to edit from then on,
so a file already in DIR is replaced only when it is what import writes now, or when an earlier
import wrote it and it is unchanged since: the bundle (canspec.yaml) records the sha256 of the
spec file it wrote. Anything else is refused, naming the files, unless --force."""

from __future__ import annotations

import hashlib
import re
from pathlib import Path

BUNDLE = "canspec.yaml"
MARKER = "# canspec bundle written by `canspec import`"
_RECORD = re.compile(r"^# import wrote (\S+) with sha256 ([0-9a-f]{64})\b", re.MULTILINE)
_NAME = re.compile(r"^name: (\S+)\nfiles:\n  - (\S+)$", re.MULTILINE)


def _sha256(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def spec_file(name: str) -> str:
    """The spec's file name: `<name>.yaml`, unless that is the bundle's (a protocol named canspec)."""
    return f"{name}.yaml" if f"{name}.yaml" != BUNDLE else f"{name}_spec.yaml"


def bundle(name: str, file: str, spec: bytes | None) -> bytes:
    """The bundle naming the spec file; with `spec`, the line recording its digest (None: the
    bundle as imports before the record wrote it)."""
    record = f"# import wrote {file} with sha256 {_sha256(spec)}: a later import replaces it only while it is unchanged\n" \
        if spec is not None else ""
    return f"{MARKER}\n{record}schema_version: 1\nkind: bundle\nname: {name}\nfiles:\n  - {file}\n".encode()


def _recorded(path: Path) -> dict[str, str] | None:
    """The spec files (name → sha256) an unchanged import-written bundle records; None when the
    bundle is not import's, or was edited."""
    try:
        data = path.read_bytes()
    except OSError:
        return None
    text = data.decode("utf-8", errors="replace")
    name = _NAME.search(text)
    if not text.startswith(MARKER) or name is None:
        return None
    record = _RECORD.search(text)
    recorded = {record.group(1): record.group(2)} if record else {}
    rebuilt = bundle(name.group(1), name.group(2), None)
    if record:  # the record line is rebuilt from its own digest
        rebuilt = rebuilt.replace(b"\n", f"\n{text.splitlines()[1]}\n".encode(), 1)
    return recorded if rebuilt == data else None


def _replaceable(path: Path, data: bytes, recorded: dict[str, str] | None) -> bool:
    if not path.exists() and not path.is_symlink():
        return True
    if not path.is_file():
        return False
    current = path.read_bytes()
    if current == data:
        return True
    if recorded is None:
        return False
    return path.name == BUNDLE or recorded.get(path.name) == _sha256(current)


def refusal(out: Path, write: dict[str, bytes], force: bool) -> str | None:
    """Why import must not write `write` into `out`; None when it may."""
    if out.exists() and not out.is_dir():
        return f"-o {out}: exists and is not a directory (hint: name a new directory, or one import wrote before)"
    if not out.is_dir():
        return None
    others = [rel for rel in write if (out / rel).exists() and not (out / rel).is_file()]
    if others:
        return f"-o {out}: {', '.join(others)} in it is not a regular file: nothing written (hint: choose another -o directory)"
    recorded = _recorded(out / BUNDLE)
    kept = [rel for rel, data in write.items() if not force and not _replaceable(out / rel, data, recorded)]
    if kept:
        return (f"-o {out}: {', '.join(kept)} already there, not written by canspec import or edited since: nothing written "
                "(hint: --force replaces them; or choose another -o directory)")
    return None
