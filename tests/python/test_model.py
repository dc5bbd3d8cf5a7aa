"""Loading models and running kinematics through the Python API."""

from __future__ import annotations

import math

import numpy as np
import pytest

import camlink
from conftest import STUCK_FOUR_BAR, STUCK_TIME, four_bar_toml


def test_load_reads_bodies_joints_and_analysis(four_bar_file):
    model = camlink.load(four_bar_file)
    assert model.name == "four_bar"
    assert [b["name"] for b in model.bodies] == ["crank", "coupler", "rocker"]
    assert model.bodies[1]["points"]["P"] == pytest.approx([1.3, 0.5])
    assert [j["name"] for j in model.joints] == ["O", "A", "B", "C", "motor"]
    assert model.joints[-1]["driver"] is True
    assert model.analysis["t_end"] == 1.0
    assert model.analysis["points"] == ["coupler.P", "crank.A"]


def test_check_counts_a_fully_driven_four_bar(four_bar_file):
    report = camlink.load(four_bar_file).check()
    assert report["bodies"] == 3
    assert report["coordinates"] == 9
    assert report["equations"] == 9
    assert report["dof"] == 0
    assert report["redundant"] == []
    kinds = {j["name"]: (j["kind"], j["equations"]) for j in report["joints"]}
    assert kinds["O"] == ("revolute", 2)
    assert kinds["motor"][1] == 1


def test_run_uses_the_file_analysis_by_default(four_bar_file):
    res = camlink.load(four_bar_file).run()
    assert len(res) == 101
    assert res.t[0] == 0.0 and res.t[-1] == pytest.approx(1.0)
    assert res.complete


def test_run_follows_the_driver_and_closes_the_loop(four_bar_file):
    res = camlink.load(four_bar_file).run(t_end=0.5, step=0.005)
    phi = res["crank.phi"]
    assert phi == pytest.approx(math.radians(60) + 2 * math.pi * res.t, abs=1e-9)
    assert res["crank.omega"] == pytest.approx(np.full_like(res.t, 2 * math.pi))
    # Crank pin A is at r (cos φ, sin φ), and the rocker tip stays on the coupler.
    assert res["crank.A.x"] == pytest.approx(np.cos(phi), abs=1e-9)
    assert res["crank.A.y"] == pytest.approx(np.sin(phi), abs=1e-9)
    bx = res["rocker.x"] + 2.5 * np.cos(res["rocker.phi"])
    by = res["rocker.y"] + 2.5 * np.sin(res["rocker.phi"])
    cx = res["coupler.x"] + 2.6 * np.cos(res["coupler.phi"])
    cy = res["coupler.y"] + 2.6 * np.sin(res["coupler.phi"])
    assert bx == pytest.approx(cx, abs=1e-8)
    assert by == pytest.approx(cy, abs=1e-8)
    # Velocities agree with the derivative of the positions.
    h = res.t[1] - res.t[0]
    v_fd = np.gradient(res["coupler.P.x"], h)[1:-1]
    assert v_fd == pytest.approx(res["coupler.P.vx"][1:-1], rel=1e-3, abs=1e-3)
    a_fd = np.gradient(res["rocker.omega"], h)[1:-1]
    assert a_fd == pytest.approx(res["rocker.alpha"][1:-1], rel=2e-3, abs=2e-2)


def test_run_with_explicit_times_and_points(four_bar_file):
    model = camlink.load(four_bar_file)
    res = model.run(times=[0.0, 0.1, 0.25], points=["rocker.B"])
    assert list(res.t) == [0.0, 0.1, 0.25]
    assert "rocker.B.ax" in res.channels
    assert "coupler.P.x" not in res.channels


def test_channel_order_bodies_then_points(four_bar_file):
    res = camlink.load(four_bar_file).run(t_end=0.02)
    assert res.channels[:9] == [
        f"crank.{c}" for c in ("x", "y", "phi", "vx", "vy", "omega", "ax", "ay", "alpha")
    ]
    assert res.channels[27:33] == [
        f"coupler.P.{c}" for c in ("x", "y", "vx", "vy", "ax", "ay")
    ]


@pytest.mark.parametrize(
    "kwargs, fragment",
    [
        (dict(t_end=1.0, step=0.0), "step"),
        (dict(t_end=-1.0, step=0.1), "t_end must be"),
        (dict(times=[0.0, 0.2, 0.1]), "^times must increase, but 0.1 follows 0.2$"),
        (dict(times=[0.0, float("nan")]), "^times must be finite numbers$"),
        (dict(times=[]), "non-empty"),
        (dict(points=["coupler.Q"]), "no point 'Q'"),
        (dict(points=["nobody.P"]), "no body named 'nobody'"),
        (dict(output="results.xlsx"), "unknown file type"),
    ],
)
def test_bad_run_arguments_raise_model_error(four_bar_file, kwargs, fragment):
    with pytest.raises(camlink.ModelError, match=fragment):
        camlink.load(four_bar_file).run(**kwargs)


def test_model_error_is_a_value_error():
    assert issubclass(camlink.ModelError, ValueError)
    assert issubclass(camlink.AnalysisError, RuntimeError)


def test_missing_file_is_file_not_found(tmp_path):
    with pytest.raises(FileNotFoundError):
        camlink.load(tmp_path / "nope.toml")


def test_bad_text_names_source_line_and_field():
    text = four_bar_toml().replace('body_i = "crank"', 'body_i = "crnak"')
    with pytest.raises(camlink.ModelError) as e:
        camlink.loads(text, "toml", "mine.toml")
    msg = str(e.value)
    assert "mine.toml:" in msg and "crnak" in msg and "crank" in msg


def test_analysis_error_keeps_partial_results(stuck_file):
    model = camlink.load(stuck_file)
    with pytest.raises(camlink.AnalysisError) as e:
        model.run(t_end=0.5, step=0.01)
    err = e.value
    assert 0.1 < err.time <= STUCK_TIME + 0.02
    assert err.residual >= 0
    assert isinstance(err.joints, list)
    partial = err.results
    assert not partial.complete
    assert 5 < len(partial) < 50
    assert partial.t[-1] < err.time
    assert err.data is not None and err.data.shape == (len(partial), len(err.names))
    assert partial["crank.phi"] == pytest.approx(math.radians(60) + 2 * math.pi * partial.t)
    assert STUCK_FOUR_BAR["L"] == 2.6


def test_run_summary_counts_steps_and_reports_assembly_moves():
    from conftest import ROOT

    res = camlink.load(ROOT / "tests" / "models" / "four_bar.toml").run()
    s = res.summary
    assert s["steps"] == len(res)
    assert s["newton_iterations"] >= s["steps"] - 1
    assert isinstance(s["warnings"], list)
    # The file places the coupler and rocker roughly; assembly moves them.
    moved = dict(s["assembly_moves"])
    assert set(moved) <= {"crank", "coupler", "rocker"}
    assert "rocker" in moved or "coupler" in moved
