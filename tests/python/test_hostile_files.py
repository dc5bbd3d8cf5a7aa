"""What camlink defends at the file system: a model cannot read files outside
its folder, data files are capped and regular, a run never writes over its
inputs or a good earlier output, and a file being written stays readable
whatever stops the process (SIGKILL, SIGTERM, SIGHUP, Ctrl-C)."""

from __future__ import annotations

import _thread
import os
import random
import shutil
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pyarrow.parquet as pq
import pytest

import camlink
from camlink import ModelError, Results
from conftest import ROOT, four_bar_toml, run_cli

EXAMPLES = ROOT / "examples"


def cam_model(folder: Path, file: str, name: str = "cam.toml") -> Path:
    """The CSV-profile cam example in `folder`, reading its points from `file`."""
    text = (EXAMPLES / "cam_csv_profile.toml").read_text()
    text = text.replace('file = "data/cam_profile.csv"', f'file = "{file}"')
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / name
    path.write_text(text)
    return path


PROFILE = EXAMPLES / "data" / "cam_profile.csv"


# -- reading: confined, capped, quoted briefly --------------------------------


def test_data_file_outside_the_model_folder_is_refused(tmp_path):
    secret = tmp_path / "secret.csv"
    secret.write_text("user,hash\nroot,$6$secret-hash$\n")
    model = cam_model(tmp_path / "shared", "../secret.csv")
    with pytest.raises(ModelError, match="outside the model's folder") as e:
        camlink.load(model)
    assert "secret-hash" not in str(e.value)
    proc = run_cli("check", model)
    assert proc.returncode == 2, proc.stderr
    assert "outside the model's folder" in proc.stderr and "secret-hash" not in proc.stderr
    # Opted in, the file is read (and is no points file).
    with pytest.raises(ModelError) as e:
        camlink.load(model, allow_outside=True)
    assert "outside" not in str(e.value).replace(str(tmp_path), "")
    shutil.copy(PROFILE, secret)
    assert run_cli("check", "--allow-outside-data", model).returncode == 0


def test_symlink_leaving_the_model_folder_is_refused(tmp_path):
    shutil.copy(PROFILE, tmp_path / "profile.csv")
    folder = tmp_path / "shared"
    model = cam_model(folder, "link.csv")
    (folder / "link.csv").symlink_to(tmp_path / "profile.csv")
    with pytest.raises(ModelError, match="outside the model's folder"):
        camlink.load(model)
    assert camlink.load(model, allow_outside=True).inputs[-1] == (tmp_path / "profile.csv").resolve()


def test_loads_resolves_data_files_against_base_dir(tmp_path):
    shutil.copy(PROFILE, tmp_path / "p.csv")
    text = cam_model(tmp_path, "p.csv").read_text()
    model = camlink.loads(text, base_dir=tmp_path)
    assert model.inputs == [(tmp_path / "p.csv").resolve()]
    with pytest.raises(ModelError, match="outside the model's folder"):
        (tmp_path / "sub").mkdir()
        camlink.loads(text.replace('"p.csv"', '"../p.csv"'), base_dir=tmp_path / "sub")


