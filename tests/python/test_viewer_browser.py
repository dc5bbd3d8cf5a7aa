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
from camlink.viz.viewer import page_data, view_pixel

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


def _redness(image: npt.NDArray[Any], u: float, v: float, reach: int = 1) -> int:
    """The reddest (r − g) of the pixels round (u, v)."""
    i, j = round(v), round(u)
    patch = image[i - reach:i + reach + 1, j - reach:j + reach + 1].astype(int)
    return int((patch[..., 0] - patch[..., 1]).max())


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

    # The slider at row k puts every pin at its pixel from the results: a
    # dark centre dot in a white ring 5 px across; the traced coupler
    # point's path passes through its place at other rows.
    stage = page.locator("#stage").bounding_box()
    border = page.evaluate("document.getElementById('stage').clientLeft")
    box = data["view"]["box"]
    for k in (0, 80, 301):
        page.eval_on_selector(
            "#slider", "(el, v) => { el.value = v; el.dispatchEvent(new Event('input')); }", str(k)
        )
        assert page.evaluate("camlinkViewer.frame()") == k
        shot = pg.shot(tmp_path / f"four_bar_{k}.png")
        image = shot.astype(float).mean(axis=2)
        for joint, (x, y) in four_bar_pins(res, k).items():
            u, v = view_pixel(box, x, y)
            u, v = u + stage["x"] + border, v + stage["y"] + border
            assert page.evaluate(f"camlinkViewer.pixel({x}, {y})") == pytest.approx([u, v], abs=1e-6)
            i, j = round(v), round(u)
            assert image[i - 1:i + 2, j - 1:j + 2].min() < 110, (joint, k, image[i, j])
            fill = [image[round(v + 3 * s), round(u + 3 * c)] for c, s in ((1, 0), (0, 1), (-1, 0), (0, -1))]
            assert min(fill) > 200, (joint, k, fill)
        for j in (k + 40, k + 90):
            u, v = page.evaluate(f"camlinkViewer.pixel({res['coupler.P.x'][j]}, {res['coupler.P.y'][j]})")
            assert _redness(shot, u, v) > 80, (k, j)
        # The plot cursors stand at the time of row k, in red.
        for n in range(2):
            x, _ = page.evaluate(f"camlinkViewer.front.plotPixel({n}, {k})")
            over = page.locator(".u-over").nth(n).bounding_box()
            assert _redness(shot, x, over["y"] + 4) > 80, (n, k)
    # Axes: tick numbers in mm, and in m when asked.
    assert page.locator("#units-length").input_value() == "mm"

    # Clicking a plot sets the time.
    over = page.locator(".u-over").nth(1).bounding_box()
    page.mouse.click(over["x"] + 0.75 * over["width"], over["y"] + over["height"] / 2)
    assert page.evaluate("camlinkViewer.time()") == pytest.approx(0.75 * res.t[-1], abs=2 * res.t[1])

    # Hovering a pin reads out its coordinates; the plot's readout is the
    # channel's value at the row under the cursor.
    k = page.evaluate("camlinkViewer.frame()")
    x, y = four_bar_pins(res, k)["A"]
    u, v = page.evaluate(f"camlinkViewer.pixel({x}, {y})")
    page.mouse.move(u, v)
    assert page.locator("#readout").text_content().startswith(
        f"A: x = {1000 * x:.3f} mm, y = {1000 * y:.3f} mm")
    page.mouse.move(over["x"] + 0.3 * over["width"], over["y"] + 10)
    value = page.locator(".cl-value").nth(1)
    row = int(value.get_attribute("data-row"))
    assert float(value.text_content().split(":")[1].split()[0]) == pytest.approx(
        np.degrees(res["rocker.phi"][row]), rel=1e-6)

    # Keyboard: arrows step, space plays and pauses.
    page.locator("#stage").click(position={"x": 5, "y": 5})
    k = page.evaluate("camlinkViewer.frame()")
    page.keyboard.press("ArrowRight")
    assert page.evaluate("camlinkViewer.frame()") == k + 1
    page.keyboard.press("ArrowLeft")
    page.keyboard.press("ArrowLeft")
    assert page.evaluate("camlinkViewer.frame()") == k - 1

    # The wheel zooms about the pointer: the point under it stays put.
    u0, v0 = stage["x"] + 300, stage["y"] + 200
    page.mouse.move(u0, v0)
    before = page.evaluate(f"camlinkViewer.front.world({u0}, {v0})")
    page.mouse.wheel(0, -240)
    page.wait_for_timeout(50)
    assert page.evaluate(f"camlinkViewer.front.world({u0}, {v0})") == pytest.approx(before, abs=1e-9)
    assert page.evaluate(f"camlinkViewer.pixel({before[0] + 0.01}, {before[1]})")[0] - u0 > 10 * 0.01 * (
        view_pixel(box, 1, 0)[0] - view_pixel(box, 0, 0)[0]) / 10
    # Dragging empty space pans.
    page.mouse.move(stage["x"] + 20, stage["y"] + 20)
    page.mouse.down()
    page.mouse.move(stage["x"] + 70, stage["y"] + 50)
    page.mouse.up()
    after = page.evaluate(f"camlinkViewer.front.world({u0 + 50}, {v0 + 30})")
    assert after == pytest.approx(before, abs=1e-9)

    # Play advances the frames.
    page.eval_on_selector("#slider", "(el) => { el.value = 0; el.dispatchEvent(new Event('input')); }")
    before_t = page.locator("#time").text_content()
    page.click("#play")
    page.wait_for_timeout(400)
    page.click("#play")
    assert page.evaluate("camlinkViewer.frame()") > 10
    assert page.locator("#time").text_content() != before_t
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


