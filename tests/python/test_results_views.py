"""Results hand out read-only views, find ``t`` by name, and type their
summary."""

from __future__ import annotations

import numpy as np
import pytest

import camlink
from camlink.results import Results


def test_result_arrays_are_read_only_views():
    data = np.column_stack([np.linspace(0.0, 1.0, 5), np.arange(5.0)])
    res = Results(["t", "x"], data)
    for array in (res["x"], res.t, res.data):
        with pytest.raises(ValueError, match="read-only"):
            array[0] = 42.0
    # The caller's array is neither copied into nor locked.
    assert data.flags.writeable
    data[0, 1] = 7.0
    assert res["x"][0] == 7.0


def test_to_pandas_finds_t_by_name():
    t = np.array([0.0, 0.5, 1.0])
    res = Results(["a", "t", "b"], np.column_stack([10 + t, t, 20 + t]))
    df = res.to_pandas()
    assert df.index.name == "t" and df.index.tolist() == t.tolist()
    assert list(df.columns) == ["a", "b"]
    assert df["a"].tolist() == (10 + t).tolist() and df["b"].tolist() == (20 + t).tolist()


def test_to_pandas_without_t_counts_steps():
    res = Results(["a"], np.array([[1.0], [2.0]]))
    df = res.to_pandas()
    assert df.index.name == "step" and df["a"].tolist() == [1.0, 2.0]


def test_a_run_summary_holds_typed_records(four_bar_file):
    res = camlink.load(four_bar_file).run(t_end=0.1, step=0.05)
    s = res.summary
    assert s["analysis"] == "kinematics" and s["steps"] == 3
    assert isinstance(s["warnings"], list) and s["lift_off"] == []
    assert all(isinstance(b, str) and len(d) == 3 for b, d in s["assembly_moves"])
