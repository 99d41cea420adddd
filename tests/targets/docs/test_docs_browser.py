"""The handbook in a real browser: Debian's chromium, headless, driven by selenium through Debian's
chromedriver (nothing downloads a browser or a driver), the built site served on 127.0.0.1.
Screenshots go to build/docs-screenshots/ (not committed)."""

from __future__ import annotations

import functools
import http.server
import importlib.util
import os
import shutil
import tempfile
import threading
import time
from pathlib import Path
from urllib.parse import urlsplit

import pytest
from docs_support import SCREENSHOTS, built_site, require, require_mkdocs

CHROMIUM = "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"
WAIT_S = 20


class _QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, format, *args):
        pass


@pytest.fixture(scope="module")
def server():
    require_mkdocs()
    site = built_site()
    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(_QuietHandler, directory=str(site)))
    thread = threading.Thread(target=httpd.serve_forever, daemon=True)
    thread.start()
    yield f"http://127.0.0.1:{httpd.server_address[1]}"
    httpd.shutdown()
    httpd.server_close()


@pytest.fixture(scope="module")
def browser():
    require(os.access(CHROMIUM, os.X_OK) and os.access(CHROMEDRIVER, os.X_OK), "Debian chromium + chromium-driver")
    require(importlib.util.find_spec("selenium") is not None, "selenium")
    os.environ.setdefault("SE_OFFLINE", "true")  # selenium-manager must never fetch a driver
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    profile = tempfile.mkdtemp(prefix="canspec-chromium-")
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for arg in ("--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
                "--disable-sync", "--no-first-run", "--disable-dev-shm-usage", f"--user-data-dir={profile}", "--window-size=1440,1000",
                "--lang=zh-CN"):
        options.add_argument(arg)
    driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
    driver.set_page_load_timeout(60)
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    yield driver
    driver.quit()
    shutil.rmtree(profile, ignore_errors=True)


def wait_for(predicate, what: str):
    deadline = time.monotonic() + WAIT_S
    while time.monotonic() < deadline:
        value = predicate()
        if value:
            return value
        time.sleep(0.1)
    raise AssertionError(f"timed out after {WAIT_S}s waiting for {what}")


def screenshot(driver, name: str, full_page: bool = False) -> Path:
    path = SCREENSHOTS / f"{name}.png"
    if full_page:
        height = driver.execute_script("return document.documentElement.scrollHeight")
        driver.set_window_size(1440, min(max(height, 1000), 6000))
    driver.save_screenshot(str(path))
    if full_page:
        driver.set_window_size(1440, 1000)
    assert path.stat().st_size > 10_000
    return path


def test_index_page(browser, server, can):
    from selenium.webdriver.common.by import By

    browser.get(f"{server}/index.html")
    h1 = browser.find_element(By.CSS_SELECTOR, "article h1")
    assert "开沃汽车智能驾驶系统网关通讯协议" in h1.text and "V2.0.5" in h1.text
    links = browser.find_elements(By.CSS_SELECTOR, "article table a[href^='messages/']")
    hrefs = {a.get_attribute("href").rsplit("/", 1)[1] for a in links}
    assert hrefs == {f"{m.name}.html" for m in can.messages}
    tables = browser.find_elements(By.CSS_SELECTOR, "article table")
    assert len(tables) >= 4 and all(t.size["height"] > 40 for t in tables)
    screenshot(browser, "index")


def test_message_page_diagram_and_tables(browser, server, can):
    from selenium.webdriver.common.by import By

    msg = can.message("autocar_eps_command")
    browser.get(f"{server}/messages/{msg.name}.html")
    img = browser.find_element(By.CSS_SELECTOR, "img.bit-layout")
    wait_for(lambda: browser.execute_script("return arguments[0].complete && arguments[0].naturalWidth", img), "the bit diagram to load")
    assert browser.execute_script("return arguments[0].naturalWidth", img) >= 800
    assert img.size["width"] >= 600 and img.size["height"] >= 300  # laid out, not collapsed
    rows = browser.find_elements(By.XPATH, "//h2[@id='signals']/following::table[1]/tbody/tr")
    names = [r.find_element(By.TAG_NAME, "td").text for r in rows]
    assert names == [s.name for s in msg.signals]
    steer = next(r for r in rows if r.text.startswith("steering_angle_cmd"))
    assert "方向盘角度指令" in steer.text and "-1080" in steer.text and steer.size["height"] > 10
    browser.execute_script("document.getElementById('bit-layout').scrollIntoView()")
    screenshot(browser, "message-autocar_eps_command")
    screenshot(browser, "message-autocar_eps_command-full", full_page=True)


def test_bit_diagram_renders_its_spans(browser, server, can):
    from selenium.webdriver.common.by import By

    msg = can.message("vehicle_state_1")
    browser.get(f"{server}/messages/{msg.name}.svg")
    groups = browser.find_elements(By.CSS_SELECTOR, "g.signal")
    assert len(groups) == sum(len(s.segments) for s in msg.signals)
    box = browser.execute_script("const b = document.querySelector('g.signal rect').getBBox(); return [b.width, b.height];")
    assert box[0] > 0 and box[1] > 0
    screenshot(browser, "svg-vehicle_state_1")


def test_search_finds_a_signal_by_its_chinese_name(browser, server):
    from selenium.webdriver.common.by import By
    from selenium.webdriver.common.keys import Keys

    browser.get(f"{server}/index.html")
    box = wait_for(lambda: next((e for e in browser.find_elements(By.CSS_SELECTOR, "input.md-search__input") if e.is_displayed()), None), "the search box")
    box.click()  # as a user does: focus the header's search box, then type
    box.send_keys("方向盘角度指令")

    def result_pages() -> set[str]:
        hits = browser.find_elements(By.CSS_SELECTOR, ".md-search-result__item a")
        return {urlsplit(a.get_attribute("href")).path for a in hits}

    # The three EPS command messages carry the signal 方向盘角度指令 (steering_angle_cmd).
    want = {f"/messages/{m}.html" for m in ("autocar_eps_command", "rgate_eps_command", "tele_eps_command")}
    pages = wait_for(lambda: result_pages() >= want and result_pages(), "search results for 方向盘角度指令")
    assert want <= pages, pages
    meta = browser.find_element(By.CSS_SELECTOR, ".md-search-result__meta").text
    assert "结果" in meta  # "N 个符合条件的结果"
    marks = [m.text for m in browser.find_elements(By.CSS_SELECTOR, ".md-search-result mark")]
    assert any("方向盘" in m or "角度" in m for m in marks), marks
    screenshot(browser, "search-zh-steering_angle_cmd")
    box.send_keys(Keys.ESCAPE)
