# SPDX-License-Identifier: GPL-2.0-or-later
"""The live page in a real browser: Debian's chromium, headless, driven over
the DevTools protocol (cdp.py).  The page is loaded against a running HAL
(wall clock) with a siggen; what it shows is compared with halcmd and with a
model of siggen; a value changed on the page is read back with halcmd getp;
screenshots are kept in $HM_BUILD/test-artifacts/halview/."""

from __future__ import annotations

import json
import math
import os
import time
from pathlib import Path
from typing import Iterator

import pytest

from cdp import Browser, Page
from hvutil import BIN, BUILD, BUILT, LiveHal, Siggen

pytestmark = pytest.mark.requires_build(*BUILT, "/usr/bin/chromium")

ARTIFACTS = BUILD / "test-artifacts" / "halview"

LIVE = """\
loadrt threads name1=fast period1=1000000
loadrt siggen
addf siggen.0.update fast
setp siggen.0.frequency 10
newsig free float
sets free 1.5
start
"""


@pytest.fixture(scope="module")
def browser() -> Iterator[Browser]:
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    with Browser() as b:
        yield b


@pytest.fixture
def live(tmp_path: Path) -> Iterator[LiveHal]:
    hal = LiveHal(tmp_path, LIVE)
    yield hal
    hal.stop()


def shot(page: Page, name: str) -> None:
    page.screenshot(ARTIFACTS / f"{name}.png")
    assert (ARTIFACTS / f"{name}.png").stat().st_size > 5000


def no_errors(page: Page) -> None:
    errs = [e for e in page.console_errors() if "favicon" not in e]
    assert errs == []


def test_tree_shows_hal_and_sets_a_parameter(browser: Browser, live: LiveHal) -> None:
    _, url = live.start_web(BIN / "halshow", "--web")
    page = browser.new_page(url)
    try:
        page.wait_for("!!document.querySelector('#tree .leaf[data-name=\"siggen.0.amplitude\"]')")
        shown = page.eval(
            "document.querySelector('#tree .leaf[data-name=\"siggen.0.amplitude\"] .val')"
            ".textContent"
        )
        assert shown == live.getp("siggen.0.amplitude")
        pins = page.eval(
            "[...document.querySelectorAll('#section-pin .leaf')].map(e => e.dataset.name)"
        )
        assert pins == live.halcmd("list", "pin").stdout.split()
        # a user types a frequency into the tree's field and presses set
        sel = '#tree .leaf[data-name="siggen.0.frequency"]'
        page.type_into(f"{sel} .tree-set-input", "12.5")
        page.click(f"{sel} .tree-set-button")
        page.wait_for(
            f"(document.querySelector('{sel} .set-result') || {{}}).textContent?.includes('set')"
        )
        assert live.getp("siggen.0.frequency") == "12.5"
        # a bad value: halcmd's reason on the page, HAL unchanged
        page.type_into(f"{sel} .tree-set-input", "fast")
        page.click(f"{sel} .tree-set-button")
        page.wait_for(f"document.querySelector('{sel} .set-result').className.includes('error')")
        text = page.eval(f"document.querySelector('{sel} .set-result').textContent").strip()
        assert text == "value 'fast' invalid for float"
        assert live.getp("siggen.0.frequency") == "12.5"
        # an output pin has no set field (halcmd would refuse it)
        assert not page.eval(
            "!!document.querySelector('#tree .leaf[data-name=\"siggen.0.sine\"] input')"
        )
        # the filter narrows the tree
        page.type_into("#filter", "siggen.0.s")
        page.wait_for(
            "document.getElementById('tree-count').textContent === '3 objects'"
        )  # sawtooth, sine, square
        shot(page, "halshow-tree")
        no_errors(page)
    finally:
        page.close()


def test_watch_list_matches_halcmd(browser: Browser, live: LiveHal) -> None:
    _, url = live.start_web(BIN / "halmeter", "--web", "pin", "siggen.0.amplitude", "sig", "free")
    page = browser.new_page(url)
    try:
        cell = "(document.querySelector('#watch-list tr[data-key=\"{}\"] .watch-value') || {{}}).textContent"
        page.wait_for(cell.format("sig+free") + " === '1.5'")
        assert page.eval(cell.format("pin+siggen.0.amplitude")) == live.getp("siggen.0.amplitude")
        live.halcmd("setp", "siggen.0.amplitude", "0.5")
        page.wait_for(cell.format("pin+siggen.0.amplitude") + " === '0.5'")
        row = '#watch-list tr[data-key="sig+free"]'
        page.type_into(f"{row} .set-input", "-2.75")
        page.click(f"{row} .set-button")
        page.wait_for(cell.format("sig+free") + " === '-2.75'")
        assert live.halcmd("gets", "free").stdout.strip() == "-2.75"
        # add a watch by name, as a user types it
        page.type_into("#watch-add", "param+fast.tmax")
        page.click("#watch-add-button")
        page.wait_for(cell.format("param+fast.tmax") + " !== ''")
        time.sleep(0.5)
        shot(page, "halmeter-watch")
        no_errors(page)
    finally:
        page.close()


