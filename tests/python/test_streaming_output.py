"""Runs that write an output file stream it in chunks and keep only the
chunk: the file holds the same numbers, metadata and summary as the run in
memory, the returned `Results` read the file back lazily with the same API,
and the peak memory of a long run stays that of a short one."""

from __future__ import annotations

import gc
import json
import math
import os
import pickle
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow.parquet as pq
import pytest

import camlink
import camlink.io.output
import camlink.io.results_file
import camlink.model
from camlink import ModelError, Results
from camlink.io.output import BackgroundWriter, sidecar_path
from camlink.io.results_file import CsvColumns, ParquetColumns

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
SUFFIXES = [".csv", ".parquet"]


def assert_same_results(lazy: Results, memory: Results) -> None:
    """Every channel, the rows, the frame and the summary are identical."""
    assert lazy.channels == memory.channels
    assert len(lazy) == len(memory)
    for name in ["t", *memory.channels]:
        column = lazy[name]
        assert not column.flags.writeable, name
        np.testing.assert_array_equal(column, memory[name], err_msg=name)
    np.testing.assert_array_equal(lazy.t, memory.t)
    assert not lazy.data.flags.writeable
    np.testing.assert_array_equal(lazy.data, memory.data)
    pd.testing.assert_frame_equal(lazy.to_pandas(), memory.to_pandas())
    assert lazy.summary == memory.summary
    assert lazy.metadata() == memory.metadata()
    pd.testing.assert_frame_equal(lazy.lift_off, memory.lift_off)
    pd.testing.assert_frame_equal(lazy.impacts, memory.impacts)
    assert lazy.complete and lazy.model == memory.model


