"""A Python force that raises stops the run with a camlink error of kind
``force_failed`` (no panic unwinds through the core), naming the force and
the time, with the Python exception chained as ``__cause__``."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

import camlink

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _pendulum() -> camlink.Model:
    return camlink.load(EXAMPLES / "dyn_pendulum.toml")


class Boom(Exception):
    """The user's own exception type."""


Triple = tuple[float, float, float]


def _failing_after(t_fail: float) -> Callable[[float, Triple, Triple], Triple]:
    def push(t: float, q: Triple, qd: Triple) -> Triple:
        if t >= t_fail:
            raise Boom(f"sensor lost at {t}")
        return (0.1, 0.0, 0.0)

    return push


def test_forward_dynamics_reports_the_force_the_time_and_the_cause() -> None:
    model = _pendulum().with_force("push", "arm", _failing_after(0.05))
    with pytest.raises(camlink.AnalysisError) as info:
        model.simulate(t_end=0.1, step=0.01, h=0.001)
    e = info.value
    assert e.kind == "force_failed"
    assert "force 'push' failed: Boom: sensor lost" in str(e)
    assert 0.05 <= e.time < 0.0511
    assert isinstance(e.__cause__, Boom)
    # The rows before the failure are kept.
    np.testing.assert_allclose(e.results.t, 0.01 * np.arange(5), atol=1e-12)


def test_equilibrium_and_inverse_dynamics_report_it_too() -> None:
    model = _pendulum().with_force("push", "arm", _failing_after(0.0))
    with pytest.raises(camlink.AnalysisError) as info:
        model.equilibrium()
    assert info.value.kind == "force_failed"
    assert isinstance(info.value.__cause__, Boom)


def test_a_bad_return_value_is_a_force_failure_with_a_model_error_cause() -> None:
    model = _pendulum().with_force("bad", "arm", lambda t, q, qd: "three")  # type: ignore[arg-type, return-value]
    with pytest.raises(camlink.AnalysisError, match="force 'bad' failed") as info:
        model.simulate(t_end=0.01, step=0.01)
    assert info.value.kind == "force_failed"
    assert isinstance(info.value.__cause__, camlink.ModelError)
    assert "must return three numbers" in str(info.value.__cause__)


def test_the_model_runs_again_after_a_failure() -> None:
    calls = {"n": 0}

    def flaky(t: float, q: Triple, qd: Triple) -> Triple:
        calls["n"] += 1
        if calls["n"] == 3:
            raise Boom("once")
        return (0.0, 0.0, 0.0)

    model = _pendulum().with_force("flaky", "arm", flaky)
    with pytest.raises(camlink.AnalysisError):
        model.simulate(t_end=0.01, step=0.01, h=0.001)
    again = model.simulate(t_end=0.01, step=0.01, h=0.001)
    plain = _pendulum().simulate(t_end=0.01, step=0.01, h=0.001)
    np.testing.assert_allclose(again["arm.phi"], plain["arm.phi"], atol=1e-15)
