"""Results files carry their metadata: the camlink version, the model name,
the analysis, each channel's unit and the run summary, in a CSV's sidecar
``<name>.csv.json`` and as schema metadata in Parquet, and `Results.load`
reads them back."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import camlink
from camlink import Results
from camlink.io.output import sidecar_path

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_a_run_to_csv_writes_a_sidecar_that_load_reads_back(tmp_path: Path) -> None:
    model = camlink.load(EXAMPLES / "dyn_pendulum.toml")
    res = model.simulate(t_end=0.02, step=0.01, output=tmp_path / "out.csv")
    lines = (tmp_path / "out.csv").read_text().splitlines()
    assert lines[0].startswith("t,arm.x,")
    assert len(lines) == 1 + len(res)
    meta = json.loads(sidecar_path(tmp_path / "out.csv").read_text())
    assert meta["camlink"] == camlink.__version__
    assert meta["model"] == model.name
    assert meta["analysis"] == "dynamics"
    assert meta["summary"]["steps"] == res.summary["steps"]
    assert meta["units"]["t"] == "s" and meta["units"]["arm.phi"] == "rad"
    assert meta["units"]["arm.omega"] == "rad/s" and meta["units"]["energy.total"] == "J"
    assert list(meta["units"]) == ["t", *res.channels]
    back = Results.load(tmp_path / "out.csv")
    assert back.model == model.name
    np.testing.assert_array_equal(back.data, res.data)
    for key in ("analysis", "steps", "newton_iterations", "factorizations"):
        assert back.summary[key] == res.summary[key], key
    # Other readers read the plain table.
    frame = pd.read_csv(tmp_path / "out.csv")
    np.testing.assert_array_equal(frame.to_numpy(), res.data)


@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_a_run_to_a_file_stores_the_summary_save_stores(tmp_path: Path, suffix: str) -> None:
    """One form of the summary in files: a forward-dynamics run written
    with ``output=`` stores what `Results.save` of the same run in memory
    stores, the drift of energy and constraints included (computed in Rust
    as the rows are written, by every writer alike)."""
    model = camlink.load(EXAMPLES / "dyn_slider_crank.toml")
    memory = model.simulate(t_end=0.05, step=0.01)
    streamed = model.simulate(t_end=0.05, step=0.01, output=tmp_path / f"run{suffix}")
    saved = Results.load(memory.save(tmp_path / f"saved{suffix}"))
    back = Results.load(tmp_path / f"run{suffix}")
    assert back.summary == saved.summary
    energy = memory["energy.total"]
    drift = {
        "energy_drift": float(np.max(np.abs(energy - energy[0]))),
        "constraint_drift": float(np.max(memory["constraint.residual"])),
        "velocity_drift": float(np.max(memory["constraint.velocity"])),
    }
    for key, value in drift.items():
        assert memory.summary[key] == value, key  # type: ignore[literal-required]
        assert streamed.summary[key] == value, key  # type: ignore[literal-required]
        assert back.summary[key] == value, key  # type: ignore[literal-required]
    assert drift["energy_drift"] > 0.0


@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_saved_results_keep_model_analysis_units_and_summary(tmp_path: Path, suffix: str) -> None:
    res = camlink.load(EXAMPLES / "four_bar.toml").run(t_end=0.05, step=0.01)
    back = Results.load(res.save(tmp_path / f"out{suffix}"))
    assert back.model == res.model
    assert back.summary["analysis"] == "kinematics"
    assert back.summary["steps"] == res.summary["steps"]
    assert back.summary["warnings"] == res.summary["warnings"]
    meta = res.metadata()
    assert meta["units"]["crank.phi"] == "rad" and meta["camlink"] == camlink.__version__


def test_a_failed_run_keeps_the_header_but_no_summary(stuck_file: Path, tmp_path: Path) -> None:
    model = camlink.load(stuck_file)
    with pytest.raises(camlink.AnalysisError) as info:
        model.kinematics(t_end=0.3, step=0.01, output=tmp_path / "out.csv")
    partial = info.value.output
    assert partial is not None
    assert Path(partial).read_text().startswith("t,")
    meta = json.loads(sidecar_path(Path(partial)).read_text())
    assert meta["camlink"] == camlink.__version__ and "summary" not in meta
    back = Results.load(partial)
    assert back.model == model.name and back.summary == {}
    assert len(back) == len(info.value.results)
