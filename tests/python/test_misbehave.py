"""Mechanisms that misbehave, from tests/models/misbehave: each model file
gives its documented diagnosis or message, its exit status, and keeps what
was computed before a failure."""

from __future__ import annotations

import pytest

from camlink.results import Results
from conftest import ROOT, run_cli

MODELS = ROOT / "tests" / "models" / "misbehave"


def clean(proc):
    assert "Traceback" not in proc.stderr, proc.stderr
    assert "panicked" not in proc.stderr, proc.stderr


def test_extra_revolute_is_named_redundant():
    proc = run_cli("check", MODELS / "redundant_revolute.toml")
    clean(proc)
    assert proc.returncode == 0, proc.stderr
    assert "O4_again.x = 1·O4.x" in proc.stdout
    assert "O4_again.y = 1·O4.y" in proc.stdout
    assert "rank of Φ_q 8" in proc.stdout and "degrees of freedom  1" in proc.stdout


def test_double_parallelogram_counts_zero_but_moves():
    proc = run_cli("check", MODELS / "double_parallelogram.toml")
    clean(proc)
    assert "coordinates  12" in proc.stdout and "equations    12" in proc.stdout
    assert "rank of Φ_q 11" in proc.stdout
    assert "redundant" in proc.stdout
    # The free motion turns the three cranks together.
    motion = next(line for line in proc.stdout.splitlines() if "free motion 1" in line)
    for crank in ("crank1.phi", "crank2.phi", "crank3.phi"):
        assert crank in motion


@pytest.mark.parametrize(
    ("name", "t_fail", "joints"),
    [
        ("crank_past_limit", 1.6494, ("B",)),
        ("slider_past_dead_centre", (0.4 - 0.34199) / 0.1, ("A", "B")),
    ],
)
def test_driver_past_reach_stops_with_time_joints_and_residual(name, t_fail, joints, tmp_path):
    out = tmp_path / f"{name}.parquet"
    proc = run_cli("run", MODELS / f"{name}.toml", "-o", out)
    clean(proc)
    assert proc.returncode == 1, proc.stderr
    err = proc.stderr
    time = float(err.split("at t = ")[1].split(" s")[0])
    assert abs(time - t_fail) < 0.01, err
    for j in joints:
        assert f"'{j}'" in err, err
    assert "largest residual" in err and "condition of Φ_q" in err
    # The partial file is complete and valid up to the failure; the output
    # name holds no failed run.
    assert not out.exists()
    res = Results.load(out.with_name(f"{name}.partial.parquet"))
    assert len(res) > 10
    assert res.t[-1] < time <= res.t[-1] + 0.01 + 1e-12


def test_change_point_passes_with_a_warning(tmp_path):
    out = tmp_path / "p.csv"
    proc = run_cli("run", MODELS / "parallelogram_change_point.toml", "-o", out)
    clean(proc)
    assert proc.returncode == 0, proc.stderr
    assert "near-singular configuration" in proc.stderr
    t_warn = float(proc.stderr.split("warning: at t = ")[1].split(" s")[0])
    assert abs(t_warn - (3.141592653589793 - 2.0) / 2.0) < 0.01
    res = Results.load(out)
    # No branch flip: the rocker stays parallel to the crank throughout.
    assert max(abs(res["crank.phi"] - res["rocker.phi"])) < 1e-8
