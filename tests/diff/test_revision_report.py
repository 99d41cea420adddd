"""`canspec diff OLD NEW --format html`, the revision report published with a release: every
computed change (the JSON format's, read independently) is on the page with its class, and each
item of the new revision's change record (read from the YAML) stands beside the changes it
declares; what the record misses or invents is flagged. One page, nothing fetched, text escaped."""

from __future__ import annotations

import contextlib
import html
import io
import json
import re
import shutil
from html.parser import HTMLParser
from pathlib import Path

import yaml
from canspec.cli import main
from repo_paths import ROOT, SPEC

V204 = SPEC / "history" / "v2.0.4"
DBC = ROOT / "generated" / "dbc" / "kaiwo_gateway.dbc"


class Page(HTMLParser):
    """The page's text, tags and resource references, and whether its tags balance."""

    VOID = frozenset({"meta", "br", "link", "img", "hr", "input"})

    def __init__(self, text: str) -> None:
        super().__init__()
        self.stack: list[str] = []
        self.refs: list[str] = []
        self.text: list[str] = []
        self.feed(text)

    def handle_starttag(self, tag, attrs):  # type: ignore[no-untyped-def]
        self.refs += [v for k, v in attrs if k in ("src", "href") and v]
        if tag not in self.VOID:
            self.stack.append(tag)

    def handle_endtag(self, tag):  # type: ignore[no-untyped-def]
        assert self.stack and self.stack.pop() == tag, f"unbalanced </{tag}>"

    def handle_data(self, data):  # type: ignore[no-untyped-def]
        self.text.append(data)

    def plain(self) -> str:
        return " ".join(" ".join(self.text).split())


def run_cli(*argv: object) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main([str(a) for a in argv])
    return code, out.getvalue(), err.getvalue()


def report(old: Path, new: Path) -> tuple[str, Page, dict]:
    code, out, err = run_cli("diff", old, new, "--format", "html")
    assert code == 0, err
    code, js, err = run_cli("diff", old, new, "--format", "json")
    assert code == 0, err
    page = Page(out)
    assert page.stack == [], page.stack
    return out, page, json.loads(js)


def declared_items(version: str) -> list[dict]:
    log = yaml.safe_load((SPEC / "history" / "changelog.yaml").read_text(encoding="utf-8"))
    return next(v for v in log["versions"] if str(v["version"]) == version)["items"]


def test_release_report_of_the_shipped_version():
    out, page, data = report(V204, SPEC)
    text = page.plain()
    assert "kaiwo_gateway 2.0.4 → kaiwo_gateway 2.0.5" in text
    counts = data["summary"]["counts"]
    assert re.search(r"合计 Total\s+" + r"\s+".join(str(counts[c]) for c in ("wire", "source", "compatible", "docs")) + rf"\s+{sum(counts.values())}", text)
    assert f"Suggested version bump: {data['summary']['bump']} (2.0.4 → {data['summary']['suggested_version']})" in text
    for ch in data["changes"]:  # every computed change, with its class
        assert html.escape(ch["detail"], quote=False) in out and ch["kind"] in out and ch["frame_id"] in out
    for n, item in enumerate(declared_items("2.0.5"), start=1):
        assert item["zh"] in text and item["en"] in text
        declared = [c for c in item["changes"] if c["kind"] != "unreconstructed"]
        # the "Declared in" cell of each change the item declares names the item
        assert text.count(f"V2.0.5 #{n}") == len(declared), (n, item["zh"])
    assert "Every computed change (docs-only changes aside) is declared in the record" in text
    assert "⚠ not recorded" not in text and "declared, not in the diff" not in text


def test_a_change_the_record_misses_is_flagged(tmp_path):
    spec = tmp_path / "spec"
    shutil.copytree(SPEC, spec)
    gateway = spec / "can" / "gateway.yaml"
    source = gateway.read_text(encoding="utf-8")
    assert source.count("cycle_ms: 500") == 1
    gateway.write_text(source.replace("cycle_ms: 500", "cycle_ms: 1000"), encoding="utf-8")
    _, page, data = report(V204, spec)
    text = page.plain()
    missed = next(c for c in data["changes"] if c["kind"] == "message_cycle_changed")
    assert "Computed changes no item declares" in text and missed["detail"] in text
    assert text.count("⚠ not recorded 未记录") == 1


def test_what_the_record_declares_but_the_diff_does_not_show_is_flagged():
    # The 2.0.5 DBC against the 2.0.5 spec: the same wire, so the 2.0.5 items' additions are not in the diff.
    _, page, _ = report(DBC, SPEC)
    text = page.plain()
    assert text.count("declared, not in the diff") == sum(len(i["changes"]) for i in declared_items("2.0.5"))


def test_one_page_nothing_fetched_text_escaped(tmp_path):
    base = ROOT / "tests" / "diff" / "fixtures" / "base.yaml"
    new = tmp_path / "new.yaml"
    new.write_text(base.read_text(encoding="utf-8").replace("    title: Status\n", "    title: Status <b>&amp; more</b>\n"), encoding="utf-8")
    out, page, _ = report(base, new)
    assert page.refs == [] and "<script" not in out and "<link" not in out  # styles inline, no resources
    assert "&lt;b&gt;&amp;amp; more&lt;/b&gt;" in out and "<b>&amp; more</b>" not in out
    assert "Status <b>&amp; more</b>" in page.plain()  # the text as written, shown literally
