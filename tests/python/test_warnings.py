"""camlink's warnings reach Python's `warnings`, one category per kind."""

from __future__ import annotations

import warnings

import pytest
from test_dynamics import OMEGA_JUMP, flat_follower_on_the_seed_cam, valve_turn

import camlink
from conftest import ROOT

EXAMPLES = ROOT / "examples"
MISBEHAVE = ROOT / "tests" / "models" / "misbehave"


def test_near_singular_position_warns():
    model = camlink.load(MISBEHAVE / "parallelogram_change_point.toml")
    with pytest.warns(camlink.NearSingularWarning, match="near-singular configuration"):
        res = model.run()
    assert res.summary["warnings"]


def test_lift_off_warns():
    with pytest.warns(camlink.LiftOffWarning, match="would leave cam"):
        valve_turn(1.01 * OMEGA_JUMP)


def test_design_finding_warns():
    flat = flat_follower_on_the_seed_cam()
    with pytest.warns(camlink.DesignWarning, match="concave"):
        camlink.loads(flat, "toml", "flat.toml").design_check()


def test_a_quiet_run_issues_no_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error", camlink.CamlinkWarning)
        camlink.load(EXAMPLES / "four_bar.toml").run()
