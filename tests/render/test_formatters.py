"""The formatter registry (render/formatters.py): every formatter generated code goes through is
registered once, with its install hint; a missing, failing or hanging one is one clear error line
naming the tool (generation writes nothing, the CLI exits non-zero, no traceback)."""

from __future__ import annotations

import dataclasses
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from canspec.render import formatters
from canspec.render.formatters import FORMATTERS, Formatter, FormatterError

from repo_paths import CANSPEC_ENV, ROOT


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


def _clang_format_package(root: Path, binary: str | None) -> dict[str, str]:
    """An environment whose `clang_format` package is a stand-in under `root`, holding `binary`
    as its data/bin/clang-format (or no binary), and whose PATH is an empty folder."""
    package = root / "site" / "clang_format"
    (package / "data" / "bin").mkdir(parents=True)
    (package / "__init__.py").write_text("")
    if binary is not None:
        exe = package / "data" / "bin" / "clang-format"
        exe.write_text(binary)
        exe.chmod(0o755)
    (root / "bin").mkdir()
    return {**CANSPEC_ENV, "PYTHONPATH": f"{root / 'site'}{os.pathsep}{CANSPEC_ENV['PYTHONPATH']}", "PATH": str(root / "bin")}


def test_cli_without_clang_format_is_one_line_and_exit_1(tmp_path):
    env = _clang_format_package(tmp_path, None)  # a clang_format package without its binary, nothing on PATH
    cmd = [sys.executable, "-m", "canspec", "gen", "-t", "c", "-o", str(tmp_path / "out")]
    proc = subprocess.run(cmd, env=env, capture_output=True, text=True, check=False)
    assert proc.returncode == 1
    assert "clang-format not found" in proc.stderr and "apt-get install clang-format" in proc.stderr and "Traceback" not in proc.stderr, proc.stderr
    assert not (tmp_path / "out" / "c").exists()


def _fake(tmp_path: Path, version_line: str) -> Formatter:
    script = tmp_path / "fake-format"
    script.write_text(f"#!/bin/sh\necho '{version_line}'\n")
    script.chmod(0o755)
    return dataclasses.replace(FORMATTERS["clang-format"], locate=lambda: str(script))


def test_the_pinned_clang_format_wheel_comes_before_path(tmp_path, monkeypatch):
    """canspec depends on clang-format==CLANG_FORMAT_VERSION (pyproject.toml): that binary formats,
    whatever another clang-format earlier on PATH says."""
    other = tmp_path / "clang-format"
    other.write_text("#!/bin/sh\necho 'clang-format version 18.1.3'\n")
    other.chmod(0o755)
    monkeypatch.setenv("PATH", f"{tmp_path}{os.pathsep}{os.environ['PATH']}")
    exe = FORMATTERS["clang-format"].locate()
    assert exe is not None and Path(exe).parts[-3:] == ("data", "bin", "clang-format"), exe
    assert "clang-format version " + formatters.CLANG_FORMAT_VERSION in subprocess.run([exe, "--version"], capture_output=True, text=True).stdout
    assert formatters.version_notes(["clang-format", "ruff", "rustfmt"]) == []  # the tools installed here are the pinned ones


@pytest.mark.parametrize(
    ("line", "warned"),
    [
        ("Ubuntu clang-format version 15.0.7", True),
        ("clang-format version 14.0.6 (https://github.com/ssciwr/clang-format-wheel)", False),
        ("no version here", False),
    ],
)
def test_another_formatter_version_is_a_warning(tmp_path, line, warned):
    note = _fake(tmp_path, line).version_note()
    if not warned:
        assert note is None
        return
    assert note == (f"clang-format 15.0.7 is installed, but generated code is laid out by clang-format {formatters.CLANG_FORMAT_VERSION}: files may "
                    f"differ in layout from other machines' output (pip install clang-format=={formatters.CLANG_FORMAT_VERSION})")


def test_gen_with_another_clang_format_warns_and_still_writes(tmp_path):
    """A real `canspec gen` whose clang-format reports another version: one warning line naming
    both versions and the fix; the headers are written (and formatted: the stand-in runs the
    pinned binary for everything but --version)."""
    real = FORMATTERS["clang-format"].locate()
    assert real is not None, "clang-format missing (run `make setup`)"
    stand_in = f'#!/bin/sh\nif [ "$1" = --version ]; then echo "clang-format version 15.0.7"; exit 0; fi\nexec {real} "$@"\n'
    env = _clang_format_package(tmp_path, stand_in)
    cmd = [sys.executable, "-m", "canspec", "gen", "-t", "c", "-o", str(tmp_path / "out")]
    proc = subprocess.run(cmd, env=env, capture_output=True, text=True, check=False, cwd=ROOT)
    assert proc.returncode == 0, proc.stderr
    warnings = [line for line in proc.stderr.splitlines() if "warning" in line]
    assert warnings == [f"canspec gen: warning: clang-format 15.0.7 is installed, but generated code is laid out by clang-format "
                        f"{formatters.CLANG_FORMAT_VERSION}: files may differ in layout from other machines' output "
                        f"(pip install clang-format=={formatters.CLANG_FORMAT_VERSION})"], proc.stderr
    for header in (ROOT / "generated" / "c").glob("*.h"):
        assert (tmp_path / "out" / "c" / header.name).read_bytes() == header.read_bytes(), header.name


LONG_CALL = "fn main() { let x = some_function_name(argument_one, argument_two, argument_three); }\n"


@pytest.mark.parametrize("where", [".", "sub/dir"])
@pytest.mark.parametrize("config", ["rustfmt.toml", ".rustfmt.toml"])
def test_a_rustfmt_config_of_the_users_project_does_not_change_the_generated_rust(tmp_path, monkeypatch, where, config):
    """rustfmt reads a rustfmt.toml in its working directory or above: run in a firmware repo that has
    one, `make gen` laid the crate out by that file's rules (here max_width = 40), and `gen --check`
    failed against the committed output. The generated crate's own rules come from the committed
    templates/rust/rustfmt.toml instead."""
    monkeypatch.setenv("CANSPEC_NO_CACHE", "1")
    want = formatters.rustfmt(LONG_CALL, "x.rs")
    assert want == "fn main() {\n    let x = some_function_name(argument_one, argument_two, argument_three);\n}\n"
    (tmp_path / config).write_text("max_width = 40\n", encoding="utf-8")
    (tmp_path / where).mkdir(parents=True, exist_ok=True)
    monkeypatch.chdir(tmp_path / where)
    assert formatters.rustfmt(LONG_CALL, "x.rs") == want
