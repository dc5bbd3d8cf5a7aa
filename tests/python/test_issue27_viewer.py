"""Issue 27 (Trust), the viewer page: a model's name cannot inject markup
or script (checked in the HTML text and in Debian's chromium through
Playwright, every network request blocked), and `to_html` thins a long run
and writes its page safely."""

from __future__ import annotations

import base64
import html
import json
import re
import shutil
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import camlink
from camlink.results import Results
from camlink.viz.viewer import MOST_ROWS, fill, script_json, thin, to_html

ROOT = Path(__file__).resolve().parents[2]
FOUR_BAR = ROOT / "examples" / "four_bar.toml"

#: Names that broke the page: a placeholder of the template (the data was
#: pasted into <title> and <h1>), a comment and a script opener (the page
#: went blank), a script closer and a script.
HOSTILE = [
    "__DATA__<img src=x onerror=alert(1)>",
    "<!--<script>",
    "</script><script>alert(1)</script>",
    "__TITLE__",
    "a\u2028b & \"c\" 'd' __SCRIPT_HASH__",
]


def _model(name: str) -> camlink.Model:
    text = FOUR_BAR.read_text(encoding="utf-8")
    assert 'name = "four_bar"' in text
    return camlink.loads(text.replace('name = "four_bar"', f"name = {json.dumps(name)}", 1))


@pytest.fixture(scope="module")
def runs() -> dict[str, Results]:
    return {name: _model(name).run(t_end=0.5, step=0.01) for name in HOSTILE}


def _data_of(page: str) -> dict[str, Any]:
    m = re.search(r'<script id="camlink-data" type="application/json">(.*?)</script>', page, re.DOTALL)
    assert m
    data: dict[str, Any] = json.loads(m.group(1))
    return data


@pytest.mark.parametrize("name", HOSTILE)
def test_issue27_viewer_name_injection_text(name: str, runs: dict[str, Results]) -> None:
    page = to_html(runs[name])
    assert isinstance(page, str)
    # The name is text in <title> and <h1>, escaped once.
    shown = html.escape(name, quote=True)
    assert f"<title>{shown} · camlink viewer</title>" in page
    assert f"<h1>{shown}</h1>" in page
    # Two script elements (the data, the viewer), no comment, no image.
    assert page.count("<script") == 2 and page.count("</script") == 2
    assert "<!--" not in page and "<img" not in page.lower()
    # The data element holds the whole run and the name, unchanged.
    data = _data_of(page)
    assert data["title"] == name
    assert len(np.frombuffer(base64.b64decode(data["t"]), "<f8")) == len(runs[name])
    # Only the viewer's own script may run, and nothing may be fetched or sent.
    policy = re.search(r'http-equiv="Content-Security-Policy" content="([^"]*)"', page)
    assert policy
    rules = dict(r.strip().split(" ", 1) for r in policy.group(1).split(";"))
    assert rules["default-src"] == "'none'"
    assert re.fullmatch(r"'sha256-[A-Za-z0-9+/]{43}='", rules["script-src"])
    assert rules["connect-src"] == rules["base-uri"] == rules["form-action"] == "'none'"


def test_issue27_viewer_fill_is_one_pass() -> None:
    # Text a value brings in is not searched again.
    assert fill("<t>__A__</t><b>__B__</b>", {"A": "__B__", "B": "x"}) == "<t>__B__</t><b>x</b>"
    with pytest.raises(ValueError, match="__C__"):
        fill("__C__", {})
    text = script_json({"s": "</script><!--<script>&\u2028\u2029"})
    assert not re.search(r"[<>&\u2028\u2029]", text)
    assert json.loads(text) == {"s": "</script><!--<script>&\u2028\u2029"}


def test_issue27_viewer_thins_to_most_rows(tmp_path: Path) -> None:
    model = camlink.load(FOUR_BAR)
    res = model.run(t_end=2.0, step=2.0 / (3 * MOST_ROWS))
    assert len(res) > MOST_ROWS
    small = thin(res)
    assert len(small) == MOST_ROWS
    assert small.t[0] == res.t[0] and small.t[-1] == res.t[-1]
    assert np.all(np.diff(small.t) > 0)
    k = int(np.searchsorted(res.t, small.t[777]))
    assert small["coupler.phi"][777] == res["coupler.phi"][k]
    out = to_html(res, tmp_path / "long.html")
    assert isinstance(out, Path)
    data = _data_of(out.read_text(encoding="utf-8"))
    assert len(np.frombuffer(base64.b64decode(data["t"]), "<f8")) == MOST_ROWS


