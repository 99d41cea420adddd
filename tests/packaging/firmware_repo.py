"""A scratch firmware repository as the README's "CI and pre-commit" section assumes it: the spec in
`spec/`, one ECU's generated C committed in `generated/`; and the two ways it goes stale."""

from __future__ import annotations

import shutil
from pathlib import Path

from repo_paths import SPEC

GIT_IDENTITY = {"GIT_AUTHOR_NAME": "Firmware Dev", "GIT_AUTHOR_EMAIL": "dev@example.com",
                "GIT_COMMITTER_NAME": "Firmware Dev", "GIT_COMMITTER_EMAIL": "dev@example.com"}


def make(root: Path) -> Path:
    root.mkdir(parents=True, exist_ok=True)
    shutil.copytree(SPEC, root / "spec")
    return root


def change_spec(root: Path) -> None:
    """A change the AUTOCAR ECU's headers carry and the change record needs no item for (a title:
    docs only), so `canspec check` still passes and only the generated files are stale."""
    gateway = root / "spec" / "can" / "gateway.yaml"
    text = gateway.read_text(encoding="utf-8")
    assert text.count("title: AUTOCAR EPS Command\n") == 1, "spec/can/gateway.yaml: the EPS command's title not found"
    gateway.write_text(text.replace("title: AUTOCAR EPS Command\n", "title: AUTOCAR EPS Command (steering)\n"), encoding="utf-8")


def break_spec(root: Path) -> None:
    gateway = root / "spec" / "can" / "gateway.yaml"
    gateway.write_text(gateway.read_text(encoding="utf-8").replace("cycle_ms: 20", "cycle_ms: twenty", 1), encoding="utf-8")


def edit_header(root: Path) -> Path:
    """A hand edit of a generated header (what review must never let through)."""
    header = next((root / "generated" / "c").glob("*_messages.h"))
    header.write_text(header.read_text(encoding="utf-8") + "/* quick fix */\n", encoding="utf-8")
    return header
