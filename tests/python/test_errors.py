"""Analysis errors and warnings carry a stable kind, the time and the joints
involved; tests and programs match the kind, not the message."""

from __future__ import annotations

import dataclasses
import re

import pytest

import camlink
from camlink.errors import ERROR_KINDS, WARNING_KINDS
from conftest import ROOT, STUCK_TIME

ERRORS = ROOT / "tests" / "models" / "errors"
MISBEHAVE = ROOT / "tests" / "models" / "misbehave"


def documented_kinds() -> list[tuple[str, str]]:
    page = (ROOT / "docs" / "errors.md").read_text(encoding="utf-8")
    table = page.split("<!-- kinds -->")[1].split("<!-- /kinds -->")[0]
    return re.findall(r"^\| `(\w+)` \| (error|warning) \|", table, flags=re.MULTILINE)


def test_the_kinds_are_those_documented():
    want = [(k, "error") for k in ERROR_KINDS] + [(k, "warning") for k in WARNING_KINDS]
    assert documented_kinds() == want


@pytest.mark.parametrize(
    ("name", "kind"),
    [
        ("under_driven", "not_driven"),
        ("over_driven", "redundant"),
        ("cannot_assemble", "not_assembled"),
        ("past_reach", "not_converged"),
        ("jump", "branch_jump"),
        ("no_ground", "invalid_input"),
    ],
)
def test_each_failure_has_its_kind(name, kind):
    with pytest.raises(camlink.AnalysisError) as info:
        camlink.load(ERRORS / f"{name}.toml").run()
    err = info.value
    assert err.kind == kind, str(err)
    assert err.kind in ERROR_KINDS
    assert isinstance(err.time, float) and isinstance(err.joints, list)


def test_a_lock_up_names_time_and_joints(stuck_file):
    with pytest.raises(camlink.AnalysisError) as info:
        camlink.load(stuck_file).run(t_end=0.5, step=0.01)
    err = info.value
    assert err.kind == "not_converged"
    assert 0.1 < err.time <= STUCK_TIME + 0.02
    assert err.joints and all(isinstance(j, str) for j in err.joints)


def test_a_dynamics_failure_names_its_joints():
    # A mechanism that cannot be assembled fails in forward dynamics too,
    # naming the joints furthest from closing.
    with pytest.raises(camlink.AnalysisError) as info:
        camlink.load(ERRORS / "cannot_assemble.toml").simulate(t_end=0.01)
    err = info.value
    assert err.kind in ("not_assembled", "not_converged", "lock_up"), str(err)
    assert err.time == 0.0
    assert {"A", "B"} & set(err.joints), err.joints


def test_warnings_are_frozen_records_with_a_kind():
    res = camlink.load(MISBEHAVE / "parallelogram_change_point.toml").run()
    warnings = res.summary["warnings"]
    assert [w.kind for w in warnings] == ["near_singular"]
    w = warnings[0]
    assert isinstance(w, camlink.RunWarning)
    assert abs(w.time - (3.141592653589793 - 2.0) / 2.0) < 0.01
    assert "near-singular" in w.message and str(w).startswith("at t = ")
    with pytest.raises(dataclasses.FrozenInstanceError):
        w.kind = "other"  # type: ignore[misc]
