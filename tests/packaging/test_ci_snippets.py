"""The README's CI snippets (GitHub Actions, GitLab CI), read from the README and run with the
release wheel's `canspec` in a scratch firmware repository: they pass on fresh generated files and
fail on a stale spec or a hand-edited header. They run the same commands as the pre-commit hooks."""

from __future__ import annotations

import re
import shlex
import tomllib

import yaml

import firmware_repo
from readme_snippets import ci_commands, yaml_block
from release_env import run
from repo_paths import ROOT


def _hook_commands() -> list[str]:
    """Each configured hook's command line: its entry (.pre-commit-hooks.yaml) and the README's args."""
    entries = {h["id"]: h["entry"] for h in yaml.safe_load((ROOT / ".pre-commit-hooks.yaml").read_text(encoding="utf-8"))}
    config = yaml_block("# .pre-commit-config.yaml")
    return [shlex.join([*shlex.split(entries[h["id"]]), *h.get("args", [])]) for repo in config["repos"] for h in repo["hooks"]]


def _normalized(command: str) -> list[str]:
    """canspec's words, with `--check` (a flag) moved last: `gen --check spec` is `gen spec --check`."""
    words = shlex.split(command)
    return [w for w in words if w != "--check"] + (["--check"] if "--check" in words else [])


def test_both_cis_run_the_hooks_commands():
    commands = ci_commands()
    assert commands["github"] == commands["gitlab"]
    canspec = [c for c in commands["github"] if c.startswith("canspec ")]
    assert [_normalized(c) for c in canspec] == [_normalized(c) for c in _hook_commands()]


def test_ci_commands_pass_when_fresh_and_fail_when_stale(release_venv, tmp_path):
    version = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["version"]
    install, *checks = ci_commands()["github"]
    # The snippet's install line stands for installing the release wheel (release_venv): it must
    # pin this version, or `gen --check` would compare against another canspec's output.
    assert re.fullmatch(rf"pip install canspec=={re.escape(version)}", install), install
    repo = firmware_repo.make(tmp_path / "firmware")
    gen = [c for c in checks if "--check" in c.split()]
    assert len(gen) == 1, checks

    def ci() -> list[tuple[str, int, str]]:
        return [(c, r.returncode, r.stdout + r.stderr) for c in checks for r in [run(c, cwd=repo, env=release_venv.env)]]

    def regenerate() -> None:
        r = run(" ".join(w for w in gen[0].split() if w != "--check"), cwd=repo, env=release_venv.env)
        assert r.returncode == 0, r.stderr

    regenerate()
    assert [(c, rc) for c, rc, _ in ci()] == [(c, 0) for c in checks]
    firmware_repo.change_spec(repo)
    failed = [(c, out) for c, rc, out in ci() if rc != 0]
    assert [c for c, _ in failed] == gen and "stale: generated/c/kaiwo_gateway_messages.h" in failed[0][1], failed
    regenerate()
    firmware_repo.edit_header(repo)
    assert [c for c, rc, _ in ci() if rc != 0] == gen
