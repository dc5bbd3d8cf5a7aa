"""Error-controlled dynamics with extreme largest steps: the integrator lands
on every output time without a sliver step, and a trial step whose Newton
iteration fails is rejected and shortened rather than ending the run."""

from __future__ import annotations

from pathlib import Path

import numpy as np

import camlink

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_steps_land_on_output_times_without_slivers() -> None:
    # With largest step 1 ms and outputs every 0.5 s, rounding left a
    # remainder of about 1e-13 s before an output time; the step taken
    # there had a singular Newton matrix ("the Newton iteration matrix is
    # singular" at t = 2.5 s).
    model = camlink.load(EXAMPLES / "dyn_pendulum.toml")
    res = model.simulate(t_end=3, step=0.5, h=1e-3, adaptive=True, atol=1e-8, rtol=1e-8)
    np.testing.assert_array_equal(res.t, 0.5 * np.arange(7))
    # Against fixed steps of 0.1 ms (second order: its own error is about
    # 1e-8 rad here); the swing is 0.01 rad.
    ref = model.simulate(t_end=3, step=0.5, h=1e-4)
    assert np.max(np.abs(res["arm.phi"] - ref["arm.phi"])) < 1e-6


def test_a_huge_largest_step_is_shortened_when_newton_fails() -> None:
    # h = 1e11 s made the first trial step the whole 3 s interval; its
    # Newton iteration failed and the run stopped at t = 0 s.
    model = camlink.load(EXAMPLES / "dyn_slider_crank.toml")
    res = model.simulate(t_end=3, step=3, h=1e11, adaptive=True)
    np.testing.assert_array_equal(res.t, [0.0, 3.0])
    # The crank is driven by w t + 0.3 sin(w t), w = 4π rad/s: 12π rad at
    # t = 3 s (sin 12π is a rounding error), the slider back where it started.
    assert abs(res["crank.phi"][-1] - 12 * np.pi) < 1e-9
    assert abs(res["slider.x"][-1] - res["slider.x"][0]) < 1e-9
    # The same run with an ordinary largest step agrees.
    small = model.simulate(t_end=3, step=3, h=1e-3, adaptive=True)
    np.testing.assert_allclose(res["crank.phi"], small["crank.phi"], atol=1e-12)
