"""The PDF handbook (`canspec pdf`, `make docs-pdf`) read back with poppler: pdftotext finds every
message ID, title and signal name, the chapters where the contents say they are, and a numbered
foot on every page; pdftoppm's page images are not blank and the message pages carry their coloured
bit diagrams; pdffonts shows the Chinese font embedded. The same spec gives the same bytes.

Needs WeasyPrint, Debian's fonts-noto-cjk and poppler-utils (.ci/setup.d/75-pdf.sh): a missing
one fails, it is never skipped."""

from __future__ import annotations

import functools
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from repo_paths import CANSPEC_ENV, GENERATED, ROOT

MINIMAL = ROOT / "tests" / "fixtures" / "valid" / "minimal_can.yaml"
# Fill colours of the bit diagrams' signal spans (targets/docs/svg.py PALETTE, first three).
SPAN_FILLS = ((0xCF, 0xE6, 0xF7), (0xFD, 0xE2, 0xC0), (0xC9, 0xEC, 0xDF))
TOC_LINE = re.compile(r"^(.+?)\s*(?:\.\s*){3,}(\d+)$")


def tool(name: str) -> str:
    path = shutil.which(name)
    assert path, f"{name} is not installed (poppler-utils: bash .ci/setup.d/75-pdf.sh)"
    return path


def build(spec: Path | str, out: Path, *extra: str) -> Path:
    r = subprocess.run([sys.executable, "-m", "canspec", "pdf", str(spec), "-o", str(out), *extra], cwd=ROOT, env=CANSPEC_ENV,
                       capture_output=True, text=True, timeout=600, check=False)
    assert r.returncode == 0, r.stderr
    return out


@pytest.fixture(scope="module")
def pdf(tmp_path_factory) -> Path:
    return build("spec", tmp_path_factory.mktemp("pdf") / "handbook.pdf")


@functools.lru_cache(maxsize=4)
def pages(path: Path) -> list[str]:
    text = subprocess.run([tool("pdftotext"), "-enc", "UTF-8", str(path), "-"], capture_output=True, text=True, check=True).stdout
    return text.split("\f")[:-1]  # pdftotext ends every page with a form feed


def page_count(path: Path) -> int:
    info = subprocess.run([tool("pdfinfo"), str(path)], capture_output=True, text=True, check=True).stdout
    return int(re.search(r"^Pages:\s+(\d+)$", info, re.MULTILINE).group(1))


def test_text_has_every_message_and_signal(pdf, spec):
    text = "\n".join(pages(pdf))
    can = spec.can
    assert can.title_zh in text and can.title in text and f"V{spec.version}" in text and spec.sha256 in text
    for msg in can.messages:
        for needle in (f"0x{msg.frame_id:08X}", msg.zh, msg.title, *(s.name for s in msg.data_signals), *(s.zh for s in msg.data_signals if s.zh)):
            assert needle in text, (msg.name, needle)
    for title in ("修订历史 Revision history", "概览 Overview", "值表 Value tables", "总线负载 Bus load", "勘误 Errata"):
        assert title in text


def test_every_page_is_numbered_and_the_count_is_stable(pdf):
    texts, total = pages(pdf), page_count(pdf)
    assert len(texts) == total and 60 <= total <= 200
    for n, text in enumerate(texts[1:], start=2):  # the cover has no foot
        assert f"{n} / {total}" in text, n


def contents(pdf: Path) -> dict[str, int]:
    """The contents page's entries: title → page number (WeasyPrint's target-counter)."""
    lines = [ln.strip() for ln in pages(pdf)[1].splitlines()]
    return {m.group(1): int(m.group(2)) for ln in lines if (m := TOC_LINE.match(ln))}


