"""Every example model loads, checks and runs."""

from __future__ import annotations

import pytest

import camlink
from conftest import ROOT

# Cam design files (`cam_design_*.toml`) are not models: test_cam_design.py runs them;
# nor are study files (`study_*.toml`): test_study.py runs them; nor synthesis problems
# (`synthesis_*.toml`): test_synthesis.py solves them and runs their models.
EXAMPLES = sorted(
    p
    for p in (ROOT / "examples").glob("**/*.toml")
    if not p.name.startswith(("cam_design_", "study_", "synthesis_"))
) + sorted((ROOT / "examples").glob("**/*.json"))
MODELS = sorted((ROOT / "tests" / "models").glob("*.toml")) + sorted(
    (ROOT / "tests" / "models").glob("*.json")
)


def test_the_examples_are_found():
    # An empty glob would parametrize nothing and pass silently.
    assert len(EXAMPLES) >= 20 and len(MODELS) >= 2, (EXAMPLES, MODELS)


@pytest.mark.parametrize("path", EXAMPLES + MODELS, ids=lambda p: p.name)
def test_example_runs_end_to_end(path, tmp_path):
    model = camlink.load(path)
    if model.analysis_type in ("kinematics", "inverse_dynamics"):
        assert model.check()["dof"] == 0
    out = tmp_path / "out.parquet"
    res = model.run(output=out)
    assert res.complete and (len(res) > 1 or model.analysis_type == "equilibrium")
    assert res.t[0] == 0.0
    back = camlink.Results.load(out)
    assert back.channels == res.channels and len(back) == len(res)
    # Every channel has its unit from the core, and the file keeps it.
    assert all(res.units.values()), [n for n, u in res.units.items() if not u]
    assert back.units == res.units and back.quantities == res.quantities
