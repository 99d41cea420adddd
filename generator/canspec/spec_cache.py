"""The compiled-spec cache of every command but `check` (which always compiles): compiling the
shipped spec takes 0.35 s (YAML, jsonschema, every rule, with their imports), loading it from the
cache 0.03 s; the largest opendbc DBC's spec 1.3 s and 0.2 s. `canspec import` compiles the spec it
writes through the cache, so the `canspec gen` that follows it does not compile it again.

An entry is named by what a compile depends on besides the files: canspec's version, a hash of the
generator's own source (a developer's edit invalidates it), the spec path, the working directory
(problem locations are relative to it) and the targets whose refusals apply. It holds the sha256
of every file the compile read or looked for (spec files, schema, ERRATA.md, or that it is absent),
and is used only while all of them are unchanged. It is a pickle of the spec and its problems (so
warnings still print), in $CANSPEC_CACHE_DIR, else $XDG_CACHE_HOME/canspec, else ~/.cache/canspec
(created private to its user: loading a pickle runs what it says). Only successful
compiles are kept (a failed one may have stopped before reading every file). CANSPEC_NO_CACHE=1
turns the cache off; anything wrong with it falls back to compiling, never to an error."""

from __future__ import annotations

import contextlib
import hashlib
import os
import pickle
import sys
import tempfile
import time
from collections.abc import Iterable
from pathlib import Path

import canspec
from canspec.pipeline import Compiled, compile_spec

FORMAT = 1  # of an entry: (FORMAT, [(file, sha256 or None)], spec, problems)
MAX_AGE = 30 * 86400  # seconds an entry is kept after it was written


def cache_dir() -> Path | None:
    """Where entries live; None when the cache is turned off."""
    if os.environ.get("CANSPEC_NO_CACHE", "") not in ("", "0"):
        return None
    if os.environ.get("CANSPEC_CACHE_DIR"):
        return Path(os.environ["CANSPEC_CACHE_DIR"])
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "canspec"


def compile_cached(spec: Path | str | None, targets: Iterable[str] | None = None) -> Compiled:
    """compile_spec(spec, targets), from the cache when every file it read is unchanged."""
    folder = cache_dir()
    if folder is None:
        return compile_spec(spec, targets)
    targets = None if targets is None else sorted(targets)
    try:
        entry = folder / f"{_entry_name(spec, targets)}.pickle"
    except OSError:  # an unreadable source file, a removed working directory
        return compile_spec(spec, targets)
    compiled = _read(entry)
    if compiled is None:
        started = time.time_ns()
        compiled = compile_spec(spec, targets)
        if compiled.spec is not None:
            _write(entry, compiled, started)
    return compiled


def _entry_name(spec: Path | str | None, targets: list[str] | None) -> str:
    key = [canspec.__version__, _source_hash(), os.path.abspath(spec) if spec is not None else "", os.getcwd(), repr(targets), sys.version]
    return hashlib.sha256("\0".join(key).encode()).hexdigest()


def _source_hash() -> str:
    """A hash of the generator's Python source: any edit to it gives new entries."""
    package = Path(canspec.__file__).parent
    digest = hashlib.sha256()
    for path in sorted(package.rglob("*.py")):
        digest.update(path.relative_to(package).as_posix().encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.hexdigest()


def _file_hash(path: Path) -> str | None:
    """The file's sha256; None when it does not exist."""
    try:
        return hashlib.sha256(path.read_bytes()).hexdigest()
    except FileNotFoundError:
        return None


def _read(entry: Path) -> Compiled | None:
    try:
        with entry.open("rb") as f:
            version, files, spec, problems = pickle.load(f)
        if version != FORMAT or any(_file_hash(Path(name)) != digest for name, digest in files):
            return None
        return Compiled(spec, problems, tuple(Path(name) for name, _ in files))
    except Exception:  # noqa: BLE001 - missing, unreadable, corrupt or from another canspec: compile instead
        return None


def store(entry: Path, data: bytes, prefix: str) -> None:
    """A small cache file written atomically (a temporary file renamed over it), its directory private
    to the user; an unwritable cache is only slower, so nothing here raises."""
    try:
        entry.parent.mkdir(mode=0o700, parents=True, exist_ok=True)
        fd, temp = tempfile.mkstemp(dir=entry.parent, prefix=prefix)
    except OSError:
        return
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.replace(temp, entry)
    except OSError:
        with contextlib.suppress(OSError):
            os.unlink(temp)


def _write(entry: Path, compiled: Compiled, started: int) -> None:
    """Stores the entry atomically (a temporary file renamed over it). A file modified after the
    compile started may not be what it read: then nothing is stored."""
    try:
        if any(path.exists() and path.stat().st_mtime_ns >= started for path in compiled.files):
            return
        files = [(str(path), _file_hash(path)) for path in compiled.files]
        entry.parent.mkdir(mode=0o700, parents=True, exist_ok=True)
        prune(entry.parent, "*.pickle")
        fd, temp = tempfile.mkstemp(dir=entry.parent, prefix=".entry-")
    except Exception:  # noqa: BLE001 - an unwritable cache directory: the cache is only a shortcut
        return
    try:
        with os.fdopen(fd, "wb") as f:
            pickle.dump((FORMAT, files, compiled.spec, compiled.problems), f, protocol=pickle.HIGHEST_PROTOCOL)
        os.replace(temp, entry)
    except Exception:  # noqa: BLE001 - a full disk, an unpicklable spec
        with contextlib.suppress(OSError):
            os.unlink(temp)


def prune(folder: Path, pattern: str) -> None:
    """Removes the entries matching `pattern` written (or, for those that touch theirs on use, used)
    more than MAX_AGE ago: each edit of a spec's path, of the working directory or of the generator
    leaves one behind."""
    oldest = time.time() - MAX_AGE
    for old in folder.glob(pattern):
        with contextlib.suppress(OSError):
            if old.stat().st_mtime < oldest:
                old.unlink()
