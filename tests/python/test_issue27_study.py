"""Issue 27 (studies): a scheduler address that answers but is not a Dask
scheduler, parameters named like the study's own columns, studies too
large for memory, and schedulers or batch files the study cannot use."""

from __future__ import annotations

import http.server
import socket
import threading
import time
from collections.abc import Sequence

import distributed.comm  # noqa: F401 (imported here, so that timings measure the connection)
import numpy as np
import pandas as pd
import pytest
from scipy import stats

import camlink
from camlink import _core
from camlink.cli import main
from camlink.study import max_of, range_of, run_variants, runner
from conftest import ROOT

STUDY = ROOT / "examples" / "study_four_bar.toml"
FOUR_BAR = ROOT / "examples" / "four_bar.toml"

# A block pushed along x: its largest x is x0 + v·t_end. Its parameters
# are named like the study's own columns once were.
COLLIDING = """
[parameters]
variant = 0.1   # start (m)
key = 0.5       # speed (m/s)
batch = 0.0     # offsets (m)
error = 0.0
status = 0.0

[[bodies]]
name = "block"
points = { P = [0, 0] }

[[joints]]
name = "level"
type = "absolute_y"
body = "block"
point = "P"

[[joints]]
name = "square"
type = "absolute_phi"
body = "block"

[[drivers]]
name = "push"
type = "absolute_x"
body = "block"
point = "P"
f = "variant + key*t + batch + 2*error + 3*status"

[analysis]
t_end = 1.0
step = 0.1
"""
NAMES = ["variant", "key", "batch", "error", "status"]


def _top(row):
    """The block's largest x (m) for a row of parameter values."""
    return row["variant"] + row["key"] * 1.0 + row["batch"] + 2 * row["error"] + 3 * row["status"]


# --- 1. a scheduler address that answers but is not a scheduler -----------


def _silent_listener():
    sock = socket.socket()
    sock.bind(("127.0.0.1", 0))
    sock.listen(8)
    return sock, f"tcp://127.0.0.1:{sock.getsockname()[1]}"


class _Page(http.server.BaseHTTPRequestHandler):
    def do_GET(self):
        body = b"<html>dashboard</html>"
        self.send_response(200)
        self.send_header("Content-Length", str(len(body)))
        self.end_headers()
        self.wfile.write(body)

    def log_message(self, *args):
        pass


def _run_bounded(monkeypatch, capsys, tmp_path, address, bound=1.5):
    monkeypatch.setattr(runner, "CONNECT_TIMEOUT", bound)
    start = time.monotonic()
    code = main(["study", str(STUDY), "-o", str(tmp_path / "s.parquet"), "-q", "--scheduler", address])
    took = time.monotonic() - start
    return code, took, capsys.readouterr().err


def test_issue27_scheduler_silent_listener_is_bounded(monkeypatch, capsys, tmp_path):
    sock, address = _silent_listener()
    try:
        code, took, err = _run_bounded(monkeypatch, capsys, tmp_path, address)
    finally:
        sock.close()
    assert code == 2, err
    assert took < 1.5 + 3, took
    assert f"--scheduler {address}: cannot reach the Dask scheduler (no answer within 1.5 s" in err
    assert "Traceback" not in err


def test_issue27_scheduler_http_server_is_bounded(monkeypatch, capsys, tmp_path):
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), _Page)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    address = f"tcp://127.0.0.1:{server.server_address[1]}"
    try:
        code, took, err = _run_bounded(monkeypatch, capsys, tmp_path, address)
    finally:
        server.shutdown()
        server.server_close()
    assert code == 2, err
    assert took < 1.5 + 3, took
    assert "cannot reach the Dask scheduler" in err and "8787" in err
    assert "Traceback" not in err


def test_issue27_scheduler_bound_holds_in_python(monkeypatch):
    monkeypatch.setattr(runner, "CONNECT_TIMEOUT", 1.0)
    model = camlink.load(FOUR_BAR)
    sock, address = _silent_listener()
    start = time.monotonic()
    try:
        with pytest.raises(camlink.ModelError, match="cannot reach the Dask scheduler"):
            camlink.sweep(model, {"a": [0.1]}, {"swing": range_of("rocker.phi")}, scheduler=address)
    finally:
        sock.close()
    assert time.monotonic() - start < 4


def test_issue27_scheduler_refused_and_worker_addresses(monkeypatch, capsys, tmp_path):
    from distributed import LocalCluster

    sock, address = _silent_listener()
    sock.close()  # nothing listens there now
    code, took, err = _run_bounded(monkeypatch, capsys, tmp_path, address, bound=1.0)
    assert code == 2 and took < 1.0 + 3, (code, took)
    host, port = address.removeprefix("tcp://").rsplit(":", 1)
    assert (f"--scheduler {address}: cannot reach the Dask scheduler (connection refused: "
            f"nothing listens on port {port} of {host})") in err
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False, protocol="tcp",
                      dashboard_address=None) as cluster:
        worker = next(iter(cluster.scheduler.workers))
        code, took, err = _run_bounded(monkeypatch, capsys, tmp_path, worker, bound=5.0)
    assert code == 2, err
    assert "cannot reach the Dask scheduler (what answers there is a Dask Worker)" in err


