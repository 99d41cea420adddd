"""The README's copy-paste snippets, read as the user reads them: a fenced YAML block is found by
its first line (the file it belongs in, e.g. `# .gitlab-ci.yml`)."""

from __future__ import annotations

import re

import yaml

from repo_paths import ROOT


def block(first_line: str, lang: str = "yaml") -> str:
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    found = [b for b in re.findall(rf"^```{lang}\n(.*?)^```$", text, re.MULTILINE | re.DOTALL) if b.splitlines()[0] == first_line]
    assert len(found) == 1, f"README.md: expected one ```{lang} block starting {first_line!r}, found {len(found)}"
    return found[0]


def yaml_block(first_line: str):  # type: ignore[no-untyped-def]
    return yaml.safe_load(block(first_line))


def ci_commands() -> dict[str, list[str]]:
    """Each documented CI's shell commands, in order."""
    github = yaml_block("# .github/workflows/canspec.yml")
    gitlab = yaml_block("# .gitlab-ci.yml")
    return {
        "github": [step["run"] for job in github["jobs"].values() for step in job["steps"] if "run" in step],
        "gitlab": [line for job in gitlab.values() if isinstance(job, dict) for line in job["script"]],
    }