def test_bad_line_is_quoted_briefly_and_escaped(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("alpha,rho\n0,1\n" + "\x1b[2J" + "z" * 5_000_000 + "\n")
    with pytest.raises(ModelError) as e:
        camlink.load(cam_model(tmp_path, "bad.csv"))
    message = str(e.value)
    assert len(message) < 400, len(message)
    assert "bad.csv:3:" in message and "\x1b" not in message


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs FIFOs")
def test_devices_and_fifos_are_refused_at_once(tmp_path):
    (tmp_path / "zero.csv").symlink_to("/dev/zero")
    os.mkfifo(tmp_path / "fifo.csv")
    # Refused from their metadata: reading /dev/zero never ends, and
    # opening a FIFO blocks until a writer comes.
    for name in ("zero.csv", "fifo.csv"):
        with pytest.raises(ModelError, match="not a regular file"):
            camlink.load(cam_model(tmp_path, name), allow_outside=True)


# -- writing: never over an input, never over a good file ----------------------


def test_default_output_named_like_a_data_file_is_refused(tmp_path):
    # cam.toml reading cam.csv: `camlink run cam.toml` wrote cam.csv.
    shutil.copy(PROFILE, tmp_path / "cam.csv")
    cam_model(tmp_path, "cam.csv")
    before = (tmp_path / "cam.csv").read_bytes()
    proc = run_cli("run", "cam.toml", cwd=tmp_path)
    assert proc.returncode == 2, proc.stderr
    assert "is an input of the model" in proc.stderr
    assert (tmp_path / "cam.csv").read_bytes() == before
    # --force does not make an input writable either.
    assert run_cli("run", "cam.toml", "--force", cwd=tmp_path).returncode == 2
    assert (tmp_path / "cam.csv").read_bytes() == before


def test_output_naming_an_input_or_a_link_to_one_is_refused(tmp_path, four_bar_file):
    shutil.copy(PROFILE, tmp_path / "profile.csv")
    model = cam_model(tmp_path, "profile.csv")
    (tmp_path / "link.csv").symlink_to(tmp_path / "profile.csv")
    os.link(four_bar_file, tmp_path / "hard.csv")
    for out, m in [("profile.csv", model), ("link.csv", model), ("hard.csv", four_bar_file)]:
        before = (tmp_path / out).read_bytes()
        proc = run_cli("run", m, "-o", out, cwd=tmp_path)
        assert proc.returncode == 2, (out, proc.stderr)
        assert "is an input of the model" in proc.stderr
        assert (tmp_path / out).read_bytes() == before
    with pytest.raises(ModelError, match="is an input"):
        camlink.load(model).run(output=tmp_path / "link.csv")


def test_default_output_is_not_replaced_without_force(tmp_path, four_bar_file):
    assert run_cli("run", four_bar_file, cwd=tmp_path).returncode == 0
    proc = run_cli("run", four_bar_file, cwd=tmp_path)
    assert proc.returncode == 2
    assert "four_bar.csv exists; pass --force" in proc.stderr
    assert run_cli("run", four_bar_file, "--force", cwd=tmp_path).returncode == 0


@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_failed_rerun_keeps_the_good_output(tmp_path, four_bar_file, stuck_file, suffix):
    out = tmp_path / f"out{suffix}"
    assert run_cli("run", four_bar_file, "-o", out).returncode == 0
    good = out.read_bytes()
    # A re-run that fails at its first step wrote a header over it.
    proc = run_cli("run", stuck_file, "-o", out, "--t-end", "0.5")
    assert proc.returncode == 1
    assert out.read_bytes() == good
    assert len(Results.load(tmp_path / f"out.partial{suffix}")) > 0


def test_concurrent_runs_on_one_output_leave_one_whole_file(tmp_path, four_bar_file):
    # Two runs with different widths wrote interleaved rows and both exited 0.
    out = tmp_path / "same.csv"
    args = [sys.executable, "-m", "camlink", "run", str(four_bar_file), "-o", str(out),
            "--t-end", "20", "--step", "0.0005"]
    procs = [
        subprocess.Popen(args, stderr=subprocess.PIPE, text=True),
        subprocess.Popen([*args, "-p", "coupler.P"], stderr=subprocess.PIPE, text=True),
    ]
    for p in procs:
        _, err = p.communicate(timeout=120)
        assert p.returncode == 0, err
    # Either run's file, whole: every row as wide as the header.
    res = Results.load(out)
    assert len(res) == 40001
    assert sorted(p.name for p in tmp_path.glob("same*")) == ["same.csv", "same.csv.json"]


# -- stopping: SIGKILL, SIGTERM, SIGHUP, Ctrl-C --------------------------------


def wait_for_rows(folder: Path, pattern: str, size: int = 4096) -> None:
    """Waits (on a busy machine, long) until a run's temporary file holds
    more than `size` bytes."""
    deadline = time.monotonic() + 90
    while time.monotonic() < deadline:
        if any(p.stat().st_size > size for p in folder.glob(pattern)):
            return
        time.sleep(0.05)
    raise AssertionError(f"no {pattern} grew in {folder}")

def wait_for_line(folder: Path, pattern: str, start: str) -> None:
    """Waits (on a busy machine, long) until a run's temporary file holds a
    line starting with `start`."""
    deadline = time.monotonic() + 90
    while time.monotonic() < deadline:
        for p in folder.glob(pattern):
            if any(line.startswith(start) for line in p.read_text().splitlines()):
                return
        time.sleep(0.05)
    raise AssertionError(f"no line {start!r} in {pattern} in {folder}")


LONG_RUN = """
import sys, camlink
camlink.model.CHUNK_ROWS = 64
camlink.load(sys.argv[1]).simulate(t_end=1000, step=0.001, h=0.001, output=sys.argv[2])
"""


@pytest.mark.parametrize("suffix", [".csv", ".parquet"])
def test_sigkill_at_random_times_leaves_a_readable_file(tmp_path, suffix):
    model = tmp_path / "fb.toml"
    model.write_text(four_bar_toml())
    rng = random.Random(15)
    for k in range(3):
        out = tmp_path / f"k{k}{suffix}"
        proc = subprocess.Popen([sys.executable, "-c", LONG_RUN, str(model), str(out)])
        wait_for_rows(tmp_path, f"k{k}.partial-*")
        time.sleep(rng.uniform(0.0, 1.0))
        proc.kill()
        proc.wait()
        assert not out.exists()
        # The temporary file (a CSV's metadata sidecar beside it).
        (temp,) = [p for p in tmp_path.glob(f"k{k}.partial-*") if p.suffix != ".json"]
        res = Results.load(temp)
        assert len(res) >= 64, len(res)
        t = res.t
        np.testing.assert_allclose(t, 0.001 * np.arange(len(t)), rtol=0, atol=1e-9)
        assert np.all(np.isfinite(res.data))


@pytest.mark.parametrize("signame", ["SIGTERM", "SIGHUP"])
def test_sigterm_and_sighup_stop_like_ctrl_c(tmp_path, four_bar_file, signame):
    # SIGTERM left a Parquet file without a footer.
    out = tmp_path / "out.parquet"
    proc = subprocess.Popen(
        [sys.executable, "-m", "camlink", "run", str(four_bar_file), "-a", "dynamics",
         "--t-end", "100", "--step", "1e-4", "-o", str(out)],
        stderr=subprocess.PIPE, text=True,
    )
    wait_for_rows(tmp_path, "out.partial-*")
    sig = getattr(signal, signame)
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=30)
    assert proc.returncode == 128 + sig, err
    partial = tmp_path / "out.partial.parquet"
    assert f"interrupted; the steps computed are in {partial}" in err
    assert "Traceback" not in err
    table = pq.read_table(partial)
    assert table.num_rows > 0
    assert not out.exists()


