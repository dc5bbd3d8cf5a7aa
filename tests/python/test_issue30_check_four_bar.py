"""`camlink check` names a four-bar's Grashof class and the range of its
transmission angle (issue 30)."""

from __future__ import annotations

import json

import numpy as np

import camlink
from camlink.cli import main
from camlink.viz import fourbar
from conftest import ROOT

FOUR_BAR = ROOT / "examples" / "four_bar.toml"


def test_issue30_check_reports_grashof_and_transmission_range(capsys) -> None:
    assert main(["check", str(FOUR_BAR)]) == 0
    out = capsys.readouterr().out
    assert "Grashof class: crank-rocker" in out
    assert "ground 0.4 m, crank 0.12 m, coupler 0.38 m, rocker 0.3 m" in out
    assert "transmission angle μ from 46.83° to 99.08°" in out

    assert main(["check", str(FOUR_BAR), "--json"]) == 0
    loop = json.loads(capsys.readouterr().out)["four_bar"]
    assert loop["grashof"] == "crank-rocker"
    assert (loop["crank"], loop["coupler"], loop["rocker"]) == ("crank", "coupler", "rocker")


def test_issue30_transmission_range_equals_the_motion_over_a_turn() -> None:
    # Independently: each body's frame runs along its link, so μ is the
    # angle between the coupler's and the rocker's x axes, read from a run
    # over one crank turn (w = 2π rad/s, so 1 s) at 0.05° of crank steps.
    model = camlink.load(FOUR_BAR)
    loop = fourbar.summary(model)
    assert loop is not None
    mu_range = loop["transmission"]
    assert isinstance(mu_range, list)
    lo, hi = float(mu_range[0]), float(mu_range[1])
    res = model.kinematics(times=np.linspace(0.0, 1.0, 7201))
    mu = np.arccos(np.cos(res["rocker.phi"] - res["coupler.phi"]))
    assert abs(mu.min() - lo) < 1e-6 and abs(mu.max() - hi) < 1e-6, (mu.min(), lo, mu.max(), hi)
    assert lo - 1e-12 <= mu.min() and mu.max() <= hi + 1e-12


def test_issue30_check_of_a_model_that_is_not_a_four_bar(capsys) -> None:
    path = ROOT / "examples" / "slider_crank.toml"
    assert main(["check", str(path)]) == 0
    assert "four-bar" not in capsys.readouterr().out
    assert main(["check", str(path), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["four_bar"] is None
