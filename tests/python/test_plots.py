"""Plots: channels with units, overlays, reactions, SVAJ and pressure angle."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import camlink
from camlink.viz.plots import plot, pressure_angle, reactions, svaj, svaj_data

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


def test_units_are_those_the_core_states() -> None:
    res = camlink.load(EXAMPLES / "four_bar.toml").inverse_dynamics(t_end=0.02, step=0.01)
    units = res.units
    assert units["crank.omega"] == "rad/s" and units["coupler.P.ax"] == "m/s²"
    assert units["O2.fx_j"] == "N" and units["motor.effort"] == "N·m"


def test_channels_overlays_and_xy(tmp_path: Path) -> None:
    model = camlink.load(EXAMPLES / "four_bar.toml")
    fast, slow = model.run(), model.run(t_end=1.0, step=0.01)
    fig = fast.plot("crank.omega")
    (ax,) = fig.axes
    assert ax.get_xlabel() == "t (s)" and ax.get_ylabel() == "crank.omega (rad/s)"
    assert np.array_equal(ax.lines[0].get_ydata(), fast["crank.omega"])
    fig = plot([fast, slow], ["rocker.phi", "coupler.phi"], labels=["2 s", "1 s"])
    ax = fig.axes[0]
    legend = ax.get_legend()
    assert legend is not None
    assert [t.get_text() for t in legend.get_texts()] == [
        "2 s, rocker.phi", "2 s, coupler.phi", "1 s, rocker.phi", "1 s, coupler.phi"]
    assert ax.get_ylabel() == "(rad)"
    fig = fast.plot("coupler.P.y", x="coupler.P.x")
    ax = fig.axes[0]
    assert ax.get_xlabel() == "coupler.P.x (m)"
    assert np.array_equal(ax.lines[0].get_xdata(), fast["coupler.P.x"])
    fig.savefig(tmp_path / "coupler_curve.png")
    with pytest.raises(camlink.ModelError, match="2 labels for 1 runs"):
        plot(fast, "crank.phi", labels=["a", "b"])
    with pytest.raises(KeyError, match=r"crank\.omega"):
        plot(fast, "crank.omegaa")


def test_reactions_are_the_joint_channels() -> None:
    res = camlink.load(EXAMPLES / "slider_crank.toml").inverse_dynamics()
    fig = reactions(res, "A")
    ax = fig.axes[0]
    assert np.array_equal(ax.lines[0].get_ydata(), res["A.fx"])
    assert np.array_equal(ax.lines[1].get_ydata(), res["A.fy"])
    with pytest.raises(camlink.ModelError, match="no reaction channels"):
        reactions(camlink.load(EXAMPLES / "slider_crank.toml").kinematics(), "A")


def test_svaj_velocity_is_the_derivative_of_the_lift(tmp_path: Path) -> None:
    res = camlink.load(EXAMPLES / "cam_seed_example_3_4_3.toml").run()
    d = svaj_data(res)
    assert d.joint == "contact" and d.units[0] == "m"
    # The cam turns once: θ from 0 to 360°.
    assert d.angle[0] == pytest.approx(0.0) and d.angle[-1] == pytest.approx(360.0)
    assert d.s.min() == 0.0
    fig = svaj(res)
    assert fig.axes[-1].get_xlabel() == "cam angle θ (deg)"
    (line,) = (ln for ln in fig.axes[1].lines if ln.get_gid() == "svaj:V")
    assert np.array_equal(line.get_ydata(), d.v)
    fig.savefig(tmp_path / "svaj.png")
    # A smooth cam (two harmonics) under an oscillating roller follower.
    res = camlink.load(EXAMPLES / "cam_oscillating_roller.toml").run()
    d = svaj_data(res)
    assert d.units == ("rad", "rad/s", "rad/s²", "rad/s³")
    t = res.t
    h = float(t[1] - t[0])
    fd = np.gradient(d.s, t)[1:-1]
    # Central differences err by h²/6 s‴ + O(h⁴), s‴ = dA/dt (from A): what
    # is left after that leading term is a few per cent of it.
    lead = h * h / 6 * np.gradient(d.a, t)[1:-1]
    bound = 0.05 * np.abs(lead).max()
    assert np.max(np.abs(fd - d.v[1:-1] - lead)) < bound
    # A wrong V (here the velocity a step late) is far outside the bound.
    assert np.max(np.abs(fd - np.roll(d.v, 1)[1:-1])) > 10 * bound


def test_svaj_of_the_eccentric_cam_is_harmonic() -> None:
    res = camlink.load(EXAMPLES / "cam_eccentric_flat.toml").run()
    d = svaj_data(res)
    e, w = 0.01, 2 * np.pi * 600 / 60
    theta = np.radians(d.angle)
    assert np.allclose(d.s, e * np.sin(theta) + e - (e * np.sin(theta) + e).min(), atol=1e-12)
    assert np.allclose(d.v, e * w * np.cos(theta), atol=1e-10)
    assert np.allclose(d.a, -e * w * w * np.sin(theta), atol=1e-7)


def test_pressure_angle_in_degrees() -> None:
    res = camlink.load(EXAMPLES / "cam_seed_example_3_4_3.toml").run()
    fig = pressure_angle(res)
    ax = fig.axes[0]
    assert np.allclose(ax.lines[0].get_ydata(), np.degrees(res["contact.pressure_angle"]))
    assert ax.get_ylabel() == "pressure angle (deg)"
    with pytest.raises(camlink.ModelError, match="no cam contact named 'x'"):
        svaj_data(res, "x")


def test_svaj_jerk_of_the_eccentric_cam_is_the_closed_form(tmp_path: Path) -> None:
    res = camlink.load(EXAMPLES / "cam_eccentric_flat.toml").run(jerk=True)
    d = svaj_data(res)
    e, w = 0.01, 2 * np.pi * 600 / 60
    theta = np.radians(d.angle)
    assert d.j is not None and d.units[3] == "m/s³"
    # y = R + e sin θ, θ = ω t: the jerk is −e ω³ cos θ (about 2.5e3 m/s³).
    assert np.allclose(d.j, -e * w**3 * np.cos(theta), rtol=0, atol=1e-6 * e * w**3)
    fig = svaj(res)
    (line,) = (ln for ln in fig.axes[3].lines if ln.get_gid() == "svaj:J")
    assert np.array_equal(line.get_ydata(), d.j)
    fig.savefig(tmp_path / "svaj_jerk.png")


def test_svaj_without_jerk_channels_says_how_to_get_them() -> None:
    res = camlink.load(EXAMPLES / "cam_eccentric_flat.toml").run()
    assert svaj_data(res).j is None
    fig = svaj(res)
    assert "jerk=True" in fig.axes[3].texts[0].get_text()
