"""Issue 30, "Plain CSV": a results CSV is a plain table that
``pandas.read_csv`` reads as is (a header of channel names, numbers below);
its metadata and units are in a sidecar ``<name>.csv.json``, which
`Results.load` reads back. CSV files of earlier versions, with ``# key:``
comment lines, still load. A saved run's driver effort has its unit."""

from __future__ import annotations

import json
import os
import warnings
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import camlink
from camlink import Results, cli
from camlink.io.output import sidecar_path
from camlink.warn import CamlinkWarning
from conftest import ROOT

EXAMPLES = ROOT / "examples"

#: (model file, analysis, end time): a kinematics and a dynamics run.
RUNS = [("four_bar.toml", "kinematics", 0.05), ("dyn_pendulum.toml", "dynamics", 0.05)]


def _assert_plain(path: Path, res: Results) -> None:
    """`path` reads with pandas' defaults as the table of `res`: the
    channel names as header, every column a float."""
    frame = pd.read_csv(path)
    assert list(frame.columns) == ["t", *res.channels]
    assert all(dtype == np.float64 for dtype in frame.dtypes), frame.dtypes
    np.testing.assert_array_equal(frame.to_numpy(), res.data)
    assert not path.read_text().startswith("#")


def _assert_restored(path: Path, res: Results, analysis: str) -> None:
    back = Results.load(path)
    assert back.model == res.model
    assert back.summary["analysis"] == analysis
    for key in ("steps", "newton_iterations", "factorizations", "warnings"):
        assert back.summary[key] == res.summary[key], key
    assert back.units == res.units
    assert back.units["t"] == "s" and back.units[res.channels[0]] == "m"
    np.testing.assert_array_equal(back.data, res.data)


@pytest.mark.parametrize(("file", "analysis", "t_end"), RUNS)
def test_issue30_cli_csv_is_plain(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], file: str, analysis: str, t_end: float
) -> None:
    out = tmp_path / "run.csv"
    code = cli.main(["run", str(EXAMPLES / file), "--t-end", str(t_end), "-o", str(out)])
    capsys.readouterr()
    assert code == 0
    res = camlink.load(EXAMPLES / file).run(t_end=t_end)
    _assert_plain(out, res)
    _assert_restored(out, res, analysis)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run.csv", "run.csv.json"]
    meta = json.loads(sidecar_path(out).read_text())
    assert meta["model"] == res.model and meta["analysis"] == analysis
    assert meta["columns"] == ["t", *res.channels] and meta["rows"] == len(res)
    assert meta["camlink"] == camlink.__version__


@pytest.mark.parametrize(("file", "analysis", "t_end"), RUNS)
def test_issue30_saved_csv_is_plain(tmp_path: Path, file: str, analysis: str, t_end: float) -> None:
    res = camlink.load(EXAMPLES / file).run(t_end=t_end)
    out = res.save(tmp_path / "saved.csv")
    _assert_plain(out, res)
    _assert_restored(out, res, analysis)
    # A run written as it goes is the same table.
    lazy = camlink.load(EXAMPLES / file).run(t_end=t_end, output=tmp_path / "lazy.csv")
    _assert_plain(tmp_path / "lazy.csv", lazy)
    _assert_restored(tmp_path / "lazy.csv", lazy, analysis)


def test_issue30_old_commented_csv_still_loads(tmp_path: Path) -> None:
    path = tmp_path / "old.csv"
    path.write_text(
        '# camlink: "0.1.0"\n# model: "arm"\n# analysis: "kinematics"\n'
        '# units: {"t": "s", "arm.x": "m"}\nt,arm.x\n0,1\n1,2\n'
        '# summary: {"analysis": "kinematics", "steps": 2}\n'
    )
    back = Results.load(path)
    assert back.model == "arm" and back.summary == {"analysis": "kinematics", "steps": 2}
    assert back.units == {"t": "s", "arm.x": "m"}
    np.testing.assert_array_equal(back.data, [[0, 1], [1, 2]])


def test_issue30_a_sidecar_of_another_file_is_not_used(tmp_path: Path) -> None:
    res = camlink.load(EXAMPLES / "four_bar.toml").run(t_end=0.05)
    out = res.save(tmp_path / "r.csv")
    # The CSV edited (a row dropped) but not its sidecar: read without it.
    lines = out.read_text().splitlines(keepends=True)
    out.write_text("".join(lines[:-1]))
    with pytest.warns(CamlinkWarning, match=r"r\.csv\.json' describes another file"):
        back = Results.load(out)
    assert back.model == "r" and back.summary == {} and len(back) == len(res) - 1
    # Without the sidecar it loads, named after the file, silently.
    os.remove(sidecar_path(out))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        back = Results.load(out)
    assert back.model == "r" and len(back) == len(res) - 1
    # A sidecar that is not metadata is an error naming it.
    sidecar_path(out).write_text("[1, 2]")
    with pytest.raises(camlink.ModelError, match=r"r\.csv\.json': expected a JSON object"):
        Results.load(out)


def test_issue30_the_sidecar_is_never_written_over_an_input(tmp_path: Path) -> None:
    text = (EXAMPLES / "pendulum.toml").read_text()
    model_file = tmp_path / "run.csv.json"
    model = camlink.loads(text, "toml", str(model_file), base_dir=tmp_path)
    model.source = model_file
    model_file.write_text("{}")
    with pytest.raises(camlink.ModelError, match=r"metadata file .*run\.csv\.json.* is an input"):
        model.run(t_end=0.02, output=tmp_path / "run.csv")
    assert model_file.read_text() == "{}"
    assert not (tmp_path / "run.csv").exists()


def test_issue30_a_stopped_run_keeps_its_metadata(stuck_file: Path, tmp_path: Path) -> None:
    model = camlink.load(stuck_file)
    with pytest.raises(camlink.AnalysisError) as info:
        model.kinematics(t_end=0.3, step=0.01, output=tmp_path / "out.csv")
    partial = info.value.output
    assert partial is not None and Path(partial).name == "out.partial.csv"
    assert sidecar_path(Path(partial)).exists()
    assert not (tmp_path / "out.csv").exists() and not (tmp_path / "out.csv.json").exists()
    back = Results.load(partial)
    assert back.model == model.name and back.summary == {}
    assert back.units["t"] == "s"
    assert len(back) == len(info.value.results)


@pytest.mark.parametrize(
    ("file", "effort", "unit"),
    [("dyn_slider_crank.toml", "motor.effort", "N·m"),
     ("slider_crank_slider_driven.toml", None, "N")],
)
@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_issue30_saved_effort_has_its_unit(
    tmp_path: Path, file: str, effort: str | None, unit: str, suffix: str
) -> None:
    model = camlink.load(EXAMPLES / file)
    driver = next(j["name"] for j in model.joints if j["driver"])
    name = effort or f"{driver}.effort"
    res = model.run(t_end=0.05, analysis="inverse_dynamics")
    assert name in res
    for path in (res.save(tmp_path / f"saved{suffix}"),
                 _written(model, tmp_path / f"written{suffix}")):
        assert Results.load(path).units[name] == unit, path
        if suffix == ".csv":
            assert json.loads(sidecar_path(path).read_text())["units"][name] == unit


def _written(model: camlink.Model, path: Path) -> Path:
    model.run(t_end=0.05, analysis="inverse_dynamics", output=path)
    return path
