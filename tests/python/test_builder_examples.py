"""Every example file's mechanism built in code with `camlink.Mechanism`
(one method per model-file table, `curve()` included) gives the file's
results."""

from __future__ import annotations

import math
import tomllib
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import camlink
from conftest import ROOT

#: The tables of a model file; other example files (cam designs) are not models.
MODEL_TABLES = {"$schema", "model", "parameters", "ground", "bodies", "curves", "joints",
                "drivers", "forces", "analysis"}

EXAMPLES = sorted(
    p
    for p in (ROOT / "examples").glob("*.toml")
    if set(tomllib.loads(p.read_text())) <= MODEL_TABLES
)


def test_examples_are_found():
    assert len(EXAMPLES) >= 10


#: The typed joint methods and the fields each takes as keywords (the
#: rest are its positional arguments).
TYPED = {"revolute": ("limits", "friction"),
         "translational": ("axis", "angle", "limits", "friction")}


def in_code(path: Path, typed: bool = False) -> camlink.Mechanism:
    """The model of `path`, built call by call from its tables; with
    `typed`, revolute and translational joints through `m.revolute` and
    `m.translational` instead of `m.joint`."""
    d: dict[str, Any] = tomllib.loads(path.read_text())
    model = d.get("model", {})
    m = camlink.Mechanism(
        model.get("name", path.stem), gravity=model.get("gravity"), units=model.get("units"),
        base_dir=path.parent
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
        name, kind = j.pop("name"), j.pop("type")
        if typed and kind in TYPED:
            keywords = {k: j.pop(k) for k in TYPED[kind] if k in j}
            ends = [j.pop(k, None) for k in ("body_i", "point_i", "body_j", "point_j")]
            assert not j, f"{path.name}: {name}: fields the typed method does not take: {j}"
            getattr(m, kind)(name, *ends, **keywords)
        else:
            m.joint(name, kind, **j)
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


#: Model files written in millimetres and degrees (`[model] units`).
UNIT_MODELS = sorted((ROOT / "crates" / "camlink-model" / "tests" / "units").glob("*.toml"))


@pytest.mark.parametrize("path", [*EXAMPLES, *UNIT_MODELS], ids=lambda p: p.stem)
def test_typed_joint_methods_and_units_give_the_file(path):
    """`m.revolute`/`m.translational` with `limits=` and `friction=`, and
    `Mechanism(units=…)`, write what the file says: the same results."""
    d = tomllib.loads(path.read_text())
    if not any(j.get("type") in TYPED for j in d.get("joints", [])) and path not in UNIT_MODELS:
        pytest.skip("no revolute or translational joint")
    from_file = camlink.load(path)
    built = in_code(path, typed=True).build()
    settings: dict[str, Any] = {}
    if from_file.analysis_type != "equilibrium":
        grid = from_file.times()
        settings["times"] = grid[: min(len(grid), 200)]
    a, b = from_file.run(**settings), built.run(**settings)
    assert a.channels == b.channels
    np.testing.assert_array_equal(a.data, b.data)


def test_typed_methods_carry_limits_friction_and_units():
    m = camlink.Mechanism("stop", gravity=(0, -9810), units={"length": "mm", "angle": "deg"})
    m.body("bar", mass=1, inertia=0.01, centroid=(200, 0), points={"O": (0, 0)})
    m.revolute("pivot", "ground", None, "bar", "O",
               limits={"lower": -45, "upper": 90, "restitution": 0.6},
               friction={"mu": 0.1, "radius": 5})
    m.body("slider", position=(0, -300), mass=1, inertia=0.01)
    m.translational("guide", "ground", (0, -300), "slider", None, axis=(1, 0),
                    limits={"lower": -50, "upper": 50}, friction={"mu": 0.3})
    d = m.to_dict()
    assert d["model"]["units"] == {"length": "mm", "angle": "deg"}
    pivot, guide = d["joints"]
    assert pivot["limits"] == {"lower": -45, "upper": 90, "restitution": 0.6}
    assert pivot["friction"] == {"mu": 0.1, "radius": 5}
    assert guide["limits"] == {"lower": -50, "upper": 50}
    assert guide["friction"] == {"mu": 0.3}
    # Loaded in SI: the same motion as the model written in m and rad.
    si = camlink.Mechanism("stop", gravity=(0, -9.81))
    si.body("bar", mass=1, inertia=0.01, centroid=(0.2, 0), points={"O": (0, 0)})
    si.revolute("pivot", "ground", None, "bar", "O",
                limits={"lower": -math.pi / 4, "upper": math.pi / 2, "restitution": 0.6},
                friction={"mu": 0.1, "radius": 0.005})
    si.body("slider", position=(0, -0.3), mass=1, inertia=0.01)
    si.translational("guide", "ground", (0, -0.3), "slider", None, axis=(1, 0),
                     limits={"lower": -0.05, "upper": 0.05}, friction={"mu": 0.3})
    a = m.build().simulate(t_end=1.0, step=0.01)
    b = si.build().simulate(t_end=1.0, step=0.01)
    assert a.channels == b.channels
    np.testing.assert_allclose(a.data, b.data, rtol=1e-9, atol=1e-12)
    # The bar reaches its stop at -45° within the run.
    assert float(np.min(a["bar.phi"])) == pytest.approx(-math.pi / 4, abs=1e-6)


def test_a_bad_limit_is_refused_at_the_call():
    m = camlink.Mechanism("stop")
    m.body("bar", points={"O": (0, 0)})
    with pytest.raises(camlink.ModelError, match=r"joints\[0\]\.limits\.upper"):
        m.revolute("pivot", "ground", None, "bar", "O", limits={"lower": 1.0, "upper": 0.5})
    assert m.to_dict().get("joints", []) == []


def test_curve_method_writes_a_curves_table():
    m = camlink.Mechanism("c")
    m.body("cam")
    assert m.curve("lobe", "cam", "expression", kind="polar", rho="1 + 0.2*cos(a)") == "lobe"
    assert m.to_dict()["curves"] == [
        {"name": "lobe", "body": "cam", "source": "expression", "kind": "polar",
         "rho": "1 + 0.2*cos(a)"}
    ]
    assert "[[curves]]" in m.to_toml()
