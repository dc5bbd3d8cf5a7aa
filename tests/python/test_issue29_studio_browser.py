"""Issue 29, the studio in Debian's chromium through Playwright, every
request off 127.0.0.1 blocked: drags, sliders, readouts, saving,
unassemblable edits and markup in names. Marked `browser`."""

from __future__ import annotations

import http.server
import json
import shutil
import threading
import time
import tomllib
import urllib.request
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import camlink
from camlink.cli import main
from camlink.studio import RUNS_KEY
from camlink.studio.document import Document
from camlink.studio.embed import ServedStudio as Studio
from conftest import STUCK_FOUR_BAR, four_bar_toml

pytestmark = pytest.mark.browser

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


class Page:
    """The studio page, with console errors and blocked requests recorded."""

    def __init__(self, browser: Any, url: str) -> None:
        self.errors: list[str] = []
        self.blocked: list[str] = []
        self.page = browser.new_page(viewport={"width": 1300, "height": 900})
        self.page.on("console", lambda m: self.errors.append(m.text) if m.type == "error" else None)
        self.page.on("pageerror", lambda e: self.errors.append(str(e)))

        def route(r: Any) -> None:
            if r.request.url.startswith("http://127.0.0.1:"):
                r.continue_()
            else:
                self.blocked.append(r.request.url)
                r.abort()

        self.page.route("**/*", route)
        self.page.goto(url)
        self.wait()

    def wait(self) -> None:
        """Until every request sent has its answer."""
        self.page.wait_for_function(
            "() => window.camlinkStudio && camlinkStudio.answered >= camlinkStudio.sent()"
            " && camlinkStudio.sent() > 0", timeout=20_000)

    def js(self, expr: str) -> Any:
        return self.page.evaluate(f"() => {expr}")

    def slider(self, name: str, value: float) -> None:
        self.page.eval_on_selector(
            f'#params input[data-name="{name}"]',
            "(el, v) => { el.value = v; el.dispatchEvent(new Event('input')); "
            "el.dispatchEvent(new Event('change')); }", str(value))
        self.wait()


@pytest.fixture
def studio(tmp_path: Path) -> Iterator[tuple[Studio, Path]]:
    path = tmp_path / "four_bar.toml"
    shutil.copy(EXAMPLES / "four_bar.toml", path)
    s = Studio(path)
    yield s, path
    s.stop()


def test_issue29_studio_drag_moves_joint_by_pixels(browser: Any, studio: tuple[Studio, Path]) -> None:
    s, path = studio
    pg = Page(browser, s.url)
    page = pg.page
    k = 40
    pg.js(f"camlinkStudio.front.setFrame({k})")
    scale = pg.js("camlinkStudio.front.scale()")
    old = pg.js("camlinkStudio.front.handle('joint:A')")
    u, v = pg.js(f"camlinkStudio.front.pixel({old[0]}, {old[1]})")
    doc = s.server.doc
    assert isinstance(doc, Document)
    crank = doc.solution.pose("crank", k)
    coupler = doc.solution.pose("coupler", k)
    page.mouse.move(u, v)
    page.mouse.down()
    for n in range(1, 6):
        page.mouse.move(u + 6 * n, v - 4 * n)
    page.mouse.up()
    pg.wait()
    page.click("#save")
    pg.wait()
    assert "saved four_bar.toml" in page.locator("#message").text_content()
    # 30 px right and 20 px up at `scale` px/m.
    target = (old[0] + 30 / scale, old[1] + 20 / scale)
    saved = {b["name"]: b["points"] for b in tomllib.loads(path.read_text())["bodies"]}
    for body, q in (("crank", crank), ("coupler", coupler)):
        c, sn = np.cos(q[2]), np.sin(q[2])
        dx, dy = target[0] - q[0], target[1] - q[1]
        assert saved[body]["A"] == pytest.approx([c * dx + sn * dy, -sn * dx + c * dy], abs=2e-9)
    # One undo step for the whole drag.
    page.click("#undo")
    pg.wait()
    assert s.server.doc.text() == (path.parent / "four_bar.toml.bak").read_text()
    assert pg.errors == [] and pg.blocked == []


