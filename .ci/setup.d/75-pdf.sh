#!/usr/bin/env bash
# The PDF handbook (`make docs-pdf`, tests/pdf/test_pdf.py): WeasyPrint (pinned: its layout decides
# the pages) on Debian's Pango, the Noto CJK fonts for the Chinese text, poppler-utils to read the PDF
# back (pdftotext, pdftoppm, pdffonts). The spreadsheet's readers (openpyxl, pandas) come with '.[test]'.
set -euo pipefail
apt_install fonts-noto-cjk poppler-utils libpango-1.0-0 libpangoft2-1.0-0 libharfbuzz-subset0
python3 -m pip install -q --disable-pip-version-check 'weasyprint==70.0' 'markdown>=3.5'