# --- 2. parameters named like the study's own columns ---------------------


def test_issue27_study_column_collision_keeps_swept_values(tmp_path):
    model = camlink.loads(COLLIDING, "toml", str(tmp_path / "block.toml"))
    values = {"variant": [0.1, 0.2], "key": [0.5, 0.7], "batch": [0.01], "error": [0.02, 0.03],
              "status": [0.004]}
    out = tmp_path / "sweep.parquet"
    table = camlink.sweep(model, values, {"top": max_of("block.x")}, output=out)
    assert len(table) == 8
    assert list(table.columns) == ["study.variant", *NAMES, "top", "study.status", "study.error",
                                   "study.key", "study.batch"]
    assert list(table["study.variant"]) == list(range(8))
    assert set(table["study.status"]) == {"ok"}
    grid = pd.DataFrame(camlink.study.sweep_variants(values))
    for name in NAMES:
        np.testing.assert_array_equal(table[name], grid[name])
    np.testing.assert_allclose(table["top"], grid.apply(_top, axis=1), rtol=0, atol=1e-12)
    # The files hold them too.
    back = pd.read_parquet(out).sort_values("study.variant", ignore_index=True)
    pd.testing.assert_frame_equal(back[table.columns], table)


def test_issue27_study_column_collision_from_the_command_line(tmp_path, capsys):
    (tmp_path / "block.toml").write_text(COLLIDING)
    (tmp_path / "study.toml").write_text(
        '[study]\nmodel = "block.toml"\nmode = "zip"\n'
        "[study.parameters]\nvariant = [0.1, 0.2]\nkey = [0.5, 0.6]\nbatch = [0.0, 0.01]\n"
        "error = [0.0, 0.02]\nstatus = [0.0, 0.003]\n"
        '[study.outputs]\ntop = { kind = "max", channel = "block.x" }\n'
    )
    out = tmp_path / "s.parquet"
    assert main(["study", str(tmp_path / "study.toml"), "-o", str(out)]) == 0
    assert "2 variants of block on local cores: 2 ok, 0 failed" in capsys.readouterr().out
    back = pd.read_parquet(out).sort_values("study.variant", ignore_index=True)
    assert list(back["status"]) == [0.0, 0.003] and list(back["batch"]) == [0.0, 0.01]
    assert list(back["study.status"]) == ["ok", "ok"]
    np.testing.assert_allclose(back["top"], back.apply(_top, axis=1), rtol=0, atol=1e-12)


def test_issue27_study_output_named_like_a_study_column_is_refused():
    model = camlink.loads(COLLIDING, "toml", "block.toml")
    with pytest.raises(camlink.ModelError, match=r"outputs\.study\.status: the name is taken"):
        camlink.sweep(model, {"key": [0.5]}, {"study.status": max_of("block.x")})


def test_issue27_study_old_batch_files_are_read_and_rewritten(tmp_path, monkeypatch):
    """A batch file written with unprefixed own columns (where a parameter
    named ``batch`` lost its values to the batch id) resumes without running
    again, and is rewritten with the prefix and the parameter's values."""
    model = camlink.loads(COLLIDING, "toml", str(tmp_path / "block.toml"))
    values = {"key": [0.5, 0.6], "batch": [0.01, 0.02]}
    out = tmp_path / "sweep.parquet"
    whole = camlink.sweep(model, values, {"top": max_of("block.x")}, output=out)
    (f,) = out.glob("batch-*.parquet")
    # The layout such a file had: the own columns overwrote the parameters.
    old = pd.DataFrame({"variant": whole["study.variant"], "key": whole["study.key"],
                        "batch": whole["study.batch"], "top": whole["top"],
                        "status": whole["study.status"], "error": whole["study.error"]})
    old.to_parquet(f, index=False)
    assert "batch" in pd.read_parquet(f).columns and "study.key" not in pd.read_parquet(f).columns

    def no_run(*args, **kwargs):
        raise AssertionError("a variant already in the folder ran again")

    monkeypatch.setattr(_core, "run_batch", no_run)
    again = camlink.sweep(model, values, {"top": max_of("block.x")}, output=out, check_outputs=False)
    pd.testing.assert_frame_equal(again, whole)
    rewritten = pd.read_parquet(f)
    pd.testing.assert_frame_equal(rewritten[whole.columns], whole)
    assert list(rewritten.columns) == list(whole.columns)


# --- 4. studies too large for memory -------------------------------------


