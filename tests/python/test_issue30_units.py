"""Units: every channel's unit and quantity from the core (issue 28), model
files in mm and degrees, results written in mm and degrees, and the
questions asked of scales that look mistaken (issue 30)."""

from __future__ import annotations

import shutil
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import camlink
from camlink import Results
from camlink.warn import LoadWarning
from conftest import ROOT, run_cli

EXAMPLES = ROOT / "examples"
MM_DEG = ROOT / "crates" / "camlink-model" / "tests" / "units"


def _short(name: str, analysis: str) -> Results:
    return camlink.load(EXAMPLES / name).run(analysis=analysis, t_end=0.02, step=0.01)


def test_issue28_units_come_with_the_channels_from_the_core() -> None:
    cam = _short("cam_valve_jump.toml", "inverse_dynamics")
    assert cam.units["bucket.normal_force"] == "N"
    assert cam.quantities["bucket.normal_force"] == "force"
    assert cam.units["bucket.tangential_force"] == "N"
    gears = _short("gear_train.toml", "kinematics")
    assert gears.units["mesh12.theta"] == "rad"
    # A driver's effort by what it drives: an angle, a length.
    assert _short("four_bar.toml", "inverse_dynamics").units["motor.effort"] == "N·m"
    pushed = _short("slider_crank_slider_driven.toml", "inverse_dynamics")
    assert pushed.units["stroke.effort"] == "N"
    assert pushed.units["t"] == "s" and pushed.units["constraint.residual"] == "m or rad"


def test_issue30_results_in_mm_and_degrees(tmp_path: Path) -> None:
    res = _short("four_bar.toml", "inverse_dynamics")
    mm = res.in_units("mm,deg")
    assert mm.value_units == "mm,deg" and mm.mechanism is None
    assert mm.units["coupler.P.x"] == "mm" and mm.units["crank.omega"] == "deg/s"
    assert mm.units["coupler.P.ax"] == "mm/s²" and mm.units["motor.effort"] == "N·m"
    np.testing.assert_allclose(mm["coupler.P.x"], 1000 * res["coupler.P.x"], rtol=1e-15)
    np.testing.assert_allclose(mm["crank.omega"], np.degrees(res["crank.omega"]), rtol=1e-15)
    np.testing.assert_array_equal(mm["motor.effort"], res["motor.effort"])
    np.testing.assert_array_equal(mm.t, res.t)
    # Back to SI: the same numbers to 1e-12.
    back = mm.in_units("m,rad")
    np.testing.assert_allclose(back.data, res.data, rtol=1e-12, atol=1e-12)

    # A file in those units, plain for pandas, its units in the sidecar.
    path = res.save(tmp_path / "r.csv", units="mm,deg")
    frame = pd.read_csv(path)
    np.testing.assert_array_equal(frame.to_numpy(), mm.data)
    loaded = Results.load(path)
    assert loaded.value_units == "mm,deg" and loaded.units == mm.units
    assert loaded.quantities == res.quantities
    np.testing.assert_allclose(loaded.in_units("si").data, res.data, rtol=1e-12, atol=1e-12)
    # Parquet too.
    pq = Results.load(res.save(tmp_path / "r.parquet", units="mm"))
    assert pq.value_units == "mm,rad" and pq.units["crank.omega"] == "rad/s"

    with pytest.raises(camlink.ModelError, match="m, cm, mm, in"):
        res.in_units("furlong,deg")


def test_issue30_results_of_a_file_without_quantities_are_not_converted() -> None:
    old = Results(["t", "x"], np.zeros((2, 2)))
    with pytest.raises(camlink.ModelError, match="no recorded quantity"):
        old.in_units("mm,deg")


def test_issue30_camlink_run_writes_the_units_asked_for(tmp_path: Path) -> None:
    model = EXAMPLES / "four_bar.toml"
    proc = run_cli("run", model, "-o", tmp_path / "si.csv", "--t-end", "0.1", "--units", "m,rad")
    assert proc.returncode == 0, proc.stderr
    proc = run_cli("run", model, "-o", tmp_path / "mm.csv", "--t-end", "0.1", "--units", "mm,deg")
    assert proc.returncode == 0, proc.stderr
    si, mm = Results.load(tmp_path / "si.csv"), Results.load(tmp_path / "mm.csv")
    assert mm.units["rocker.B.y"] == "mm" and mm.units["rocker.phi"] == "deg"
    np.testing.assert_allclose(mm.in_units("si").data, si.data, rtol=1e-12, atol=1e-12)
    proc = run_cli("run", model, "-o", "-", "--t-end", "0.01", "--units", "mm")
    assert proc.returncode == 0, proc.stderr
    bad = run_cli("run", model, "-o", tmp_path / "x.csv", "--units", "mm,grad")
    assert bad.returncode == 2 and "--units: units 'mm,grad'" in bad.stderr


def test_issue30_an_example_written_in_mm_and_degrees_runs_as_its_si_version() -> None:
    si = camlink.load(EXAMPLES / "slider_crank.toml").run(t_end=0.05)
    mm = camlink.load(MM_DEG / "slider_crank_mm_deg.toml").run(t_end=0.05)
    assert mm.channels == si.channels and mm.units == si.units
    scale = np.maximum(1.0, np.abs(si.data).max(axis=0))
    assert np.all(np.abs(mm.data - si.data) <= 1e-12 * scale)


def test_issue30_a_cam_design_with_a_base_circle_metres_long_is_questioned(
    tmp_path: Path,
) -> None:
    from camlink.cam import design as cam_design

    # The packaging cam's base circle written in mm: 90 for 0.09.
    design = tmp_path / "packaging.toml"
    shutil.copy(EXAMPLES / "cam_design_packaging.toml", design)
    text = design.read_text().replace("base_radius = 0.09", "base_radius = 90", 1)
    design.write_text(text.replace("base_radius_search = [0.02, 0.2]", ""))
    with pytest.warns(LoadWarning, match=r"\[cam\] base_radius: a base circle of radius 90 m: "
                      r"is it 90 mm \(0.09 m\)\?"):
        cam_design.load(design)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        cam_design.load(EXAMPLES / "cam_design_packaging.toml")
