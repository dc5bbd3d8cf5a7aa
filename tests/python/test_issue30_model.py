"""Issue 30, "model what you mean": bodies in global coordinates from the
builder, and warnings about defaults measured in a rough placement."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

import camlink
from camlink.cli import main

ROOT = Path(__file__).resolve().parents[2]

# A crank–rocker four-bar drawn at t = 0: crank O–A, coupler A–B, rocker B–D.
PO, PA, PB, PD = (0.0, 0.0), (0.0, 0.1), (0.4, 0.3), (0.4, 0.0)


def _joints(m: camlink.Mechanism) -> None:
    m.revolute("O", "ground", "O", "crank", "O")
    m.revolute("A", "crank", "A", "coupler", "A")
    m.revolute("B", "coupler", "B", "rocker", "B")
    m.revolute("D", "rocker", "D", "ground", "D")
    m.revolute_driver("motor", "O", "2*pi*t")
    m.analysis(t_end=0.5, step=0.01, points=["coupler.A", "coupler.B"])


def test_issue30_builder_link_in_global_coordinates() -> None:
    g = camlink.Mechanism("global")
    g.ground_point("O", PO)
    g.ground_point("D", PD)
    g.link("crank", O=PO, A=PA)
    g.link("coupler", A=PA, B=PB)
    g.link("rocker", B=PB, D=PD)
    _joints(g)
    f = camlink.Mechanism("frames")
    f.ground_point("O", PO)
    f.ground_point("D", PD)
    f.body("crank", points={"O": (0, 0), "A": (0, 0.1)})
    f.body("coupler", position=PA, points={"A": (0, 0), "B": (0.4, 0.2)})
    f.body("rocker", position=PD, points={"D": (0, 0), "B": (0, 0.3)})
    _joints(f)
    # Two descriptions of one mechanism take different Newton paths; a
    # tolerance near rounding makes both land on the same positions.
    rg, rf = g.run(tol=1e-14), f.run(tol=1e-14)
    for ch in ("coupler.A.x", "coupler.A.y", "coupler.B.x", "coupler.B.y", "coupler.B.vx"):
        assert np.max(np.abs(rg[ch] - rf[ch])) < 1e-12, ch
    # The frame of a link is at the mean of its points, angle 0.
    coupler = next(b for b in g.build().bodies if b["name"] == "coupler")
    assert coupler["position"] == pytest.approx([0.2, 0.2])
    assert coupler["angle"] == 0.0
    assert coupler["points"]["A"] == pytest.approx([-0.2, -0.1])
    assert "global_points" in g.to_toml()


def test_issue30_link_without_points_is_a_model_error() -> None:
    with pytest.raises(camlink.ModelError, match="at least one point"):
        camlink.Mechanism("m").link("coupler")


# The quick-return with the slot's offset left out and the lever written
# 1 mm off its pivot: the offset is measured there, and differs in the
# placement that assembles the pivot.
ROUGH = (
    (ROOT / "examples" / "quick_return.toml")
    .read_text()
    .replace("offset = 0\n", "")
    .replace('angle = "deg(5)"', 'position = [0.001, 0]\nangle = "deg(5)"')
)


def test_issue30_default_warning_is_issued_and_listed() -> None:
    with pytest.warns(camlink.LoadWarning, match=r"joint 'slot'.*\(used\).*\(assembled\)"):
        model = camlink.loads(ROUGH, "toml", "rough.toml")
    (w,) = model.warnings
    assert w["kind"] == "default_unassembled"
    assert w["field"] == "joints[2].offset"
    assert w["text"].startswith("joints[2].offset: joint 'slot'")
    # A file that says what it means loads without a word.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert camlink.load(ROOT / "examples" / "quick_return.toml").warnings == []


def test_issue30_cli_run_prints_the_default_warning(tmp_path, capsys) -> None:
    path = tmp_path / "rough.toml"
    path.write_text(ROUGH)
    assert main(["run", str(path), "-o", str(tmp_path / "out.csv"), "--t-end", "0.1"]) == 0
    err = capsys.readouterr().err
    assert "camlink: warning: joints[2].offset: joint 'slot'" in err
