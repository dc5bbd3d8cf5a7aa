"""The compiled binding converts and nothing more: analysis settings are
keyword-only, with the core's defaults."""

from __future__ import annotations

import pytest

import camlink
from camlink import _core


def test_analysis_settings_are_keyword_only(four_bar_file):
    model = camlink.load(four_bar_file)
    times = model.times(t_end=0.1, step=0.05)
    with pytest.raises(TypeError):
        model._core.run_kinematics(times, 1e-10)  # type: ignore[call-arg]
    with pytest.raises(TypeError):
        model._core.run_dynamics(times, 1e-3)  # type: ignore[call-arg]
    names, data, _, quantities = model._core.run_kinematics(times, tol=1e-10)
    assert names[0] == "t" and data.shape == (3, len(names))
    assert quantities[0] == "time" and len(quantities) == len(names)


def test_run_takes_its_settings_by_keyword(four_bar_file):
    model = camlink.load(four_bar_file)
    with pytest.raises(TypeError):
        model.run(0.1, 0.05, None, 1e-10)  # type: ignore[call-arg]
    assert len(model.run(0.1, 0.05, tol=1e-10)) == 3


@pytest.mark.parametrize(
    ("t_end", "step"), [(0.3, 0.1), (1.0, 0.01), (0.0, 0.5), (2.0, 0.3), (1e-3, 1e-4)]
)
def test_issue28_time_grid_rows_counts_the_grid(t_end: float, step: float) -> None:
    # The CLI's row count is the grid's, end times within rounding of a
    # multiple of the step included, without building the grid.
    assert _core.time_grid_rows(t_end, step) == len(_core.time_grid(t_end, step))


def test_issue28_time_grid_rows_refuses_a_bad_step() -> None:
    with pytest.raises(camlink.ModelError, match="time step"):
        _core.time_grid_rows(1.0, 0.0)
