#!/usr/bin/env bash
# The protocol handbook (`make docs`) and its browser test: MkDocs + Material (pinned), jieba for
# Chinese search segmentation, selenium driving Debian's chromium through Debian's chromedriver
# (no tool downloads a browser or a driver), and a CJK font so screenshots show the Chinese text.
set -euo pipefail
apt_install chromium chromium-driver fonts-wqy-microhei
python3 -m pip install -q --disable-pip-version-check \
  mkdocs==1.6.1 mkdocs-material==9.8.1 pymdown-extensions==13.1 jieba==0.42.1 selenium==4.51.0
