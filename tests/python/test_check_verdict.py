"""`camlink check` says "ready for" only the analyses that accept the model:
dynamics and equilibrium accept redundant equations, and so do kinematics
and inverse dynamics once the model is fully driven, unless a driver is
among the redundant equations (over-driven)."""

from __future__ import annotations

import json
from pathlib import Path

import camlink
from conftest import ROOT, run_cli

MODELS = ROOT / "tests" / "models" / "misbehave"


def verdict(path: Path) -> str:
    proc = run_cli("check", str(path))
    assert proc.returncode == 0, proc.stderr
    assert "Traceback" not in proc.stderr, proc.stderr
    return next(line for line in proc.stdout.splitlines() if "degrees of freedom" in line)


def test_redundant_free_model_is_ready_for_dynamics_not_kinematics() -> None:
    line = verdict(MODELS / "redundant_revolute.toml")
    assert "ready for dynamics and equilibrium" in line, line
    assert "add 1 driver for kinematics" in line, line


def driven(tmp_path: Path, f: str) -> Path:
    """redundant_revolute.toml with a motor on O2 at angle `f`."""
    text = (MODELS / "redundant_revolute.toml").read_text()
    text += f'\n[[drivers]]\nname = "motor"\ntype = "revolute_angle"\njoint = "O2"\nf = "{f}"\n'
    path = tmp_path / "redundant_driven.toml"
    path.write_text(text)
    return path


def test_redundant_driven_model_is_ready_for_kinematics_and_runs(tmp_path: Path) -> None:
    path = driven(tmp_path, "1.2 + t")
    line = verdict(path)
    assert "fully driven, with redundant equations: ready for kinematics and inverse" in line
    for analysis in ("kinematics", "inverse_dynamics"):
        out = tmp_path / f"{analysis}.csv"
        proc = run_cli("run", str(path), "-a", analysis, "--t-end", "1", "--step", "0.1", "-o", out)
        assert proc.returncode == 0, proc.stderr
        assert "Traceback" not in proc.stderr, proc.stderr
        assert "O4_again.x" in proc.stderr and "redundant" in proc.stderr, proc.stderr


def test_over_driven_model_is_not_ready_for_kinematics() -> None:
    line = verdict(ROOT / "tests" / "models" / "errors" / "over_driven.toml")
    assert "ready for" not in line, line
    assert "over-driven" in line, line


def test_independent_driven_model_is_ready_for_kinematics() -> None:
    line = verdict(ROOT / "examples" / "four_bar.toml")
    assert "fully driven: ready for kinematics and inverse dynamics" in line, line


def test_check_names_the_drivers_among_the_redundant_equations(tmp_path: Path) -> None:
    # motor.phi depends on brake.phi: both drivers are named, the
    # redundant one first.
    over = camlink.load(ROOT / "tests" / "models" / "errors" / "over_driven.toml").check()
    assert [r["equation"] for r in over["redundant"]] == ["motor.phi"]
    assert over["redundant_drivers"] == ["motor", "brake"]
    # A redundant revolute beside a driver involves no driver.
    fine = camlink.load(driven(tmp_path, "1.2 + t")).check()
    assert [r["equation"] for r in fine["redundant"]] == ["O4_again.x", "O4_again.y"]
    assert fine["redundant_drivers"] == []


def test_check_json_carries_the_redundant_drivers() -> None:
    proc = run_cli("check", str(ROOT / "tests" / "models" / "errors" / "over_driven.toml"), "--json")
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["redundant_drivers"] == ["motor", "brake"]
