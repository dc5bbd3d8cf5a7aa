"""The browser viewer: one self-contained HTML file of a run.

`to_html(results, path)` writes a page drawn by the front end the studio
uses (``web/camlink.js``, with uPlot inlined): the animated mechanism on
axes with a grid and tick numbers (mm or m), traces of the file's
``[analysis] points``, springs and dampers, force arrows of runs with
joint forces, zoom (wheel) and pan (drag), play/pause, a time slider,
playback speed, the keyboard (space, arrows), a hover read-out of pins,
and plots of any channel with numbers on their axes, units and a readout
at the cursor, whose cursor follows the time and where a click sets the
time. Script, style and data are all inside the file; the page loads
nothing from a network (its Content-Security-Policy forbids it).

Body poses and channels are stored as base64 float32 (times as float64);
a run of more than `MOST_VALUES` values keeps only the plotted channels
(a 200-body, 10,000-row run is about 32 MB). A run of more than
`MOST_ROWS` rows is thinned to that many, evenly, keeping the first and
the last.

The page is filled in one pass, each value escaped for where it goes: the
model's name as HTML text, the data as JSON in which ``<``, ``>``, ``&``
and the line separators U+2028 and U+2029 are ``\\u`` escapes, so that no
string in it can end the script element or open a comment or another
script. The page's policy lets only its own viewer script run (by its
SHA-256), and allows no fetch, form, base URL or resource from anywhere.
"""

from __future__ import annotations

import base64
import hashlib
import html
import json
import os
import re
from collections.abc import Sequence
from importlib import resources
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from camlink._core import ModelError
from camlink.io.output import _Target, check_not_input
from camlink.results import Results
from camlink.viz.drawing import resolve

if TYPE_CHECKING:
    from camlink.model import Model

__all__ = ["MOST_ROWS", "MOST_VALUES", "PLOT", "STAGE", "default_plots", "fill", "thin", "to_html"]

#: Stage canvas size (CSS px).
STAGE = (640, 480)
#: Plot canvas size (CSS px).
PLOT = (420, 170)
#: Most output rows a page holds: at this many, each moving body adds
#: about 320 kB to the page.
MOST_ROWS = 20_000
#: Most channel values a page holds whole; a bigger run holds only the
#: poses and the plotted channels.
MOST_VALUES = 4_000_000

# JSON text that no HTML parser reads as markup inside <script>.
_SCRIPT_SAFE = str.maketrans({
    "<": "\\u003c", ">": "\\u003e", "&": "\\u0026",
    "\u2028": "\\u2028", "\u2029": "\\u2029",
})
_PLACEHOLDER = re.compile(r"__([A-Z_]+?)__")


def _b64(a: npt.ArrayLike, dtype: type) -> str:
    little = np.ascontiguousarray(a, dtype=dtype).astype("<" + np.dtype(dtype).str[1:])
    return base64.b64encode(little.tobytes()).decode("ascii")


def default_plots(results: Results) -> list[str]:
    """Two channels worth plotting: the first body's angle and the last
    body's coordinate that moves most (its angle if it turns)."""
    model = results.mechanism
    bodies = [b["name"] for b in model.bodies] if model is not None else []
    if not bodies:
        return results.channels[:2]
    first, last = bodies[0], bodies[-1]
    out = [f"{first}.phi"]
    if np.ptp(results[f"{last}.phi"]) > 1e-9 and last != first:
        out.append(f"{last}.phi")
    else:
        x, y = np.ptp(results[f"{last}.x"]), np.ptp(results[f"{last}.y"])
        out.append(f"{last}.{'x' if x >= y else 'y'}")
    return out


def page_data(results: Results, model: Model, plots: Sequence[str] | None = None) -> dict[str, Any]:
    """What the page draws (`camlink.viz.front.frame_data`): times, body poses
    (float32), the scene, traces of the file's ``[analysis] points``,
    springs, forces and channels; every channel when the run has at most
    `MOST_VALUES` values, else the plotted ones."""
    from camlink.viz.front import frame_data
    from camlink.viz.scene import Scene

    missing = [p for p in plots or () if p not in results]
    if missing:
        results[missing[0]]  # raises KeyError naming close matches
    names = list(results.channels)
    values = np.column_stack([results[c] for c in names]) if names else np.zeros((len(results), 0))
    scene = Scene.of(model, tol=1e-4)
    points = [str(p) for p in (model.analysis.get("points") or [])]
    sent = None if values.size <= MOST_VALUES else list(plots or [])
    data = frame_data(model, scene, np.asarray(results.t, dtype=np.float64), names, values, None,
                      points=points, plots=plots, pose_dtype="f32", channels=sent,
                      units=results.units)
    data["t"] = data["t"]["f64"]
    data["handles"] = [{"id": f"pin:{p.joint}", "label": p.joint, "body": p.body_i, "s": list(p.s_i)}
                       for p in scene.pins]
    data["view"] = {"width": STAGE[0], "height": STAGE[1], "box": data["box"],
                    "plot_width": PLOT[0], "plot_height": PLOT[1]}
    return data