def test_issue29_studio_fast_drag_sends_one_edit_at_a_time(
        browser: Any, studio: tuple[Studio, Path]) -> None:
    # Forty positions of a drag made while the first is being solved: the
    # page sends the first, then only the latest, then the drag's end; the
    # handle ends at the last position and the drag is one undo step.
    s, path = studio
    pg = Page(browser, s.url)
    old = pg.js("camlinkStudio.front.handle('joint:A')")
    sent = pg.page.evaluate("""([x, y]) => {
      const F = camlinkStudio.front, before = camlinkStudio.timing.sent;
      for (let n = 1; n <= 40; n++) {
        F.onEdit({ op: "move", handle: "joint:A", row: 0, x: x + 1e-4 * n, y: y - 5e-5 * n,
                   gesture: "fast" });
      }
      F.onEditEnd("fast");
      return camlinkStudio.timing.sent - before;
    }""", old)
    assert sent == 1
    pg.wait()
    # The first position, the last, the end.
    assert pg.js("camlinkStudio.timing.sent") == 3 and pg.js("camlinkStudio.timing.edits") == 40
    now = pg.js("camlinkStudio.front.handle('joint:A')")
    assert now == pytest.approx([old[0] + 4e-3, old[1] - 2e-3], abs=1e-9)
    page = pg.page
    page.click("#undo")
    pg.wait()
    assert s.server.doc.text() == path.read_text()
    assert pg.errors == [] and pg.blocked == []


def test_issue29_studio_slider_same_trace_as_python_run(browser: Any, studio: tuple[Studio, Path]) -> None:
    s, _ = studio
    pg = Page(browser, s.url)
    pg.slider("a", 0.131)
    page_x = np.array(pg.js("Array.from(camlinkStudio.front.channel('coupler.P.x'))"))
    page_y = np.array(pg.js("Array.from(camlinkStudio.front.channel('coupler.P.y'))"))
    res = camlink.load(EXAMPLES / "four_bar.toml").with_parameters(a=0.131).run()
    assert np.abs(page_x - res["coupler.P.x"]).max() <= 1e-9
    assert np.abs(page_y - res["coupler.P.y"]).max() <= 1e-9
    assert np.abs(page_x - camlink.load(EXAMPLES / "four_bar.toml").run()["coupler.P.x"]).max() > 1e-3
    # The readout at the cursor is the channel's value at that row.
    box = pg.page.locator(".cl-plot .u-over").first.bounding_box()
    pg.page.mouse.move(box["x"] + 0.37 * box["width"], box["y"] + box["height"] / 2)
    value = pg.page.locator(".cl-value").first
    row = int(value.get_attribute("data-row"))
    channel = pg.page.locator(".cl-pick").first.input_value()
    assert channel == "coupler.P.x"
    text = value.text_content()
    assert f"t = {res.t[row]:.4f} s:" in text
    shown = float(text.split(":")[1].split()[0])
    assert shown == pytest.approx(res["coupler.P.x"][row], rel=1e-6)
    # Any channel can be picked; an angle is read in degrees.
    pg.page.locator(".cl-pick").first.select_option("rocker.phi")
    pg.page.mouse.move(box["x"] + 0.37 * box["width"] + 1, box["y"] + box["height"] / 2)
    text = value.text_content()
    row = int(value.get_attribute("data-row"))
    assert float(text.split(":")[1].split()[0]) == pytest.approx(
        np.degrees(res["rocker.phi"][row]), rel=1e-6)
    assert text.endswith("°")
    # A channel whose values the page has not got yet is asked for.
    assert pg.js("camlinkStudio.front.channel('coupler.vx')") is None
    pg.page.locator(".cl-pick").nth(1).select_option("coupler.vx")
    pg.page.wait_for_function("() => camlinkStudio.front.channel('coupler.vx') !== null")
    got = np.array(pg.js("Array.from(camlinkStudio.front.channel('coupler.vx'))"))
    assert np.array_equal(got, res["coupler.vx"])
    assert pg.errors == [] and pg.blocked == []


def test_issue29_studio_save_reload_rerun(browser: Any, studio: tuple[Studio, Path]) -> None:
    s, path = studio
    pg = Page(browser, s.url)
    pg.slider("c", 0.32)
    pg.page.click("#save")
    pg.wait()
    before = np.array(pg.js("Array.from(camlinkStudio.front.channel('rocker.phi'))"))
    pg.page.reload()
    pg.wait()
    after = np.array(pg.js("Array.from(camlinkStudio.front.channel('rocker.phi'))"))
    assert np.array_equal(before, after)
    res = camlink.load(path).run()
    assert np.array_equal(res["rocker.phi"], after)
    assert "c = 0.32" in path.read_text()
    assert pg.errors == [] and pg.blocked == []


