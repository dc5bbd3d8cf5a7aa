"""The dynamics examples (`examples/dyn_*.toml`) run their own analysis and
agree with an answer computed here independently: closed forms, or energy
computed from the bodies' masses and the kinematic channels."""

from __future__ import annotations

import math

import numpy as np

import camlink
from camlink.cam.jump import flight_summary
from conftest import ROOT

EXAMPLES = ROOT / "examples"


def load(name: str) -> camlink.Model:
    return camlink.load(EXAMPLES / name)


def zero_crossings(t: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Times where x crosses zero upwards, by linear interpolation."""
    k = np.nonzero((x[:-1] < 0) & (x[1:] >= 0))[0]
    return t[k] - x[k] * (t[k + 1] - t[k]) / (x[k + 1] - x[k])


def centroid_motion(model: camlink.Model, res: camlink.Results, body: str):
    """Velocity and acceleration of a body's centroid (global), from the
    frame's channels: r_c = r + A s'_c."""
    b = next(b for b in model.bodies if b["name"] == body)
    sx, sy = b["centroid"]
    phi, w, al = res[f"{body}.phi"], res[f"{body}.omega"], res[f"{body}.alpha"]
    cx = np.cos(phi) * sx - np.sin(phi) * sy  # A s'_c
    cy = np.sin(phi) * sx + np.cos(phi) * sy
    vx = res[f"{body}.vx"] - w * cy
    vy = res[f"{body}.vy"] + w * cx
    ax = res[f"{body}.ax"] - al * cy - w * w * cx
    ay = res[f"{body}.ay"] + al * cx - w * w * cy
    yc = res[f"{body}.y"] + cy
    return b, (vx, vy), (ax, ay), yc


def test_dyn_slider_crank_motor_torque_matches_power_balance():
    # "dyn_slider_crank.toml": τ ω = d(T + V)/dt, with T, V and their rates
    # computed from masses, inertias and the kinematic channels alone.
    model = load("dyn_slider_crank.toml")
    assert model.analysis_type == "inverse_dynamics"
    res = model.run()
    assert res.complete and res.summary["analysis"] == "inverse_dynamics"
    g = np.array(model.gravity)
    kinetic = np.zeros(len(res))
    rate = np.zeros(len(res))  # d(T + V_gravity + V_spring)/dt
    for name in ("crank", "rod", "slider"):
        b, (vx, vy), (ax, ay), _ = centroid_motion(model, res, name)
        m, J = b["mass"], b["inertia"]
        w, al = res[f"{name}.omega"], res[f"{name}.alpha"]
        kinetic += 0.5 * m * (vx * vx + vy * vy) + 0.5 * J * w * w
        # dT/dt = m v·a + J ω α;  dV_g/dt = −m g·v
        rate += m * (vx * ax + vy * ay) + J * w * al - m * (g[0] * vx + g[1] * vy)
    # Spring from the wall point W = (−0.2, 0) to the slider: k (l − l0) dl/dt.
    k, l0 = 400.0, 0.35
    length = res["slider.x"] + 0.2
    rate += k * (length - l0) * res["slider.vx"]

    power = res["motor.effort"] * res["crank.omega"]
    peak = np.max(np.abs(power))
    assert peak > 10.0  # the check is not vacuous
    err = np.max(np.abs(power - rate))
    assert err <= 1e-8 * peak, (err, peak)
    # The energy channel agrees with the kinetic energy computed here.
    assert np.max(np.abs(res["energy.kinetic"] - kinetic)) <= 1e-10 * np.max(kinetic)
    # And the pins of a planar revolute joint carry no torque.
    for j in ("O", "A", "B"):
        assert np.max(np.abs(res[f"{j}.torque"])) < 1e-9


def test_dyn_spring_pendulum_equilibrium_matches_closed_form():
    # "dyn_spring_pendulum.toml": k φ + m g l cos φ = 0, solved here by Newton.
    model = load("dyn_spring_pendulum.toml")
    res = model.run()
    assert len(res) == 1 and res.summary["analysis"] == "equilibrium"
    m, length, k, g = 1.0, 0.5, 20.0, 9.81
    phi = 0.0
    for _ in range(50):
        phi -= (k * phi + m * g * length * math.cos(phi)) / (k - m * g * length * math.sin(phi))
    assert abs(res["arm.phi"][0] - phi) < 1e-10, (res["arm.phi"][0], phi)
    assert abs(res["arm.tip.x"][0] - 2 * length * math.cos(phi)) < 1e-10
    # The pivot holds the weight: (0, m g) on the arm, (0, −m g) on the ground.
    assert abs(res["pivot.fx_j"][0]) < 1e-9
    assert abs(res["pivot.fy_j"][0] - m * g) < 1e-9
    assert abs(res["pivot.fy"][0] + m * g) < 1e-9
    assert abs(res["energy.kinetic"][0]) == 0.0


def test_dyn_pendulum_small_amplitude_period():
    # "dyn_pendulum.toml": a point mass on a massless rod, θ0 = 0.01 rad:
    # T = 2π √(L/g) (1 + θ0²/16 + …); the amplitude term is 6e-6, the
    # measured relative error 7.9e-6 (h = 1 ms).
    model = load("dyn_pendulum.toml")
    res = model.run()
    assert res.summary["analysis"] == "dynamics" and len(res) == 3001
    theta = res["arm.phi"] + math.pi / 2
    crossings = zero_crossings(res.t, theta)
    assert len(crossings) >= 2
    period = float(np.mean(np.diff(crossings)))
    L, g = 0.5, 9.81
    expected = 2 * math.pi * math.sqrt(L / g)
    assert abs(period - expected) / expected < 2e-5, (period, expected)
    # The amplitude stays the release angle (ρ∞ = 0.9 damps only frequencies
    # near 1/h, far above the pendulum's).
    assert abs(np.max(theta) - 0.01) < 1e-6


def test_dyn_incline_friction_slides_and_sticks():
    # "dyn_incline_friction.toml": μ = 0.3. The block on the 30° guide
    # slides at a = g (sin α − μ cos α) (2.357 m/s²), with the friction
    # μ m g cos α up the slope; the one on the 10° guide (below the
    # friction angle) is held by m g sin α and creeps at less than the
    # transition speed, 1e-4 m/s (docs/friction.md).
    model = load("dyn_incline_friction.toml")
    res = model.run()
    g, mu, m = 9.81, 0.3, 2.0
    steep, shallow = math.radians(30), math.radians(10)
    a = g * (math.sin(steep) - mu * math.cos(steep))
    along = res["slider.ax"] * math.cos(steep) + res["slider.ay"] * math.sin(steep)
    assert np.max(np.abs(along[1:] + a)) < 1e-6
    assert np.allclose(res["steep_guide.friction_force"][1:], mu * m * g * math.cos(steep))
    held = res["shallow_guide.friction_force"][10:]
    assert np.allclose(held, m * g * math.sin(shallow), rtol=1e-5)
    moved = math.hypot(res["sticker.x"][-1] - 0.6, res["sticker.y"][-1])
    assert moved < 1e-4 * res.t[-1]
    assert np.all(res["shallow_guide.friction_power"] <= 0)


def test_every_dyn_example_has_a_test():
    this = open(__file__, encoding="utf-8").read()
    names = sorted(p.name for p in EXAMPLES.glob("dyn_*.toml"))
    assert names
    for name in names:
        assert f'"{name}"' in this, f"{name} has no test in {__file__}"


def test_dyn_pendulum_stop_rebounds_with_the_closed_form_speed():
    # "dyn_pendulum_stop.toml": a uniform bar (L = 0.4 m) released from the
    # horizontal hits its stop at θ_s = −π/4. Energy: θ̇² = k sin(−θ),
    # k = 3g/L, so it arrives at v = √(k sin π/4) after
    # t₁ = ∫₀^{π/4} dψ/√(k sin ψ) (ψ = u²: a smooth integrand, Simpson's
    # rule here) and leaves at e v (e = 0.6), never passing the stop.
    model = load("dyn_pendulum_stop.toml")
    res = model.run()
    assert res.summary["analysis"] == "dynamics"
    L, g, e = 0.4, 9.81, 0.6
    k = 3 * g / L
    v = math.sqrt(k * math.sin(math.pi / 4))
    u = np.linspace(0.0, math.sqrt(math.pi / 4), 20001)
    f = np.full_like(u, 2 / math.sqrt(k))  # the limit at u = 0
    f[1:] = 2 * u[1:] / np.sqrt(k * np.sin(u[1:] ** 2))
    h = u[1] - u[0]
    t1 = h / 3 * (f[0] + f[-1] + 4 * f[1:-1:2].sum() + 2 * f[2:-1:2].sum())
    impacts = res.impacts
    first = impacts.iloc[0]
    assert first["joint"] == "pivot.lower"
    # h = 1 ms: measured 2.6e-7 s and 1.2e-6 (relative), the integrator's
    # O(h²) error.
    assert abs(first["time"] - t1) < 5e-7, (first["time"], t1)
    assert abs(first["approach_speed"] - v) < 2e-6 * v, (first["approach_speed"], v)
    assert abs(first["separation_speed"] - e * first["approach_speed"]) < 1e-9 * v
    # The bar stays above the stop and ends resting on it.
    assert res["bar.phi"].min() > -math.pi / 4 - 1e-9
    assert bool(impacts["closed"].iloc[-1])
    assert res["pivot.lower.state"][-1] == 1.0
    # The stop's gap is an angle, its push a torque.
    assert res.units["pivot.lower.gap"] == "rad"
    assert res.units["pivot.lower.moment"] == "N·m"
    # `camlink run`'s line on the impacts.
    line = flight_summary(res, model.joints)
    assert line is not None and line.startswith(f"pivot.lower: {len(impacts)} impacts")
    assert "rad/s), on its stop from t = " in line
