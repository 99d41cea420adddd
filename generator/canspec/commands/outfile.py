"""Where `canspec decode -o` and `canspec plot -o` write. A file is written to a temporary file beside it and renamed
over it only when the run succeeds, so a failed run (an unreadable input, an internal error,
Ctrl-C) leaves an existing file as it was and no temporary behind. A device or FIFO (`-o
/dev/null`) is written in place: renaming over it would replace the device node. For Parquet's
directory, the place is checked before any decoding, so a bad -o fails at once."""

from __future__ import annotations

import os
import stat
import tempfile
from typing import IO, Any


class OutputFile:
    def __init__(self, path: str) -> None:
        self.path = os.path.realpath(path)  # through a symlink: its target is replaced, not the link
        self.temp: str | None = None

    def open(self, binary: bool = False) -> IO[Any]:
        """The stream to write (text, or bytes when `binary`); OSError when the file cannot be written there."""
        try:
            st = os.stat(self.path)
        except FileNotFoundError:
            st = None
        if st is not None and stat.S_ISDIR(st.st_mode):
            raise IsADirectoryError(21, "Is a directory")
        if st is not None and not stat.S_ISREG(st.st_mode):
            return open(self.path, "wb") if binary else open(self.path, "w", encoding="utf-8")  # noqa: SIM115 - closed by finish()
        folder, name = os.path.split(self.path)
        fd, self.temp = tempfile.mkstemp(prefix=f".{name}.", suffix=".tmp", dir=folder)
        # the mode an ordinary open() would give: the old file's, else 0666 less the umask
        os.chmod(fd, stat.S_IMODE(st.st_mode) if st is not None else 0o666 & ~_umask())
        return os.fdopen(fd, "wb") if binary else os.fdopen(fd, "w", encoding="utf-8")

    def finish(self, out: IO[Any], keep: bool) -> None:
        """Closes `out`; the temporary replaces the file when `keep`, else is removed. OSError
        (a full disk on the last flush) leaves the file as it was."""
        try:
            out.close()
            if self.temp is not None and keep:
                os.replace(self.temp, self.path)
                self.temp = None
        finally:
            if self.temp is not None:
                os.unlink(self.temp)
                self.temp = None


def _umask() -> int:
    mask = os.umask(0)  # the only way to read it: set and restore (the CLI is single-threaded here)
    os.umask(mask)
    return mask


def directory_problem(path: str) -> str | None:
    """Why `path` cannot be (or be made) a directory to write tables in; None when it can."""
    if os.path.isdir(path):
        return None if os.access(path, os.W_OK | os.X_OK) else "permission denied"
    if os.path.lexists(path):
        return "it exists and is not a directory (--format parquet writes a directory of tables)"
    parent = os.path.dirname(os.path.abspath(path))
    while not os.path.lexists(parent):
        parent = os.path.dirname(parent)
    if not os.path.isdir(parent):
        return f"{parent} is not a directory"
    return None if os.access(parent, os.W_OK | os.X_OK) else f"permission denied in {parent}"
