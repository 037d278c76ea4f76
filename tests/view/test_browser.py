"""The viewer page in a real headless Chromium (the ``browser`` tier: tests/view/run_browser.sh).

Skipped, saying why, where Chromium or the websocket client is missing. Pixels are read from the
page's own WebGL canvas (it keeps its drawing buffer), through a 2D canvas in the page.
"""

from __future__ import annotations

import json
import pathlib
from collections.abc import Iterator
from typing import Any

import pytest

from robodesc.options import build_options
from robodesc.view import write_view_html
from tests.view.cases import GRIPPER, QUADRUPED
from tests.view.cdp import Browser, find_chromium

pytestmark = pytest.mark.browser

REGION = 40  # half the side of the square looked at around a link, in CSS pixels


@pytest.fixture(scope="module")
def browser() -> Iterator[Browser]:
    if find_chromium() is None:
        pytest.skip("no chromium: tests/view/run_browser.sh installs Debian's")
    pytest.importorskip("websocket", reason="pip install websocket-client")
    with Browser(1200, 800) as b:
        yield b


def pixels(b: Browser, x: float, y: float, half: int = REGION) -> list[int]:
    """RGB values of the canvas square centred at (x, y), as a flat list."""
    script = f"""(() => {{
        const c = document.querySelector('#view canvas');
        const k = c.width / c.clientWidth;
        const s = {2 * half} * k, x0 = Math.round(({x} - {half}) * k), y0 = Math.round(({y} - {half}) * k);
        const two = document.createElement('canvas'); two.width = s; two.height = s;
        const g = two.getContext('2d'); g.drawImage(c, -x0, -y0);
        const d = g.getImageData(0, 0, s, s).data; const out = [];
        for (let i = 0; i < d.length; i += 4) out.push(d[i], d[i + 1], d[i + 2]);
        return out; }})()"""
    values: list[int] = b.eval(script)
    return values


def difference(a: list[int], b: list[int]) -> float:
    return sum(abs(p - q) for p, q in zip(a, b, strict=True)) / len(a)


def whole_canvas(b: Browser) -> list[int]:
    size: dict[str, Any] = b.eval(
        "(() => { const c = document.querySelector('#view canvas'); return {w: c.clientWidth, h: c.clientHeight}; })()"
    )
    return pixels(b, size["w"] / 2, size["h"] / 2, int(min(size["w"], size["h"]) / 2) - 1)


def open_page(b: Browser, path: pathlib.Path) -> None:
    b.console_errors.clear()
    b.requests.clear()
    b.open(str(path))
    b.settle()


def test_loads_offline_without_errors(browser: Browser, tmp_path: pathlib.Path) -> None:
    page = tmp_path / "gripper.html"
    write_view_html(GRIPPER, str(page))
    open_page(browser, page)
    assert browser.console_errors == []
    assert browser.eval("window.robodesc.errors") == []
    # The only request is the page itself: no script, style, mesh or font came from anywhere else.
    assert [u for u in browser.requests if not u.startswith(("data:", "blob:"))] == [page.as_uri()]
    values = whole_canvas(browser)
    mean = sum(values) / len(values)
    spread = (sum((v - mean) ** 2 for v in values) / len(values)) ** 0.5
    assert spread > 10, "the canvas is blank"


def test_slider_moves_the_link(browser: Browser, tmp_path: pathlib.Path) -> None:
    page = tmp_path / "gripper.html"
    write_view_html(GRIPPER, str(page))
    open_page(browser, page)
    where = browser.eval("window.robodesc.project('forearm')")
    base = browser.eval("window.robodesc.project('base_link')")
    before, base_before = pixels(browser, where["x"], where["y"]), pixels(browser, base["x"], base["y"], 15)
    # Through the slider, as a user would: its value, then its input event.
    browser.eval(
        "(() => { const s = document.getElementById('joint-shoulder_pitch'); s.value = s.max;"
        " s.dispatchEvent(new Event('input')); })()"
    )
    browser.settle()
    assert browser.eval("window.robodesc.jointValue('shoulder_pitch')") == pytest.approx(
        float(browser.eval("document.getElementById('joint-shoulder_pitch').max"))
    )
    after, base_after = pixels(browser, where["x"], where["y"]), pixels(browser, base["x"], base["y"], 15)
    assert difference(before, after) > 5, "the forearm did not move"
    assert difference(base_before, base_after) < 1, "the base moved too"
    assert browser.console_errors == []


