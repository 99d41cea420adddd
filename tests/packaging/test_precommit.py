"""The pre-commit hooks (.pre-commit-hooks.yaml) with the real `pre-commit`, configured as the README
shows, in a scratch firmware repository: pre-commit installs canspec from a local copy of this
repository (language: python, pip from PyPI), and `git commit` fails on a stale or hand-edited
generated header and on a broken spec, and passes on fresh files."""

from __future__ import annotations

import re
import shutil
import sys
from pathlib import Path

import yaml

import firmware_repo
from readme_snippets import yaml_block
from release_env import ok, run, user_env
from repo_paths import ROOT

# What pre-commit needs of the hook repository: the hooks file and what `pip install .` builds from.
HOOK_REPO_FILES = (".pre-commit-hooks.yaml", "pyproject.toml", "README.md", "generator", "spec", "templates")


def _git(cwd: Path, *args: str, env: dict[str, str]):  # type: ignore[no-untyped-def]
    return run(["git", *args], cwd=cwd, env=env)


def _hook_repo(root: Path, env: dict[str, str]) -> str:
    """A git repository holding this checkout's files (committed or not); its commit."""
    root.mkdir()
    for name in HOOK_REPO_FILES:
        src = ROOT / name
        if src.is_dir():
            shutil.copytree(src, root / name, ignore=shutil.ignore_patterns("__pycache__"))
        else:
            shutil.copy2(src, root / name)
    ok(_git(root, "init", "-q", env=env))
    ok(_git(root, "add", "-A", env=env))
    ok(_git(root, "commit", "-q", "-m", "canspec", env=env))
    return ok(_git(root, "rev-parse", "HEAD", env=env)).stdout.strip()


def test_hooks_guard_the_commit(tmp_path):
    env = {**user_env(), **firmware_repo.GIT_IDENTITY, "PRE_COMMIT_HOME": str(tmp_path / "pre-commit-home")}
    rev = _hook_repo(tmp_path / "canspec", env)
    config = yaml_block("# .pre-commit-config.yaml")
    config["repos"][0].update(repo=str(tmp_path / "canspec"), rev=rev)
    gen_args = next(h["args"] for h in config["repos"][0]["hooks"] if h["id"] == "canspec-gen-check")

    repo = firmware_repo.make(tmp_path / "firmware")
    (repo / ".pre-commit-config.yaml").write_text(yaml.safe_dump(config, sort_keys=False), encoding="utf-8")
    ok(_git(repo, "init", "-q", env=env))
    ok(run([sys.executable, "-m", "pre_commit", "install"], cwd=repo, env=env))

    def regenerate() -> None:  # this checkout's canspec: the version the hook repository holds
        ok(run([sys.executable, "-m", "canspec", "gen", *gen_args], cwd=repo, env={**env, "PYTHONPATH": str(ROOT / "generator")}))

    def commit(message: str) -> tuple[int, str]:
        ok(_git(repo, "add", "-A", env=env))
        done = _git(repo, "commit", "-q", "-m", message, env=env)
        return done.returncode, done.stdout + done.stderr  # git hands the hooks' output to stderr

    regenerate()
    status, out = commit("spec and its generated C")
    assert status == 0 and re.search(r"^canspec check .*Passed$", out, re.MULTILINE) and re.search(r"^canspec gen --check .*Passed$", out, re.MULTILINE), out

    firmware_repo.change_spec(repo)
    status, out = commit("spec changed, headers not regenerated")
    assert status == 1 and "stale: generated/c/kaiwo_gateway_messages.h" in out and re.search(r"^canspec check .*Passed$", out, re.MULTILINE), out
    regenerate()
    assert commit("regenerated")[0] == 0

    firmware_repo.edit_header(repo)
    status, out = commit("a quick fix in a generated header")
    assert status == 1 and "stale: generated/c/kaiwo_gateway_messages.h" in out, out
    regenerate()  # the header back as generated

    firmware_repo.break_spec(repo)
    status, out = commit("a broken spec")
    assert status == 1 and re.search(r"^canspec check .*Failed$", out, re.MULTILINE) and re.search(r"spec/can/gateway\.yaml:\d+:\d+: error: .*cycle_ms", out), (
        out
    )
    assert ok(_git(repo, "log", "--format=%s", env=env)).stdout.split("\n")[:2] == ["regenerated", "spec and its generated C"]
