"""Issue 27 (results): lazily read results whose file is rewritten while
they read it, the notebook display of long lazily read results, and
`Results.load` on damaged files."""

from __future__ import annotations

import subprocess
import sys
import textwrap

import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq
import pytest

import camlink
from camlink.io.results_file import CsvColumns, ParquetColumns
from camlink.results import Results
from camlink.viz import notebook
from conftest import ROOT

# A block pushed along x and swinging: 4 channels that move.
BLOCK = """
[[bodies]]
name = "block"
points = { P = [0, 0] }

[[joints]]
name = "level"
type = "absolute_y"
body = "block"
point = "P"

[[drivers]]
name = "push"
type = "absolute_x"
body = "block"
point = "P"
f = "0.1 + 0.5*t"

[[drivers]]
name = "swing"
type = "absolute_phi"
body = "block"
f = "0.3*sin(2*pi*t)"

[analysis]
t_end = T_END
step = 0.001
"""


def _block(t_end: float) -> camlink.Model:
    return camlink.loads(BLOCK.replace("T_END", str(t_end)), "toml", "block.toml")


# --- 3. a results file rewritten while lazily read ----------------------------

REWRITTEN = textwrap.dedent("""
    import os, sys, threading, time
    import numpy as np
    import camlink
    from camlink import ModelError

    path = sys.argv[1]
    model = camlink.loads(sys.argv[2], "toml", "block.toml")
    res = model.run(output=path)
    assert res.source is not None, "results read lazily"
    expected = {name: model.run()[name].copy() for name in res.channels}
    blob = open(path, "rb").read()
    stamp = os.stat(path).st_mtime_ns
    stop = threading.Event()

    def rewrite():
        # In place, cut short then whole again, with the time stamp put back:
        # reads run into the file while it is shorter than when mapped.
        while not stop.is_set():
            with open(path, "r+b") as f:
                f.truncate(0)
                f.write(blob[: len(blob) // 3])
                f.flush()
                f.write(blob[len(blob) // 3 :])
            os.utime(path, ns=(stamp, stamp))

    threading.Thread(target=rewrite, daemon=True).start()
    ok = refused = 0
    start = time.monotonic()
    while time.monotonic() - start < 1.0:
        for name in res.channels:
            res._columns.clear()
            try:
                values = res[name]
            except ModelError as e:
                assert "cannot read results from" in str(e), e
                refused += 1
                continue
            assert np.array_equal(values, expected[name]), "other numbers"
            ok += 1
    stop.set()
    print(ok, refused)
""")


def test_issue27_results_rewritten_during_lazy_read_is_a_model_error(tmp_path):
    """Run in a process of its own: a memory-mapped read of a file cut short
    under it ends the process with SIGBUS."""
    text = BLOCK.replace("T_END", "20.0")
    done = subprocess.run(
        [sys.executable, "-c", REWRITTEN, str(tmp_path / "run.parquet"), text],
        capture_output=True, text=True, timeout=60, cwd=ROOT,
    )
    assert done.returncode == 0, (done.returncode, done.stderr[-2000:])
    _ok, refused = map(int, done.stdout.split())
    assert refused > 0


def test_issue27_results_lazy_parquet_reads_through_the_open_file(tmp_path):
    """No memory map: the reads go through the file held open, which keeps
    the rows of a file deleted since."""
    model = _block(1.0)
    res = model.run(output=tmp_path / "run.parquet")
    whole = model.run()
    (tmp_path / "run.parquet").unlink()
    np.testing.assert_array_equal(res["block.phi"], whole["block.phi"])
    np.testing.assert_array_equal(res.data, whole.data)


# --- 5. a notebook display of long lazily read results ------------------------


@pytest.mark.parametrize("suffix", [".parquet", ".csv"])
def test_issue27_results_notebook_reads_only_what_it_shows(tmp_path, monkeypatch, suffix):
    model = _block(20.0)  # 20,001 rows
    res = model.run(output=tmp_path / f"run{suffix}")
    whole = model.run()
    assert res.source is not None
    source = ParquetColumns if suffix == ".parquet" else CsvColumns

    read: list[list[str]] = []
    table = source.table

    def every_row(self, names):
        read.append(list(names))
        return table(self, names)

    monkeypatch.setattr(source, "table", every_row)
    page = notebook.results_html(res)
    assert res._data is None
    # Only the channels plotted and t were read whole, one at a time.
    assert all(len(names) == 1 for names in read), read
    assert {n for names in read for n in names} <= {"t", "block.x", "block.y", "block.phi"}
    assert len({n for names in read for n in names}) <= 4
    head = whole.to_pandas().iloc[:, : notebook.HEAD_COLUMNS].head(notebook.HEAD_ROWS)
    assert head.to_html(float_format=lambda v: f"{v:.6g}") in page
    assert "<img src=\"data:image/png;base64," in page


