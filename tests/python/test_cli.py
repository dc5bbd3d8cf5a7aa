"""The `camlink` command: exit statuses, messages, no tracebacks."""

from __future__ import annotations

import json
import tomllib

import pytest

from camlink.results import Results
from conftest import ROOT, run_cli

BAD = ROOT / "tests" / "models" / "bad"


def assert_clean(proc):
    assert "Traceback" not in proc.stderr, proc.stderr
    assert "panicked" not in proc.stderr, proc.stderr


def test_run_writes_csv_next_to_cwd_and_exits_0(four_bar_file, tmp_path):
    proc = run_cli("run", four_bar_file, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert "101 steps" in proc.stdout and "four_bar.csv" in proc.stdout
    res = Results.load(tmp_path / "four_bar.csv")
    assert len(res) == 101


def test_run_with_options(four_bar_file, tmp_path):
    out = tmp_path / "r.parquet"
    proc = run_cli(
        "run", four_bar_file, "-o", out, "--t-end", "0.3", "--step", "0.05", "-p", "rocker.B"
    )
    assert proc.returncode == 0, proc.stderr
    res = Results.load(out)
    assert len(res) == 7
    assert "rocker.B.x" in res.channels and "coupler.P.x" not in res.channels


def test_analysis_failure_exits_1_and_keeps_results(stuck_file, tmp_path):
    out = tmp_path / "run.csv"
    proc = run_cli("run", stuck_file, "-o", out, "--t-end", "0.5")
    assert proc.returncode == 1
    assert_clean(proc)
    assert proc.stderr.startswith("camlink: error: at t = ")
    assert "residual" in proc.stderr and "joints involved: " in proc.stderr
    partial = tmp_path / "run.partial.csv"
    assert f"written to {partial}" in proc.stderr
    assert len(Results.load(partial)) > 5
    assert not out.exists()


@pytest.mark.parametrize(
    "args, fragment",
    [
        (["run", "missing.toml"], "missing.toml: no such model file"),
        (["check", "missing.toml"], "missing.toml"),
        (["run", "{model}", "-o", "out.xlsx"], "unknown file type"),
        (["run", "{model}", "-o", "no/such/dir/out.csv"], "No such file or directory"),
        (["run", "{model}", "--step", "0"], "step"),
        (["run", "{model}", "-p", "coupler.Q"], "no point 'Q'"),
        (["run", "{model}", "--t-end", "soon"], "invalid float value"),
        (["frobnicate"], "invalid choice"),
    ],
)
def test_bad_input_exits_2_without_traceback(four_bar_file, tmp_path, args, fragment):
    args = [a.format(model=four_bar_file) for a in args]
    proc = run_cli(*args, cwd=tmp_path)
    assert proc.returncode == 2, proc.stderr
    assert_clean(proc)
    assert fragment in proc.stderr
    assert proc.stderr.startswith(("camlink: error:", "usage:"))


def test_directory_as_model_exits_2(tmp_path):
    proc = run_cli("check", tmp_path)
    assert proc.returncode == 2
    assert_clean(proc)


def bad_models():
    expected = BAD / "expected.toml"
    if not expected.exists():
        return []
    return sorted(tomllib.loads(expected.read_text()).items())


@pytest.mark.skipif(not bad_models(), reason="tests/models/bad not present")
@pytest.mark.parametrize("name, fragments", bad_models() or [("", [])])
@pytest.mark.parametrize("command", ["check", "run"])
def test_broken_model_files(tmp_path, name, fragments, command):
    proc = run_cli(command, BAD / name, cwd=tmp_path)
    assert proc.returncode == 2, proc.stdout + proc.stderr
    assert_clean(proc)
    assert proc.stderr.startswith("camlink: error: ")
    for fragment in fragments:
        assert fragment in proc.stderr


def test_check_reports_constraints_and_dof(four_bar_file):
    proc = run_cli("check", four_bar_file)
    assert proc.returncode == 0, proc.stderr
    out = proc.stdout
    assert "coordinates  9" in out
    assert "equations    9" in out
    assert "revolute" in out and "motor" in out
    assert "degrees of freedom  0" in out


def test_check_json(four_bar_file):
    proc = run_cli("check", four_bar_file, "--json")
    assert proc.returncode == 0
    report = json.loads(proc.stdout)
    assert report["dof"] == 0 and report["model"] == "four_bar"


def test_check_under_driven_model_names_the_free_motion(tmp_path):
    from conftest import four_bar_toml

    text = four_bar_toml()
    text = text[: text.index("[[drivers]]")] + text[text.index("[analysis]") :]
    path = tmp_path / "free.toml"
    path.write_text(text)
    proc = run_cli("check", path)
    assert proc.returncode == 0, proc.stderr
    assert "degrees of freedom  1" in proc.stdout
    assert "free motion 1:" in proc.stdout


def test_schema_is_json():
    proc = run_cli("schema")
    assert proc.returncode == 0
    schema = json.loads(proc.stdout)
    assert isinstance(schema, dict)


def test_version():
    proc = run_cli("--version")
    assert proc.returncode == 0 and proc.stdout.startswith("camlink ")


def test_schema_into_a_closed_pipe_is_quiet():
    import subprocess
    import sys

    proc = subprocess.run(
        f'"{sys.executable}" -m camlink schema | head -1',
        shell=True,
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert proc.stdout.strip() == "{"
    assert proc.stderr == ""
