"""The dynamic analyses from Python: choosing the analysis, settings that do
not fit it, energy conservation, the Python force callback, design checks,
follower lift-off as data."""

from __future__ import annotations

import math

import numpy as np
import pytest

import camlink
from camlink.results import LIFT_OFF_COLUMNS
from conftest import ROOT

EXAMPLES = ROOT / "examples"

DOUBLE_PENDULUM = """
[model]
name = "double pendulum"
gravity = [0, -9.81]

[[bodies]]
name = "upper"
angle = 0                   # released from the horizontal
mass = 1.0
inertia = 0.02
centroid = [0.25, 0]
points = { O = [0, 0], E = [0.5, 0] }

[[bodies]]
name = "lower"
position = [0.5, 0]
angle = 0.5
mass = 0.7
inertia = 0.01
centroid = [0.2, 0]
points = { E = [0, 0] }

[[joints]]
name = "shoulder"
type = "revolute"
body_i = "ground"
body_j = "upper"
point_j = "O"

[[joints]]
name = "elbow"
type = "revolute"
body_i = "upper"
point_i = "E"
body_j = "lower"
point_j = "E"

[analysis]
type = "dynamics"
t_end = 2.0
step = 0.01
"""


def pendulum(theta0: float = 0.01) -> camlink.Model:
    text = (EXAMPLES / "dyn_pendulum.toml").read_text()
    text = text.replace("theta0 = 0.01 ", f"theta0 = {theta0} ")
    return camlink.loads(text, "toml", "pendulum.toml")


def test_run_follows_the_file_and_analysis_overrides_it():
    model = camlink.load(EXAMPLES / "dyn_slider_crank.toml")
    assert model.analysis_type == "inverse_dynamics"
    res = model.run(t_end=0.1)
    assert "motor.effort" in res and len(res) == 101
    kin = model.run(t_end=0.1, analysis="kinematics")
    assert "motor.effort" not in kin and kin.summary["analysis"] == "kinematics"
    np.testing.assert_array_equal(kin["slider.x"], res["slider.x"])
    same = model.inverse_dynamics(t_end=0.1)
    np.testing.assert_array_equal(same.data, res.data)


def test_settings_that_do_not_fit_the_analysis_are_model_errors():
    model = camlink.load(EXAMPLES / "dyn_slider_crank.toml")
    with pytest.raises(camlink.ModelError, match="`rho_inf` does not apply to the kinematics"):
        model.run(analysis="kinematics", rho_inf=0.5)
    with pytest.raises(camlink.ModelError) as info:
        model.run(analysis="equilibrium", t_end=1.0)
    assert str(info.value) == (
        "`t_end` does not apply to the equilibrium analysis "
        "(it is a setting of kinematics, inverse_dynamics and dynamics)"
    )
    with pytest.raises(camlink.ModelError, match="unknown analysis 'statics'"):
        model.run(analysis="statics")
    # The core's rule and message, as for a file's [analysis].
    with pytest.raises(camlink.ModelError, match="`atol` sets the error control: it needs adaptive = true"):
        pendulum().simulate(atol=1e-6)
    with pytest.raises(camlink.ModelError, match="`h_min` sets the error control"):
        pendulum().run(h_min=1e-9)
    with pytest.raises(camlink.ModelError, match="rho_inf must be between 0 and 1"):
        pendulum().simulate(rho_inf=2.0)


def test_inverse_dynamics_of_a_free_mechanism_is_an_analysis_error():
    with pytest.raises(camlink.AnalysisError) as info:
        pendulum().inverse_dynamics(t_end=0.1)
    assert info.value.kind == "not_driven"
    assert info.value.results.complete is False


