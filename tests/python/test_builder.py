"""A model built in code equals the same model read from a file."""

from __future__ import annotations

import math
import sys

import numpy as np
import pytest

import camlink
from conftest import four_bar_toml


def four_bar_in_code() -> camlink.Mechanism:
    """The four-bar of `four_bar_toml()`, built with the Python API."""
    import tomllib

    spec = tomllib.loads(four_bar_toml())
    bodies = {b["name"]: b for b in spec["bodies"]}
    m = camlink.Mechanism("four_bar", gravity=(0, -9.81))
    for k, v in spec["parameters"].items():
        m.parameter(k, v)
    m.ground_point("O", (0, 0))
    m.point("ground", "C", ("d", 0))
    m.body("crank", angle="deg(60)", mass=1.0, inertia=0.1, points={"O": (0, 0), "A": ("r", 0)})
    m.body(
        "coupler",
        position=bodies["coupler"]["position"],
        angle=bodies["coupler"]["angle"],
        mass=2.6,
        inertia=1.5,
        points={"A": (0, 0), "B": ("L", 0)},
    )
    m.point("coupler", "P", ("L/2", 0.5))
    m.body(
        "rocker",
        ("d", 0),
        np.float64(bodies["rocker"]["angle"]),
        mass=2.5,
        inertia=1.3,
        points={"C": (0, 0), "B": ("b", 0)},
    )
    m.revolute("O", "ground", "O", "crank", "O")
    m.revolute("A", "crank", "A", "coupler", "A")
    m.revolute("B", "coupler", "B", "rocker", "B")
    m.revolute("C", "rocker", "C", "ground", "C")
    m.revolute_driver("motor", "O", f="deg(60) + w*t")
    m.analysis(t_end=1.0, step=0.01, points=["coupler.P", "crank.A"])
    return m


def test_builder_and_file_give_identical_results(four_bar_file):
    from_file = camlink.load(four_bar_file).run()
    from_code = four_bar_in_code().build().run()
    assert from_code.channels == from_file.channels
    np.testing.assert_array_equal(from_code.data, from_file.data)


def test_builder_describes_the_same_model(four_bar_file):
    a = camlink.load(four_bar_file)
    b = four_bar_in_code().build()
    assert a.bodies == b.bodies
    assert a.joints == b.joints
    assert a.analysis == b.analysis


@pytest.mark.parametrize("fmt", ["toml", "json"])
def test_to_toml_and_to_json_load_back_to_the_same_model(fmt):
    m = four_bar_in_code()
    text = m.to_toml() if fmt == "toml" else m.to_json()
    again = camlink.loads(text, fmt, f"built.{fmt}")
    res_a = again.run(t_end=0.2)
    res_b = m.run(t_end=0.2)
    np.testing.assert_array_equal(res_a.data, res_b.data)


def test_slider_crank_in_code():
    r, L = 0.1, 0.3
    m = camlink.Mechanism("slider_crank")
    m.body("crank", angle=0.0, points={"A": (r, 0)})
    m.body("rod", position=(r, 0), angle=0.0, points={"A": (0, 0), "B": (L, 0)})
    m.body("slider", position=(r + L, 0))
    m.revolute("O", "ground", (0, 0), "crank", (0, 0))
    m.revolute("A", "crank", "A", "rod", "A")
    m.revolute("B", "rod", "B", "slider", (0, 0))
    m.translational("guide", "ground", (0, 0), "slider", (0, 0), axis=(1, 0))
    m.revolute_driver("motor", "O", f="2*pi*t")
    res = m.run(t_end=1.0, step=0.01)
    phi = 2 * math.pi * res.t
    x = r * np.cos(phi) + np.sqrt(L**2 - (r * np.sin(phi)) ** 2)
    assert res["slider.x"] == pytest.approx(x, abs=1e-9)
    assert res["slider.y"] == pytest.approx(0.0, abs=1e-9)


def _line() -> int:
    """The line of the caller."""
    return sys._getframe(1).f_lineno


def test_builder_errors_go_through_the_loader():
    m = camlink.Mechanism("broken")
    m.body("arm", points={"A": (1, 0)})
    with pytest.raises(camlink.ModelError, match="amr"):
        m.revolute("pin", "ground", (0, 0), "amr", (0, 0))


@pytest.mark.parametrize(
    ("call", "message"),
    [
        # An unknown body, with the nearest name.
        (lambda m: m.revolute("pin", "ground", (0, 0), "amr", (0, 0)),
         "joints[0].body_j: no body named 'amr' (did you mean 'arm'?)"),
        # An unknown point.
        (lambda m: m.revolute("pin", "ground", (0, 0), "arm", "B"),
         "joints[0].point_j: body 'arm' has no point named 'B'"),
        # A bad joint kind.
        (lambda m: m.joint("pin", "revolut", body_i="ground", body_j="arm"),
         "(did you mean 'revolute'?)"),
        # A wrong type.
        (lambda m: m.body("rod", mass=[1, 2]), "bodies[1].mass: invalid type"),
        # A bad expression, and a parameter not declared before.
        (lambda m: m.parameter("w", "2*pi*"), "parameters.w: invalid expression"),
        (lambda m: m.body("rod", angle="th0"), "unknown name 'th0'"),
        # A point of an existing body.
        (lambda m: m.point("arm", "B", ("r", 0)), "unknown name 'r'"),
        (lambda m: m.analysis(t_end=-1.0, step=0.1), "analysis.t_end"),
    ],
)
def test_a_faulty_call_raises_at_the_call_naming_its_line(call, message):
    m = camlink.Mechanism("m")
    m.body("arm", points={"A": (1, 0)})
    before = m.to_dict()
    with pytest.raises(camlink.ModelError) as e:
        call(m)
    text = str(e.value)
    # The call is in this file (in the lambda above).
    assert text.startswith(f"{__file__}:"), text
    assert message in text, text
    # The model is as it was before the call, and goes on.
    assert m.to_dict() == before
    m.revolute("O", "ground", (0, 0), "arm", (0, 0))
    assert m.build().joints


def test_a_call_site_names_the_line_of_the_user_code():
    m = camlink.Mechanism("m")
    m.body("arm", points={"A": (1, 0)})
    line = _line() + 2
    with pytest.raises(camlink.ModelError, match=rf"test_builder.py:{line}: joints\[0\]"):
        m.revolute("pin", "ground", (0, 0), "arm", "Q")


def test_an_error_found_by_build_names_the_line_of_its_call():
    # A joint before its bodies cannot be checked at its call (the model
    # has no body yet); build() names the joint's line.
    m = camlink.Mechanism("m")
    line = _line() + 1
    m.revolute("pin", "ground", (0, 0), "arm", "A")
    m.body("rod", points={"A": (1, 0)})
    with pytest.raises(camlink.ModelError, match=rf"test_builder.py:{line}: joints\[0\].body_j"):
        m.build()


def test_point_on_unknown_body_is_a_key_error():
    m = camlink.Mechanism("m")
    with pytest.raises(KeyError, match="no body named 'arm'"):
        m.point("arm", "A", (1, 0))
