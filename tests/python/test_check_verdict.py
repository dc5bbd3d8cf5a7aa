"""`camlink check` says "ready for" only the analyses that accept the model:
dynamics and equilibrium accept redundant equations, kinematics and
inverse dynamics do not."""

from __future__ import annotations

from pathlib import Path

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
    assert "add 1 driver and remove the redundant equations for kinematics" in line, line


def test_redundant_driven_model_is_not_ready_for_kinematics(tmp_path: Path) -> None:
    text = (MODELS / "redundant_revolute.toml").read_text()
    driven = text + '\n[[drivers]]\nname = "motor"\ntype = "revolute_angle"\njoint = "O2"\nf = "1.2"\n'
    path = tmp_path / "redundant_driven.toml"
    path.write_text(driven)
    line = verdict(path)
    assert "ready for" not in line, line
    assert "remove them for kinematics and inverse dynamics" in line, line


def test_independent_driven_model_is_ready_for_kinematics() -> None:
    line = verdict(ROOT / "examples" / "four_bar.toml")
    assert "fully driven: ready for kinematics and inverse dynamics" in line, line