def test_energy_of_an_undamped_double_pendulum_is_conserved():
    # Released from the horizontal, chaotic; ρ∞ = 0.9, h = 1 ms. The
    # largest |E − E0| is held to 5e-5 of the peak kinetic energy (measured
    # 1.8e-5 at h = 1 ms, 4.5e-6 at 0.5 ms), |Φ| to 1e-9 m (measured 7e-11)
    # and |Φ_q q̇ − ν| to 1e-4 rad/s (2.7e-5: Newton's tolerance on q̇).
    model = camlink.loads(DOUBLE_PENDULUM, "toml", "double.toml")
    res = model.simulate(rho_inf=0.9)
    assert res.complete and len(res) == 201
    s = res.summary
    peak = float(np.max(res["energy.kinetic"]))
    assert peak > 1.0
    assert s["energy_drift"] <= 5e-5 * peak, (s["energy_drift"], peak)
    assert s["constraint_drift"] < 1e-9 and s["velocity_drift"] < 1e-4, s
    # Halving h shrinks the energy error (second order: about four times).
    fine = model.simulate(rho_inf=0.9, h=5e-4)
    assert fine.summary["energy_drift"] < 0.5 * s["energy_drift"]


def test_large_swing_pendulum_energy_and_adaptive_steps():
    model = pendulum(theta0=1.2)
    fixed = model.simulate(t_end=2.0, step=0.01, h=2.5e-4)
    # Measured: 6.7e-8 of the peak kinetic energy.
    drift = fixed.summary["energy_drift"] / np.max(fixed["energy.kinetic"])
    assert drift < 1e-6, drift
    adaptive = model.simulate(t_end=2.0, step=0.01, h=0.01, adaptive=True, atol=1e-7)
    assert adaptive.summary["steps"] < fixed.summary["steps"]
    # Measured: 876 steps instead of 8,000, 9.3e-5 rad apart.
    assert np.max(np.abs(adaptive["arm.phi"] - fixed["arm.phi"])) < 3e-4


def test_python_force_matches_the_same_damper_in_the_file():
    # A viscous torque −c ω on the arm, once as an RSDA from the file and
    # once as a Python function.
    c = 0.05
    text = (EXAMPLES / "dyn_pendulum.toml").read_text().replace(
        "theta0 = 0.01 ", "theta0 = 0.5 "
    )
    damper = f"""
[[forces]]
type = "rsda"
body_i = "ground"
body_j = "arm"
damping = {c}
"""
    in_file = camlink.loads(text + damper, "toml", "damped.toml").simulate(t_end=1.0)
    calls = []

    def torque(t, q, qd):
        calls.append(t)
        return (0.0, 0.0, -c * qd[2])

    model = camlink.loads(text, "toml", "free.toml").with_force("damper", "arm", torque)
    assert [f["kind"] for f in model.forces] == ["callback"]
    in_python = model.simulate(t_end=1.0)
    assert len(calls) >= 1000
    np.testing.assert_allclose(in_python["arm.phi"], in_file["arm.phi"], atol=1e-9)
    # It damps: the energy falls.
    e = in_python["energy.total"]
    assert e[-1] < e[0] - 1e-3


def test_an_exception_in_a_python_force_stops_the_run():
    def broken(t, q, qd):
        if t > 0.05:
            raise ZeroDivisionError("broken force")
        return (0.0, 0.0, 0.0)

    model = pendulum().with_force("broken", "arm", broken)
    with pytest.raises(camlink.AnalysisError, match="force 'broken' failed") as info:
        model.simulate(t_end=0.2)
    assert info.value.kind == "force_failed"
    assert isinstance(info.value.__cause__, ZeroDivisionError)
    bad = pendulum().with_force("bad", "arm", lambda t, q, qd: (1.0, 2.0))
    with pytest.raises(camlink.AnalysisError, match="must return three numbers") as info:
        bad.simulate(t_end=0.01)
    assert isinstance(info.value.__cause__, camlink.ModelError)
    with pytest.raises(camlink.ModelError, match="no moving body named 'ground'"):
        pendulum().with_force("f", "ground", broken)
    with pytest.raises(camlink.ModelError, match="must be callable"):
        pendulum().with_force("f", "arm", 3.0)  # type: ignore[arg-type]