@pytest.mark.parametrize("suffix", SUFFIXES)
def test_a_run_written_in_chunks_gives_the_in_memory_numbers_metadata_and_summary(
    tmp_path: Path, suffix: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Chunks of 7 rows, Parquet row groups of 16, CSV read back in blocks of
    # 4 kB (a few rows): many of each.
    monkeypatch.setattr(camlink.model, "CHUNK_ROWS", 7)
    monkeypatch.setattr(camlink.io.output, "ROW_GROUP_ROWS", 16)
    monkeypatch.setattr(camlink.io.results_file, "CSV_BLOCK", 4096)
    model = camlink.load(EXAMPLES / "four_bar.toml")
    memory = model.kinematics(t_end=0.5, step=0.01, jerk=True)
    out = tmp_path / f"run{suffix}"
    lazy = model.kinematics(t_end=0.5, step=0.01, jerk=True, output=out)
    assert lazy.source == out and memory.source is None
    assert_same_results(lazy, memory)
    # The file itself, read whole, carries the run's summary.
    back = Results.load(out)
    np.testing.assert_array_equal(back.data, memory.data)
    for key in ("analysis", "steps", "newton_iterations", "factorizations", "warnings"):
        assert back.summary[key] == memory.summary[key], key
    written = [out.name] + ([sidecar_path(out).name] if suffix == ".csv" else [])
    assert sorted(p.name for p in tmp_path.iterdir()) == written
    if suffix == ".parquet":
        assert pq.ParquetFile(out).num_row_groups == math.ceil(len(memory) / 16)
        meta = json.loads(pq.read_metadata(out).metadata[b"camlink"])
        assert meta["summary"]["steps"] == memory.summary["steps"] == len(memory)
        assert meta["units"]["crank.phi"] == "rad" and meta["analysis"] == "kinematics"
    else:
        meta = json.loads(sidecar_path(out).read_text())
        assert meta["summary"]["steps"] == len(memory) == meta["rows"]


@pytest.mark.parametrize("suffix", SUFFIXES)
def test_dynamics_with_impacts_streams_its_summary(
    tmp_path: Path, suffix: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(camlink.model, "CHUNK_ROWS", 100)
    model = camlink.load(EXAMPLES / "cam_valve_jump.toml")
    memory = model.run(t_end=0.01)
    lazy = model.run(t_end=0.01, output=tmp_path / f"valve{suffix}")
    assert len(memory.impacts) > 0 and len(memory.lift_off) > 0
    assert lazy.summary["energy_drift"] == memory.summary["energy_drift"]
    assert_same_results(lazy, memory)


@pytest.mark.parametrize(("suffix", "source"), [(".csv", CsvColumns), (".parquet", ParquetColumns)])
def test_lazy_results_read_only_the_channels_asked_for_once(
    tmp_path: Path,
    suffix: str,
    source: type[CsvColumns] | type[ParquetColumns],
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    asked: list[str] = []
    read = source.column

    def spy(self: CsvColumns | ParquetColumns, name: str) -> np.ndarray:
        asked.append(name)
        return read(self, name)  # type: ignore[arg-type]

    monkeypatch.setattr(source, "column", spy)
    res = camlink.load(EXAMPLES / "four_bar.toml").kinematics(
        t_end=0.1, step=0.01, output=tmp_path / f"run{suffix}"
    )
    assert asked == [] and len(res) == 11
    phi = res["crank.phi"]
    assert res["crank.phi"] is phi
    assert asked == ["crank.phi"]


@pytest.mark.parametrize("suffix", SUFFIXES)
def test_lazy_results_read_their_own_file_after_it_is_replaced_or_deleted(
    tmp_path: Path, suffix: str
) -> None:
    model = camlink.load(EXAMPLES / "four_bar.toml")
    out = tmp_path / f"run{suffix}"
    first = model.kinematics(t_end=0.1, step=0.01, output=out)
    memory = model.kinematics(t_end=0.1, step=0.01)
    # Another run replaces the output, then the file is deleted.
    model.kinematics(t_end=0.2, step=0.01, output=out)
    np.testing.assert_array_equal(first["crank.phi"], memory["crank.phi"])
    out.unlink()
    np.testing.assert_array_equal(first.data, memory.data)


@pytest.mark.parametrize("suffix", SUFFIXES)
def test_lazy_results_pickle_with_their_rows(tmp_path: Path, suffix: str) -> None:
    model = camlink.load(EXAMPLES / "four_bar.toml")
    lazy = model.kinematics(t_end=0.1, step=0.01, output=tmp_path / f"run{suffix}")
    back = pickle.loads(pickle.dumps(lazy))
    assert back.source is None and lazy.source is not None
    # The original, its open file and the file itself are gone.
    del lazy
    gc.collect()
    (tmp_path / f"run{suffix}").unlink()
    np.testing.assert_array_equal(back.data, model.kinematics(t_end=0.1, step=0.01).data)


@pytest.mark.parametrize("suffix", SUFFIXES)
def test_lazy_results_refuse_a_file_changed_in_place(tmp_path: Path, suffix: str) -> None:
    out = tmp_path / f"run{suffix}"
    res = camlink.load(EXAMPLES / "four_bar.toml").kinematics(t_end=0.1, step=0.01, output=out)
    with out.open("ab") as f:
        f.write(b"0\n")
    with pytest.raises(ModelError, match=r"run\..*changed after the run wrote it"):
        res["crank.phi"]


@pytest.mark.parametrize("suffix", SUFFIXES)
def test_a_failed_run_returns_lazy_partial_results(
    stuck_file: Path, tmp_path: Path, suffix: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(camlink.model, "CHUNK_ROWS", 4)
    model = camlink.load(stuck_file)
    with pytest.raises(camlink.AnalysisError) as memory:
        model.kinematics(t_end=0.5, step=0.01)
    with pytest.raises(camlink.AnalysisError) as lazy:
        model.kinematics(t_end=0.5, step=0.01, output=tmp_path / f"run{suffix}")
    partial = lazy.value.results
    assert partial.source == tmp_path / f"run.partial{suffix}" and not partial.complete
    assert len(partial) == len(memory.value.results) > 5
    np.testing.assert_array_equal(partial.data, memory.value.results.data)


def test_the_binding_keeps_no_rows_when_told_and_hands_column_major_chunks() -> None:
    model = camlink.load(EXAMPLES / "four_bar.toml")
    times = model.times(t_end=0.5, step=0.01)
    chunks: list[np.ndarray] = []

    def collect(names: list[str], rows: np.ndarray, quantities: list[str]) -> None:
        assert rows.flags.f_contiguous and len(quantities) == len(names)
        chunks.append(rows.copy())

    names, kept, _, _ = model._core.run_kinematics(times, on_chunk=collect, chunk_rows=10)
    streamed: list[np.ndarray] = chunks[:]
    chunks.clear()
    names2, none, _, _ = model._core.run_kinematics(
        times, on_chunk=collect, chunk_rows=10, keep_rows=False
    )
    assert names2 == names and none.shape == (0, len(names))
    assert [len(c) for c in chunks] == [10, 10, 10, 10, 10, 1]
    np.testing.assert_array_equal(np.vstack(chunks), kept)
    np.testing.assert_array_equal(np.vstack(streamed), kept)


def test_a_chunk_holds_at_most_two_mebibytes_of_rows() -> None:
    model = camlink.load(EXAMPLES / "four_bar.toml")
    times = model.times(t_end=0.1, step=1e-5)
    sizes: list[int] = []
    names, _, _, _ = model._core.run_kinematics(
        times,
        on_chunk=lambda names, rows, quantities: sizes.append(len(rows)),
        chunk_rows=10**9,
        keep_rows=False,
    )
    cap = (2 << 20) // (8 * len(names))
    assert sizes[0] == cap and sum(sizes) == len(times)
    assert max(sizes) == cap


def test_the_background_writer_writes_the_chunks_waiting_together() -> None:
    gate = threading.Event()
    calls: list[np.ndarray] = []

    class Slow:
        path = Path("slow.csv")

        def write(self, names: list[str], rows: np.ndarray, quantities: list[str]) -> None:
            calls.append(rows.copy())
            assert rows.flags.f_contiguous
            gate.wait(60)

        def close(self, names: list[str], complete: bool = True,
                  metadata: dict[str, object] | None = None) -> Path:
            return self.path

    writer = BackgroundWriter(Slow())  # type: ignore[arg-type]
    chunks = [np.asfortranarray(np.arange(6.0).reshape(3, 2) + 10 * k) for k in range(5)]
    writer.write(["t", "x"], chunks[0])
    # The thread is busy with the first chunk while the others queue up.
    while not calls:
        time.sleep(0.01)
    for chunk in chunks[1:]:
        writer.write(["t", "x"], chunk)
    gate.set()
    writer.close(["t", "x"])
    assert [len(c) for c in calls] == [3, 12]
    np.testing.assert_array_equal(np.vstack(calls), np.vstack(chunks))


# -- memory of long runs -------------------------------------------------------

# The peak is the process's own high-water mark (VmHWM), not `getrusage`'s
# ru_maxrss, which on Linux starts from the parent's size at fork (here the
# test process's).
PEAK = """
import sys
import camlink
steps, output = int(sys.argv[1]), sys.argv[2]
camlink.load(sys.argv[3]).kinematics(t_end=steps * 1e-5, step=1e-5, output=output)
with open("/proc/self/status") as status:
    print(next(int(line.split()[1]) for line in status if line.startswith("VmHWM:")) / 1024)
"""


def peak_mb(steps: int, output: Path) -> float:
    """Peak resident memory (MB) of a fresh process that runs the four-bar
    for `steps` steps to `output`."""
    out = subprocess.run(
        [sys.executable, "-c", PEAK, str(steps), str(output), str(EXAMPLES / "four_bar.toml")],
        check=True,
        capture_output=True,
        text=True,
    )
    return float(out.stdout)


def growth_mb(folder: Path, suffix: str, base: int, steps: int) -> float:
    """How much higher (MB) the peak of a run of `steps` steps to a
    `suffix` file is than that of a run of `base` steps."""
    low = peak_mb(base, folder / f"base{suffix}")
    return peak_mb(steps, folder / f"run{suffix}") - low


@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="needs Linux's /proc")
@pytest.mark.parametrize("suffix", SUFFIXES)
def test_memory_of_a_run_to_a_file_does_not_grow_with_its_length(
    tmp_path: Path, suffix: str
) -> None:
    # Past its first 10⁵ steps (the writer's buffers full), a run holds no
    # more: 2·10⁵ more rows of 40 channels would be 64 MB.
    assert growth_mb(tmp_path, suffix, 100_000, 300_000) < 16


@pytest.mark.skipif(
    os.environ.get("CAMLINK_LONG_RUN") != "1" or not Path("/proc/self/status").exists(),
    reason="a 10⁶-step run (several seconds): set CAMLINK_LONG_RUN=1 (Linux)",
)
@pytest.mark.parametrize("suffix", SUFFIXES)
def test_memory_of_a_million_step_run_stays_within_50_mb_of_a_short_one(
    tmp_path: Path, suffix: str
) -> None:
    assert growth_mb(tmp_path, suffix, 1_000, 1_000_000) < 50
