"""Issue 29 leftovers: cam profile pictures whose followers stay inside the
frame, each labelled with its cam angle, with the undercut ranges
highlighted where they are; and no "-0" in the text that results show."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from matplotlib.colors import to_rgba
from matplotlib.patches import Circle

from camlink import Results
from camlink.cam import design as cam_design
from camlink.cam import plots as cam_plots
from conftest import ROOT

#: A roller far larger than the steep rise's pitch curvature: undercut.
UNDERCUT = """\
name = "undercut"
[cam]
base_radius = 0.02
[follower]
type = "translating-roller"
roller_radius = 0.015
[[segments]]
law = "cycloidal"
span_deg = 30
lift = 0.02
[[segments]]
law = "dwell"
span_deg = 150
[[segments]]
law = "cycloidal"
span_deg = 30
lift = -0.02
[[segments]]
law = "dwell"
span_deg = 150
"""


def _design(tmp_path: Path, name: str) -> cam_design.Design:
    if name == "undercut":
        path = tmp_path / "undercut.toml"
        path.write_text(UNDERCUT)
        return cam_design.load(path)
    return cam_design.load(ROOT / "examples" / f"cam_design_{name}.toml")


def _inside(points: np.ndarray, xlim: tuple[float, float], ylim: tuple[float, float]) -> bool:
    return bool(
        np.all(points[:, 0] >= xlim[0]) and np.all(points[:, 0] <= xlim[1])
        and np.all(points[:, 1] >= ylim[0]) and np.all(points[:, 1] <= ylim[1])
    )


@pytest.mark.parametrize("name", ["valve", "packaging", "indexing", "undercut"])
@pytest.mark.parametrize("followers", [4, 6])
def test_issue29_cam_profile_followers_inside_and_labelled(
    tmp_path: Path, name: str, followers: int
) -> None:
    design = _design(tmp_path, name)
    core = design.core()
    fig = cam_plots.profile(core, base_radius=design.base_radius, followers=followers)
    fig.savefig(tmp_path / f"{name}.png", dpi=60)
    ax = fig.axes[0]
    xlim, ylim = ax.get_xlim(), ax.get_ylim()
    ts = np.linspace(0.0, 2.0 * math.pi, followers, endpoint=False)
    circles = [p for p in ax.patches if p.get_gid() == "follower"]
    faces = [line for line in ax.lines if line.get_gid() == "follower"]
    assert len(circles) + len(faces) == followers
    if circles:
        centres = np.asarray(core.pitch(ts))
        for circle, centre in zip(circles, centres, strict=True):
            assert isinstance(circle, Circle)
            np.testing.assert_allclose(circle.center, centre)
            r = circle.radius
            assert _inside(np.array(circle.center) + r * np.array(
                [[1, 0], [-1, 0], [0, 1], [0, -1]]), xlim, ylim), name
    for face in faces:
        assert _inside(np.asarray(face.get_xydata()), xlim, ylim), name
    # Each follower labelled with its cam angle, the text inside the axes.
    labels = [t for t in ax.texts if t.get_gid() == "follower label"]
    assert [t.get_text() for t in labels] == [f"θ = {math.degrees(t):.0f}°" for t in ts]
    renderer = fig.canvas.get_renderer()  # type: ignore[attr-defined]
    box = ax.get_window_extent(renderer)
    for label in labels:
        extent = label.get_window_extent(renderer)
        assert box.x0 <= extent.x0 and extent.x1 <= box.x1, label.get_text()
        assert box.y0 <= extent.y0 and extent.y1 <= box.y1, label.get_text()
    # The undercut ranges, only there, over the surface in the highlight colour.
    ranges = core.geometry()["undercut"]
    marks = [line for line in ax.lines if line.get_gid() == "undercut"]
    assert (len(ranges) > 0) == (name == "undercut")
    assert len(marks) == len(ranges)
    for (a, b), mark in zip(ranges, marks, strict=True):
        assert to_rgba(mark.get_color()) == to_rgba(cam_plots.UNDERCUT_COLOUR)
        xy = np.asarray(mark.get_xydata())
        ends = np.asarray(core.surface(np.array([a, b])))
        np.testing.assert_allclose(xy[[0, -1]], ends, atol=1e-12)
        # Every point on the surface between the range's ends.
        dense = np.asarray(core.surface(np.linspace(a, b, 20 * len(xy))))
        gaps = np.min(np.linalg.norm(xy[:, None, :] - dense[None, :, :], axis=2), axis=1)
        assert gaps.max() < 1e-3 * design.base_radius
    cam_plots.save(fig, tmp_path / "x.png")


def test_issue29_no_negative_zero_in_reprs() -> None:
    data = np.array([[-0.0, -0.0, 1.5], [1.0, -0.0, -2.0]])
    res = Results(["t", "a.x", "a.y"], data, model="m")
    text = repr(res)
    assert "t = 0 … 1 s" in text and "-0" not in text
    html = res._repr_html_()
    table = html.split("<table")[1].split("</table>")[0]
    assert "-0<" not in table and "-0.0" not in table and ">0<" in table
    assert "-2<" in table

