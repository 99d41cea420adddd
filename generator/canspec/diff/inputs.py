"""Turn a diff argument (spec file/directory or DBC file) into a comparison model."""

from __future__ import annotations

from pathlib import Path

from canspec.diff.dbcimport import InputError, load_dbc
from canspec.diff.model import ProtocolModel, from_spec
from canspec.pipeline import compile_spec


def load_model(arg: str) -> ProtocolModel:
    path = Path(arg)
    if not path.exists():
        raise InputError(f"{arg}: no such file or directory (pass a spec bundle, spec directory or .dbc file)")
    if path.is_file() and path.suffix.lower() == ".dbc":
        return load_dbc(path, arg)
    if path.is_file() and path.suffix.lower() not in (".yaml", ".yml"):
        raise InputError(f"{arg}: not a spec (.yaml) or DBC (.dbc) file")
    compiled = compile_spec(path, targets=[])  # a revision is compared as the spec rules read it: what a target refuses is that target's concern
    if compiled.spec is None:
        shown = "\n".join(p.format() for p in compiled.errors[:10])
        more = f"\n  ... and {len(compiled.errors) - 10} more" if len(compiled.errors) > 10 else ""
        raise InputError(f"{arg}: the spec has errors (run `canspec check {arg}`):\n{shown}{more}")
    if compiled.spec.can is None:
        raise InputError(f"{arg}: the spec has no CAN protocol to compare")
    return from_spec(compiled.spec, arg)