def nav_headings() -> dict[str, str]:
    """Each page of the site (generated/docs/, the same content) → its title in the navigation and
    its first heading: what the contents list and where each chapter starts."""
    def walk(nav: list) -> list[tuple[str, str]]:
        return [pair for entry in nav for title, target in entry.items() for pair in (walk(target) if isinstance(target, list) else [(title, target)])]

    nav = yaml.safe_load((GENERATED / "docs" / "mkdocs.nav.yml").read_text(encoding="utf-8"))["nav"]
    out = {}
    for title, path in walk(nav):
        lines = (GENERATED / "docs" / path).read_text(encoding="utf-8").splitlines()
        out[title] = re.sub(r"\s*\{#[^}]*\}$", "", next(ln[2:] for ln in lines if ln.startswith("# ")))
    return out


def flat(text: str) -> str:
    return " ".join(text.split())


def test_contents_point_at_the_chapters(pdf):
    toc, texts, headings = contents(pdf), pages(pdf), nav_headings()
    assert set(toc) == set(headings)
    assert next(iter(toc)) == "修订历史 Revision history"  # the change record first, as the document prints it
    numbers = list(toc.values())
    assert numbers == sorted(numbers) and len(set(numbers)) == len(numbers)  # one chapter after the other
    for title, number in toc.items():
        assert flat(headings[title]) in flat(texts[number - 1]), (title, number)


def _image(pdf: Path, number: int, tmp_path: Path):  # type: ignore[no-untyped-def]
    from PIL import Image  # WeasyPrint's own dependency

    stem = tmp_path / f"p{number}"
    subprocess.run([tool("pdftoppm"), "-r", "40", "-f", str(number), "-l", str(number), "-singlefile", "-png", str(pdf), str(stem)], check=True)
    return Image.open(f"{stem}.png").convert("RGB")


def test_page_images_are_not_blank_and_show_bit_diagrams(pdf, spec, tmp_path):
    toc, texts = contents(pdf), pages(pdf)
    cover = _image(pdf, 1, tmp_path)
    assert sum(n for n, px in cover.getcolors(cover.width * cover.height) if px != (255, 255, 255)) > 0.005 * cover.width * cover.height
    drawn = [m for m in spec.can.messages if m.signals]
    for msg in drawn:  # every diagram is drawn: its labels (bit columns, the last cell's bit number) are on the message's first page
        text = texts[toc[f"0x{msg.frame_id:08X} {msg.zh}"] - 1].split()
        assert {"bit", "7", "0", "byte", str(8 * msg.dlc - 1)} <= set(text), msg.name
    for msg in (drawn[0], max(drawn, key=lambda m: len(m.signals)), spec.can.message("device_id")):  # and looks drawn
        img = _image(pdf, toc[f"0x{msg.frame_id:08X} {msg.zh}"], tmp_path)
        colours = img.getcolors(img.width * img.height)  # (count, rgb) pairs
        ink = sum(n for n, px in colours if px != (255, 255, 255))
        spans = sum(n for n, px in colours if any(all(abs(a - b) <= 6 for a, b in zip(px, fill)) for fill in SPAN_FILLS))
        assert ink > 0.05 * img.width * img.height, msg.name
        assert spans > 0.01 * img.width * img.height, f"{msg.name}: no coloured bit diagram on its first page"


def test_same_spec_same_bytes_chinese_font_embedded(tmp_path):
    """No clock or randomness in the PDF: the page count (and every byte) is the same on every build.
    The HTML it is printed from stands alone: every image is embedded, nothing is fetched."""
    first = build(MINIMAL, tmp_path / "a.pdf", "--html", str(tmp_path / "a.html")).read_bytes()
    second = build(MINIMAL, tmp_path / "b.pdf").read_bytes()
    assert first == second and first.startswith(b"%PDF-")
    assert page_count(tmp_path / "a.pdf") >= 5
    # The Chinese font is embedded: subset, with a Unicode map (text extracts). Checked on this small
    # PDF, as the fonts do not depend on the spec (pdffonts walks every page's resources: slow on a big one).
    fonts = subprocess.run([tool("pdffonts"), str(tmp_path / "a.pdf")], capture_output=True, text=True, check=True).stdout
    cjk = [ln for ln in fonts.splitlines() if "NotoSansCJK" in ln.replace("-", "")]
    assert cjk and all(" yes yes yes " in ln for ln in cjk), fonts
    html = (tmp_path / "a.html").read_text(encoding="utf-8")
    assert re.findall(r'src="([^"]{0,26})', html) and all(src.startswith("data:image/svg+xml;base64,") for src in re.findall(r'src="([^"]{0,26})', html))
    assert "http://" not in html.replace("http://www.w3.org/2000/svg", "") and "https://" not in html