def test_ctrl_c_stops_a_run_whose_rows_are_far_apart(four_bar_file):
    # Signals were checked every 1024 rows: this run, 1e8 steps per row,
    # ignored Ctrl-C until its end. It must stop within the first rows,
    # keeping them, with exit code 130 (the timeout only guards the suite).
    # One row per chunk, so that the row at t = 0 reaches the file from
    # inside the run: once it is there, the run is in its long stretch.
    out = four_bar_file.with_name("x.csv")
    cli = "import sys, camlink.model, camlink.cli; camlink.model.CHUNK_ROWS = 1; " \
          "sys.exit(camlink.cli.main(sys.argv[1:]))"
    proc = subprocess.Popen(
        [sys.executable, "-c", cli, "run", str(four_bar_file), "-a", "dynamics",
         "--t-end", "1000", "--step", "100", "--h", "1e-6", "-o", str(out)],
        stderr=subprocess.PIPE, text=True,
    )
    wait_for_line(four_bar_file.parent, "x.partial-*", "0.0,")
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, err
    assert "interrupted" in err
    partial = out.with_name("x.partial.csv")
    rows = Results.load(partial)
    assert 1 <= len(rows) < 11, len(rows)
    assert rows.t[0] == 0.0
    assert not out.exists()


def test_keyboard_interrupt_reaches_python_during_a_run(four_bar_file):
    # KeyboardInterrupt arrived only at the end of the run: here, after
    # 1e9 integration steps. It must stop the run within its first rows.
    model = camlink.load(four_bar_file)
    rows: list[int] = []
    timer = threading.Timer(0.5, _thread.interrupt_main)
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        model.simulate(t_end=1000, step=100, h=1e-6, on_rows=rows.append)
    timer.cancel()
    assert sum(rows) < 11, rows


