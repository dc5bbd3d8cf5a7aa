"""Forces of state in model files against the same force as a Python
callback (issue 30)."""

from __future__ import annotations

import numpy as np
import pytest

import camlink

SLIDE = """
[[bodies]]
name = "block"
position = [1.2, 0]
mass = 3
velocity = [0.4, 0]

[[joints]]
type = "translational"
name = "slide"
body_i = "ground"
axis = [1, 0]
body_j = "block"

[[forces]]
type = "tsda"
body_i = "ground"
body_j = "block"
stiffness = 2000
free_length = 1.0
"""

CUT = """
[[forces]]
type = "point_force"
name = "cut"
body = "block"
fx = "step(block_vx, 0, 0, 0.5, -500)"
"""


Vec3 = tuple[float, float, float]


def cutting(t: float, q: Vec3, qd: Vec3) -> Vec3:
    """500 N against the block while it moves forward, rising over 0.5 m/s
    as ADAMS STEP does."""
    u = min(max(qd[0] / 0.5, 0.0), 1.0)
    return (-500.0 * u * u * (3.0 - 2.0 * u), 0.0, 0.0)


def test_issue30_forward_stroke_cutting_force_equals_a_python_callback():
    in_file = camlink.loads(SLIDE + CUT, "toml", "cut.toml")
    assert [f["kind"] for f in in_file.forces] == ["tsda", "state_force"]
    a = in_file.simulate(t_end=1.0, step=0.01, h=1e-3, tol=1e-10)
    in_python = camlink.loads(SLIDE, "toml", "slide.toml").with_force("cut", "block", cutting)
    b = in_python.simulate(t_end=1.0, step=0.01, h=1e-3, tol=1e-10)
    # The callback's derivatives are taken as zero: its Newton iteration
    # stops at the same tolerance by another path.
    np.testing.assert_allclose(a["block.x"], b["block.x"], atol=1e-8)
    np.testing.assert_allclose(a["block.vx"], b["block.vx"], atol=1e-7)
    # The force takes energy on every forward stroke.
    e = a["energy.total"]
    assert e[-1] < e[0] - 10.0


def test_issue30_an_unknown_channel_is_a_model_error():
    with pytest.raises(camlink.ModelError, match=r"unknown name 'block_vz' \(did you mean 'block_vx'\?\)"):
        camlink.loads(SLIDE + CUT.replace("block_vx", "block_vz"), "toml", "cut.toml")
