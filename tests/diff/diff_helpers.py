"""Helpers for the diff tests (not a conftest.py: the root tests import `conftest` by name):
fixture specs derived from fixtures/base.yaml by exact text edits, and the CLI run in-process."""

from __future__ import annotations

import contextlib
import functools
import io
import os
import subprocess
import sys
from pathlib import Path

from canspec.cli import main
from canspec.diff.compare import compare
from canspec.diff.inputs import load_model

HERE = Path(__file__).resolve().parent
BASE = HERE / "fixtures" / "base.yaml"
ROOT = HERE.parent.parent


def edited(tmp_path: Path, edits: list[tuple[str, str]], name: str = "new.yaml") -> Path:
    text = BASE.read_text(encoding="utf-8")
    for old, new in edits:
        assert text.count(old) == 1, f"fixture edit does not apply exactly once: {old!r}"
        text = text.replace(old, new)
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


@functools.cache
def _repo_model(path: str):  # type: ignore[no-untyped-def]
    return load_model(path)


def model(path: Path | str):  # type: ignore[no-untyped-def]
    """The comparison model of `path`; the repository's own specs and DBC are read once per session."""
    text = str(path)
    return _repo_model(text) if Path(text).resolve().is_relative_to(ROOT) else load_model(text)


def diff_paths(old: Path | str, new: Path | str):  # type: ignore[no-untyped-def]
    return compare(model(old), model(new))


def run_cli(*argv: object) -> tuple[int, str, str]:
    """The CLI in this process: (exit status, stdout, stderr)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main([str(a) for a in argv])
    return code, out.getvalue(), err.getvalue()


def run_subprocess(*argv: str) -> tuple[int, str, str]:
    """The CLI in a child process: for commands whose output goes through foundation helpers
    that bind sys.stderr at import time (pytest's capture cannot see them in-process)."""
    env = {**os.environ, "PYTHONPATH": str(ROOT / "generator")}
    proc = subprocess.run([sys.executable, "-m", "canspec", *map(str, argv)], capture_output=True, text=True, env=env, check=False)
    return proc.returncode, proc.stdout, proc.stderr
