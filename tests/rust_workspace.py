"""Generated crates of several specs in one cargo workspace (one build, one target directory,
offline with the shipped crate's pins): each member's package renamed apart, its library keeping
the name the crate's own tests use. Used by tests/targets/rust/test_rust_fixtures.py and
tests/runtime/test_random_runners.py."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

from repo_paths import GENERATED


def add_member(files: dict[str, bytes], root: Path, name: str, package_prefix: str) -> str:
    """Write `files` (rendered targets, relative paths) under `root/name/`; the crate's package is
    renamed `<package_prefix>-<name>`. Returns the member path (`name/rust`)."""
    for rel, data in files.items():
        (root / name / rel).parent.mkdir(parents=True, exist_ok=True)
        (root / name / rel).write_bytes(data)
    toml = root / name / "rust" / "Cargo.toml"
    text = toml.read_text(encoding="utf-8")
    lib = re.search(r'^name = "([^"]+)"', text, re.MULTILINE)
    assert lib, text
    package = f"{package_prefix}-{name.replace('_', '-')}"
    toml.write_text(text.replace(lib.group(0), f'name = "{package}"', 1) + f'\n[lib]\nname = "{lib.group(1)}"\npath = "src/lib.rs"\n', encoding="utf-8")
    return f"{name}/rust"


def write_workspace(root: Path, members: list[str]) -> None:
    (root / "Cargo.toml").write_text('[workspace]\nresolver = "2"\nmembers = [\n' + "".join(f'    "{m}",\n' for m in members) + "]\n", encoding="utf-8")
    shutil.copy(GENERATED / "rust" / "Cargo.lock", root / "Cargo.lock")  # the shipped crate's pins
