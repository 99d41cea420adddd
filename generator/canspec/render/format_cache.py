"""Formatted text kept by what it was formatted from, so that a piece of generated code the
formatter has seen before is not formatted again: the formatters are over half of a large spec's
`gen` (the largest opendbc DBC: clang-format, rustfmt and ruff 6.3 of 11.5 CPU s), and a spec edit
changes few of its pieces (formatters.chunks cuts where the text says, not at offsets).

An entry is named by the sha256 of the formatter's executable (path, size, time), its arguments,
the contents of a style file an argument names, and the text; it holds the formatted text,
zlib-compressed. Entries live in spec_cache's directory (`format-<key>`, private to the user),
are written atomically, kept 30 days after their last use, and are only ever a shortcut: an
unreadable or corrupt entry is formatted again; CANSPEC_NO_CACHE=1 turns them off."""

from __future__ import annotations

import hashlib
import itertools
import os
import zlib
from pathlib import Path

from canspec.spec_cache import cache_dir, prune, store

_STYLE_FILE = "--style=file:"  # clang-format's; rustfmt's --config-path names its file as the next argument
_pruned: set[Path] = set()  # folders already pruned by this process


def key(exe: str, args: list[str], text: str) -> str | None:
    """The entry name of `text` formatted by `exe args`; None when the executable or a style file
    cannot be read."""
    styles = [a[len(_STYLE_FILE):] for a in args if a.startswith(_STYLE_FILE)]
    styles += [path for flag, path in itertools.pairwise(args) if flag == "--config-path"]
    try:
        info = os.stat(exe)
        contents = [Path(style).read_bytes() for style in styles]
    except OSError:
        return None
    digest = hashlib.sha256(f"{exe}\0{info.st_size}\0{info.st_mtime_ns}\0".encode())
    for part in [*(a.encode() for a in args), *contents, text.encode("utf-8")]:
        digest.update(len(part).to_bytes(8, "little") + part)
    return digest.hexdigest()


def _entry(name: str) -> Path | None:
    folder = cache_dir()
    return None if folder is None else folder / f"format-{name}"


def lookup(name: str | None) -> str | None:
    """The formatted text of an entry, or None (no entry, caching off, or an entry that does not read)."""
    entry = _entry(name) if name is not None else None
    if entry is None:
        return None
    try:
        text = zlib.decompress(entry.read_bytes()).decode("utf-8")
        os.utime(entry)  # in use: kept another MAX_AGE
    except (OSError, zlib.error, UnicodeDecodeError):
        return None
    return text


def keep(name: str | None, formatted: str) -> None:
    entry = _entry(name) if name is not None else None
    if entry is None:
        return
    _prune(entry.parent)
    store(entry, zlib.compress(formatted.encode("utf-8"), 1), ".format-")


def _prune(folder: Path) -> None:
    """Removes entries unused for MAX_AGE, once per folder and process."""
    if folder not in _pruned:
        _pruned.add(folder)
        prune(folder, "format-*")
