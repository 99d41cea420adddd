"""Print the handbook's HTML to PDF with WeasyPrint: a paged-media renderer (running heads, page
numbers, contents with page numbers, PDF bookmarks from the headings) whose output for the same
HTML and fonts is the same bytes. Fonts come from the system: Debian's fonts-noto-cjk for the
Chinese text (installed by .ci/setup.d/75-pdf.sh)."""

from __future__ import annotations

from pathlib import Path

INSTALL_HINT = "pip install 'canspec[pdf]' (WeasyPrint; on Debian also: apt-get install fonts-noto-cjk libpango-1.0-0 libpangoft2-1.0-0)"


class RendererMissing(RuntimeError):
    pass


def write_pdf(html: str, out: Path) -> None:
    try:
        import weasyprint
    except (ImportError, OSError) as exc:  # OSError: WeasyPrint installed but Pango missing
        raise RendererMissing(f"the PDF renderer is not available ({exc}): {INSTALL_HINT}") from None
    weasyprint.HTML(string=html, base_url=str(out.parent)).write_pdf(out)
