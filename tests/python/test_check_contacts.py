"""`camlink check` on a model with a unilateral contact: a contact open at
the placement (or compliant) removes no freedom at the start, so it is not
counted, and the report says so (issue 27)."""

from __future__ import annotations

import json
from pathlib import Path

import camlink
from conftest import run_cli

DISC = """
[model]
name = "disc"

[[bodies]]
name = "disc"
position = [0.3, {y}]
mass = 2
inertia = 0.01

[[curves]]
name = "rim"
body = "disc"
source = "circle"
centre = [0, 0]
radius = 0.1

[[joints]]
type = "flat_follower"
name = "floor"
curve_i = "rim"
body_j = "ground"
axis = [1, 0]
unilateral = true
"""


def disc(tmp_path: Path, y: float) -> Path:
    path = tmp_path / "disc.toml"
    path.write_text(DISC.format(y=y))
    return path


def test_issue27_check_open_contact_is_not_counted(tmp_path: Path) -> None:
    path = disc(tmp_path, 0.6)
    r = camlink.load(path).check()
    assert r["dof"] == 3
    [c] = r["released"]
    assert c["joint"] == "floor"
    assert c["gap"] is not None and abs(c["gap"] - 0.5) < 1e-9
    proc = run_cli("check", path)
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.splitlines()
    assert (
        "  contact 'floor': open at t = 0 s (gap 0.5 m): its 2 equations and 1 own "
        "coordinate are not counted"
    ) in lines, proc.stdout
    dof = next(line for line in lines if line.startswith("degrees of freedom"))
    assert dof.startswith("degrees of freedom  3 "), dof
    assert "3 free motions: ready for dynamics and equilibrium" in dof, dof
    report = json.loads(run_cli("check", path, "--json").stdout)
    assert report["dof"] == 3
    assert report["released"][0]["joint"] == "floor"


def test_issue27_check_closed_contact_is_counted(tmp_path: Path) -> None:
    path = disc(tmp_path, 0.1)
    r = camlink.load(path).check()
    assert r["released"] == []
    assert r["dof"] == 2
    proc = run_cli("check", path)
    assert proc.returncode == 0, proc.stderr
    assert "not counted" not in proc.stdout
    assert "degrees of freedom  2 " in proc.stdout
