"""The `camlink` command with the dynamic analyses: the file's analysis type
or --analysis, exit statuses, design warnings and verbose output."""

from __future__ import annotations

import pytest

from camlink.results import Results
from conftest import ROOT, run_cli

EXAMPLES = ROOT / "examples"


def assert_clean(proc):
    assert "Traceback" not in proc.stderr, proc.stderr
    assert "panicked" not in proc.stderr, proc.stderr


@pytest.mark.parametrize(
    ("example", "kind", "rows", "channel"),
    [
        ("pendulum.toml", "kinematics", 201, "arm.phi"),
        ("dyn_slider_crank.toml", "inverse_dynamics", 1001, "motor.effort"),
        ("dyn_spring_pendulum.toml", "equilibrium", 1, "pivot.fy_j"),
        ("dyn_pendulum.toml", "dynamics", 3001, "energy.total"),
    ],
)
def test_run_uses_the_files_analysis_and_exits_0(tmp_path, example, kind, rows, channel):
    out = tmp_path / "out.csv"
    proc = run_cli("run", EXAMPLES / example, "-o", out)
    assert proc.returncode == 0, proc.stderr
    assert_clean(proc)
    assert proc.stdout.startswith(f"{kind} of ")
    res = Results.load(out)
    assert len(res) == rows and channel in res.channels
    if kind == "dynamics":
        assert "energy drift" in proc.stdout


def test_analysis_option_overrides_the_file(tmp_path, four_bar_file):
    out = tmp_path / "out.csv"
    proc = run_cli("run", EXAMPLES / "dyn_slider_crank.toml", "-o", out, "--analysis", "kinematics")
    assert proc.returncode == 0, proc.stderr
    assert "motor.effort" not in Results.load(out).channels
    proc = run_cli("run", four_bar_file, "-o", out, "-a", "inverse_dynamics", "--t-end", "0.2")
    assert proc.returncode == 0, proc.stderr
    assert "O.fx" in Results.load(out).channels
    proc = run_cli(
        "run", EXAMPLES / "dyn_pendulum.toml", "-o", out, "--t-end", "0.5", "--h", "5e-4",
        "--rho-inf", "0.7", "--adaptive",
    )
    assert proc.returncode == 0, proc.stderr
    assert len(Results.load(out)) == 501


def test_settings_that_do_not_fit_exit_2(tmp_path):
    proc = run_cli("run", EXAMPLES / "dyn_slider_crank.toml", "-o", tmp_path / "o.csv", "--rho-inf", "0.5")
    assert proc.returncode == 2
    assert_clean(proc)
    assert "`rho_inf` does not apply to the inverse_dynamics analysis" in proc.stderr
    bad = tmp_path / "bad.toml"
    bad.write_text(
        (EXAMPLES / "dyn_spring_pendulum.toml").read_text().replace(
            'type = "equilibrium"', 'type = "equilibrium"\nt_end = 1'
        )
    )
    proc = run_cli("run", bad, "-o", tmp_path / "o.csv")
    assert proc.returncode == 2
    assert "analysis.t_end: `t_end` does not apply to type = \"equilibrium\"" in proc.stderr
    proc = run_cli("run", bad, "--analysis", "statics")
    assert proc.returncode == 2 and "invalid choice" in proc.stderr


def test_analysis_that_cannot_proceed_exits_1(tmp_path):
    # Inverse dynamics needs a driven mechanism; the free pendulum has 1 DOF.
    proc = run_cli("run", EXAMPLES / "dyn_pendulum.toml", "-o", tmp_path / "o.csv", "-a", "inverse_dynamics")
    assert proc.returncode == 1, proc.stderr
    assert_clean(proc)
    assert proc.stderr.startswith("camlink: error: ")
    # No equilibrium: a constant torque on a pendulum without gravity.
    free = tmp_path / "free.toml"
    free.write_text(
        (EXAMPLES / "dyn_pendulum.toml").read_text().replace(
            "gravity = [0, -9.81]", "gravity = [0, 0]"
        )
        + '\n[[forces]]\ntype = "torque"\nbody = "arm"\ntorque = 1\n'
    )
    proc = run_cli("run", free, "-o", tmp_path / "o.csv", "-a", "equilibrium")
    assert proc.returncode == 1, proc.stderr
    assert_clean(proc)


def flat_follower_file(tmp_path):
    text = (EXAMPLES / "cam_seed_example_3_4_3.toml").read_text()
    path = tmp_path / "flat.toml"
    path.write_text(
        text.replace(
            'type = "cam_follower"\nname = "contact"\ncurve_i = "lobe"\ncurve_j = "roller"',
            'type = "flat_follower"\nname = "contact"\ncurve_i = "lobe"\nbody_j = "follower"\n'
            "axis = [1, 0]",
        )
    )
    return path


def test_design_warnings_of_a_flat_follower_on_a_concave_cam(tmp_path):
    path = flat_follower_file(tmp_path)
    proc = run_cli("check", path)
    assert proc.returncode == 0, proc.stderr
    assert "design       warning: joint 'contact': " in proc.stdout
    assert "concave" in proc.stdout
    # `run` prints the warning before the run, which then stops where the
    # face meets the hollow (exit 1).
    proc = run_cli("run", path, "-o", tmp_path / "o.csv")
    assert_clean(proc)
    lines = proc.stderr.splitlines()
    assert lines[0].startswith("camlink: warning: joint 'contact': ") and "concave" in lines[0]
    assert proc.returncode == 1
    # A sound cam has no findings.
    proc = run_cli("check", EXAMPLES / "cam_seed_example_3_4_3.toml")
    assert "design " not in proc.stdout


def test_verbose_run_prints_assembly_moves_and_counts(tmp_path):
    out = tmp_path / "o.csv"
    proc = run_cli("run", EXAMPLES / "slider_crank.toml", "-o", out, "-v")
    assert proc.returncode == 0, proc.stderr
    assert "camlink: assembly moved 'rod' by Δx = " in proc.stderr
    assert "camlink: kinematics: steps " in proc.stderr
    quiet = run_cli("run", EXAMPLES / "slider_crank.toml", "-o", out)
    assert "assembly moved" not in quiet.stderr