def test_issue29_studio_unassemblable_edit_marks_range(browser: Any, tmp_path: Path) -> None:
    path = tmp_path / "four_bar.toml"
    path.write_text(four_bar_toml())
    s = Studio(path)
    try:
        pg = Page(browser, s.url)
        assert pg.page.locator("#status").text_content() == ""
        pg.slider("b", STUCK_FOUR_BAR["b"])
        status = pg.page.locator("#status").text_content()
        assert status.startswith("does not assemble at ")
        ok = pg.js("Array.from(camlinkStudio.front.data().ok)")
        assert 0 in ok and ok[0] == 1
        # The strip under the slider is red over the missing rows.
        k = ok.index(0) + 3
        pg.js(f"camlinkStudio.front.setFrame({k})")
        shot = pg.page.screenshot(path=str(tmp_path / "stuck.png"))
        assert shot
        box = pg.page.locator("#reach").bounding_box()
        rows = len(ok)
        from PIL import Image

        image = np.asarray(Image.open(tmp_path / "stuck.png").convert("RGB")).astype(int)
        r, g, b = image[round(box["y"] + 3), round(box["x"] + k / (rows - 1) * box["width"])]
        assert r > 180 and g < 90 and b < 90
        # The page keeps working: back to an assembling linkage.
        pg.slider("b", 2.5)
        assert pg.page.locator("#status").text_content() == ""
        assert all(pg.js("Array.from(camlinkStudio.front.data().ok)"))
        assert pg.errors == [] and pg.blocked == []
    finally:
        s.stop()


def test_issue29_studio_names_with_markup_render_as_text(browser: Any, tmp_path: Path) -> None:
    name = '<img src=x onerror="window.pwned=1">"</script><b>x'
    text = four_bar_toml().replace('name = "four_bar"', f"name = '{name}'")
    path = tmp_path / "markup.toml"
    path.write_text(text)
    s = Studio(path)
    try:
        pg = Page(browser, s.url)
        assert pg.page.locator("#title").text_content() == name
        assert pg.page.title() == f"{name} · camlink studio"
        assert pg.page.locator("img").count() == 0 and pg.page.locator("b").count() == 0
        assert pg.js("window.pwned === undefined")
        assert pg.errors == [] and pg.blocked == []
    finally:
        s.stop()


def _stage_rgb(pg: Page, u: float, v: float) -> tuple[int, int, int]:
    """The stage canvas's colour at page pixel (u, v)."""
    r, g, b = pg.js(
        f"(() => {{ const c = document.getElementById('stage'), r = c.getBoundingClientRect();"
        f" const d = window.devicePixelRatio || 1;"
        f" return Array.from(c.getContext('2d').getImageData(Math.round(({u} - r.left - c.clientLeft) * d),"
        f" Math.round(({v} - r.top - c.clientTop) * d), 1, 1).data).slice(0, 3); }})()")
    return int(r), int(g), int(b)


def test_issue29_studio_picked_point_velocity_and_acceleration(
        browser: Any, studio: tuple[Studio, Path]) -> None:
    s, _ = studio
    pg = Page(browser, s.url)
    k = 40
    pg.js(f"camlinkStudio.front.setFrame({k})")
    # A click (no move) on the handle of pin B picks it; nothing is edited.
    u, v = pg.js("camlinkStudio.front.pixel(...camlinkStudio.front.handle('joint:B'))")
    pg.page.mouse.click(u, v)
    pg.page.wait_for_function("() => document.getElementById('picked').dataset.vx !== undefined")
    assert not s.server.doc.dirty
    box = pg.page.locator("#picked")
    res = camlink.load(EXAMPLES / "four_bar.toml").run()
    assert int(box.get_attribute("data-row")) == k
    # B of the coupler (the page, from the coupler's channels) is B of the
    # rocker (the core's point channels).
    for c in ("vx", "vy", "ax", "ay"):
        want = res[f"rocker.B.{c}"][k]
        assert float(box.get_attribute(f"data-{c}")) == pytest.approx(want, rel=1e-9, abs=1e-12), c
    vb = np.hypot(res["rocker.B.vx"][k], res["rocker.B.vy"][k])
    text = box.text_content()
    assert f"|v| = {1000 * vb:.6g} mm/s" in text
    # The arrows: 0.15 of the stage's smaller side (520 px) for the largest
    # speed and acceleration of B over the cycle, drawn from B's pixel.
    bx, by = res["rocker.B.x"][k], res["rocker.B.y"][k]
    pu, pv = pg.js(f"camlinkStudio.front.pixel({bx}, {by})")
    for c, color in (("v", (0x1F, 0x77, 0xB4)), ("a", (0x94, 0x67, 0xBD))):
        fx, fy = res[f"rocker.B.{c}x"], res[f"rocker.B.{c}y"]
        scale = 0.15 * 520 / np.hypot(fx, fy).max()
        tip = (pu + fx[k] * scale, pv - fy[k] * scale)
        along = (pu + 0.7 * (tip[0] - pu), pv + 0.7 * (tip[1] - pv))
        got = _stage_rgb(pg, *along)
        assert all(abs(g - w) <= 12 for g, w in zip(got, color, strict=True)), (c, got)
    # Another click on empty space drops the pick.
    stage = pg.page.locator("#stage").bounding_box()
    pg.page.mouse.click(stage["x"] + 30, stage["y"] + 30)
    assert box.text_content() == ""
    assert pg.errors == [] and pg.blocked == []


