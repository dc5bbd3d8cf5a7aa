"""Every example file's mechanism built in code with `camlink.Mechanism`
(one method per model-file table, `curve()` included) gives the file's
results."""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import camlink
from conftest import ROOT

# Cam design files (`cam_design_*.toml`) are not models: test_cam_design.py runs them.
EXAMPLES = sorted(
    p for p in (ROOT / "examples").glob("*.toml") if not p.name.startswith("cam_design_")
)


def test_examples_are_found():
    assert len(EXAMPLES) >= 10


def in_code(path: Path) -> camlink.Mechanism:
    """The model of `path`, built call by call from its tables."""
    d: dict[str, Any] = tomllib.loads(path.read_text())
    model = d.get("model", {})
    m = camlink.Mechanism(
        model.get("name", path.stem), gravity=model.get("gravity"), base_dir=path.parent
    )
    for name, value in d.get("parameters", {}).items():
        m.parameter(name, value)
    for name, xy in d.get("ground", {}).get("points", {}).items():
        m.ground_point(name, xy)
    for b in d.get("bodies", []):
        m.body(**b)
    for c in d.get("curves", []):
        m.curve(**c)
    for j in d.get("joints", []):
        j = dict(j)
        m.joint(j.pop("name"), j.pop("type"), **j)
    for dr in d.get("drivers", []):
        dr = dict(dr)
        m.driver(dr.pop("name"), dr.pop("type"), **dr)
    for f in d.get("forces", []):
        f = dict(f)
        m.force(f.pop("type"), f.pop("name", None), **f)
    if "analysis" in d:
        m.analysis(**d["analysis"])
    return m


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_example_built_in_code_matches_the_file(path):
    from_file = camlink.load(path)
    built = in_code(path).build()
    kind = from_file.analysis_type
    settings: dict[str, Any] = {}
    if kind != "equilibrium":
        grid = from_file.times()
        settings["times"] = grid[: min(len(grid), 200)]
    a = from_file.run(**settings)
    b = built.run(**settings)
    assert a.channels == b.channels
    np.testing.assert_array_equal(a.data, b.data)


def test_curve_method_writes_a_curves_table():
    m = camlink.Mechanism("c")
    m.body("cam")
    assert m.curve("lobe", "cam", "expression", kind="polar", rho="1 + 0.2*cos(a)") == "lobe"
    assert m.to_dict()["curves"] == [
        {"name": "lobe", "body": "cam", "source": "expression", "kind": "polar",
         "rho": "1 + 0.2*cos(a)"}
    ]
    assert "[[curves]]" in m.to_toml()