def view_pixel(box: Sequence[float], x: float, y: float) -> tuple[float, float]:
    """Where the page first draws the global point (x, y) (m), before any
    zoom or pan: CSS px from the stage canvas's top left, for the view
    `box` = (x0, x1, y0, y1)."""
    x0, x1, y0, y1 = box
    w, h = STAGE
    scale = min(w / (x1 - x0), h / (y1 - y0))
    ox, oy = (w - (x1 - x0) * scale) / 2, (h - (y1 - y0) * scale) / 2
    return ox + (x - x0) * scale, oy + (y1 - y) * scale


def thin(results: Results, most: int = MOST_ROWS) -> Results:
    """`results` with at most `most` rows, evenly spread over the run and
    keeping the first and the last (the same results when they have no
    more)."""
    n = len(results)
    if n <= most:
        return results
    rows = np.unique(np.linspace(0, n - 1, most).round().astype(np.intp))
    names = ["t", *results.channels]
    data = np.column_stack([results[c][rows] for c in names])
    return results._like(names, data)


def fill(template: str, values: dict[str, str]) -> str:
    """`template` with each ``__NAME__`` replaced by ``values["NAME"]``, in
    one pass: text a value brings in is never searched again."""
    def value(m: re.Match[str]) -> str:
        try:
            return values[m.group(1)]
        except KeyError:
            raise ValueError(f"viewer template: no value for {m.group(0)}") from None

    return _PLACEHOLDER.sub(value, template)


def script_json(data: object) -> str:
    """`data` as JSON to put inside a ``<script>`` element: ``<``, ``>``,
    ``&``, U+2028 and U+2029 written as ``\\u`` escapes, so that no value
    can end the element or open a comment or a script in it."""
    return json.dumps(data, separators=(",", ":")).translate(_SCRIPT_SAFE)


def page(template: str, title: str, data: object) -> str:
    """The viewer page of `template` for the model named `title` with the
    page's `data`: the front end (uPlot, ``web/camlink.js`` and the
    viewer's start) inlined as one script, the only one its policy lets
    run."""
    from camlink.viz.front import asset

    script = "\n".join(asset(n) for n in ("uPlot.iife.min.js", "camlink.js", "viewer_boot.js"))
    if re.search(r"</script|<!--", script, re.IGNORECASE):
        raise ValueError("viewer script: holds text that would end its <script> element")
    style = "\n".join(asset(n) for n in ("uPlot.min.css", "studio.css"))
    digest = hashlib.sha256(script.encode("utf-8")).digest()
    return fill(template, {
        "SCRIPT_HASH": f"'sha256-{base64.b64encode(digest).decode('ascii')}'",
        "TITLE": html.escape(title, quote=True),
        "DATA": script_json(data),
        "SCRIPT": script,
        "STYLE": style,
    })


def to_html(
    source: Model | Results,
    path: str | os.PathLike[str] | None = None,
    *,
    plots: Sequence[str] | None = None,
) -> Path | str:
    """Writes the viewer of a run (or of a model's kinematic run over its
    file's times) to `path` and returns the path; without `path` returns the
    page's text. `plots` names the channels of the linked plots (default
    `default_plots`). A run of more than `MOST_ROWS` rows is thinned to
    that many.

    The page is written to a temporary file beside `path` and renamed over
    it when complete; `ModelError` when `path` is one of the model's inputs
    (its file, its data files)."""
    from camlink.viz.drawing import motion_of

    model, res = resolve(source)
    if path is not None:
        check_not_input(Path(path), model.inputs)
    if res is None:
        res = motion_of(model)
    if res is None or len(res) == 0:
        raise ModelError(f"model '{model.name}' has no motion to show (not fully driven)")
    chosen = list(plots) if plots else []
    for name in chosen:
        if name not in res:
            try:
                res[name]
            except KeyError as e:
                raise ModelError(f"cannot plot {name!r}: {e.args[0]}") from None
    res = thin(res)
    data = page_data(res, model, chosen or None)
    template = resources.files("camlink.viz").joinpath("viewer.html").read_text(encoding="utf-8")
    text = page(template, model.name, data)
    if path is None:
        return text
    path = Path(path)
    target = _Target(path, path.suffix)
    try:
        target.temp.write_text(text, encoding="utf-8")
    except BaseException:
        target.temp.unlink(missing_ok=True)
        raise
    return target.finish(target.temp, True)