def test_issue27_study_too_many_variants_is_refused_before_building():
    model = camlink.load(FOUR_BAR)
    grid = {p: np.linspace(0.1, 0.2, 1000) for p in ("a", "b", "c")}  # 10⁹ variants
    start = time.monotonic()
    with pytest.raises(camlink.ModelError, match=r"sweep \(grid\): 1,000,000,000 variants need about"):
        camlink.sweep(model, grid, {"swing": range_of("rocker.phi")})
    with pytest.raises(camlink.ModelError, match=r"sweep \(zip\): 1,000,000,000 variants need about"):
        camlink.sweep(model, {"a": range(10**9)}, {"swing": range_of("rocker.phi")}, mode="zip")
    with pytest.raises(camlink.ModelError, match="monte_carlo: 1,000,000,000 variants need about"):
        camlink.monte_carlo(model, {"a": stats.norm(0.12, 0.001)}, {"swing": range_of("rocker.phi")},
                            n=10**9)

    class Lazy(Sequence[dict[str, float]]):
        """10⁹ parameter sets, none built."""

        def __len__(self):
            return 10**9

        def __getitem__(self, k):
            if not 0 <= k < 10**9:
                raise IndexError(k)
            return {"a": 0.1}

    with pytest.raises(camlink.ModelError, match="study: 1,000,000,000 variants"):
        run_variants(model, Lazy(), {"swing": range_of("rocker.phi")})
    assert time.monotonic() - start < 5


def test_issue27_study_size_names_the_largest_part(monkeypatch):
    monkeypatch.setattr(runner, "_available_memory", lambda: 8_000_000_000)
    per = runner.BYTES_PER_VARIANT + 3 * runner.BYTES_PER_VALUE
    runner.check_size(8_000_000_000 // per, 3, "study")
    with pytest.raises(camlink.ModelError) as e:
        runner.check_size(8_000_000_000 // per + 1, 3, "study")
    most = 8_000_000_000 // per
    assert f"8 GB is available; split the study into parts of at most {most:,}" in str(e.value)


def test_issue27_study_file_too_many_variants_is_a_usage_error(tmp_path, capsys):
    (tmp_path / "study.toml").write_text(
        f'[study]\nmodel = "{FOUR_BAR}"\n'
        "[study.parameters]\na = { start = 0.1, stop = 0.2, num = 1000000000 }\n"
        '[study.outputs]\nswing = { kind = "range", channel = "rocker.phi" }\n'
    )
    start = time.monotonic()
    assert main(["study", str(tmp_path / "study.toml"), "-o", str(tmp_path / "s.parquet")]) == 2
    err = capsys.readouterr().err
    assert "study.toml: study.parameters: 1,000,000,000 variants need about" in err
    (tmp_path / "mc.toml").write_text(
        f'[study]\nmodel = "{FOUR_BAR}"\nkind = "monte_carlo"\nn = 2000000000\n'
        '[study.parameters]\na = { dist = "norm", loc = 0.12, scale = 0.001 }\n'
        '[study.outputs]\nswing = { kind = "range", channel = "rocker.phi" }\n'
    )
    assert main(["study", str(tmp_path / "mc.toml"), "-o", str(tmp_path / "m.parquet")]) == 2
    assert "mc.toml: study.n: 2,000,000,000 variants need about" in capsys.readouterr().err
    assert time.monotonic() - start < 5


# --- 6. schedulers and batch files the study cannot use --------------------


@pytest.mark.parametrize(("address", "says"), [
    ("tls://127.0.0.1:9", "a tls:// scheduler needs certificates"),
    ("wss://127.0.0.1:9", "a wss:// scheduler needs certificates"),
    ("ucx://127.0.0.1:9", "not ucx://"),
    ("inproc://127.0.0.1/1/2", "not inproc://"),
    ("nonsense://x", "not nonsense://"),
    ("tcp://[::1", "invalid address"),
    ("tcp://", "give the scheduler's host and port"),
])
def test_issue27_study_scheduler_scheme_is_a_usage_error(tmp_path, capsys, address, says):
    start = time.monotonic()
    code = main(["study", str(STUDY), "-o", str(tmp_path / "s.parquet"), "-q", "--scheduler", address])
    err = capsys.readouterr().err
    assert code == 2, err
    assert f"--scheduler {address}: " in err and says in err, err
    assert "internal error" not in err
    assert time.monotonic() - start < 5


@pytest.mark.parametrize(("column", "value", "says"), [
    ("study.status", 1, "column 'study.status' holds 1, not text"),
    ("study.status", "fine", "column 'study.status' holds 'fine', not one of ok"),
    ("study.error", None, "column 'study.error' holds None, not text"),
    ("study.key", 7.5, "column 'study.key' holds 7.5, not text"),
    ("swing", "wide", "column 'swing' holds 'wide', not a number"),
])
def test_issue27_study_resumed_batch_file_with_wrong_types(tmp_path, capsys, column, value, says):
    out = tmp_path / "s.parquet"
    assert main(["study", str(STUDY), "-o", str(out), "-q", "--batch-size", "5"]) == 0
    f = sorted(out.glob("batch-*.parquet"))[0]
    frame = pd.read_parquet(f)
    frame[column] = [value] * len(frame)
    frame.to_parquet(f, index=False)
    assert main(["study", str(STUDY), "-o", str(out), "-q"]) == 2
    err = capsys.readouterr().err
    assert f"{f}: {says}" in err and "delete it to run its variants again" in err, err
    assert "internal error" not in err
