"""The handbook's pages as one printable HTML document.

The content is the site's: the docs target renders its Markdown pages and bit-layout SVGs in
memory, in the order of its navigation, and each page becomes a chapter here — Markdown to HTML
with the site's extensions, every id prefixed with its page (`messages-eps_state--signals`) so the
pages can share one document, links between pages turned into links inside it, and each SVG
embedded as a data URI so the document needs no other file. The change record comes first, as
protocol documents print it; then the pages in the site's order.
"""

from __future__ import annotations

import base64
import posixpath
import re
from dataclasses import dataclass
from typing import Any

import yaml

from canspec import ir
from canspec.generation import GenerationError, generate

DOCS = "docs/"
NAV = "mkdocs.nav.yml"  # the docs target's navigation (pages in order, with their titles)
FIRST = ("history.md",)  # chapters printed before the site's order
EXTENSIONS = ["tables", "attr_list", "admonition", "toc", "fenced_code"]
_ATTR = re.compile(r'(?<![\w-])(id|href|src)="([^"]*)"')
_EXTERNAL = re.compile(r"^(?:[a-z][a-z0-9+.-]*:|//)", re.IGNORECASE)


@dataclass(frozen=True)
class Chapter:
    path: str  # the page in the site: "messages/eps_state.md"
    title: str  # its title in the navigation
    part: str | None  # the navigation section it belongs to ("报文 Messages"), if any
    anchor: str  # id of the chapter in the document
    html: str


def slug(path: str) -> str:
    return path.removesuffix(".md").replace("/", "-")


def nav_pages(nav: list[Any], part: str | None = None) -> list[tuple[str, str, str | None]]:
    """(path, title, section) of every page, in navigation order."""
    out: list[tuple[str, str, str | None]] = []
    for entry in nav:
        for title, target in entry.items():
            if isinstance(target, list):
                out += nav_pages(target, title)
            else:
                out.append((target, title, part))
    return out


def relink(html: str, page: str, pages: set[str], files: dict[str, bytes]) -> str:
    """Ids prefixed with the page, links to pages and anchors made document-internal, images embedded."""
    here, base = slug(page), posixpath.dirname(page)

    def attr(m: re.Match[str]) -> str:
        name, value = m.group(1), m.group(2)
        if name == "id":
            return f'id="{here}--{value}"'
        if _EXTERNAL.match(value):
            return m.group(0)
        target, _, fragment = value.partition("#")
        resolved = posixpath.normpath(posixpath.join(base, target)) if target else page
        if name == "src":
            data = base64.b64encode(files[DOCS + resolved]).decode("ascii")
            return f'src="data:image/svg+xml;base64,{data}"'
        if resolved not in pages:
            raise GenerationError(f"handbook: {page} links to {value!r}, a page the docs target did not write")
        return f'href="#{slug(resolved)}' + (f"--{fragment}" if fragment else "") + '"'

    return _ATTR.sub(attr, html)


def chapters(spec: ir.Spec) -> list[Chapter]:
    try:
        import markdown  # the PDF extra's dependency (MkDocs brings it too)
    except ImportError:
        raise GenerationError("the PDF handbook needs Python-Markdown: pip install 'canspec[pdf]'") from None

    files = generate(spec, ["docs"])["docs"]  # a failing page is a GenerationError naming the target
    order = nav_pages(yaml.safe_load(files[DOCS + NAV])["nav"])
    order = [p for p in order if p[0] in FIRST] + [p for p in order if p[0] not in FIRST]
    pages = {path for path, _, _ in order}
    out = []
    for path, title, part in order:
        text = files[DOCS + path].decode("utf-8")
        html = markdown.markdown(text, extensions=EXTENSIONS, output_format="html")
        out.append(Chapter(path, title, part, slug(path), relink(html, path, pages, files)))
    return out
