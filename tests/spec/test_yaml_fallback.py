"""canspec parses with libyaml's event parser when PyYAML has it, else with pure-Python PyYAML.
Both must give the same problems at the same places, and the same spec: run the CLI with
libyaml hidden and compare with the normal run."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
from canspec_cli import FIXTURES, ROOT, assert_no_traceback, canspec_env, run_canspec

PURE = "import sys; sys.modules['yaml.cyaml'] = None; sys.modules['yaml._yaml'] = None; from canspec.cli import main; sys.exit(main(sys.argv[1:]))"


def run_pure(*args: str | Path, cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-c", PURE, *map(str, args)], cwd=cwd, env=canspec_env(), capture_output=True, text=True, timeout=300, check=False)


def test_fallback_is_really_pure_python() -> None:
    probe = subprocess.run(
        [
            sys.executable,
            "-c",
            PURE.replace("from canspec.cli import main; sys.exit(main(sys.argv[1:]))", "from canspec.spec import yamlsource; print(yamlsource._CParser)"),
        ],
        env=canspec_env(),
        capture_output=True,
        text=True,
        check=False,
    )
    assert probe.stdout.strip() == "None", probe.stderr


@pytest.mark.parametrize(
    "path",
    [
        ROOT / "spec",
        FIXTURES / "invalid" / "value-out-of-field.yaml",  # a column after Chinese text
        FIXTURES / "invalid" / "yaml-duplicate-key.yaml",
        FIXTURES / "broken" / "billion_laughs.yaml",
        FIXTURES / "broken" / "recursive_alias.yaml",
        FIXTURES / "broken" / "duplicate_key_flow.yaml",
    ],
    ids=lambda p: p.name,
)
def test_same_report_with_and_without_libyaml(path: Path) -> None:
    fast = run_canspec("check", path.name, cwd=path.parent)
    pure = run_pure("check", path.name, cwd=path.parent)
    assert_no_traceback(pure)
    assert (pure.returncode, pure.stderr) == (fast.returncode, fast.stderr)


@pytest.mark.parametrize(
    "text, where",
    [
        ("a: 模式\nb: x\0y\n", "2:5"),  # a control character after multi-byte text: same line:col both ways
        ("a: " + "[" * 50_000 + "]" * 50_000 + "\n", "1:"),
        ("a: [1, 2\n", "2:1"),
    ],
)
def test_same_location_for_bad_yaml(text: str, where: str, tmp_path: Path) -> None:
    (tmp_path / "bad.yaml").write_text(text, encoding="utf-8")
    for proc in (run_canspec("check", "bad.yaml", cwd=tmp_path), run_pure("check", "bad.yaml", cwd=tmp_path)):
        assert_no_traceback(proc)
        assert proc.returncode == 1 and proc.stderr.startswith(f"bad.yaml:{where}"), proc.stderr
