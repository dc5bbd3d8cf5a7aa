"""Issue 29, matplotlib drawings as a new user found them: springs and
dampers, titles, angles near a whole turn, ground symbols, traced points,
body and joint names, force labels, units of efforts, normal forces and
gear angles. Pictures are checked where their pieces land in pixels."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest
from matplotlib.lines import Line2D
from matplotlib.patches import Polygon
from matplotlib.transforms import Bbox
from PIL import Image

import camlink
from camlink.results import Results
from camlink.viz.drawing import Drawing, angle_text, draw, number_text
from camlink.viz.plots import plot

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"

Array = npt.NDArray[np.float64]


def _line(drawing: Drawing, gid: str) -> Line2D:
    return next(ln for ln in drawing.ax.lines if ln.get_gid() == gid)


def _xy(line: Line2D) -> Array:
    return np.asarray(line.get_xydata(), dtype=np.float64)


def _corners(drawing: Drawing, gid: str) -> Array:
    patch = next(p for p in drawing.ax.patches if p.get_gid() == gid)
    assert isinstance(patch, Polygon)
    return np.asarray(patch.get_xy(), dtype=np.float64)


def _display(drawing: Drawing, xy: npt.ArrayLike) -> Array:
    return np.asarray(drawing.ax.transData.transform(np.asarray(xy, dtype=np.float64).reshape(-1, 2)))


def _rgb(drawing: Drawing, path: Path) -> Array:
    drawing.figure.savefig(path)
    return np.asarray(Image.open(path).convert("RGB"), dtype=np.float64)


def _boxes(drawing: Drawing) -> dict[str, Bbox]:
    """Every text's box (display pixels, background patch included), by its
    gid (the time read-out as ``"time"``)."""
    out = {}
    for text in drawing.ax.texts:
        if not text.get_text():
            continue
        out[text.get_gid() or "time"] = drawing._extent(text)
    return out


def test_issue29_springs_and_dampers_drawn(tmp_path: Path) -> None:
    model = camlink.load(EXAMPLES / "dyn_slider_crank.toml")
    res = model.run()
    drawing = Drawing(model, res)
    amp_px = 0.6 * drawing.half_width * drawing.frame.px_per_m
    assert amp_px > 3
    for k in (0, 130, 377, 800):
        drawing.show(k)
        line = _line(drawing, "spring:return_spring")
        xy = _display(drawing, _xy(line))
        # From the ground point W = (-0.2, 0) to the slider's point B (its origin).
        a, b = _display(drawing, [[-0.2, 0.0], [res["slider.x"][k], res["slider.y"][k]]])
        assert np.allclose(xy[0], a, atol=1e-6) and np.allclose(xy[-1], b, atol=1e-6)
        # Between them a zigzag: coils alternately either side of the line a–b,
        # each the spring's half-width from it, evenly spread along it.
        u = (b - a) / np.hypot(*(b - a))
        n = np.array([-u[1], u[0]])
        coils = xy[2:-2]
        assert len(coils) == 12
        side = (coils - a) @ n
        assert np.allclose(np.abs(side), amp_px, rtol=1e-9)
        assert np.all(np.sign(side[:-1]) == -np.sign(side[1:]))
        along = (coils - a) @ u
        assert np.all(np.diff(along) > 0) and along[0] > 0 and along[-1] < np.hypot(*(b - a))
        # The picture shows it: the spring's green at the middle of a coil's
        # leg (the greenest pixel within one of it: the line is 1.7 px wide).
        image = _rgb(drawing, tmp_path / f"spring_{k}.png")
        height = drawing.figure.bbox.height
        for p in (0.5 * (coils[3] + coils[4]), 0.5 * (coils[7] + coils[8])):
            col, row = round(p[0]), round(height - p[1])
            near = image[row - 1:row + 2, col - 1:col + 2].reshape(-1, 3)
            r, g, bl = near[np.argmax(near[:, 1] - near[:, 0])]
            assert g > r + 40 and g > bl + 40 and g < 170, (k, near)
    # Ends marked at the attachment points.
    end = _line(drawing, "spring-end:return_spring:j")
    assert np.allclose(_xy(end)[0], [res["slider.x"][800], res["slider.y"][800]])

    # With damping too: a spring and a dashpot side by side between the ends.
    text = (EXAMPLES / "dyn_slider_crank.toml").read_text().replace(
        "free_length = 0.35", "free_length = 0.35\ndamping = 5")
    damped = camlink.loads(text, base_dir=EXAMPLES)
    assert damped._core.forces[0]["damping"] == 5.0
    res = damped.run()
    drawing = Drawing(damped, res)
    k = 200
    drawing.show(k)
    a, b = _display(drawing, [[-0.2, 0.0], [res["slider.x"][k], res["slider.y"][k]]])
    u = (b - a) / np.hypot(*(b - a))
    n = np.array([-u[1], u[0]])
    spring = _display(drawing, _xy(_line(drawing, "spring:return_spring")))
    pot = _xy(_line(drawing, "damper:return_spring"))
    pieces = np.split(pot, np.flatnonzero(np.isnan(pot[:, 0])))
    pieces = [_display(drawing, p[~np.isnan(p[:, 0])]) for p in pieces]
    assert np.allclose(spring[0], a) and np.allclose(spring[-1], b)
    assert np.allclose(pieces[0][0], a) and np.allclose(pieces[-1][-1], b)
    # The spring's coils on one side of the axis, the dashpot's cylinder on
    # the other, its open end towards b with the piston's plate inside.
    assert np.all((spring[4:-4] - a) @ n > 0)
    cylinder, plate = pieces[1], pieces[2]
    assert np.all((cylinder - a) @ n < 0)
    walls = (cylinder - a) @ n
    assert np.ptp(walls) == pytest.approx(2 * amp_px, rel=1e-9)
    assert ((plate - a) @ u).min() > ((cylinder - a) @ u).min()
    assert ((plate - a) @ u).max() < ((cylinder - a) @ u).max()

    # A spring on points given by expressions ([0, "H"] on the ground).
    model = camlink.load(EXAMPLES / "cam_valve_spring.toml")
    force = model._core.forces[0]
    assert force["kind"] == "tsda" and force["s_i"] == [0.0, 0.1] and (force["stiffness"] or 0) > 0
    res = model.run()
    drawing = Drawing(model, res)
    drawing.show(160)
    xy = _xy(_line(drawing, "spring:valve_spring"))
    assert np.allclose(xy[0], [0.0, 0.1])
    assert np.allclose(xy[-1], [res["tappet.x"][160], res["tappet.y"][160]])

    # A torsion spring: a spiral round the pin joining its two bodies.
    model = camlink.load(EXAMPLES / "dyn_spring_pendulum.toml")
    drawing = Drawing(model)
    drawing.show(0)
    spiral = _xy(_line(drawing, "torsion:spring"))
    radius = np.hypot(spiral[:, 0], spiral[:, 1])
    assert radius.min() > drawing.pin_radius and radius.max() < 4 * drawing.pin_radius
    turned = np.unwrap(np.arctan2(spiral[:, 1], spiral[:, 0]))
    assert turned[-1] - turned[0] == pytest.approx(5 * np.pi)


def test_issue29_titles_not_clipped() -> None:
    model = camlink.load(EXAMPLES / "four_bar.toml")
    res = model.run()
    for width, title in ((6.4, "four-bar"), (4.5, "a four-bar crank-rocker with its coupler "
                                                    "curve traced over two turns of the crank")):
        drawing = Drawing(model, res, width=width, title=title)
        drawing.show(0)
        renderer = drawing._renderer()
        box = drawing.ax.title.get_window_extent(renderer)
        figure = drawing.figure.bbox
        assert figure.x0 <= box.x0 and box.x1 <= figure.x1, (title, box, figure)
        assert figure.y0 <= box.y0 and box.y1 <= figure.y1, (title, box, figure)
        # Above the frame, not over it.
        assert box.y0 >= drawing.ax.bbox.y1
        assert drawing.ax.title.get_text().replace("\n", " ") == title


def test_issue29_angle_near_0_is_0_degrees_and_no_negative_zero() -> None:
    assert angle_text(-1.6543612251060553e-24) == "0.0°"
    assert angle_text(2 * np.pi - 1e-9) == "0.0°"
    assert angle_text(np.radians(-0.04)) == "0.0°"
    assert angle_text(np.radians(359.94)) == "359.9°"
    assert angle_text(np.radians(-90.0)) == "270.0°"
    assert angle_text(np.radians(720.3)) == "0.3°"
    assert number_text(-1e-12, ".3f") == "0.000"
    assert number_text(-0.0, ".3g") == "0"
    assert number_text(-0.0004, ".3f") == "0.000"
    assert number_text(-0.0006, ".3f") == "-0.001"
    # The lecture's cam starts a hair under φ = 0 (-1.7e-24 rad).
    model = camlink.load(EXAMPLES / "cam_seed_example_3_4_3.toml")
    res = model.run()
    assert res["cam.phi"][0] < 0
    drawing = Drawing(model, res)
    drawing.show(0)
    assert drawing.label.get_text() == "t = 0.000 s   θ = 0.0°"
    # A run whose first time is a rounding error below zero.
    data = np.array(res.data)
    data[0, res._names.index("t")] = -1e-15
    shifted = Results(res._names, data, model=res.model)
    shifted.mechanism = model
    drawing = Drawing(model, shifted)
    drawing.show(0)
    assert drawing.label.get_text() == "t = 0.000 s   θ = 0.0°"
    assert "-0" not in drawing.label.get_text() and "−0" not in drawing.label.get_text()


def test_issue29_ground_symbols_oriented_away_from_the_links(tmp_path: Path) -> None:
    # The pendulum hangs from a ceiling pivot: its anchor stands above it.
    model = camlink.load(EXAMPLES / "pendulum.toml")
    res = model.run()
    drawing = Drawing(model, res)
    pivot = np.array([0.0, 1.2])
    hatch = np.vstack([np.column_stack([ln.get_xdata(), ln.get_ydata()]) for ln in drawing.ax.lines
                       if ln.get_gid() in ("ground:pivot:hatch", "ground:pivot:base")])
    corners = _corners(drawing, "ground:pivot")
    # Every part of the symbol but the pin's own corner is on the far side
    # of the pivot from the bob, at every row.
    phi = res["arm.phi"]
    to_bob = np.column_stack([np.sin(phi), -np.cos(phi)])
    for part in (hatch, corners[1:3]):
        away = (part - pivot) @ to_bob.T
        assert np.all(away < -0.5 * drawing.pin_radius), away.max()
    # In the picture: the base's line above the pin, the arm's fill below.
    drawing.show(0)
    image = _rgb(drawing, tmp_path / "pendulum.png")
    base = 0.5 * (corners[1] + corners[2])
    (u, v), = drawing.pixel([base])
    assert image[round(v), round(u)].mean() < 110
    (u, v), = drawing.pixel([pivot + (base - pivot) * np.array([1.0, -1.0])])
    assert image[round(v), round(u)].mean() > 180

    # The four-bar's crank turns all the way round: its anchor stays under
    # the pivot; the rocker swings above its pivot: under it too.
    model = camlink.load(EXAMPLES / "four_bar.toml")
    drawing = Drawing(model, model.run())
    for joint, at in (("O2", (0.0, 0.0)), ("O4", (0.4, 0.0))):
        tri = _corners(drawing, f"ground:{joint}")
        assert np.all(tri[1:3, 1] < at[1] - 2 * drawing.pin_radius), joint
        assert np.allclose(tri[1:3, 0].mean(), at[0])


def test_issue29_traced_points_marked(tmp_path: Path) -> None:
    model = camlink.load(EXAMPLES / "four_bar.toml")
    res = model.run()
    drawing = Drawing(model, res, traces=["coupler.P", "rocker.B"])
    for k in (0, 90, 250):
        drawing.show(k, grow=True)
        image = _rgb(drawing, tmp_path / f"marks_{k}.png")
        for name in ("coupler.P", "rocker.B"):
            mark = _line(drawing, f"mark:{name}")
            at = [res[f"{name}.x"][k], res[f"{name}.y"][k]]
            assert np.allclose(_xy(mark)[0], at, atol=1e-12)
            (u, v), = drawing.pixel([at])
            r, g, b = image[round(v), round(u)]
            # The trace's red, dot-sized: red at the point and at 1.5 px off it.
            assert r > 140 and g < 110 and b < 110, (name, k, image[round(v), round(u)])
            for du, dv in ((1.5, 0), (-1.5, 0), (0, 1.5), (0, -1.5)):
                r, g, b = image[round(v + dv), round(u + du)]
                assert r > g + 40, (name, k, du, dv)


def test_issue29_optional_body_and_joint_labels(tmp_path: Path) -> None:
    model = camlink.load(EXAMPLES / "four_bar.toml")
    res = model.run()
    plain = Drawing(model, res)
    plain.show(0)
    assert [t.get_gid() for t in plain.ax.texts if t.get_text()] == [None]
    drawing = Drawing(model, res, labels=True)
    pin_px = drawing.pin_radius * drawing.frame.px_per_m
    for k in (0, 60, 150, 333):
        drawing.show(k)
        boxes = _boxes(drawing)
        assert set(boxes) == {"time", "body:crank", "body:coupler", "body:rocker",
                              "joint:O2", "joint:A", "joint:B", "joint:O4"}
        # A joint's name beside its pin, clear of it, within two pin radii
        # and a name's size.
        phi = res["crank.phi"][k]
        pins = {"O2": (0.0, 0.0), "O4": (0.4, 0.0), "A": (0.12 * np.cos(phi), 0.12 * np.sin(phi)),
                "B": (res["rocker.B.x"][k], res["rocker.B.y"][k])}
        for joint, at in pins.items():
            (x, y), = _display(drawing, [at])
            box = boxes[f"joint:{joint}"]
            nearest = np.array([np.clip(x, box.x0, box.x1), np.clip(y, box.y0, box.y1)])
            gap = float(np.hypot(*(nearest - (x, y))))
            assert pin_px < gap < 2 * pin_px + 2 * box.height, (joint, k, gap)
        # A body's name on the body: over the middle of its link.
        for body, local in (("crank", (0.06, 0.0)), ("rocker", (0.15, 0.0))):
            q = [res[f"{body}.x"][k], res[f"{body}.y"][k], res[f"{body}.phi"][k]]
            c, s = np.cos(q[2]), np.sin(q[2])
            middle = (q[0] + c * local[0] - s * local[1], q[1] + s * local[0] + c * local[1])
            (x, y), = _display(drawing, [middle])
            box = boxes[f"body:{body}"]
            assert np.hypot(x - 0.5 * (box.x0 + box.x1), y - 0.5 * (box.y0 + box.y1)) < 3 * box.height
        # No two names overlap, and all are inside the frame.
        names = list(boxes.values())
        for i in range(len(names)):
            for j in range(i):
                assert not names[i].overlaps(names[j]), (k, list(boxes)[i], list(boxes)[j])
        frame = drawing.ax.bbox
        for name, box in boxes.items():
            assert frame.x0 <= box.x0 <= box.x1 <= frame.x1, name
            assert frame.y0 <= box.y0 <= box.y1 <= frame.y1, name
    drawing.figure.savefig(tmp_path / "labels.png")
    # Through `draw` too, for a model with gears, slots and cams.
    joints = {"gear_train": "mesh12", "rack_pinion": "mesh", "slot_circular_pin": "pin_in_slot",
              "cam_seed_example_3_4_3": "contact", "slider_crank": "guide"}
    for name, joint in joints.items():
        fig = draw(camlink.load(EXAMPLES / f"{name}.toml"), labels=True, width=4.0, dpi=60)
        gids = {t.get_gid() for t in fig.axes[0].texts}
        assert any(str(g).startswith("body:") for g in gids)
        assert f"joint:{joint}" in gids, (name, gids)


def test_issue29_force_labels_do_not_collide() -> None:
    model = camlink.load(EXAMPLES / "dyn_slider_crank.toml")
    res = model.run()
    # At the notebook's width, without this the labels of O, A and B met
    # at 18 of 200 rows.
    for width, labels in ((4.5, False), (3.0, False), (6.4, True)):
        drawing = Drawing(model, res, forces=["A", "B", "O"], width=width, labels=labels)
        for k in range(0, len(res), 5):
            drawing.show(k)
            boxes = _boxes(drawing)
            assert {"force-label:A", "force-label:B", "force-label:O"} <= set(boxes)
            items = list(boxes.items())
            for i in range(len(items)):
                for j in range(i):
                    assert not items[i][1].overlaps(items[j][1]), (width, k, items[i][0], items[j][0])
            # Each still names its force's magnitude, near its arrow's tip.
            for joint in "ABO":
                text = next(t for t in drawing.ax.texts if t.get_gid() == f"force-label:{joint}")
                mag = float(np.hypot(res[f"{joint}.fx_j"][k], res[f"{joint}.fy_j"][k]))
                assert text.get_text() == f"{joint}: {number_text(mag, '.3g')} N"
                arrow = next(a for a in drawing._arrows if a[4] == joint)
                (x, y), = _display(drawing, [arrow[1][k] + arrow[2][k]])
                box = boxes[f"force-label:{joint}"]
                nearest = np.array([np.clip(x, box.x0, box.x1), np.clip(y, box.y0, box.y1)])
                assert np.hypot(*(nearest - (x, y))) < 6 * box.height, (width, k, joint)


def test_issue29_units_on_efforts_normal_forces_and_gear_angles() -> None:
    # An effort is a torque or a force by what its driver drives: the core
    # says which with the channel.
    four_bar = camlink.load(EXAMPLES / "four_bar.toml").inverse_dynamics(t_end=0.01, step=0.01)
    assert four_bar.units["motor.effort"] == "N·m"
    pushed = camlink.load(EXAMPLES / "slider_crank_slider_driven.toml")
    units = pushed.inverse_dynamics(t_end=0.01, step=0.01).units
    assert units["stroke.effort"] == "N" and units["O.fx"] == "N"
    # On the plots.
    res = camlink.load(EXAMPLES / "dyn_slider_crank.toml").run()
    assert res.plot("motor.effort").axes[0].get_ylabel() == "motor.effort (N·m)"
    res = camlink.load(EXAMPLES / "cam_valve_jump.toml").run()
    assert res.plot("bucket.normal_force").axes[0].get_ylabel() == "bucket.normal_force (N)"
    assert plot(res, ["bucket.normal_force", "bucket.tangential_force"]).axes[0].get_ylabel() == "(N)"
    res = camlink.load(EXAMPLES / "gear_train.toml").run()
    assert res.plot("mesh12.theta").axes[0].get_ylabel() == "mesh12.theta (rad)"