# -- names and channels that break outputs -------------------------------------


def test_duplicate_output_points_are_refused(four_bar_file, tmp_path):
    # `-p coupler.P -p coupler.P` gave 40 CSV columns but 34 in Parquet.
    proc = run_cli("run", four_bar_file, "-p", "coupler.P", "-p", "coupler.P", cwd=tmp_path)
    assert proc.returncode == 2
    assert "point 'coupler.P' is listed twice" in proc.stderr
    with pytest.raises(ModelError, match="listed twice"):
        camlink.load(four_bar_file).run(points=["coupler.P", "coupler.P"])


def test_csv_header_is_quoted_and_numbers_are_shortest(tmp_path):
    # A channel name with a comma split the header; %.17g wrote 0.3 as
    # 0.29999999999999999.
    res = Results(["t", "a,b", 'say "hi"'], np.array([[0.3, 0.1 + 0.2, -0.0]]))
    out = res.save(tmp_path / "r.csv")
    text = "".join(line for line in out.open() if not line.startswith("# "))
    assert text == 't,"a,b","say ""hi"""\n0.3,0.30000000000000004,0.0\n'
    back = Results.load(out)
    assert back.channels == ["a,b", 'say "hi"']
    rng = np.random.default_rng(9)
    values = rng.standard_normal(200) * 10.0 ** rng.integers(-300, 300, 200)
    data = np.column_stack([np.arange(200.0), values])
    again = Results.load(Results(["t", "x"], data).save(tmp_path / "x.csv"))
    np.testing.assert_array_equal(again.data, data)


# -- settings: one validation for file, CLI and Python -------------------------


@pytest.mark.parametrize(
    "args, option",
    [
        (["--max-iter", "-5"], "--max-iter: max_iter must be a whole number of at least 1 (-5)"),
        (["--max-iter", "0"], "--max-iter: max_iter must be"),
        (["--tol", "-1"], "--tol: tol must be a positive finite number (-1)"),
        (["--tol", "0"], "--tol: tol must be a positive"),
        (["--tol", "nan"], "--tol: tol must be a positive finite number (NaN)"),
        (["-a", "dynamics", "--h", "-1"], "--h: h must be"),
        (["-a", "dynamics", "--rho-inf", "2"], "--rho-inf: rho_inf must be between 0 and 1"),
        (["-a", "dynamics", "--adaptive", "--atol", "-1"], "--atol: atol must be"),
        (["-a", "dynamics", "--adaptive", "--h-min", "nan"], "--h-min: h_min must be"),
    ],
)
def test_cli_settings_exit_2_naming_the_option(four_bar_file, tmp_path, args, option):
    proc = run_cli("run", four_bar_file, "-o", "x.csv", *args, cwd=tmp_path)
    assert proc.returncode == 2, proc.stderr
    assert option in proc.stderr, proc.stderr
    assert "Traceback" not in proc.stderr


