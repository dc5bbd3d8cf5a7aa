"""Drawings of a mechanism: pins at their computed pixels, cam outlines on the
exact curve, the frame holding the whole motion."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest
from four_bar_pins import four_bar_pins
from PIL import Image

import camlink
from camlink.results import Results
from camlink.viz.drawing import Drawing, draw

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


def _render(drawing: Drawing, path: Path) -> npt.NDArray[np.float64]:
    drawing.figure.savefig(path)
    return np.asarray(Image.open(path).convert("L"), dtype=np.float64)


def test_four_bar_pins_land_at_their_pixels(tmp_path: Path) -> None:
    model = camlink.load(EXAMPLES / "four_bar.toml")
    res = model.run()
    drawing = Drawing(model, res, traces=["coupler.P"])
    for k in (0, 37, 150):
        drawing.show(k)
        image = _render(drawing, tmp_path / f"four_bar_{k}.png")
        r_px = drawing.pin_radius * drawing.frame.px_per_m
        assert r_px > 4
        for joint, xy in four_bar_pins(res, k).items():
            (u, v), = drawing.pixel([xy])
            # The pin's patch is centred there ...
            patch = next(p for p in drawing.ax.patches if p.get_gid() == f"pin:{joint}")
            verts = np.asarray(patch.get_verts())
            centre = verts[:-1].mean(axis=0)
            assert np.allclose([centre[0], drawing.figure.bbox.height - centre[1]], [u, v], atol=1e-6)
            # ... and the image shows it: a dark centre dot, white fill, a dark ring.
            i, j = round(v), round(u)
            assert image[i, j] < 110, (joint, k, image[i, j])
            fill = [image[round(v + 0.55 * r_px * s), round(u + 0.55 * r_px * c)]
                    for c, s in ((1, 0), (0, 1), (-1, 0), (0, -1))]
            assert min(fill) > 200, (joint, k, fill)
            ring = [image[round(v + r_px * np.sin(a)), round(u + r_px * np.cos(a))]
                    for a in np.linspace(0, 2 * np.pi, 16, endpoint=False)]
            assert np.median(ring) < 150, (joint, k, ring)


def test_frame_holds_the_whole_motion_on_one_scale() -> None:
    model = camlink.load(EXAMPLES / "four_bar.toml")
    res = model.run()
    drawing = Drawing(model, res, traces=["coupler.P"])
    (x0, x1), (y0, y1) = drawing.frame.xlim, drawing.frame.ylim
    paths = [res["rocker.B.x"], res["rocker.B.y"], res["coupler.P.x"], res["coupler.P.y"]]
    assert x0 < min(paths[0].min(), paths[2].min()) and max(paths[0].max(), paths[2].max()) < x1
    assert y0 < min(paths[1].min(), paths[3].min()) and max(paths[1].max(), paths[3].max()) < y1
    d = drawing.ax.transData.transform([[0.0, 0.0], [0.1, 0.1]])
    assert abs((d[1, 0] - d[0, 0]) - (d[1, 1] - d[0, 1])) < 1e-6
    assert drawing.ax.get_xlabel() == "x (m)" and drawing.ax.get_ylabel() == "y (m)"
    # The trace is the coupler point's path from the results.
    trace = next(ln for ln in drawing.ax.lines if ln.get_gid() == "trace:coupler.P")
    assert np.allclose(trace.get_xdata(), res["coupler.P.x"], atol=1e-12)
    assert np.allclose(trace.get_ydata(), res["coupler.P.y"], atol=1e-12)


def test_sliders_on_guides_are_framed_with_their_travel() -> None:
    # Blocks on guides to the ground, with no other named point: the frame
    # once shrank to the ground's one point (0.3 mm across) and hatched the
    # rails with 77,000 strokes.
    model = camlink.load(EXAMPLES / "dyn_incline_friction.toml")
    res = model.run()
    drawing = Drawing(model, res)
    (x0, x1), (y0, y1) = drawing.frame.xlim, drawing.frame.ylim
    for body in ("slider", "sticker"):
        x, y = res[f"{body}.x"], res[f"{body}.y"]
        assert x0 < x.min() and x.max() < x1 and y0 < y.min() and y.max() < y1, body
    hatches = [ln for ln in drawing.ax.lines if str(ln.get_gid()).endswith(":hatch")]
    assert 0 < len(hatches) < 200


def _distance_to_polyline(
    p: npt.NDArray[np.float64], poly: npt.NDArray[np.float64]
) -> npt.NDArray[np.float64]:
    a, b = poly[:-1], poly[1:]
    d = b - a
    out = np.full(len(p), np.inf)
    for start in range(0, len(p), 2000):
        q = p[start:start + 2000, None, :]
        w = q - a[None]
        u = np.clip((w * d).sum(-1) / np.maximum((d * d).sum(-1), 1e-300), 0.0, 1.0)
        e = w - u[..., None] * d
        out[start:start + 2000] = np.sqrt((e * e).sum(-1)).min(axis=1)
    return out


def test_seed_cam_outline_on_the_exact_curve_within_half_a_pixel(tmp_path: Path) -> None:
    model = camlink.load(EXAMPLES / "cam_seed_example_3_4_3.toml")
    res = model.run()
    drawing = Drawing(model, res)
    k = 57
    drawing.show(k)
    drawing.figure.savefig(tmp_path / "cam.png")
    patch = next(p for p in drawing.ax.patches if p.get_gid() == "curve:contact:cam")
    drawn = np.asarray(patch.get_verts(), dtype=np.float64)
    # The lecture's profile ρ(α) on the cam turned by φ.
    alpha = np.linspace(0.0, 2 * np.pi, 40001)
    rho = np.where(alpha <= 2 * np.pi / 3, 1.25 - np.cos(3 * alpha) / 4, 1.0)
    phi = res["cam.phi"][k]
    exact = np.column_stack([rho * np.cos(alpha + phi), rho * np.sin(alpha + phi)])
    exact_px = drawing.ax.transData.transform(exact)
    assert drawing.frame.px_per_m > 100
    assert _distance_to_polyline(exact_px, drawn).max() < 0.5
    assert _distance_to_polyline(drawn, exact_px).max() < 0.5


def test_draw_accepts_model_or_results_and_names_missing_pieces() -> None:
    model = camlink.load(EXAMPLES / "slider_crank.toml")
    fig = draw(model, t=0.05)
    assert fig.axes[0].get_aspect() == 1.0
    res = model.run()
    assert draw(res, t=0.05).axes
    from_file = Results(res._names, res.data)
    with pytest.raises(camlink.ModelError, match="carry no model"):
        draw(from_file)
    with pytest.raises(KeyError, match=r"no body point 'crank\.Q'"):
        draw(res, traces=["crank.Q"])
    with pytest.raises(camlink.ModelError, match="force channels"):
        draw(res, forces=["crank_pivot"])


def test_every_example_draws() -> None:
    # Cam design, study and synthesis problem files are not models.
    not_models = ("cam_design_", "study_", "synthesis_")
    paths = [p for p in sorted(EXAMPLES.glob("*.toml")) if not p.name.startswith(not_models)]
    assert len(paths) >= 20
    for path in paths:
        model = camlink.load(path)
        fig = draw(model, width=3.0, dpi=40)
        assert fig.axes, path.name


def _coupler_outline(outline: str) -> str:
    return (EXAMPLES / "four_bar.toml").read_text().replace(
        'points = { A = [0, 0], B = ["b", 0], P = ["b/2", "p"] }',
        'points = { A = [0, 0], B = ["b", 0], P = ["b/2", "p"] }\n' + f"outline = {outline}",
    )


def test_outline_from_the_model_file_replaces_the_derived_link() -> None:
    text = _coupler_outline('[[0, -0.01], ["b", -0.01], ["b", 0.01], ["b/2", "p + 0.02"], [0, 0.01]]')
    model = camlink.loads(text)
    res = model.run()
    drawing = Drawing(model, res)
    k = 40
    drawing.show(k)
    gids = {p.get_gid() for p in drawing.ax.patches}
    assert "outline:coupler" in gids and "link:coupler" not in gids and "link:crank" in gids
    patch = next(p for p in drawing.ax.patches if p.get_gid() == "outline:coupler")
    corners = np.array([[0, -0.01], [0.38, -0.01], [0.38, 0.01], [0.19, 0.12], [0, 0.01]])
    phi = res["coupler.phi"][k]
    c, s = np.cos(phi), np.sin(phi)
    world = np.column_stack([res["coupler.x"][k] + c * corners[:, 0] - s * corners[:, 1],
                             res["coupler.y"][k] + s * corners[:, 0] + c * corners[:, 1]])
    drawn = np.asarray(patch.get_verts())[:-1]
    assert np.allclose(drawn, drawing.ax.transData.transform(world), atol=1e-6)
    with pytest.raises(camlink.ModelError, match=r"bodies\[1\]\.outline.*at least three corners"):
        camlink.loads(_coupler_outline("[[0, 0], [1, 0]]"))


def test_time_and_cam_angle_are_written_on_the_frame() -> None:
    model = camlink.load(EXAMPLES / "cam_seed_example_3_4_3.toml")
    res = model.run()
    drawing = Drawing(model, res)
    for k in (0, 57, 399):
        drawing.show(k)
        theta = f"{np.degrees(res['cam.phi'][k]) % 360.0:.1f}"
        # An angle a hair under a whole turn reads 0.0°, not 360.0°.
        theta = "0.0" if theta == "360.0" else theta
        assert drawing.label.get_text() == f"t = {res.t[k]:.3f} s   θ = {theta}°"
    drawing.show(0)
    assert drawing.label.get_text().endswith("θ = 0.0°")
    assert drawing.row(0.2501) == 100
