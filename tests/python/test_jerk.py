"""The jerk channels from Python (`Model.run(jerk=True)`) and the command
line (`camlink run --jerk`), on example files."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import numpy.typing as npt
import pytest

import camlink
from camlink import ModelError
from camlink.results import Results
from conftest import ROOT, run_cli

EXAMPLES = ROOT / "examples"


def _derivative(res: Results, name: str) -> npt.NDArray[np.float64]:
    """d/dt of a channel by fourth-order central differences (interior)."""
    y, h = res[name], res.t[1] - res.t[0]
    return (y[:-4] - 8 * y[1:-3] + 8 * y[3:-1] - y[4:]) / (12 * h)


def test_four_bar_jerk_is_the_derivative_of_the_acceleration() -> None:
    model = camlink.load(EXAMPLES / "four_bar.toml")
    res = model.run(t_end=1.0, step=1e-3, jerk=True)
    for body in ("crank", "coupler", "rocker"):
        for c in ("jx", "jy", "jphi"):
            assert f"{body}.{c}" in res.channels
    for point in ("coupler.P", "rocker.B"):
        assert f"{point}.jx" in res.channels and f"{point}.jy" in res.channels
    for jerk, acc in [
        ("rocker.jphi", "rocker.alpha"),
        ("coupler.jphi", "coupler.alpha"),
        ("coupler.jx", "coupler.ax"),
        ("coupler.P.jy", "coupler.P.ay"),
    ]:
        fd, exact = _derivative(res, acc), res[jerk][2:-2]
        scale = np.abs(exact).max()
        assert scale > 1.0, jerk
        assert np.abs(fd - exact).max() < 1e-6 * scale, jerk


def test_cam_follower_jerk_on_the_seed_cam() -> None:
    # Roller follower on the seed's lobed cam (an expression profile): the
    # follower's jerk inside the lobe against differences of its acceleration.
    model = camlink.load(EXAMPLES / "cam_seed_example_3_4_3.toml")
    res = model.run(step=5e-4, jerk=True)
    exact = res["follower.jy"][2:-2]
    fd = _derivative(res, "follower.ay")
    t = res.t[2:-2]
    # The cam turns once a second; the lobe is α ∈ (0, 2π/3), met away from
    # its ends (where ρ″ jumps and the jerk has a step).
    alpha = res["contact.alpha_i"][2:-2] % (2 * np.pi)
    inside = (alpha > 0.2) & (alpha < 2 * np.pi / 3 - 0.2)
    assert inside.sum() > 100
    scale = np.abs(exact[inside]).max()
    assert scale > 10.0
    err = np.abs(fd - exact)[inside]
    assert err.max() < 1e-5 * scale, t[inside][np.argmax(err)]


def test_jerk_only_when_asked_for_and_only_for_kinematics() -> None:
    model = camlink.load(EXAMPLES / "four_bar.toml")
    assert not any(c.endswith(".jphi") for c in model.run(t_end=0.1).channels)
    assert model.analysis["jerk"] is False
    with pytest.raises(ModelError, match="jerk"):
        model.run(t_end=0.1, jerk=True, analysis="inverse_dynamics")


def test_cli_run_with_jerk(tmp_path: Path) -> None:
    out = tmp_path / "fb.csv"
    proc = run_cli(
        "run",
        str(EXAMPLES / "four_bar.toml"),
        "-o",
        str(out),
        "--t-end",
        "0.2",
        "--jerk",
    )
    assert proc.returncode == 0, proc.stderr
    res = Results.load(out)
    assert "rocker.jphi" in res.channels and "coupler.P.jx" in res.channels
    proc = run_cli(
        "run", str(EXAMPLES / "four_bar.toml"), "-o", str(out), "--t-end", "0.2"
    )
    assert proc.returncode == 0, proc.stderr
    assert "rocker.jphi" not in Results.load(out).channels


def test_file_option_and_its_override(tmp_path: Path) -> None:
    text = (EXAMPLES / "four_bar.toml").read_text()
    path = tmp_path / "fb_jerk.toml"
    path.write_text(text.replace("step = 0.005", "step = 0.005\njerk = true"))
    model = camlink.load(path)
    assert model.analysis["jerk"] is True
    assert "rocker.jphi" in model.run(t_end=0.05).channels
    assert "rocker.jphi" not in model.run(t_end=0.05, jerk=False).channels
    out = tmp_path / "r.csv"
    proc = run_cli("run", str(path), "-o", str(out), "--t-end", "0.05", "--no-jerk")
    assert proc.returncode == 0, proc.stderr
    assert "rocker.jphi" not in Results.load(out).channels
