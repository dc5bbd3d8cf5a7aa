"""Path generation, dead-centre synthesis and cognates through `camlink synth`
and the Python API: the models written run, and the coupler point, the
rocker or the cognates do what the report says (1e-9 m, rad); the atlas
draws each target at its pixel and each curve through its points; bad
input is a usage error naming the field."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import camlink
from camlink import synth
from camlink.cli import main
from camlink.synth import atlas as synth_atlas
from conftest import ROOT

PATH = ROOT / "examples" / "synthesis_path.toml"
DEAD = ROOT / "examples" / "synthesis_dead_centre.toml"
COGNATES = ROOT / "examples" / "synthesis_cognates.toml"
TOL = 1e-9


def run(model: camlink.Model, extra: list[float]) -> tuple[np.ndarray, camlink.Results]:
    times = np.unique(np.r_[np.linspace(0.0, 1.0, 201), extra])
    return times, model.kinematics(times=times, tol=1e-12)


def test_issue31_cli_path_writes_models_that_reach_their_targets(tmp_path: Path, capsys) -> None:
    atlas = tmp_path / "atlas.png"
    assert main(["synth", str(PATH), "-o", str(tmp_path / "out"), "--json", "--atlas", str(atlas)]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["kind"] == "path"
    best = out["solutions"][0]
    assert best["checks"]["defects"] == [] and best["checks"]["grashof"] == "crank-rocker"
    for s in out["solutions"]:
        times, res = run(camlink.load(s["model"]), s["point_times"])
        for target, t, err in zip(s["targets"], s["point_times"], s["error"]["points"], strict=True):
            k = int(np.searchsorted(times, t))
            d = math.hypot(res["coupler.P.x"][k] - target[0], res["coupler.P.y"][k] - target[1])
            assert abs(d - err) < TOL
    assert atlas.stat().st_size > 0
    # `camlink run` runs a model as is.
    assert main(["run", out["solutions"][0]["model"], "-o", str(tmp_path / "run.csv")]) == 0


def test_issue31_cli_dead_centre_swing_and_time_ratio(tmp_path: Path, capsys) -> None:
    assert main(["synth", str(DEAD), "-o", str(tmp_path), "--json"]) == 0
    (s,) = json.loads(capsys.readouterr().out)["solutions"]
    t1, t2 = s["extremes"]["times"]
    times, res = run(camlink.load(s["model"]), [t1, t2])
    psi = res["rocker.phi"]
    k1, k2 = int(np.searchsorted(times, t1)), int(np.searchsorted(times, t2))
    assert abs(psi[k2] - psi[k1] - math.radians(45)) < TOL
    assert psi.min() >= psi[k1] - 1e-12 and psi.max() <= psi[k2] + 1e-12
    assert abs((t2 - t1) / (1 - t2) - 1.25) < TOL


def test_issue31_cli_cognates_trace_one_curve(tmp_path: Path, capsys) -> None:
    assert main(["synth", str(COGNATES), "-o", str(tmp_path), "-q"]) == 0
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == [
        "synthesis_cognates_cognate1.toml",
        "synthesis_cognates_cognate2.toml",
        "synthesis_cognates_given.toml",
    ]
    runs = [run(camlink.load(tmp_path / n), [])[1] for n in names]
    for r in runs[:2]:
        d = np.hypot(r["coupler.P.x"] - runs[2]["coupler.P.x"], r["coupler.P.y"] - runs[2]["coupler.P.y"])
        assert d.max() < TOL


def _pixel(fig: Any, ax: Any, xy: Any) -> tuple[int, int]:
    x, y = ax.transData.transform(xy)
    h = fig.canvas.get_width_height()[1]
    return round(x), round(h - y)


def test_issue31_atlas_draws_targets_and_curves_at_their_pixels() -> None:
    result = synth.solve(PATH)
    fig = synth_atlas.atlas(result)
    fig.canvas.draw()
    canvas: Any = fig.canvas
    img = np.asarray(canvas.buffer_rgba())[:, :, :3].astype(int)
    red = np.array([0xD6, 0x27, 0x28])
    blue = np.array([0x1F, 0x77, 0xB4])
    checked_middle = False
    for s, ax in zip(result.solutions, fig.axes, strict=True):
        # Each target: its red dot at its computed pixel.
        for p in s.report["targets"]:
            x, y = _pixel(fig, ax, (p[0] * 1000, p[1] * 1000))
            assert np.abs(img[y, x] - red).max() < 40, (p, img[y, x])
        # The curve passes through its points: blue near every 10th point
        # (a target dot may cover it).
        xs, ys = synth_atlas.curve_mm(s.report)
        for k in range(0, len(xs), 10):
            x, y = _pixel(fig, ax, (xs[k], ys[k]))
            patch = img[y - 1 : y + 2, x - 1 : x + 2].reshape(-1, 3)
            assert any(np.abs(c - blue).max() < 60 or np.abs(c - red).max() < 40 for c in patch)
        # The middle of the target loop is empty where the loop is drawn
        # large enough to have a middle (over 40 pixels across).
        t = np.asarray(s.report["targets"]) * 1000
        corners = [_pixel(fig, ax, tuple(t.min(axis=0))), _pixel(fig, ax, tuple(t.max(axis=0)))]
        if min(abs(corners[1][0] - corners[0][0]), abs(corners[1][1] - corners[0][1])) > 40:
            x, y = _pixel(fig, ax, tuple(t.mean(axis=0)))
            assert img[y, x].min() > 230
            checked_middle = True
    assert checked_middle


def test_issue31_atlas_refuses_problems_without_curves() -> None:
    with pytest.raises(camlink.ModelError, match="no coupler curves"):
        synth_atlas.atlas(synth.solve(ROOT / "examples" / "synthesis_function.toml"))


BAD = [
    ("units = \"mm\"\n", "x [mm], y [m]\n", "mixed units ('mm' and 'm')"),
    ("units = \"m\"\n", "x [mm], y [mm]\n", "synthesis.units: mixed units"),
]


@pytest.mark.parametrize(("extra", "header", "message"), BAD)
def test_issue31_targets_in_mixed_units_are_refused(
    tmp_path: Path, capsys, extra: str, header: str, message: str
) -> None:
    (tmp_path / "t.csv").write_text(header + "1, 2\n3, 4\n5, 1\n2, 6\n")
    problem = tmp_path / "p.toml"
    problem.write_text(f'[synthesis]\ntype = "path"\ntarget_file = "t.csv"\n{extra}')
    assert main(["synth", str(problem), "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert str(problem) in err and message in err
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize(
    ("body", "message"),
    [
        ("targets = [[0, 0], [0.1, 0], [0.1, 0], [0, 0.1]]", "synthesis.targets: points 2 and 3 coincide"),
        (
            'targets = [[0, 0], [0.1, 0], [0.2, 0], [0.3, 0]]\nclosure = "closed"',
            "synthesis.targets: the points of a closed curve lie on one line",
        ),
        (
            'targets = [[0, 0], [0.1, 0], [0.2, 0.05], [0.3, 0.1]]\nmethod = "precision_points"',
            "synthesis.crank_rotations: missing",
        ),
    ],
)
def test_issue31_bad_path_problems_name_the_field(tmp_path: Path, capsys, body: str, message: str) -> None:
    problem = tmp_path / "p.toml"
    problem.write_text(f'[synthesis]\ntype = "path"\n{body}\n')
    assert main(["synth", str(problem), "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert str(problem) in err and message in err


def test_issue31_dead_centre_without_solution_says_why(tmp_path: Path, capsys) -> None:
    problem = tmp_path / "p.toml"
    problem.write_text(DEAD.read_text() + "ground = 10.0\n")
    assert main(["synth", str(problem), "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert "synthesis.ground: no crank-rocker with a ground link of 10 m" in err


def test_issue31_atlas_never_replaces_the_problem_file(tmp_path: Path, capsys) -> None:
    # `--atlas` is a PNG beside the models: never the problem it reads, never
    # another kind of file; both refused before anything is solved or written.
    problem = tmp_path / "cognates.toml"
    text = COGNATES.read_text(encoding="utf-8")
    problem.write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    assert main(["synth", str(problem), "-o", str(out), "--atlas", str(problem)]) == 2
    assert "name a .png file" in capsys.readouterr().err
    link = tmp_path / "problem.png"
    link.symlink_to(problem)
    assert main(["synth", str(problem), "-o", str(out), "--atlas", str(link)]) == 2
    assert "is an input of the model" in capsys.readouterr().err
    assert problem.read_text(encoding="utf-8") == text and not out.exists()
    # A good name is written whole, through a temporary file.
    atlas = tmp_path / "atlas.png"
    assert main(["synth", str(problem), "-o", str(out), "-q", "--atlas", str(atlas)]) == 0
    assert atlas.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["atlas.png", "cognates.toml", "out", "problem.png"]