def match_model(sine: list[float], freq: float) -> int:
    """Index k such that siggen's sine after updates k+1.. equals the trace."""
    g = Siggen(freq)
    model = [g.update(1_000_000)["sine"] for _ in range(400_000)]
    for k in range(len(model) - len(sine)):
        if model[k] == sine[0] and model[k : k + len(sine)] == sine:
            return k
    raise AssertionError("the trace is not a stretch of siggen's sine")


def test_scope_trace_matches_hal(browser: Browser, live: LiveHal, tmp_path: Path) -> None:
    _, url = live.start_web(
        BIN / "halscope",
        "--web",
        "-c",
        "siggen.0.square,siggen.0.sine",
        "--thread",
        "fast",
        "--trigger",
        "siggen.0.square",
        "--level",
        "0",
        "--samples",
        "400",
        "--position",
        "20",
    )
    page = browser.new_page(url)
    try:
        # the capture and what was plotted from it, read at one moment (normal
        # mode re-arms: the next capture may arrive at any time)
        page.wait_for("window.halweb.lastCapture", 30)
        cap, plotted = page.eval("[window.halweb.lastCapture, window.halweb.plotted]")
        assert cap["names"] == ["siggen.0.square", "siggen.0.sine"]
        assert cap["interval"] == 1_000_000 and cap["trigger"] == 80
        sq, sine = cap["columns"]
        assert len(sq) == 400 and sq[79] == -1.0 and sq[80] == 1.0
        rises = [i for i in range(1, 400) if sq[i - 1] < 0 <= sq[i]]
        assert rises[0] == 80 and all(b - a == 100 for a, b in zip(rises, rises[1:]))
        k = match_model(sine, 10.0)
        g = Siggen(10.0)
        ref = [g.update(1_000_000)["square"] for _ in range(k + 400)][k:]
        assert sq == ref
        assert page.eval("document.querySelectorAll('#scope-plot canvas').length") > 0
        assert plotted["rows"] == 400 and plotted["first"][0] == -80.0
        assert plotted["first"][1:] == [sq[0], sine[0]]
        assert plotted["last"][1:] == [sq[-1], sine[-1]]
        shot(page, "halscope-trace")
        # the user changes the record and the trigger on the page and runs it
        n0 = page.eval("window.halweb.captures")
        page.type_into("#scope-samples", "250")
        page.type_into("#scope-position", "50")
        page.eval("document.getElementById('scope-edge').value = 'falling'")
        page.click("#scope-run")
        page.wait_for(
            f"window.halweb.captures > {n0} && window.halweb.lastCapture.columns[0].length === 250",
            30,
        )
        cap = page.eval("window.halweb.lastCapture")
        sq = cap["columns"][0]
        assert cap["trigger"] == 125 and sq[124] == 1.0 and sq[125] == -1.0
        shot(page, "halscope-falling")
        # a setup file loaded through the page's file field fills the form
        setup = tmp_path / "mine.halscope"
        setup.write_text(
            "thread fast\nsamples 321\nmode single\n"
            "trigger siggen.0.sine falling 0.5 position 30\n"
            "chan pin siggen.0.sine scale 2 offset 1\n"
        )
        page.set_file("#scope-load", setup)
        page.wait_for("document.getElementById('scope-samples').value === '321'")
        assert page.eval(
            "[document.getElementById('scope-channels').value, document.getElementById("
            "'scope-mode').value, document.getElementById('scope-trigger').value, "
            "document.getElementById('scope-edge').value, document.getElementById("
            "'scope-position').value]"
        ) == ["siggen.0.sine", "single", "siggen.0.sine", "falling", "30"]
        assert page.eval("JSON.stringify(window.halweb.scopeSetup.channels)") == (
            '[{"name":"siggen.0.sine","scale":2,"offset":1}]'
        )
        no_errors(page)
    finally:
        page.close()


def test_browser_closed_mid_stream(live: LiveHal) -> None:
    """The whole browser goes away while the scope rolls and values stream:
    the server keeps serving the next page, HAL keeps running."""
    srv, url = live.start_web(
        BIN / "halscope",
        "--web",
        "-c",
        "siggen.0.sine",
        "--thread",
        "fast",
        "--mode",
        "roll",
        "--rate",
        "50",
    )
    with Browser() as b:
        page = b.new_page(url)
        page.wait_for("window.halweb.lastChunk && window.halweb.stats.updates > 5", 30)
        b.proc.kill()  # no goodbye
    time.sleep(0.5)
    assert srv.poll() is None
    with Browser() as b:
        page = b.new_page(url)
        page.wait_for("window.halweb.lastChunk && window.halweb.stats.updates > 5", 30)
        assert page.eval("window.halweb.lastChunk.lost") == 0
        shot(page, "halscope-roll")
    assert live.getp("siggen.0.frequency") == "10"
    assert "scope.sample" in live.halcmd("show", "thread").stdout