def test_a_spec_the_handbook_cannot_show_is_a_clear_error(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("schema_version: 1\nkind: can_protocol\n", encoding="utf-8")
    r = subprocess.run([sys.executable, "-m", "canspec", "pdf", str(bad), "-o", str(tmp_path / "x.pdf")], cwd=ROOT, env=CANSPEC_ENV,
                       capture_output=True, text=True, timeout=300, check=False)
    assert r.returncode == 1 and "Traceback" not in r.stderr and "canspec pdf: the spec has errors" in r.stderr
    assert not (tmp_path / "x.pdf").exists()


FD_FLOAT = ROOT / "tests" / "fixtures" / "valid" / "motorola_fd_float.yaml"


def test_a_motorola_fd_float_bus_prints_every_row_of_its_64_byte_frame(tmp_path):
    """The handbook of a Motorola / CAN FD / float bus: the signals, their byte order and float type,
    the FD lengths; the 64-byte frame's diagram in four parts, each on a page of its own with its
    coloured spans, together printing the bit number of every one of the 512 cells (none cut off)."""
    from canspec.targets.docs.svg import PALETTE

    pdf = build(FD_FLOAT, tmp_path / "fd.pdf")
    data = yaml.safe_load(FD_FLOAT.read_text(encoding="utf-8"))
    texts = pages(pdf)
    text = "\n".join(texts)
    for needle in ("float32", "float64", "Motorola", "Intel", "64 bytes (DLC code 15)", "12 bytes (DLC code 9)", "2000 kbit/s",
                   *(s["name"] for m in data["messages"] for s in m["signals"])):
        assert needle in text, needle
    toc = contents(pdf)
    first, after = toc["0x2B0 radar_objects"], toc["0x3C0 body_status"]
    tokens = set(" ".join(texts[first - 1:after - 1]).split())
    assert {str(n) for n in range(512)} <= tokens
    fills = [tuple(int(f[i:i + 2], 16) for i in (1, 3, 5)) for f, _ in PALETTE]
    for number in range(first, first + 4):  # bytes 0–15, 16–31, 32–47, 48–63
        img = _image(pdf, number, tmp_path)
        spans = sum(n for n, px in img.getcolors(img.width * img.height) if any(all(abs(a - b) <= 6 for a, b in zip(px, f)) for f in fills))
        assert spans > 0.002 * img.width * img.height, number
        assert "bit 7" in texts[number - 1], number


MUX = ROOT / "tests" / "fixtures" / "valid" / "multiplexed.yaml"


def test_a_multiplexed_message_prints_one_diagram_per_page_and_when_each_field_is_present(tmp_path):
    """The mux fixture's handbook: every signal, and the pages' conditions (the Present column and the
    diagrams' captions) as the fixture's comment states them (mode 0; 1, 4…6; channel 0 or 1…3 under mode 2)."""
    pdf = build(MUX, tmp_path / "mux.pdf")
    text = " ".join(" ".join(pages(pdf)).split())
    data = yaml.safe_load(MUX.read_text(encoding="utf-8"))
    for needle in (*(s["name"] for m in data["messages"] for s in m["signals"]), "mode = 0", "mode = 1, 4…6", "mode = 2 and channel = 0",
                   "mode = 2 and channel = 1…3", "every frame"):
        assert needle in text, needle