def test_issue29_studio_dead_centres_marked(browser: Any, studio: tuple[Studio, Path]) -> None:
    s, _ = studio
    pg = Page(browser, s.url)
    marks = pg.js("camlinkStudio.front.data().marks")
    # Crank and coupler in line: |O2 B| = a + b or b − a, B on the rocker's
    # circle about O4, in the triangle O2 O4 B (d = 0.4, a = 0.12,
    # b = 0.38, c = 0.3); twice per turn over two turns.
    d, a, b, c = 0.4, 0.12, 0.38, 0.3
    out = np.arccos(((a + b) ** 2 + d * d - c * c) / (2 * (a + b) * d))
    fold = np.pi + np.arccos(((b - a) ** 2 + d * d - c * c) / (2 * (b - a) * d))
    assert [m["kind"] for m in marks] == ["dead centre"] * 4
    for m, want in zip(marks, (out, fold, out, fold), strict=True):
        assert _wrap_angle(m["crank"] - want) == pytest.approx(0, abs=1e-9)
    # At each mark's time the core's solution has the links in line, and B
    # where the mark is drawn.
    model = camlink.load(EXAMPLES / "four_bar.toml")
    res = model.kinematics(times=[m["t"] for m in marks], points=["crank.A", "rocker.B"])
    for i, m in enumerate(marks):
        ax, ay, bx, by = (res[n][i] for n in ("crank.A.x", "crank.A.y", "rocker.B.x", "rocker.B.y"))
        assert abs(ax * (by - ay) - ay * (bx - ax)) / (a * b) < 1e-9
        assert (m["x"], m["y"]) == pytest.approx((bx, by), abs=1e-9)
    # Listed under the stage, a diamond at B on the stage, a tick on the
    # time strip.
    lines = pg.page.locator(".cl-mark")
    assert lines.count() == 4
    first = f"dead centre at t = {marks[0]['t']:.5f} s, crank {np.degrees(out):.3f}°"
    assert lines.first.text_content() == first
    u, v = pg.js(f"camlinkStudio.front.pixel({marks[1]['x']}, {marks[1]['y']})")
    assert _stage_rgb(pg, u, v) == (0x22, 0x22, 0x22)
    t_end = 2.0
    tick = pg.js(f"Array.from(document.getElementById('reach').getContext('2d').getImageData("
                 f"Math.round({marks[0]['t'] / t_end} * 380 * (window.devicePixelRatio || 1)),"
                 " 3, 1, 1).data)")
    assert tick[:3] == [0x22, 0x22, 0x22]
    assert pg.errors == [] and pg.blocked == []


def _wrap_angle(a: float) -> float:
    return float((a + np.pi) % (2 * np.pi) - np.pi)


def test_issue29_viewer_marks_and_picked_point(browser: Any, tmp_path: Path) -> None:
    # The viewer file draws with the same script: the dead centres listed,
    # and a clicked pin's velocity read from the run's channels.
    model = camlink.load(EXAMPLES / "four_bar.toml")
    res = model.run()
    out = res.to_html(tmp_path / "four_bar.html")
    assert isinstance(out, Path)
    page = browser.new_page(viewport={"width": 1300, "height": 900})
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.route("**/*", lambda r: r.continue_() if r.request.url.startswith("file:") else r.abort())
    page.goto(out.as_uri())
    page.wait_for_function("window.camlinkViewer !== undefined")
    assert page.locator(".cl-mark").count() == 4
    k = 120
    page.evaluate(f"() => camlinkViewer.setFrame({k})")
    bx, by = res["rocker.B.x"][k], res["rocker.B.y"][k]
    u, v = page.evaluate(f"() => camlinkViewer.pixel({bx}, {by})")
    page.mouse.click(u, v)
    box = page.locator("#picked")
    assert box.text_content().startswith("B (")
    # (The file holds the poses as float32.)
    for c in ("vx", "vy", "ax", "ay"):
        assert float(box.get_attribute(f"data-{c}")) == pytest.approx(
            res[f"rocker.B.{c}"][k], rel=1e-6, abs=1e-9), c
    assert errors == []
    page.close()


