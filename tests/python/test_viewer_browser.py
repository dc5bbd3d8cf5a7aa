"""The HTML viewer in a real browser: Debian's chromium driven by Playwright.

The page is loaded from a file URL with every other request blocked. Marked
`browser`: skip them locally with ``-m "not browser"``; the gate runs them.
"""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
import pytest
from four_bar_pins import four_bar_pins
from PIL import Image

import camlink
from camlink.results import Results
from camlink.viz.viewer import PLOT, page_data, view_pixel

pytestmark = pytest.mark.browser

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


class Page:
    """A page with its console errors and blocked requests recorded."""

    def __init__(self, browser: Any, url: str) -> None:
        self.errors: list[str] = []
        self.blocked: list[str] = []
        self.page = browser.new_page(viewport={"width": 1180, "height": 760})
        self.page.on("console", lambda m: self.errors.append(m.text) if m.type == "error" else None)
        self.page.on("pageerror", lambda e: self.errors.append(str(e)))

        def route(r: Any) -> None:
            if r.request.url.startswith("file:"):
                r.continue_()
            else:
                self.blocked.append(r.request.url)
                r.abort()

        self.page.route("**/*", route)
        self.page.goto(url)
        self.page.wait_for_function("window.camlinkViewer !== undefined")

    def shot(self, path: Path) -> npt.NDArray[np.uint8]:
        self.page.screenshot(path=str(path))
        return np.asarray(Image.open(path).convert("RGB"))


def test_four_bar_viewer(browser: Any, tmp_path: Path) -> None:
    model = camlink.load(EXAMPLES / "four_bar.toml")
    res = model.run()
    out = res.to_html(tmp_path / "four_bar.html", plots=["crank.phi", "rocker.phi"])
    assert isinstance(out, Path)
    data = page_data(res, model, ["crank.phi", "rocker.phi"])
    pg = Page(browser, out.as_uri())
    page = pg.page
    assert page.evaluate("camlinkViewer.rows") == len(res)
    assert page.locator("canvas.plot").count() == 2

    # The slider at row k puts every pin at its pixel from the results.
    stage = page.locator("#stage").bounding_box()
    box = data["view"]["box"]
    scale = view_pixel(box, 1.0, 0.0)[0] - view_pixel(box, 0.0, 0.0)[0]
    pin = np.array(next(s for s in data["shapes"] if s["gid"] == "pin:A")["points"]).reshape(-1, 2)
    r_px = float(np.max(np.hypot(*(pin[:-1] - pin[:-1].mean(axis=0)).T))) * scale
    assert r_px > 4
    for k in (0, 80, 301):
        page.eval_on_selector(
            "#slider", "(el, v) => { el.value = v; el.dispatchEvent(new Event('input')); }", str(k)
        )
        assert page.evaluate("camlinkViewer.frame()") == k
        image = pg.shot(tmp_path / f"four_bar_{k}.png").astype(float).mean(axis=2)
        for joint, (x, y) in four_bar_pins(res, k).items():
            u, v = view_pixel(box, x, y)
            u, v = u + stage["x"], v + stage["y"]
            assert page.evaluate(f"camlinkViewer.pixel({x}, {y})") == pytest.approx([u, v], abs=1e-6)
            # The centre dot is about two pixels across: the darkest of the
            # 3 × 3 pixels round the centre.
            i, j = round(v), round(u)
            assert image[i - 1:i + 2, j - 1:j + 2].min() < 110, (joint, k, image[i, j])
            fill = [image[round(v + 0.55 * r_px * s), round(u + 0.55 * r_px * c)]
                    for c, s in ((1, 0), (0, 1), (-1, 0), (0, -1))]
            assert min(fill) > 200, (joint, k, fill)
        # The plot cursors stand at the time of row k, in red.
        shot = np.asarray(Image.open(tmp_path / f"four_bar_{k}.png").convert("RGB")).astype(int)
        for n, (cx, _) in enumerate(page.evaluate("camlinkViewer.cursors()")):
            plot = page.locator("canvas.plot").nth(n).bounding_box()
            expect = plot["x"] + 8 + (res.t[k] - res.t[0]) / (res.t[-1] - res.t[0]) * (PLOT[0] - 16)
            assert cx == pytest.approx(expect, abs=1e-6)
            r, g, b = shot[int(plot["y"]) + 4, round(expect - 0.5)]
            assert r > 180 and g < 120 and b < 120, (n, k, (r, g, b))

    # Clicking a plot sets the time.
    plot = page.locator("canvas.plot").nth(1).bounding_box()
    page.mouse.click(plot["x"] + 8 + 0.75 * (PLOT[0] - 16), plot["y"] + PLOT[1] / 2)
    assert page.evaluate("camlinkViewer.time()") == pytest.approx(0.75 * res.t[-1], abs=res.t[1])

    # Hovering the coupler reads out its coordinates.
    k = page.evaluate("camlinkViewer.frame()")
    phi = res["coupler.phi"][k]
    cx, cy = res["coupler.x"][k] + 0.19 * np.cos(phi), res["coupler.y"][k] + 0.19 * np.sin(phi)
    u, v = page.evaluate(f"camlinkViewer.pixel({cx}, {cy})")
    page.mouse.move(u, v)
    assert page.locator("#readout").text_content().startswith(
        f"coupler: x = {res['coupler.x'][k]:.5f} m")

    # Play advances the frames.
    page.eval_on_selector("#slider", "(el) => { el.value = 0; el.dispatchEvent(new Event('input')); }")
    before = page.locator("#time").text_content()
    page.click("#play")
    page.wait_for_timeout(400)
    page.click("#play")
    assert page.evaluate("camlinkViewer.frame()") > 10
    assert page.locator("#time").text_content() != before
    pg.shot(tmp_path / "four_bar_viewer.png")

    # At 2× the motion runs two seconds per second of wall time.
    page.select_option("#speed", "2")
    page.eval_on_selector("#slider", "(el) => { el.value = 0; el.dispatchEvent(new Event('input')); }")
    start = time.perf_counter()
    page.click("#play")
    page.wait_for_timeout(300)
    page.click("#play")
    wall = time.perf_counter() - start
    played = page.evaluate("camlinkViewer.time()")
    assert 2 * 0.15 < played <= 2 * wall + res.t[1]
    assert pg.errors == [] and pg.blocked == []


