"""Two-position, Burmester and slider-crank synthesis through `camlink synth`
and the Python API: the written models run and pass their poses or points
(each example also runs in test_synthesis.py's example test); reports name
the rank, the quality figure and the candidates; bad input is a usage
error naming the file, the line and the field."""

from __future__ import annotations

import json
from pathlib import Path

from test_synthesis import check_poses, check_slider_points

import camlink
from camlink import synth
from camlink.cli import main
from conftest import ROOT

FOUR = ROOT / "examples" / "synthesis_burmester_four.toml"
FIVE = ROOT / "examples" / "synthesis_burmester_five.toml"
SLIDER = ROOT / "examples" / "synthesis_slider_crank.toml"


def test_issue31_cli_burmester_four_writes_ranked_models(tmp_path: Path, capsys) -> None:
    assert main(["synth", str(FOUR), "-o", str(tmp_path / "out"), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["kind"] == "burmester"
    sols = out["solutions"]
    assert [s["rank"] for s in sols] == [1, 2, 3, 4, 5]
    values = [s["quality"]["value"] for s in sols]
    assert values == sorted(values, reverse=True)
    for s in sols:
        assert s["checks"]["defects"] == []
        assert s["candidates"]["kept"] >= 5
        check_poses(camlink.load(s["model"]), s)


def test_issue31_cli_burmester_five_text_report(tmp_path: Path, capsys) -> None:
    assert main(["synth", str(FIVE), "-o", str(tmp_path)]) == 0
    text = capsys.readouterr().out
    assert "burmester five" in text and "rank 1" in text and "no defects" in text
    result = synth.solve(FIVE)
    assert len(result.solutions[0].report["burmester_points"]) >= 2


def test_issue31_cli_slider_function_reports_metres(tmp_path: Path, capsys) -> None:
    assert main(["synth", str(SLIDER), "-o", str(tmp_path)]) == 0
    text = capsys.readouterr().out
    assert "slider three point" in text and " m at x = " in text
    s = synth.solve(SLIDER).solutions[0]
    assert s.links.rocker is None and s.links.offset is not None
    check_slider_points(s.model(), dict(s.report))


def test_issue31_burmester_no_real_solution_is_a_usage_error(tmp_path: Path, capsys) -> None:
    problem = tmp_path / "p.toml"
    problem.write_text(FOUR.read_text().replace("region = [-0.6, -0.6, 0.8, 0.6]", "region = [5, 5, 6, 6]"))
    assert main(["synth", str(problem), "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert "p.toml" in err and "synthesis.poses" in err
    assert "the region check removed every one" in err