class CamPage(Page):
    """The studio's cam design page."""

    def wait(self) -> None:
        self.page.wait_for_function(
            "() => window.camlinkCam && camlinkCam.answered >= camlinkCam.sent()"
            " && camlinkCam.sent() > 0", timeout=20_000)

    def segment(self, index: int, key: str, value: str) -> None:
        sel = f'#segments [data-index="{index}"][data-key="{key}"]'
        if key == "law":
            self.page.select_option(sel, value)
        else:
            self.page.fill(sel, value)
            self.page.press(sel, "Enter")
        self.wait()

    def bad(self) -> bool:
        return bool(self.js("document.getElementById('message').classList.contains('bad')"))


def test_issue29_studio_cam_segments_edited_in_page(browser: Any, tmp_path: Path,
                                                    capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "valve.toml"
    shutil.copy(EXAMPLES / "cam_design_valve.toml", path)
    s = Studio(path)
    try:
        pg = CamPage(browser, s.url)
        assert pg.js("document.querySelectorAll('#checks li.ok').length") > 5
        h = 0.0105
        # The rise alone breaks the program: said at the top, the last
        # curves stay (dimmed), the page keeps working.
        pg.segment(1, "lift", str(h))
        assert pg.bad() and "does not close" in pg.page.locator("#message").text_content()
        assert pg.js("document.getElementById('svaj').classList.contains('stale')")
        pg.segment(3, "lift", str(-h))
        assert not pg.bad()
        assert not pg.js("document.getElementById('svaj').classList.contains('stale')")
        # The page's peak readout: s peak h at 250°, s′ peak of the 4-5-6-7
        # rise C_v h / β (closed form), as the page's data and its text.
        peak_s = float(pg.js("document.querySelector('.cam-svaj-head[data-channel=s]').dataset.peak"))
        peak_v = float(pg.js("document.querySelector('.cam-svaj-head[data-channel=v]').dataset.peak"))
        assert peak_s == pytest.approx(h, abs=1e-12)
        assert abs(peak_v) == pytest.approx(35 / 16 * h / np.radians(100.0), rel=1e-9)
        assert "peak 10.5000 at 250.00°" in pg.js("document.querySelector('.cam-svaj-head').textContent")
        # A law with velocity jumps: its row marked, the boundaries say C0.
        pg.segment(1, "law", "constant-velocity")
        assert pg.js("document.querySelectorAll('#segments tr.cam-bad').length") == 2
        assert "C0 at 150°" in pg.page.locator("#boundaries").text_content()
        pg.page.click("#undo")
        pg.wait()
        assert pg.js("document.querySelectorAll('#segments tr.cam-bad').length") == 0
        pg.page.click("#save")
        pg.wait()
        assert "saved valve.toml" in pg.page.locator("#message").text_content()
        assert "# Pa, the designer's allowable for this pair" in path.read_text()
        segs = tomllib.loads(path.read_text())["segments"]
        assert [g.get("lift", 0.0) for g in segs] == [0.0, h, 0.0, -h]
        assert [g["law"] for g in segs] == ["dwell", "4-5-6-7", "dwell", "4-5-6-7"]
        # The CLI on the saved file: its profile CSV (every 1°) is the
        # page's profile at those angles (1e-9 m), its report the page's.
        out = tmp_path / "out"
        capsys.readouterr()
        assert main(["cam", str(path), "--out", str(out), "--json"]) in (0, 1)
        page_report = pg.js("camlinkCam.data().report")
        cli = json.loads(capsys.readouterr().out)
        assert cli["ok"] == page_report["ok"]
        for a, b in zip(cli["checks"], page_report["checks"], strict=True):
            assert a["name"] == b["name"] and a["ok"] == b["ok"]
            assert a["value"] == pytest.approx(b["value"], rel=1e-9, abs=1e-12)
        rows = np.loadtxt(out / "valve.csv", delimiter=",", skiprows=1)
        surface = np.array(pg.js("Array.from(camlinkCam.curves().surface)")).reshape(-1, 2)
        assert np.max(np.abs(surface[::4][: len(rows), :] - rows[:, 1:3])) <= 1e-9
        assert pg.errors == [] and pg.blocked == []
    finally:
        s.stop()


def runs_of(s: Studio) -> Any:
    """The server's runs."""
    return s.server._runner.app[RUNS_KEY]  # type: ignore[union-attr]


def test_issue29_studio_runs_dynamics_with_progress_and_stop(
        browser: Any, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # A long run (a million rows): progress shows, the stop stops it, and
    # the page keeps working.
    long = tmp_path / "long.toml"
    long.write_text((EXAMPLES / "dyn_pendulum.toml").read_text().replace(
        "t_end = 3.0", "t_end = 1000.0"))
    s = Studio(long)
    try:
        pg = Page(browser, s.url)
        assert pg.js("document.getElementById('run-analysis').value") == "dynamics"
        # The page offers the analyses the core runs, as the server sent them.
        offered = pg.js("[...document.querySelectorAll('#run-analysis option.analysis')]"
                        ".map(o => o.value).join(',')")
        assert offered == ",".join(camlink.ANALYSES)
        pg.page.click("#run")
        pg.page.wait_for_function(
            "() => camlinkStudio.run().state === 'running' && camlinkStudio.run().done > 0", timeout=20_000)
        assert "of 1000001 rows" in pg.page.locator("#run-status").text_content()
        assert pg.js("document.getElementById('run-progress').value") > 0
        assert pg.js("document.getElementById('run').disabled")
        pg.page.click("#stop")
        pg.page.wait_for_function("() => camlinkStudio.run().state !== 'running'", timeout=20_000)
        run = pg.js("camlinkStudio.run()")
        assert run["state"] == "stopped" and 0 < run["done"] < run["total"]
        assert "stopped after" in pg.page.locator("#run-status").text_content()
        # It keeps and plots the rows computed up to the stop, and says when.
        kept = runs_of(s).current.results
        assert kept is not None and 0 < len(kept) <= run["done"]
        status = pg.page.locator("#run-status").text_content()
        assert f"at t = {float(kept['t'][-1]):.6g} s: the {len(kept)} rows computed are kept" in status
        pg.page.wait_for_function("() => camlinkStudio.run().t && camlinkStudio.run().values", timeout=20_000)
        assert pg.js("camlinkStudio.run().t.length") == len(kept)
        name = pg.js("camlinkStudio.run().channel")
        assert np.array_equal(np.array(pg.js("Array.from(camlinkStudio.run().values)")), kept[name])
        assert pg.page.locator("#run-plot canvas").count() > 0
        assert not pg.js("document.getElementById('run').disabled")
        pg.slider("L", 0.6)
        assert s.server.doc._data["parameters"]["L"] == 0.6
        assert pg.errors == [] and pg.blocked == []
        # A page that goes away stops the run it started.
        pg.page.click("#run")
        pg.page.wait_for_function("() => camlinkStudio.run().state === 'running'", timeout=20_000)
        pg.page.close()
        runs = runs_of(s)
        assert runs.current is not None
        for _ in range(200):
            if runs.current.state != "running":
                break
            time.sleep(0.05)
        assert runs.current.state == "stopped"
    finally:
        s.stop()
    # A run to its end: its channel is the CLI run's (1e-9).
    path = tmp_path / "pendulum.toml"
    shutil.copy(EXAMPLES / "dyn_pendulum.toml", path)
    s = Studio(path)
    try:
        pg = Page(browser, s.url)
        pg.page.click("#run")
        pg.page.wait_for_function(
            "() => camlinkStudio.run().state === 'done' && camlinkStudio.run().values", timeout=30_000)
        run = pg.js("camlinkStudio.run()")
        assert run["done"] == run["total"] == 3001
        channel = run["channel"]
        assert channel == "arm.bob.x"
        values = np.array(pg.js("Array.from(camlinkStudio.run().values)"))
        t = np.array(pg.js("Array.from(camlinkStudio.run().t)"))
        out = tmp_path / "cli.csv"
        assert main(["run", str(path), "-o", str(out), "-q"]) == 0
        capsys.readouterr()
        with out.open() as f:
            head = f.readline().strip().split(",")
        table = np.loadtxt(out, delimiter=",", skiprows=1)
        assert np.max(np.abs(table[:, head.index("t")] - t)) <= 1e-12
        assert np.max(np.abs(table[:, head.index(channel)] - values)) <= 1e-9
        # Another channel on request.
        pg.page.select_option("#run-channel", "arm.phi")
        pg.page.wait_for_function("() => camlinkStudio.run().channel === 'arm.phi'", timeout=20_000)
        phi = np.array(pg.js("Array.from(camlinkStudio.run().values)"))
        assert np.max(np.abs(table[:, head.index("arm.phi")] - phi)) <= 1e-9
        assert pg.errors == [] and pg.blocked == []
    finally:
        s.stop()


def test_issue29_studio_motion_curve_segments_applied(browser: Any, tmp_path: Path) -> None:
    path = tmp_path / "cam.toml"
    shutil.copy(EXAMPLES / "cam_motion_roller.toml", path)
    s = Studio(path)
    try:
        pg = Page(browser, s.url)
        assert not pg.js("document.getElementById('motion').hidden")

        def cell(index: int, key: str) -> str:
            return f'#motion input[data-index="{index}"][data-key="{key}"]'

        assert pg.page.input_value(cell(1, "lift")) == "lift"
        # The rise alone does not close the program: refused, said, kept
        # staged; with the return it applies.
        pg.page.fill(cell(1, "lift"), "0.015")
        pg.page.press(cell(1, "lift"), "Enter")
        pg.page.click("#motion-apply")
        pg.wait()
        assert "does not close" in pg.page.locator("#message").text_content()
        assert pg.js(f"document.querySelector('{cell(1, 'lift')}').classList.contains('staged')")
        pg.page.fill(cell(3, "lift"), "-lift * 1.25")
        pg.page.press(cell(3, "lift"), "Enter")
        pg.page.click("#motion-apply")
        pg.wait()
        assert not pg.js(f"document.querySelector('{cell(1, 'lift')}').classList.contains('staged')")
        assert pg.js("document.getElementById('motion-apply').disabled")
        # The follower's lift is a default plot of a cam: the page has it.
        assert pg.js("camlinkStudio.front.picked()").count("follower.y") == 1
        page_y = np.array(pg.js("Array.from(camlinkStudio.front.channel('follower.y'))"))
        pg.page.click("#save")
        pg.wait()
        segs = tomllib.loads(path.read_text())["curves"][0]["segments"]
        assert segs[1]["lift"] == 0.015 and segs[3]["lift"] == "-lift * 1.25"
        assert "# base circle radius" in path.read_text()
        # The saved file run as the CLI runs it: the follower's lift.
        res = camlink.load(path).run()
        assert np.abs(page_y - res["follower.y"]).max() <= 1e-9
        assert np.ptp(res["follower.y"]) == pytest.approx(0.015, abs=1e-9)
        assert pg.errors == [] and pg.blocked == []
    finally:
        s.stop()


def test_issue29_studio_runs_a_study_of_the_model(
        browser: Any, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    for name in ("four_bar.toml", "study_four_bar.toml"):
        shutil.copy(EXAMPLES / name, tmp_path / name)
    s = Studio(tmp_path / "four_bar.toml")
    try:
        pg = Page(browser, s.url)
        pg.page.select_option("#run-analysis", "study:study_four_bar.toml")
        pg.page.click("#run")
        pg.page.wait_for_function("() => camlinkStudio.run().state === 'done' && camlinkStudio.run().table",
                                  timeout=60_000)
        run = pg.js("camlinkStudio.run()")
        assert run["done"] == run["total"] == 9
        assert "9 variants, 9 ok" in pg.page.locator("#run-status").text_content()
        assert pg.js("document.querySelectorAll('#study tr').length") == 10
        table = run["table"]
        assert pg.errors == [] and pg.blocked == []
    finally:
        s.stop()
    # `camlink study` of the same file: the same outputs (1e-9).
    import pandas as pd

    out = tmp_path / "sweep.parquet"
    assert main(["study", str(tmp_path / "study_four_bar.toml"), "-o", str(out), "-q"]) == 0
    capsys.readouterr()
    cli = pd.read_parquet(out).sort_values("study.variant")
    cols = table["columns"]
    for name in ("a", "swing", "rocker_max", "rocker_min", "least_transmission"):
        page = np.array([row[cols.index(name)] for row in table["rows"]], dtype=float)
        assert np.max(np.abs(page - cli[name].to_numpy())) <= 1e-9, name


def test_issue29_studio_cam_names_with_markup_render_as_text(browser: Any, tmp_path: Path) -> None:
    path = tmp_path / "design.toml"
    name = '<img src=x onerror="window.pwned=1"><b>cam</b>'
    path.write_text((EXAMPLES / "cam_design_indexing.toml").read_text().replace(
        'name = "indexing cam"', f"name = '{name}'"))
    s = Studio(path)
    try:
        pg = CamPage(browser, s.url)
        assert pg.page.locator("#title").text_content() == name
        assert pg.js("document.querySelectorAll('#top img, #top b').length") == 0
        # A law that is no law: its message (quoting it) is text too.
        pg.segment(1, "law", "cycloidal")
        pg.page.evaluate("() => camlinkCam.send({op: 'segment', index: 1, key: 'law', "
                         "value: '<i>septic</i>'})")
        pg.wait()
        assert "'<i>septic</i>' is not one of" in pg.page.locator("#message").text_content()
        assert pg.js("document.querySelectorAll('#message i').length") == 0
        assert pg.js("window.pwned === undefined")
        assert pg.errors == [] and pg.blocked == []
    finally:
        s.stop()


def test_issue29_studio_in_a_notebook_frame(browser: Any, tmp_path: Path) -> None:
    # camlink.studio.notebook serves the studio from a thread of this
    # process; its HTML, an iframe, shown in a page of this machine (a
    # notebook's, here another server on 127.0.0.1) loads the studio,
    # whose slider edits the model; after stop() the server is gone. A
    # page served by `camlink studio` refuses every frame.
    from camlink.studio import notebook

    path = tmp_path / "four_bar.toml"
    shutil.copy(EXAMPLES / "four_bar.toml", path)
    nb = notebook(path, height=700)
    try:
        html = nb._repr_html_()
        assert html.startswith("<iframe") and 'height="700"' in html
        assert f'src="{nb.url.replace("&", "&amp;")}"' in html
        # The notebook: a page of another server of this machine.
        body = f"<!DOCTYPE html><html><body><h1>notebook</h1>{html}</body></html>".encode()

        class Notebook(http.server.BaseHTTPRequestHandler):
            def do_GET(self) -> None:
                self.send_response(200)
                self.send_header("Content-Type", "text/html")
                self.send_header("Content-Length", str(len(body)))
                self.end_headers()
                self.wfile.write(body)

            def log_message(self, *args: Any) -> None:
                pass

        jupyter = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Notebook)
        threading.Thread(target=jupyter.serve_forever, daemon=True).start()
        page = browser.new_page(viewport={"width": 1300, "height": 900})
        errors: list[str] = []
        page.on("pageerror", lambda e: errors.append(str(e)))
        page.route("**/*", lambda r: r.continue_() if r.request.url.startswith("http://127.0.0.1:")
                   else r.abort())
        page.goto(f"http://127.0.0.1:{jupyter.server_address[1]}/notebooks/design.ipynb")
        frame = page.frame_locator("iframe")
        frame.locator("#params input[data-name='a']").wait_for(timeout=20_000)
        studio = next(f for f in page.frames if f.url.startswith(f"http://127.0.0.1:{nb.server.port}/"))
        studio.wait_for_function("() => camlinkStudio.answered >= 1")
        assert studio.locator("#title").text_content() == nb.doc.solution.model.name
        studio.eval_on_selector(
            "#params input[data-name='a']",
            "el => { el.value = '0.131'; el.dispatchEvent(new Event('input')); "
            "el.dispatchEvent(new Event('change')); }")
        studio.wait_for_function("() => camlinkStudio.answered >= camlinkStudio.sent()")
        assert nb.doc._data["parameters"]["a"] == 0.131
        assert errors == []
        page.close()
        jupyter.shutdown()
    finally:
        nb.stop()
    assert "stopped" in nb._repr_html_()
    with pytest.raises(OSError):
        urllib.request.urlopen(nb.url, timeout=5)
    # `camlink studio`'s own page may not be framed.
    s = Studio(path)
    try:
        with urllib.request.urlopen(s.url, timeout=10) as r:
            assert "frame-ancestors 'none'" in r.headers["Content-Security-Policy"]
    finally:
        s.stop()


def test_issue29_studio_edit_keeps_lines_and_plot_arrays(
        browser: Any, studio: tuple[Studio, Path]) -> None:
    # An edit sets the text of the lines under the stage and refills the
    # plots' arrays: the same nodes and arrays, holding the new cycle.
    s, _ = studio
    pg = Page(browser, s.url)
    before = pg.js("""(() => {
      const lines = Array.from(document.getElementById('info').children);
      lines.forEach(function (e, i) { e.dataset.kept = String(i); });
      const p = camlinkStudio.front.plots[0];
      window.keptArrays = [p.data[0], p.data[1]];
      return lines.map(function (e) { return e.textContent; });
    })()""")
    xy = pg.js("camlinkStudio.front.handle('joint:B')")
    pg.page.evaluate("""async ([x, y]) => {
      const S = camlinkStudio;
      await S.after(S.send({ op: "move", handle: "joint:B", row: 0, x: x + 0.01, y: y + 0.005,
                             gesture: "kept" }));
    }""", xy)
    after = pg.js("""(() => {
      const D = camlinkStudio.front.data(), p = camlinkStudio.front.plots[0];
      const lines = Array.from(document.getElementById('info').children);
      const v = camlinkStudio.front.channel(p.name);
      return {
        kept: lines.map(function (e) { return e.dataset.kept; }),
        texts: lines.map(function (e) { return e.textContent; }),
        info: D.info, marks: D.marks.length,
        same: p.data[0] === window.keptArrays[0] && p.data[1] === window.keptArrays[1],
        plotted: Array.from(p.data[1]), values: Array.from(v), t: Array.from(p.data[0]),
        times: Array.from(D.t),
      };
    })()""")
    assert len(before) == len(after["texts"]) == len(after["info"]) + after["marks"]
    assert after["kept"] == [str(i) for i in range(len(before))]
    assert after["texts"][: len(after["info"])] == after["info"] and after["texts"] != before
    assert after["same"] and after["t"] == after["times"]
    # The first plot is a length (the coupler point's y): its values as sent.
    assert after["plotted"] == after["values"]
    assert pg.errors == [] and pg.blocked == []