@pytest.mark.parametrize(
    "call, fragment",
    [
        (lambda m: m.kinematics(max_iter=1.5), "max_iter must be a whole number"),
        (lambda m: m.kinematics(max_iter=0), "max_iter must be"),
        (lambda m: m.kinematics(tol=float("nan")), "tol must be a positive finite number"),
        (lambda m: m.simulate(adaptive=True, atol=-1), "atol must be"),
        (lambda m: m.simulate(adaptive=True, h_min=float("nan")), "h_min must be"),
        (lambda m: m.simulate(adaptive="no"), "adaptive must be True or False"),
        (lambda m: m.equilibrium(time=float("nan")), "time must be a finite number"),
        (lambda m: m.kinematics(tol="1e-9"), "tol must be a number"),
    ],
)
def test_python_settings_are_checked_like_the_file(four_bar_file, call, fragment):
    with pytest.raises(ModelError, match=fragment):
        call(camlink.load(four_bar_file))


def test_file_settings_follow_the_same_rules(tmp_path):
    text = four_bar_toml().replace("[analysis]", "[analysis]\ntol = -1")
    with pytest.raises(ModelError, match=r"analysis.tol: tol must be a positive finite number \(-1\)"):
        camlink.loads(text)


def test_lone_surrogate_in_loads_is_a_model_error():
    with pytest.raises(ModelError, match="lone surrogate"):
        camlink.loads('[model]\nname = "a\udc80"\n')


def test_points_may_be_one_string(four_bar_file):
    res = camlink.load(four_bar_file).run(points="coupler.P", t_end=0.1)
    assert "coupler.P.x" in res.channels and "c.x" not in " ".join(res.channels)


# -- small edges ----------------------------------------------------------------


def test_results_say_how_to_get_rows(four_bar_file):
    res = camlink.load(four_bar_file).run(t_end=0.1)
    for bad in (lambda: list(res), lambda: res[0], lambda: res[0:10]):  # type: ignore[index]
        with pytest.raises(TypeError, match=r"res\.data"):
            bad()


def test_results_load_of_a_bad_file_says_read(tmp_path):
    bad = tmp_path / "r.xlsx"
    bad.write_text("x")
    with pytest.raises(ModelError, match="cannot read results from"):
        Results.load(bad)
    broken = tmp_path / "r.parquet"
    broken.write_text("not parquet")
    with pytest.raises(ModelError, match="cannot read results from"):
        Results.load(broken)


def test_error_unrelated_to_residuals_prints_no_zero_residual(four_bar_file, tmp_path,
                                                             monkeypatch, capsys):
    # Errors with nothing to do with residuals ended "largest residual: 0".
    from camlink import cli

    def fail(self, **kwargs):
        e = camlink.AnalysisError("at t = 0 s: times must increase")
        e.time, e.joints, e.residual = 0.0, [], 0.0
        e.results = Results(["t"], np.empty((0, 1)), complete=False)
        e.output = None
        raise e

    monkeypatch.setattr(camlink.Model, "run", fail)
    monkeypatch.chdir(tmp_path)
    assert cli.main(["run", str(four_bar_file), "-o", "o.csv"]) == 1
    assert "largest residual" not in capsys.readouterr().err


def test_numbers_in_messages_are_readable(four_bar_file, tmp_path):
    # `step = 1e-300` printed a 300-digit step and "18446744073709551615 steps".
    proc = run_cli("run", four_bar_file, "--step", "1e-300", "-o", "o.csv", cwd=tmp_path)
    assert proc.returncode == 2
    assert "2e+300 steps (2 s at 1e-300 s)" in proc.stderr or "1e+300 steps" in proc.stderr, proc.stderr
    assert max(len(w) for w in proc.stderr.split()) < 40


# -- extreme steps ----------------------------------------------------------------


def _pendulum() -> camlink.Model:
    return camlink.loads((EXAMPLES / "dyn_pendulum.toml").read_text())