def test_equilibrium_at_a_time_and_output_file(tmp_path):
    model = camlink.load(EXAMPLES / "dyn_spring_pendulum.toml")
    out = tmp_path / "eq.csv"
    res = model.equilibrium(time=2.0, output=out)
    assert res.t.tolist() == [2.0]
    back = camlink.Results.load(out)
    assert back.channels == res.channels and len(back) == 1


def flat_follower_on_the_seed_cam() -> str:
    """The seed example with a flat-faced follower on its concave lobe."""
    text = (EXAMPLES / "cam_seed_example_3_4_3.toml").read_text()
    flat = text.replace(
        'type = "cam_follower"\nname = "contact"\ncurve_i = "lobe"\ncurve_j = "roller"',
        'type = "flat_follower"\nname = "contact"\ncurve_i = "lobe"\nbody_j = "follower"\n'
        "axis = [1, 0]",
    )
    assert flat != text
    return flat


def test_design_check_of_a_flat_follower_on_a_concave_cam():
    flat = flat_follower_on_the_seed_cam()
    findings = camlink.loads(flat, "toml", "flat.toml").design_check()
    assert len(findings) == 1
    f = findings[0]
    assert f["severity"] == "warning" and f["joint"] == "contact"
    assert "concave" in f["message"] and f["text"].startswith("warning: joint 'contact'")
    assert camlink.load(EXAMPLES / "cam_seed_example_3_4_3.toml").design_check() == []


def test_small_amplitude_period_of_a_compound_pendulum_from_python():
    # The same pendulum with inertia J' about the centroid:
    # T = 2π √((J' + m L²)/(m g L)).
    text = (EXAMPLES / "dyn_pendulum.toml").read_text().replace(
        "inertia = 0.0 ", "inertia = 0.02 "
    )
    res = camlink.loads(text, "toml", "compound.toml").run()
    theta = res["arm.phi"] + math.pi / 2
    k = np.nonzero((theta[:-1] < 0) & (theta[1:] >= 0))[0]
    t0 = res.t[k] - theta[k] * (res.t[k + 1] - res.t[k]) / (theta[k + 1] - theta[k])
    period = float(np.mean(np.diff(t0)))
    expected = 2 * math.pi * math.sqrt((0.02 + 0.25) / (9.81 * 0.5))
    assert abs(period / expected - 1) < 2e-5


def test_mechanism_builder_with_forces_and_a_dynamic_analysis():
    m = camlink.Mechanism("sprung arm", gravity=(0, -9.81))
    m.body("arm", mass=1.0, inertia=0.02, centroid=(0.5, 0), points={"O": (0, 0)})
    m.revolute("pivot", "ground", (0, 0), "arm", "O")
    m.force("rsda", name="spring", body_i="ground", body_j="arm", stiffness=20, free_angle=0)
    m.analysis(type="equilibrium", time=0.0)
    assert 'type = "rsda"' in m.to_toml() and 'type = "equilibrium"' in m.to_toml()
    eq = m.run()
    phi = eq["arm.phi"][0]
    assert abs(20 * phi + 9.81 * 0.5 * math.cos(phi)) < 1e-9
    m.analysis(type="dynamics", t_end=0.5, step=0.01, rho_inf=0.9)
    m.python_force("push", "arm", lambda t, q, qd: (0.0, 0.0, 1.0))
    model = m.build()
    assert model.analysis["rho_inf"] == 0.9
    assert [f["name"] for f in model.forces] == ["spring", "push"]
    assert len(model.run()) == 51


# The spring-loaded valve follower of "cam_valve_spring.toml" and its closed
# form (docs/dynamics.md, "When does the valve jump?"): N(θ) = k (R − y_f)
# + m g + (k e − m e ω²) sin θ, negative around full lift (θ = 90°) above
# ω_jump = √((k (R + e − y_f) + m g) / (m e)).
VALVE = EXAMPLES / "cam_valve_spring.toml"
R, E, M, K, PRELOAD, G = 0.02, 0.004, 0.1, 5000.0, 50.0, 9.81
Y_FREE = R - E - PRELOAD / K
OMEGA_JUMP = math.sqrt((K * (R + E - Y_FREE) + M * G) / (M * E))
#: Output steps per camshaft turn: θ on every ½°.
STEPS_PER_TURN = 720