def test_issue27_results_notebook_head_of_results_in_memory():
    res = _block(0.01).run()
    rows = res._head(["t", "block.phi"], 5)
    np.testing.assert_array_equal(rows, res.data[:5, [0, res.channels.index("block.phi") + 1]])
    assert res._head(["t"], 100).shape == (len(res), 1)


def test_issue27_results_notebook_plot_keeps_the_envelope():
    """The plot of a long run draws each span's least and greatest values:
    the same extremes, first and last points as every row."""
    res = _block(20.0).run()
    channels = ["block.phi", "block.x"]
    thumb = notebook._envelope(res, channels)
    assert len(thumb) <= notebook.PLOT_ROWS + len(res) % (notebook.PLOT_ROWS // 4) + 2
    assert np.all(np.diff(thumb.t) > 0)
    for c in channels:
        assert thumb[c].min() == res[c].min() and thumb[c].max() == res[c].max()
        assert thumb[c][0] == res[c][0] and thumb[c][-1] == res[c][-1]
        # Every point drawn is a point of the run.
        np.testing.assert_array_equal(thumb[c], np.interp(thumb.t, res.t, res[c]))
    short = _block(1.0).run()
    assert notebook._envelope(short, channels) is short


# --- 6. Results.load on damaged files -------------------------------------------


def _parquet(path, meta, columns=None):
    columns = columns or {"t": pa.array([0.0, 1.0]), "a.x": pa.array([1.0, 2.0])}
    table = pa.table(columns)
    if meta is not None:
        table = table.replace_schema_metadata({"camlink": meta})
    pq.write_table(table, path)
    return path


DEEP = "[" * 100_000 + "]" * 100_000


@pytest.mark.parametrize(("meta", "says"), [
    (DEEP, "cannot read results from"),                                    # RecursionError
    ("[1, 2]", "camlink: expected a JSON object, got list"),               # AttributeError
    ('{"model": 7}', "model: expected a name, got int"),
    ('{"summary": 5}', "summary: expected a JSON object, got int"),         # TypeError
    ('{"summary": {"warnings": 5}}', "summary.warnings: expected a list of warnings"),
    ('{"summary": {"warnings": [{"kind": "k"}]}}', "summary.warnings: expected a list of warnings"),
    ('{"summary": {"warnings": [{"kind": "k", "time": "x", "joints": [], "message": ""}]}}',
     "summary.warnings: expected a list of warnings"),
    ('{"summary": {"lift_off": [1]}}', "summary.lift_off: expected a list of JSON objects"),
    ("{not json", "cannot read results from"),
])
def test_issue27_results_load_damaged_parquet_metadata(tmp_path, meta, says):
    path = _parquet(tmp_path / "r.parquet", meta)
    with pytest.raises(camlink.ModelError, match="cannot read results from") as e:
        Results.load(path)
    assert says in str(e.value) and str(path) in str(e.value)


@pytest.mark.parametrize("column", [
    pa.array(["a", "b"]),
    pa.array([[1.0], [2.0]]),
    pa.array([{"x": 1.0}, {"x": 2.0}]),
    pa.array([True, False]),
])
def test_issue27_results_load_damaged_parquet_columns(tmp_path, column):
    path = _parquet(tmp_path / "r.parquet", None, {"t": pa.array([0.0, 1.0]), "a.x": column})
    with pytest.raises(camlink.ModelError, match=r"column 'a\.x' holds .*, not numbers"):
        Results.load(path)


@pytest.mark.parametrize(("line", "says"), [
    (f"# summary: {DEEP}", "cannot read results from"),
    ("# summary: 5", "summary: expected a JSON object, got int"),
    ('# summary: {"warnings": {"a": 1}}', "summary.warnings: expected a list of warnings"),
    ("# model: [1]", "model: expected a name, got list"),
])
def test_issue27_results_load_damaged_csv(tmp_path, line, says):
    path = tmp_path / "r.csv"
    path.write_text(f"t,a.x\n0,1\n1,2\n{line}\n")
    with pytest.raises(camlink.ModelError, match="cannot read results from") as e:
        Results.load(path)
    assert says in str(e.value)


def test_issue27_results_load_keeps_reading_good_files(tmp_path):
    good = _block(0.1).run()
    for suffix in (".parquet", ".csv"):
        good.save(tmp_path / f"good{suffix}")
        back = Results.load(tmp_path / f"good{suffix}")
        np.testing.assert_array_equal(back.data, good.data)
        assert back.summary.get("analysis") == good.summary["analysis"]
        assert back.model == good.model
