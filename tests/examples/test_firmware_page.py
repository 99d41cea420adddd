"""The handbook's "Use it in your firmware" page (generated/docs/firmware.md, in the site's and the
PDF's navigation): every C name it tells a firmware engineer to use exists in the generated headers,
its node table counts what the spec's YAML says each node sends and receives, and its CMake snippet
is the function the CMake package defines."""

from __future__ import annotations

import re

import yaml
from repo_paths import GENERATED, ROOT, SPEC

PAGE = GENERATED / "docs" / "firmware.md"


def test_page_is_in_the_navigation():
    nav = yaml.safe_load((GENERATED / "docs" / "mkdocs.nav.yml").read_text(encoding="utf-8"))["nav"]
    assert {"在固件中使用 Use it in your firmware": "firmware.md"} in nav


def test_names_exist_in_the_headers():
    page = PAGE.read_text(encoding="utf-8")
    headers = "\n".join(p.read_text(encoding="utf-8") for p in (GENERATED / "c").glob("*.h"))
    assert "#define KAIWO_GATEWAY_STRATEGY" in headers and "`KAIWO_GATEWAY_STRATEGY`" in page
    assert "_decode_fixed(" in headers and "_FIXED_SCALE" in headers and "kaiwo_gateway_<message>_<signal>_decode_fixed" in page
    assert (GENERATED / "c" / "MISRA.md").is_file() and "`MISRA.md`" in page
    cmake = (ROOT / "generator" / "canspec" / "cmake" / "canspecConfig.cmake").read_text(encoding="utf-8")
    assert "function(canspec_add_protocol target)" in cmake
    assert "canspec_add_protocol(kaiwo_gateway SPEC spec/canspec.yaml NODE Wire_Car_ECU)" in page


def test_node_table_counts_the_spec():
    """Counted from the YAML (senders, receivers; ALL is every node), not from canspec's IR."""
    doc = yaml.safe_load((SPEC / "can" / "gateway.yaml").read_text(encoding="utf-8"))
    messages = doc["messages"]
    nodes = [n["name"] for n in doc["nodes"]]
    page = PAGE.read_text(encoding="utf-8")
    for node in nodes:
        def receivers(m):
            r = m.get("receivers", [])
            return nodes if r == "ALL" or r == ["ALL"] else r
        sends = sum(m["sender"] in (node, "ALL") for m in messages)
        receives = sum(node in receivers(m) and m["sender"] != node for m in messages)
        kept = sum(m["sender"] in (node, "ALL") or node in receivers(m) for m in messages)
        row = re.search(rf"^\| {node} \| (\d+) \| (\d+) \| (\d+) of (\d+) \|$", page, re.MULTILINE)
        assert row is not None, node
        assert tuple(map(int, row.groups())) == (sends, receives, kept, len(messages)), node