def test_viewer_springs_and_forces(browser: Any, tmp_path: Path) -> None:
    # Inverse dynamics of the slider-crank with mass and a spring: a force
    # arrow at each pin, and the spring's zigzag between its two ends.
    model = camlink.load(EXAMPLES / "dyn_slider_crank.toml")
    res = model.run()
    data = page_data(res, model, None)
    assert {f["joint"] for f in data["forces"]} == {"O", "A", "B"}
    assert [s["kind"] for s in data["springs"]] == ["spring"]
    out = res.to_html(tmp_path / "sc.html")
    assert isinstance(out, Path)
    pg = Page(browser, out.as_uri())
    k = int(np.argmax(np.hypot(res["A.fx_j"], res["A.fy_j"])))
    pg.page.evaluate(f"camlinkViewer.setFrame({k})")
    shot = pg.shot(tmp_path / "sc.png")
    pin = next(h for h in data["handles"] if h["id"] == "pin:A")
    q = [res[f"{pin['body']}.{c}"][k] for c in ("x", "y", "phi")]
    s = pin["s"]
    x = q[0] + np.cos(q[2]) * s[0] - np.sin(q[2]) * s[1]
    y = q[1] + np.sin(q[2]) * s[0] + np.cos(q[2]) * s[1]
    fx, fy = res["A.fx_j"][k], res["A.fy_j"][k]
    u, v = pg.page.evaluate(f"camlinkViewer.pixel({x}, {y})")
    n = np.hypot(fx, fy)
    assert n > 0
    assert min(_redness(shot, u + d * fx / n, v - d * fy / n) for d in (12, 16, 20)) > 80
    # The spring: green pixels near the middle of its ends.
    sp = data["springs"][0]
    ends = []
    for body, loc in ((sp["body_i"], sp["s_i"]), (sp["body_j"], sp["s_j"])):
        qb = [0.0, 0.0, 0.0] if body == "ground" else [res[f"{body}.{c}"][k] for c in ("x", "y", "phi")]
        ends.append((qb[0] + np.cos(qb[2]) * loc[0] - np.sin(qb[2]) * loc[1],
                     qb[1] + np.sin(qb[2]) * loc[0] + np.cos(qb[2]) * loc[1]))
    mid = np.mean(ends, axis=0)
    u, v = pg.page.evaluate(f"camlinkViewer.pixel({mid[0]}, {mid[1]})")
    i, j = round(v), round(u)
    patch = shot[i - 8:i + 9, j - 8:j + 9].astype(int)
    assert ((patch[..., 1] - patch[..., 0] > 40) & (patch[..., 1] - patch[..., 2] > 10)).any()
    assert pg.errors == [] and pg.blocked == []


def test_viewer_torsion_spring(browser: Any, tmp_path: Path) -> None:
    # A torsion spring is a spiral round its pin: green pixels 8 to 16 px
    # from the pin's centre.
    model = camlink.load(EXAMPLES / "dyn_spring_pendulum.toml")
    res = model.run()
    data = page_data(res, model, None)
    assert [s["kind"] for s in data["springs"]] == ["torsion"]
    out = res.to_html(tmp_path / "sp.html")
    assert isinstance(out, Path)
    pg = Page(browser, out.as_uri())
    shot = pg.shot(tmp_path / "sp.png").astype(int)
    sp = data["springs"][0]
    assert sp["body_i"] == "ground"
    u, v = pg.page.evaluate(f"camlinkViewer.pixel({sp['s_i'][0]}, {sp['s_i'][1]})")
    green = 0
    for r in (10, 12, 14):
        for a in np.linspace(0, 2 * np.pi, 24, endpoint=False):
            px = shot[round(v - r * np.sin(a)), round(u + r * np.cos(a))]
            green += int(px[1] - px[0] > 40 and px[1] - px[2] > 10)
    assert green >= 6
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