def test_huge_step_still_reaches_every_output_time():
    # simulate(h=1e15) took no step: a frozen pendulum, exit 0.
    m = _pendulum()
    a = m.simulate(t_end=0.5, step=0.01, h=1e15)
    b = m.simulate(t_end=0.5, step=0.01, h=0.01)
    np.testing.assert_array_equal(a.data, b.data)
    assert np.ptp(a.data[:, 3]) > 1e-3  # the first body's angle moved


def test_adaptive_step_below_rounding_fails_clearly():
    # atol=1e-300 with h_min=1e-300 took steps where t + h == t, for ever.
    # The driven pendulum meets it within a few steps (the free one of
    # dyn_pendulum.toml only after thousands).
    model = camlink.load(EXAMPLES / "pendulum.toml")
    with pytest.raises(camlink.AnalysisError, match="below the rounding of t"):
        model.simulate(t_end=0.5, step=0.1, adaptive=True, atol=1e-300, h_min=1e-300)


def test_models_pickle_through_their_text(tmp_path):
    # multiprocessing and joblib failed: Model could not be pickled.
    import pickle

    shutil.copy(PROFILE, tmp_path / "p.csv")
    for model in (
        camlink.load(EXAMPLES / "four_bar.toml"),
        camlink.load(cam_model(tmp_path, "p.csv")),
        camlink.loads((EXAMPLES / "pendulum.toml").read_text()),
    ):
        copy = pickle.loads(pickle.dumps(model))
        assert copy.name == model.name and copy.source == model.source
        np.testing.assert_array_equal(copy.run(t_end=0.1).data, model.run(t_end=0.1).data)
    forced = camlink.load(EXAMPLES / "dyn_pendulum.toml").with_force(
        "push", "arm", lambda t, q, qd: (0.0, 0.0, 0.0)
    )
    with pytest.raises(TypeError, match="cannot be pickled"):
        pickle.dumps(forced)


def test_stdin_model_and_stdout_csv(tmp_path):
    text = four_bar_toml()
    proc = subprocess.run(
        [sys.executable, "-m", "camlink", "run", "-", "-o", "-", "--t-end", "0.1"],
        input=text, capture_output=True, text=True, cwd=tmp_path, timeout=120,
    )
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.splitlines()
    assert lines[0].startswith("t,crank.x") and len(lines) == 12
    assert list(tmp_path.iterdir()) == []
    back = camlink.loads(text).run(t_end=0.1)
    assert lines[1].split(",")[0] == "0.0" and float(lines[-1].split(",")[0]) == back.t[-1]


def test_check_reports_an_assembly_failure_with_the_open_joints(tmp_path):
    # `check` said "add 1 driver" for a loop that cannot close, and never
    # printed the residual it found.
    text = four_bar_toml(r=1.0, L=0.5, b=0.5, d=3.0)
    start = text.index("[[drivers]]")
    end = text.index("[analysis]")
    model = tmp_path / "open.toml"
    model.write_text(text[:start] + text[end:])
    proc = run_cli("check", model)
    assert proc.returncode == 0, proc.stderr
    assert "assembly     failed: largest |Φ|" in proc.stdout, proc.stdout
    assert "stays open by" in proc.stdout
    assert "add 1 driver" not in proc.stdout
    report = camlink.load(model).check()
    assert report["open_joints"] and report["residual"] > 0.1


def test_parquet_output_carries_its_metadata(four_bar_file, tmp_path):
    out = tmp_path / "m.parquet"
    res = camlink.load(four_bar_file).run(t_end=0.1, output=out)
    back = Results.load(out)
    assert back.model == res.model == "four_bar"
    assert back.summary["analysis"] == "kinematics"
    assert back.summary["steps"] == res.summary["steps"]
    import json as _json

    meta = _json.loads(pq.read_schema(out).metadata[b"camlink"])
    assert meta["camlink"] == camlink.__version__ and meta["analysis"] == "kinematics"