def valve_turn(omega: float, turns: float = 1.0) -> camlink.Results:
    """Inverse dynamics of the valve example at camshaft speed ω (rad/s)."""
    text = VALVE.read_text()
    assert text.count("rpm = 3000 ") == 1
    rpm = omega * 60 / (2 * math.pi)
    model = camlink.loads(text.replace("rpm = 3000 ", f"rpm = {rpm!r} "), "toml", str(VALVE))
    steps = round(STEPS_PER_TURN * turns)
    return model.inverse_dynamics(times=np.linspace(0.0, turns * 2 * math.pi / omega, steps + 1))


def lift_off_warnings(res: camlink.Results) -> list[tuple[float, str]]:
    return [(w.time, w.message) for w in res.summary["warnings"] if w.kind == "lift_off"]


def test_valve_lift_off_above_the_jump_speed_brackets_full_lift():
    w = 1.01 * OMEGA_JUMP
    res = valve_turn(w)
    frame = res.lift_off
    assert list(frame.columns) == LIFT_OFF_COLUMNS
    assert len(frame) == 1, res.summary["warnings"]
    row = frame.iloc[0]
    assert (row["joint"], row["cam"]) == ("bucket", "cam")
    # Closed form: N(θ) = 0 at sin θ = (k (R − y_f) + m g) / (m e ω² − k e).
    th0 = math.asin((K * (R - Y_FREE) + M * G) / (M * E * w * w - K * E))
    th1 = math.pi - th0
    half_step = math.pi / STEPS_PER_TURN
    assert row["start_cam_angle"] < math.pi / 2 < row["end_cam_angle"]
    assert abs(row["start_cam_angle"] - th0) < half_step, (row["start_cam_angle"], th0)
    assert abs(row["end_cam_angle"] - th1) < half_step, (row["end_cam_angle"], th1)
    # The cam turns at ω from θ = 0 at t = 0.
    assert abs(row["start_time"] - th0 / w) < half_step / w
    assert abs(row["end_time"] - th1 / w) < half_step / w
    # The least force is at full lift, N(90°).
    assert abs(row["least_cam_angle"] - math.pi / 2) < 1e-9
    assert abs(row["least_time"] - math.pi / 2 / w) < 1e-12
    n90 = K * (R + E - Y_FREE) + M * G - M * E * w * w
    assert n90 < 0
    assert abs(row["least_force"] - n90) < 1e-8 * K * E, (row["least_force"], n90)
    # The same interval is the run's lift-off warning, at its start time.
    warnings = lift_off_warnings(res)
    assert len(warnings) == 1 and warnings[0][0] == row["start_time"]
    assert res.summary["lift_off"][0]["end_time"] == row["end_time"]


def test_valve_lift_off_open_at_the_end_of_the_run():
    # A quarter turn, ending at full lift: inside the interval.
    res = valve_turn(1.01 * OMEGA_JUMP, turns=0.25)
    frame = res.lift_off
    assert len(frame) == 1
    assert frame["start_cam_angle"].iloc[0] < math.pi / 2
    assert np.isnan(frame["end_time"].iloc[0]) and np.isnan(frame["end_cam_angle"].iloc[0])
    record = res.summary["lift_off"][0]
    assert record["end_time"] is None and record["end_cam_angle"] is None
    assert "to the end of the run" in lift_off_warnings(res)[0][1]


def test_valve_stays_on_the_cam_below_the_jump_speed():
    res = valve_turn(0.99 * OMEGA_JUMP)
    assert np.min(res["bucket.normal_force"]) > 0
    frame = res.lift_off
    assert frame.empty and list(frame.columns) == LIFT_OFF_COLUMNS
    assert res.summary["lift_off"] == [] and lift_off_warnings(res) == []
