"""The importer's YAML writer: every text a source may hold reads back as itself (PyYAML is the
oracle), written plain only where that is safe; a text ending in a newline once came back
without it, because the plain-word test used `$`, which also matches before a final newline."""

from __future__ import annotations

import pytest
import yaml
from canspec.importer.yamlout import scalar

TEXTS = ["abc", "abc\n", "abc\n\n", "\nabc", "a b", " lead", "trail ", "true", "False", "null", "~", "yes", "off", "0x10", "1e3", "12", "-",
         "a: b", "#x", "'q'", '"q"', "多路", "tab\there", "del\x7f", "c1\x85", "", "a\\b", "[x]", "{x}", "*alias", "&anchor", "!tag", "%d", "@x"]


@pytest.mark.parametrize("text", TEXTS, ids=repr)
def test_every_text_reads_back_as_itself(text):
    written = scalar(text)
    assert yaml.safe_load(f"key: {written}\n") == {"key": text}


def test_only_plain_words_go_unquoted():
    assert scalar("Speed_1") == "Speed_1"
    assert scalar("abc\n") == '"abc\\n"'
