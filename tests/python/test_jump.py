"""Follower jump from Python: the valve-jump example's flights and impacts
against the closed form, the lift picture, the CLI's summary line,
`camlink.jump_speed` and a unilateral contact from the builder."""

from __future__ import annotations

import math

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg

import camlink
from camlink.cam.jump import flight_summary, jump_plot, jump_speed
from camlink.results import IMPACT_COLUMNS, LIFT_OFF_COLUMNS
from conftest import ROOT, run_cli

VALVE = ROOT / "examples" / "cam_valve_jump.toml"

# The example's parameters and the closed form of its lift-off angle:
# N = k (R + e sin θ − y_free) + m g − m e ω² sin θ falls to zero at
# sin θ₁ = (k (R − y_free) + m g) / (e (m ω² − k)).
R, E, M, K, PRELOAD, G = 0.02, 0.004, 0.1, 5000.0, 50.0, 9.81
Y_FREE = R - E - PRELOAD / K


def lift_off_angle(rpm: float) -> float:
    w = rpm * 2 * math.pi / 60
    return math.asin((K * (R - Y_FREE) + M * G) / (E * (M * w * w - K)))


def jump_rpm() -> float:
    """The speed where min N = 0: N(90°) = 0."""
    w = math.sqrt((K * (R + E - Y_FREE) + M * G) / (M * E))
    return w * 60 / (2 * math.pi)


@pytest.fixture(scope="module")
def valve() -> camlink.Results:
    return camlink.load(VALVE).run()


def test_valve_jump_example_flies_and_lands(valve: camlink.Results) -> None:
    flights, impacts = valve.lift_off, valve.impacts
    assert list(flights.columns) == LIFT_OFF_COLUMNS
    assert list(impacts.columns) == IMPACT_COLUMNS
    assert impacts["closed"].dtype == np.bool_
    # The first flight starts at the closed-form lift-off angle (event
    # tolerance 1e-9 s at ω = 628 rad/s), is open at its end, and the
    # tappet comes to rest on the cam by the end of the first turn.
    first = flights.iloc[0]
    assert abs(first["start_cam_angle"] - lift_off_angle(6000)) < 1e-6
    assert first["end_time"] == impacts["time"].iloc[0]
    assert first["greatest_gap"] > 1e-3 and math.isnan(first["least_force"])
    assert impacts["closed"].iloc[-1]
    assert (impacts["approach_speed"] > 0).all()
    # A bounce leaves at e times the approach speed (e = 0.3).
    bounces = impacts[~impacts["closed"]]
    assert np.allclose(bounces["separation_speed"], 0.3 * bounces["approach_speed"], rtol=1e-6)
    # In flight the normal force is zero and the state 0; the gap is never
    # below the event tolerance's reach.
    state, n, gap = valve["bucket.state"], valve["bucket.normal_force"], valve["bucket.gap"]
    assert set(np.unique(state)) == {0.0, 1.0}
    assert np.all(n[state == 0] == 0.0) and np.all(gap[state == 1] == 0.0)
    assert gap.min() > -1e-8


def test_jump_plot_marks_flights_and_landings_at_their_cam_angles(
    valve: camlink.Results, tmp_path
) -> None:
    fig = jump_plot(valve, "bucket")
    (ax,) = fig.axes
    spans = [p for p in ax.patches if p.get_gid() == "flight"]
    assert len(spans) == len(valve.lift_off)
    theta0 = math.degrees(valve["cam.phi"][0])
    first = valve.lift_off.iloc[0]
    x0 = spans[0].get_x()  # type: ignore[attr-defined]
    assert abs(x0 - (math.degrees(first["start_cam_angle"]) - theta0)) < 1e-9
    (landing,) = [ln for ln in ax.lines if ln.get_gid() == "landing"]
    xs = np.asarray(landing.get_xdata(), dtype=float)
    ys = np.asarray(landing.get_ydata(), dtype=float)
    assert np.allclose(xs, np.degrees(valve.impacts["cam_angle"]) - theta0)
    # The dashed line is the cam's surface under the face, R + e sin θ
    # (mm, from the follower's lowest lift).
    (cam,) = [ln for ln in ax.lines if ln.get_gid() == "cam:bucket"]
    surface = 1e3 * (R + E * np.sin(valve["cam.phi"]) - valve["tappet.y"].min())
    assert np.allclose(cam.get_ydata(), surface, rtol=0, atol=1e-9)
    # The first landing's dot is drawn at its computed pixel: red there.
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    image = np.asarray(canvas.buffer_rgba())
    px, py = ax.transData.transform(np.array([xs[0], ys[0]]))
    r, g, b, _ = image[round(image.shape[0] - py), round(px)]
    assert r > 150 and g < 110 and b < 110, (r, g, b)
    fig.savefig(tmp_path / "jump.png")