def test_slider_range_is_the_joint_limits(browser: Browser, tmp_path: pathlib.Path) -> None:
    page = tmp_path / "gripper.html"
    write_view_html(GRIPPER, str(page))
    open_page(browser, page)
    ranges = browser.eval(
        "[...document.querySelectorAll('input[type=range]')].map(s => [s.id, +s.min, +s.max, +s.value])"
    )
    data = {j["name"]: j for j in browser.eval("window.robodesc.data.joints")}
    for ident, lo, hi, value in ranges:
        joint = data[ident.removeprefix("joint-")]
        assert [lo, hi] == pytest.approx(joint["range"]) and lo <= value <= hi
    # A mimic joint follows its leader.
    browser.eval("window.robodesc.setJoint('finger_left_joint', 0.01)")
    mimic = data["finger_right_joint"]["mimic"]
    assert browser.eval("window.robodesc.jointValue('finger_right_joint')") == pytest.approx(
        mimic["multiplier"] * 0.01 + mimic["offset"]
    )


def test_clicking_a_finding_highlights_its_link(browser: Browser, tmp_path: pathlib.Path, defects_urdf: str) -> None:
    page = tmp_path / "defects.html"
    write_view_html(defects_urdf, str(page), options=build_options({}))
    open_page(browser, page)
    findings = browser.eval("window.robodesc.data.findings")
    index = next(i for i, f in enumerate(findings) if f["link"] == "forearm")
    where = browser.eval("window.robodesc.project('forearm')")
    before = pixels(browser, where["x"], where["y"], 10)
    browser.click(f"#finding-{index}")
    browser.settle()
    assert browser.eval("window.robodesc.highlighted") == "forearm"
    assert browser.eval("document.querySelector('.tree .link.active').dataset.link") == "forearm"
    assert difference(before, pixels(browser, where["x"], where["y"], 10)) > 5, "the link is not highlighted"
    assert browser.console_errors == []


def test_toggles_and_repairs(browser: Browser, tmp_path: pathlib.Path) -> None:
    page = tmp_path / "quad.html"
    write_view_html(QUADRUPED, str(page), target="isaac")
    open_page(browser, page)
    before = whole_canvas(browser)
    for name in ("collision", "frames", "axes", "com", "inertia"):
        browser.click(f"#toggle-{name}")
    browser.settle()
    assert difference(before, whole_canvas(browser)) > 0.5
    browser.click("#repair-0")
    browser.settle()
    repair = json.loads(json.dumps(browser.eval("window.robodesc.data.repairs[0]")))
    assert browser.eval("window.robodesc.highlighted") == repair["link"]
    assert browser.console_errors == []


def test_world_ground_is_drawn_under_the_robot(browser: Browser, tmp_path: pathlib.Path) -> None:
    """``view --world``: the terrain drawn under the robot (docs/worlds.md, "Pictures")."""
    from tests.conftest import WORLDS

    pages = {}
    for name, extra in (("alone", {}), ("world", {"world": str(WORLDS / "step_20cm" / "step_20cm.world")})):
        page = tmp_path / f"{name}.html"
        write_view_html(QUADRUPED, str(page), options=build_options(extra))
        open_page(browser, page)
        assert browser.console_errors == [] and browser.eval("window.robodesc.errors") == []
        pages[name] = (
            browser.eval("window.robodesc.groundShapes || 0"),
            browser.eval("window.robodesc.project('trunk')"),
        )
        size = browser.eval("(() => { const c = document.querySelector('#view canvas'); return c.clientHeight; })()")
        pages[name] += (pixels(browser, pages[name][1]["x"], size - 50, 30),)
    assert pages["alone"][0] == 0 and pages["world"][0] == 1
    # The robot framed alike; under it, the page's background grid against the terrain.
    assert pages["world"][1]["x"] == pytest.approx(pages["alone"][1]["x"], abs=2)
    assert difference(pages["alone"][2], pages["world"][2]) > 20