def _many_cranks(n: int, rows: int) -> Results:
    """n cranks on a grid, each turning at its own speed: poses in closed
    form (the viewer's load, not the solver's)."""
    side = int(np.ceil(np.sqrt(n)))
    bodies, joints = [], []
    for k in range(n):
        x, y = 0.3 * (k % side), 0.3 * (k // side)
        bodies.append(f'[[bodies]]\nname = "c{k}"\nposition = [{x}, {y}]\n'
                      f'points = {{ O = [0, 0], A = [0.1, 0] }}\n')
        joints.append(f'[[joints]]\nname = "p{k}"\ntype = "revolute"\nbody_i = "ground"\n'
                      f'point_i = "G{k}"\nbody_j = "c{k}"\npoint_j = "O"\n')
    ground = ", ".join(f"G{k} = [{0.3 * (k % side)}, {0.3 * (k // side)}]" for k in range(n))
    text = (f'[model]\nname = "cranks"\n[ground]\npoints = {{ {ground} }}\n'
            + "".join(bodies) + "".join(joints))
    model = camlink.loads(text)
    t = np.linspace(0.0, 10.0, rows)
    cols, names = [t], ["t"]
    for k in range(n):
        x, y = 0.3 * (k % side), 0.3 * (k // side)
        cols += [np.full(rows, x), np.full(rows, y), (1 + k / n) * 2 * np.pi * t / 5]
        names += [f"c{k}.x", f"c{k}.y", f"c{k}.phi"]
    res = Results(names, np.column_stack(cols), model="cranks")
    res.mechanism = model
    return res


def test_200_bodies_10000_rows_play(browser: Any, tmp_path: Path) -> None:
    # The frame rate is a benchmark's business, not a unit test's: here the
    # frames must advance while playing and stop when paused.
    res = _many_cranks(200, 10_000)
    out = res.to_html(tmp_path / "cranks.html", plots=["c0.phi", "c199.phi"])
    assert isinstance(out, Path)
    pg = Page(browser, out.as_uri())
    page = pg.page
    assert page.evaluate("camlinkViewer.rows") == 10_000
    page.click("#play")
    seen = []
    for _ in range(3):
        page.wait_for_timeout(300)
        seen.append(page.evaluate("[camlinkViewer.stats.frames, camlinkViewer.frame()]"))
    page.click("#play")
    frames = [f for f, _ in seen]
    assert frames[0] > 0 and frames[0] < frames[1] < frames[2], seen
    assert len({row for _, row in seen}) == 3, seen
    paused = page.evaluate("camlinkViewer.frame()")
    page.wait_for_timeout(300)
    assert page.evaluate("camlinkViewer.frame()") == paused
    pg.shot(tmp_path / "cranks_viewer.png")
    assert pg.errors == [] and pg.blocked == []