def test_flight_summary_line_and_cli(valve: camlink.Results, tmp_path) -> None:
    line = flight_summary(valve)
    assert line is not None
    n_flights = len(valve.lift_off)
    assert line.startswith(f"bucket: {n_flights} flights (greatest gap ")
    assert f"{len(valve.impacts)} impacts" in line
    proc = run_cli("run", VALVE, "-o", tmp_path / "out.csv")
    assert proc.returncode == 0, proc.stderr
    assert f"  {line}" in proc.stdout.splitlines()


def test_no_flight_summary_without_unilateral_contacts() -> None:
    res = camlink.load(ROOT / "examples" / "cam_valve_spring.toml").run(
        analysis="dynamics", t_end=0.002
    )
    assert flight_summary(res) is None
    assert res.impacts.empty and list(res.impacts.columns) == IMPACT_COLUMNS


def test_jump_speed_brackets_the_closed_form() -> None:
    # Closed-form jump speed ≈ 4554 rpm: forward dynamics and the inverse
    # dynamics' prediction both first see lift-off at the first speed
    # above it.
    model = camlink.load(VALVE)
    speeds = [4000.0, 4400.0, 4700.0, 5000.0]
    j = jump_speed(model, "bucket", speeds, t_end=0.013)
    assert 4400 < jump_rpm() < 4700
    assert j.flies == (False, False, True, True)
    assert j.forward == 4700.0 and j.inverse == 4700.0


def test_jump_speed_errors_name_what_is_wrong() -> None:
    model = camlink.load(VALVE)
    with pytest.raises(camlink.ModelError, match="no parameter 'speed'"):
        jump_speed(model, "bucket", [1000.0], parameter="speed")
    with pytest.raises(camlink.ModelError, match="no joint named 'bucket2'"):
        jump_speed(model, "bucket2", [1000.0])


def test_builder_makes_a_unilateral_contact() -> None:
    # A ball of radius 0.1 m dropped from 0.2 m above a floor face on the
    # ground, e = 0.5: impact at √(2 h/g), approach √(2 g h).
    b = camlink.Mechanism("drop", gravity=(0.0, -G))
    b.body("ball", (0.0, 0.3), mass=1.0, inertia=0.004)
    b.curve("rim", "ball", "circle", centre=[0, 0], radius=0.1)
    b.joint("floor", "flat_follower", curve_i="rim", body_j="ground", axis=[1, 0],
            unilateral=True, restitution=0.5)
    res = b.build().simulate(t_end=0.3, step=1e-3)
    hit = res.impacts.iloc[0]
    assert abs(hit["time"] - math.sqrt(2 * 0.2 / G)) < 1e-8
    assert abs(hit["approach_speed"] - math.sqrt(2 * G * 0.2)) < 1e-7
    assert abs(hit["separation_speed"] - 0.5 * hit["approach_speed"]) < 1e-7


def test_bad_unilateral_settings_name_the_field(tmp_path) -> None:
    text = VALVE.read_text().replace("restitution = 0.3 ", "restitution = 1.5 ")
    with pytest.raises(camlink.ModelError, match=r"joints\[2\]\.restitution.*between 0 and 1"):
        camlink.loads(text)
    text = VALVE.read_text().replace("unilateral = true\n", "")
    with pytest.raises(camlink.ModelError, match=r"joints\[2\]\.restitution.*unilateral = true"):
        camlink.loads(text)


def test_adaptive_steps_are_refused_with_unilateral_contacts() -> None:
    with pytest.raises(camlink.AnalysisError, match=r"adaptive.*unilateral"):
        camlink.load(VALVE).simulate(t_end=0.001, adaptive=True)


def test_compliant_settings_name_the_field() -> None:
    base = VALVE.read_text()
    text = base.replace("event_tol = 1e-9 ", "event_tol = 1e-9\nstiffness = 1e8 ")
    with pytest.raises(camlink.ModelError, match=r"joints\[2\]\.restitution.*compliant"):
        camlink.loads(text)
    text = base.replace("restitution = 0.3 ", "damping = 0.1 ")
    with pytest.raises(camlink.ModelError, match=r"joints\[2\]\.damping.*stiffness"):
        camlink.loads(text)
    text = base.replace("restitution = 0.3 ", "stiffness = -1 ")
    with pytest.raises(camlink.ModelError, match=r"joints\[2\]\.stiffness.*> 0"):
        camlink.loads(text)
