"""Studies on Dask: a real LocalCluster with two worker processes runs the
same study as the local cores, identically; a worker killed mid-batch has
its batch run again; `camlink study --scheduler` sends a study file there."""

from __future__ import annotations

import logging
import os
import signal
import threading
import time
from collections.abc import Iterable

import numpy as np
import pandas as pd
import pytest

import camlink
from camlink.cli import main
from camlink.study import least_transmission_angle, range_of
from conftest import ROOT

distributed = pytest.importorskip("distributed")

FOUR_BAR = ROOT / "examples" / "four_bar.toml"
OUTPUTS = {"swing": range_of("rocker.phi"), "mu": least_transmission_angle("coupler", "rocker")}


@pytest.fixture(scope="module")
def client():
    """One LocalCluster for the module: two worker processes, one thread each."""
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
        silence_logs=logging.CRITICAL,
    ) as cluster, distributed.Client(cluster) as c:
        yield c


def test_dask_and_local_cores_give_identical_results(client, tmp_path):
    model = camlink.load(FOUR_BAR)
    values: dict[str, Iterable[float]] = {"a": np.linspace(0.08, 0.14, 12), "c": [0.3, 0.31]}
    local = camlink.sweep(model, values, OUTPUTS, batch_size=5)
    out = tmp_path / "dask.parquet"
    on_dask = camlink.sweep(model, values, OUTPUTS, batch_size=5, client=client, output=out)
    pd.testing.assert_frame_equal(local, on_dask)
    assert len(list(out.glob("batch-*.parquet"))) == 5
    # Run again: everything is in the folder, no batch is sent.
    sent: list[object] = []
    submit = client.submit

    def spy(*a, **k):
        sent.append(a)
        return submit(*a, **k)

    client.submit = spy
    try:
        again = camlink.sweep(model, values, OUTPUTS, batch_size=5, client=client, output=out)
    finally:
        client.submit = submit
    pd.testing.assert_frame_equal(again, on_dask)
    assert sent == []


def test_the_example_study_runs_on_a_scheduler_address(client, tmp_path, capsys):
    out = tmp_path / "sweep.parquet"
    address = client.scheduler.address
    assert main(["study", str(ROOT / "examples" / "study_four_bar.toml"), "-o", str(out),
                 "--scheduler", address]) == 0
    assert f"9 variants of four_bar on {address}: 9 ok" in capsys.readouterr().out
    local = tmp_path / "local.parquet"
    assert main(["study", str(ROOT / "examples" / "study_four_bar.toml"), "-o", str(local), "-q"]) == 0
    a = pd.read_parquet(out).sort_values("study.variant", ignore_index=True)
    b = pd.read_parquet(local).sort_values("study.variant", ignore_index=True)
    pd.testing.assert_frame_equal(a, b)


def test_an_unreachable_scheduler_is_a_clear_error(capsys):
    assert main(["study", str(ROOT / "examples" / "study_four_bar.toml"), "-o", "/tmp/none.parquet",
                 "--scheduler", "tcp://127.0.0.1:9"]) == 2
    assert "cannot reach the Dask scheduler" in capsys.readouterr().err


def test_a_worker_killed_mid_batch_has_its_batch_run_again(client, tmp_path):
    # Slow variants (2 crank turns in 8000 steps) so that batches take a while.
    text = FOUR_BAR.read_text().replace("step = 0.005", "step = 0.00025")
    model = camlink.loads(text, "toml", str(FOUR_BAR))
    values = {"a": np.linspace(0.08, 0.14, 24)}
    pids = client.run(os.getpid)
    killed: list[int] = []

    def kill_a_busy_worker():
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and not killed:
            busy = [w for w, tasks in client.processing().items() if tasks and w in pids]
            if busy:
                time.sleep(0.2)  # well inside the batch
                os.kill(pids[busy[0]], signal.SIGKILL)
                killed.append(pids[busy[0]])
            time.sleep(0.02)

    killer = threading.Thread(target=kill_a_busy_worker)
    killer.start()
    out = tmp_path / "killed.parquet"
    try:
        on_dask = camlink.sweep(model, values, OUTPUTS, batch_size=4, client=client, output=out)
    finally:
        killer.join()
    assert killed, "no worker was busy to kill"
    # The sweep may finish before the scheduler notices the dead worker; a
    # broadcast to it then fails on its closed connection. Wait until the
    # scheduler has dropped it and the nanny's replacement has joined.
    dead = next(w for w, pid in pids.items() if pid == killed[0])
    deadline = time.monotonic() + 60
    while dead in client.scheduler_info()["workers"] and time.monotonic() < deadline:
        time.sleep(0.1)
    assert dead not in client.scheduler_info()["workers"], "the scheduler still lists the killed worker"
    client.wait_for_workers(2, timeout=60)
    assert killed[0] not in client.run(os.getpid).values()
    local = camlink.sweep(model, values, OUTPUTS, batch_size=4)
    pd.testing.assert_frame_equal(on_dask, local)
    assert set(on_dask["study.status"]) == {"ok"}
    assert len(list(out.glob("batch-*.parquet"))) == 6
    client.wait_for_workers(2, timeout=60)
