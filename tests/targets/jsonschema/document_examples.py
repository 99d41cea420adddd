"""The JSON examples printed in the protocol document, read straight from its text (not from
the spec): the code blocks (with their line numbers and /* */ comments stripped) and the one
captured message printed inline."""

from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

FENCE = re.compile(r"```\s*\n(.*?)```", re.DOTALL)
COMMENT = re.compile(r"/\*.*?\*/", re.DOTALL)
LINE_NUMBER = re.compile(r"(?m)^\s*\d+(?=\s)")
INLINE = re.compile(r"^`(\{.*\})`\s*$", re.MULTILINE)


def block_examples(text: str) -> list[dict[str, Any]]:
    out = []
    for block in FENCE.findall(text):
        body = LINE_NUMBER.sub("", COMMENT.sub("", block))
        out.append(json.loads(body))
    return out


def inline_examples(text: str) -> list[dict[str, Any]]:
    return [json.loads(m) for m in INLINE.findall(text)]


def load(path: Path) -> tuple[list[dict[str, Any]], list[dict[str, Any]]]:
    import pytest

    if not path.is_file():
        pytest.fail(f"the protocol document is missing: {path} (the repository carries it under spec/source/)")
    text = path.read_text(encoding="utf-8")
    return block_examples(text), inline_examples(text)
