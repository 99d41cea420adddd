"""The formatter registry (render/formatters.py): every formatter generated code goes through is
registered once, with its install hint; a missing, failing or hanging one is one clear error line
naming the tool (generation writes nothing, the CLI exits non-zero, no traceback)."""

from __future__ import annotations

import dataclasses
import shutil
import subprocess
import sys

import pytest
from canspec.render import formatters
from canspec.render.formatters import FORMATTERS, Formatter, FormatterError

from repo_paths import CANSPEC_ENV


def test_each_target_language_has_its_formatter():
    assert set(FORMATTERS) == {"clang-format", "ruff", "rustfmt"}
    assert "ruff==" + formatters.RUFF_VERSION in FORMATTERS["ruff"].install
    assert "clang-format==" + formatters.CLANG_FORMAT_VERSION in FORMATTERS["clang-format"].install


@pytest.mark.parametrize("name", sorted(FORMATTERS))
def test_a_missing_formatter_names_itself_and_its_install(name):
    missing = dataclasses.replace(FORMATTERS[name], locate=lambda: None)
    with pytest.raises(FormatterError) as err:
        missing.run([], "text", "x/y.z")
    assert f"{name} not found" in str(err.value) and f"install: {FORMATTERS[name].install}" in str(err.value)


def test_a_hanging_formatter_times_out(monkeypatch):
    monkeypatch.setattr(formatters, "TIMEOUT_S", 0.2)
    sleeper = Formatter("sleep", "coreutils", lambda: shutil.which("sleep"))
    with pytest.raises(FormatterError, match=r"sleep took more than 0.2 s on a\.c"):
        sleeper.run(["5"], "", "a.c")


def test_a_failing_formatter_shows_its_message():
    failing = Formatter("python", "-", lambda: sys.executable)
    with pytest.raises(FormatterError, match="python failed on a.py: .*boom"):
        failing.run(["-c", "import sys; sys.exit('boom')"], "", "a.py")


def test_cli_without_clang_format_is_one_line_and_exit_1(tmp_path):
    empty = tmp_path / "bin"
    empty.mkdir()
    env = {**CANSPEC_ENV, "PATH": str(empty)}  # no clang-format (nor anything else) on PATH
    cmd = [sys.executable, "-m", "canspec", "gen", "-t", "c", "-o", str(tmp_path / "out")]
    proc = subprocess.run(cmd, env=env, capture_output=True, text=True, check=False)
    assert proc.returncode == 1
    assert "clang-format not found" in proc.stderr and "apt-get install clang-format" in proc.stderr and "Traceback" not in proc.stderr, proc.stderr
    assert not (tmp_path / "out" / "c").exists()
