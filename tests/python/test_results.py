"""The Results API and writing results to CSV and Parquet."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pyarrow.parquet as pq
import pytest

import camlink
from camlink.results import LIFT_OFF_COLUMNS, LiftOffRecord, Results, RunSummary


def synthetic() -> Results:
    t = np.linspace(0.0, 1.0, 11)
    data = np.column_stack([t, np.sin(t), np.cos(t) / 3])
    return Results(["t", "arm.phi", "arm.omega"], data, model="demo")


def test_columns_by_name():
    res = synthetic()
    assert res.channels == ["arm.phi", "arm.omega"]
    assert len(res) == 11
    assert res["arm.phi"] == pytest.approx(np.sin(res.t))
    assert "arm.phi" in res and "arm.x" not in res
    assert "11 steps" in repr(res)


def test_unknown_channel_suggests_close_names():
    with pytest.raises(KeyError, match=r"did you mean 'arm\.phi'"):
        synthetic()["arm.ph"]


def test_to_pandas_is_indexed_by_time():
    df = synthetic().to_pandas()
    assert isinstance(df, pd.DataFrame)
    assert df.index.name == "t"
    assert list(df.columns) == ["arm.phi", "arm.omega"]
    assert df["arm.phi"].loc[0.5] == pytest.approx(np.sin(0.5))


def test_lift_off_is_a_frame_with_one_row_per_interval():
    closed = LiftOffRecord(
        joint="bucket",
        cam="cam",
        start_time=0.1,
        start_cam_angle=1.3,
        end_time=0.2,
        end_cam_angle=1.8,
        least_force=-2.0,
        least_time=0.15,
        least_cam_angle=1.57,
    )
    still_open = LiftOffRecord(
        {**closed, "start_time": 0.9, "end_time": None, "end_cam_angle": None}
    )
    res = synthetic()
    res.summary = {"lift_off": [closed, still_open]}
    df = res.lift_off
    assert list(df.columns) == LIFT_OFF_COLUMNS
    assert df["start_time"].tolist() == [0.1, 0.9]
    assert df["end_time"].iloc[0] == 0.2 and np.isnan(df["end_time"].iloc[1])
    assert all(df[c].dtype == np.float64 for c in LIFT_OFF_COLUMNS[2:])
    assert df["joint"].tolist() == ["bucket", "bucket"]


def test_lift_off_without_intervals_is_an_empty_frame_with_the_columns():
    summaries: tuple[RunSummary, ...] = ({}, {"lift_off": []})
    for summary in summaries:
        res = synthetic()
        res.summary = summary
        df = res.lift_off
        assert df.empty and list(df.columns) == LIFT_OFF_COLUMNS
        assert all(df[c].dtype == np.float64 for c in LIFT_OFF_COLUMNS[2:])


@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_save_and_load_round_trip_exactly(tmp_path, suffix):
    res = synthetic()
    path = res.save(tmp_path / f"out{suffix}")
    back = Results.load(path)
    assert back.channels == res.channels
    np.testing.assert_array_equal(back.data, res.data)


def test_csv_is_readable_by_pandas(tmp_path):
    path = synthetic().save(tmp_path / "out.csv")
    df = pd.read_csv(path, index_col="t", comment="#")
    assert df["arm.omega"].to_numpy() == pytest.approx(np.cos(df.index.to_numpy()) / 3)


@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_run_writes_output_as_it_goes(four_bar_file, tmp_path, suffix, monkeypatch):
    # Small chunks: the file is written in several pieces.
    monkeypatch.setattr(camlink.model, "CHUNK_ROWS", 7)
    out = tmp_path / f"run{suffix}"
    res = camlink.load(four_bar_file).run(t_end=0.5, step=0.01, output=out)
    back = Results.load(out)
    np.testing.assert_array_equal(back.data, res.data)
    if suffix == ".parquet":
        # The chunks are gathered into row groups of ROW_GROUP_ROWS rows.
        assert pq.ParquetFile(out).num_row_groups == 1


@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_failed_run_leaves_a_valid_file_with_every_step(stuck_file, tmp_path, suffix, monkeypatch):
    monkeypatch.setattr(camlink.model, "CHUNK_ROWS", 4)
    out = tmp_path / f"run{suffix}"
    with pytest.raises(camlink.AnalysisError) as e:
        camlink.load(stuck_file).run(t_end=0.5, step=0.01, output=out)
    partial = e.value.results
    back = Results.load(tmp_path / f"run.partial{suffix}")
    assert len(back) == len(partial) > 5
    np.testing.assert_array_equal(back.data, partial.data)
    assert e.value.output == tmp_path / f"run.partial{suffix}"
    assert not out.exists()
    # No temporary file is left behind; a CSV's metadata is beside it.
    kept = [f"run.partial{suffix}"] + [f"run.partial{suffix}.json"] * (suffix == ".csv")
    assert sorted(p.name for p in tmp_path.glob("run*")) == kept


def test_output_to_a_missing_directory_fails_before_running(four_bar_file, tmp_path):
    with pytest.raises(FileNotFoundError):
        camlink.load(four_bar_file).run(output=tmp_path / "no" / "such" / "dir.csv")


def test_callback_error_propagates(four_bar_file):
    model = camlink.load(four_bar_file)

    def boom(names, rows, quantities):
        raise ZeroDivisionError("from the callback")

    with pytest.raises(ZeroDivisionError, match="from the callback"):
        model._core.run_kinematics(model.times(), on_chunk=boom, chunk_rows=10)


def test_callback_error_stops_the_run(four_bar_file):
    model = camlink.load(four_bar_file)
    calls = []

    def stop_at_second_chunk(names, rows, quantities):
        calls.append(len(rows))
        if len(calls) == 2:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        model._core.run_kinematics(
            model.times(t_end=10.0, step=0.001), on_chunk=stop_at_second_chunk, chunk_rows=100
        )
    assert calls == [100, 100]


def test_csv_writes_negative_zero_as_zero(tmp_path):
    res = Results(["t", "v"], np.array([[0.0, -0.0], [1.0, -2.5]]))
    path = tmp_path / "r.csv"
    res.save(path)
    fields = path.read_text().replace("\n", ",").split(",")
    assert "-0" not in fields
    assert "-2.5" in fields