def test_issue27_viewer_to_html_refuses_an_input_and_writes_whole(tmp_path: Path) -> None:
    model_file = tmp_path / "m.toml"
    shutil.copy(FOUR_BAR, model_file)
    res = camlink.load(model_file).run(t_end=0.2, step=0.01)
    before = model_file.read_bytes()
    with pytest.raises(camlink.ModelError, match="is an input of the model"):
        to_html(res, model_file)
    assert model_file.read_bytes() == before
    out = tmp_path / "m.html"
    out.write_text("old page")
    assert to_html(res, out) == out
    assert out.read_text(encoding="utf-8").startswith("<!DOCTYPE html>")
    # Nothing left beside it.
    assert sorted(p.name for p in tmp_path.iterdir()) == ["m.html", "m.toml"]


# -- in a browser --------------------------------------------------------------


class _Loaded:
    """A page loaded from a file URL with every other request blocked; its
    dialogs, script errors, blocked requests and policy violations kept."""

    def __init__(self, browser: Any, path: Path) -> None:
        self.dialogs: list[str] = []
        self.errors: list[str] = []
        self.blocked: list[str] = []
        self.page = browser.new_page(viewport={"width": 1180, "height": 760})

        def dialog(d: Any) -> None:
            self.dialogs.append(d.message)
            d.dismiss()

        self.page.on("dialog", dialog)
        self.page.on("console", lambda m: self.errors.append(m.text) if m.type == "error" else None)
        self.page.on("pageerror", lambda e: self.errors.append(str(e)))

        def route(r: Any) -> None:
            if r.request.url.startswith("file:"):
                r.continue_()
            else:
                self.blocked.append(r.request.url)
                r.abort()

        self.page.route("**/*", route)
        self.page.goto(path.as_uri())


@pytest.mark.browser
@pytest.mark.parametrize("name", HOSTILE)
def test_issue27_viewer_name_injection_browser(
    name: str, runs: dict[str, Results], browser: Any, tmp_path: Path
) -> None:
    res = runs[name]
    out = to_html(res, tmp_path / "page.html")
    assert isinstance(out, Path)
    pg = _Loaded(browser, out)
    page = pg.page
    page.wait_for_function("window.camlinkViewer !== undefined", timeout=10_000)
    page.wait_for_timeout(200)
    assert page.title() == f"{name} · camlink viewer"
    assert page.locator("h1").text_content() == name
    assert page.evaluate("camlinkViewer.rows") == len(res)
    assert page.locator("#stage").count() == 1
    assert page.locator("canvas.plot").count() == 2
    assert page.locator("img").count() == 0 and page.locator("script").count() == 2
    assert pg.dialogs == [] and pg.errors == [] and pg.blocked == []
    page.close()


@pytest.mark.browser
def test_issue27_viewer_policy_runs_only_its_own_script(
    runs: dict[str, Results], browser: Any, tmp_path: Path
) -> None:
    # Markup that got into the page by any other way would not run: an
    # inline script, an event handler, a navigation by <meta>, a form.
    text = to_html(runs[HOSTILE[0]])
    assert isinstance(text, str)
    injected = ('<script>window.pwned = 1; alert("script")</script>'
                '<img src="data:," onerror="window.pwned = 2; alert(\'handler\')">'
                '<form action="https://example.com/x" method="post"><input name="a"></form>')
    out = tmp_path / "injected.html"
    out.write_text(text.replace("<h1>", injected + "<h1>", 1), encoding="utf-8")
    pg = _Loaded(browser, out)
    page = pg.page
    page.wait_for_function("window.camlinkViewer !== undefined", timeout=10_000)
    assert page.evaluate("window.pwned === undefined")
    page.evaluate("document.querySelector('form').submit()")
    page.wait_for_timeout(300)
    assert pg.dialogs == [] and pg.blocked == []
    assert page.url == out.as_uri()
    # The refusals are reported as policy violations, and nothing else failed.
    assert pg.errors and all("Content Security Policy" in e for e in pg.errors), pg.errors
    page.close()
