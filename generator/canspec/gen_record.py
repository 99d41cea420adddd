"""The record of the last successful `canspec gen` (or full `--check`) into an output directory, so
that `gen --check` on unchanged inputs answers without compiling or rendering — it runs in
pre-commit hooks, and a full check of a 1,000-message spec takes as long as generating it.

A record is named by the output directory and what generation depends on besides the spec's
files: canspec's version, a hash of the generator's source and templates, the formatters'
executables (path, size, modification time), Python's version, the spec path, the working
directory and the options (targets, node, strict). It holds the sha256 of every file the compile
read or looked for and of every file it generated. `--check` trusts it only while every input and
every output hashes the same (a hand edit keeps neither time nor size reliably); anything else (or
no record) means the full check. Records live next
to the compiled-spec cache (spec_cache.cache_dir; CANSPEC_NO_CACHE=1 turns both off) and are only a
shortcut: any problem with one falls back to the full check, never to an error."""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import sys
from collections.abc import Iterable
from pathlib import Path

import canspec
from canspec import resources
from canspec.render.formatters import FORMATTERS
from canspec.spec_cache import _file_hash as _sha
from canspec.spec_cache import cache_dir, store

FORMAT = 1


def _tree_hash(*roots: Path) -> str:
    digest = hashlib.sha256()
    for root in roots:
        for path in sorted(p for p in root.rglob("*") if p.is_file() and "__pycache__" not in p.parts):
            digest.update(path.relative_to(root).as_posix().encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.hexdigest()


def _formatters() -> list[str]:
    out = []
    for name, formatter in sorted(FORMATTERS.items()):
        exe = formatter.locate()
        stat = os.stat(exe) if exe else None
        out.append(f"{name}={exe}:{stat.st_size}:{stat.st_mtime_ns}" if stat else f"{name}=absent")
    return out


def _entry(spec: str | None, output: Path, options: Iterable[str]) -> Path | None:
    folder = cache_dir()
    if folder is None:
        return None
    key = [str(FORMAT), canspec.__version__, _tree_hash(Path(canspec.__file__).parent, resources.templates_dir()), *_formatters(), sys.version,
           os.path.abspath(spec) if spec is not None else "", os.path.abspath(output), os.getcwd(), *options]
    return folder / f"gen-{hashlib.sha256(chr(0).join(key).encode()).hexdigest()}.json"


def write(spec: str | None, output: Path, options: Iterable[str], inputs: Iterable[Path], outputs: Iterable[str]) -> None:
    """Records a successful gen (or full check) whose output directory now holds `outputs` (relative paths)."""
    with contextlib.suppress(Exception):  # an unwritable cache: the record is only a shortcut
        entry = _entry(spec, output, options)
        if entry is None:
            return
        files = {str(p): _sha(p) for p in inputs}
        made = {rel: _sha(output / rel) for rel in outputs}
        store(entry, json.dumps({"inputs": files, "outputs": made}).encode("utf-8"), ".gen-")


def up_to_date(spec: str | None, output: Path, options: Iterable[str]) -> int | None:
    """The number of generated files when the record says the output is what gen would write; None when it cannot say."""
    try:
        entry = _entry(spec, output, options)
        if entry is None:
            return None
        record = json.loads(entry.read_text(encoding="utf-8"))
        if any(_sha(Path(name)) != digest for name, digest in record["inputs"].items()):
            return None
        if any(_sha(output / rel) != digest for rel, digest in record["outputs"].items()):
            return None
        return len(record["outputs"])
    except Exception:  # noqa: BLE001 - missing, unreadable or stale: the full check decides
        return None
