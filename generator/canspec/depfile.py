"""The dependency file of `canspec gen --depfile`: a Makefile rule naming every file the spec's
compile read (spec files, the schema, ERRATA.md when present), so a build system (CMake's
add_custom_command DEPFILE, Ninja, Make) regenerates only when one of them changed. Its target is
the output directory's manifest, which `gen --depfile` touches on every successful run: the
headers keep their times unless their bytes changed, so nothing that includes them recompiles."""

from __future__ import annotations

import errno
import os
from collections.abc import Iterable
from pathlib import Path

from canspec.render import writer


def escape(path: str) -> str:
    """A path as Make and Ninja's depfile parser read it back."""
    return path.replace("\\", "\\\\").replace(" ", "\\ ").replace("#", "\\#").replace("$", "$$")


def rule(target: Path, inputs: Iterable[Path]) -> str:
    """`target: input...`, absolute paths, one input a line. A file the compile only looked for
    (absent) is left out: Make would stop on a prerequisite it cannot make."""
    seen = sorted({os.path.abspath(p) for p in inputs if Path(p).is_file()})
    lines = [f"{escape(os.path.abspath(target))}:"] + [f" {escape(p)}" for p in seen]
    return " \\\n".join(lines) + "\n"


def write(depfile: Path, target: Path, inputs: Iterable[Path]) -> None:
    """Writes the rule atomically (a temporary file renamed over it): a directory or an unwritable
    path fails here, before gen changes any output."""
    depfile.parent.mkdir(parents=True, exist_ok=True)
    if depfile.is_dir():
        raise IsADirectoryError(errno.EISDIR, "is a directory", str(depfile))
    writer.apply(depfile.parent, writer.Plan(write={depfile.name: rule(target, inputs).encode("utf-8")}))


def touch(target: Path) -> None:
    """Marks the output up to date for the build system (the depfile rule's target)."""
    target.touch()
