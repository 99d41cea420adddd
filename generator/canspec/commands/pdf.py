"""`canspec pdf [SPEC] [-o FILE] [--html FILE]`: the protocol handbook as one bilingual PDF — the
site's pages (`make docs`) behind a cover naming the protocol, its version and the spec hash."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from canspec.commands.common import add_spec_argument, compile_or_report
from canspec.generation import GenerationError
from canspec.pdf.document import handbook_html
from canspec.pdf.render import RendererMissing, write_pdf


def run(args: argparse.Namespace) -> int:
    compiled = compile_or_report(args.spec, quiet_warnings=True, cached=True)
    if compiled.spec is None:
        print("canspec pdf: the spec has errors (see above)", file=sys.stderr)
        return 1
    out = Path(args.output)
    try:
        html = handbook_html(compiled.spec)
        out.parent.mkdir(parents=True, exist_ok=True)
        if args.html:
            Path(args.html).write_text(html, encoding="utf-8")
        write_pdf(html, out)
    except (GenerationError, RendererMissing) as exc:
        print(f"canspec pdf: {exc}", file=sys.stderr)
        return 1
    except OSError as exc:
        print(f"canspec pdf: cannot write {exc.filename or out}: {exc.strerror}", file=sys.stderr)
        return 1
    print(f"canspec pdf: wrote {out}", file=sys.stderr)
    return 0


def register(sub) -> None:  # type: ignore[no-untyped-def]
    p = sub.add_parser("pdf", help="the protocol handbook as one bilingual PDF (cover, contents, every page of the site)")
    add_spec_argument(p)
    p.add_argument("-o", "--output", default="handbook.pdf", help="the PDF to write (default: handbook.pdf)")
    p.add_argument("--html", help="also write the printable HTML the PDF is made from")
    p.set_defaults(func=run)
