"""Synthesis meets the studio and Dask: every model `camlink synth` writes
for the examples opens in the studio's document; `camlink synth --studio`
opens the best solution there; a path search spread over a Dask
LocalCluster gives the same solutions as the local cores."""

from __future__ import annotations

import logging
from pathlib import Path

import pytest

import camlink.studio
from camlink import synth
from camlink.cli import main
from camlink.studio.document import Document
from conftest import ROOT

EXAMPLES = sorted((ROOT / "examples").glob("synthesis_*.toml"))
PATH = ROOT / "examples" / "synthesis_path.toml"


@pytest.mark.parametrize("problem", EXAMPLES, ids=lambda p: p.stem)
def test_issue31_every_solution_opens_in_the_studio(problem: Path, tmp_path: Path) -> None:
    result = synth.solve(problem)
    paths = synth.write(result, tmp_path)
    assert paths
    for p in paths:
        doc = Document(p)
        assert doc.solution.error is None, f"{p.name}: {doc.solution.error}"
        assert bool(doc.solution.ok.all()), f"{p.name}: the cycle does not solve throughout"


def test_issue31_cli_synth_studio_opens_the_best_solution(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    opened: list[tuple[Path, bool]] = []

    def serve(path: str | Path, port: int = 0, browser: bool = True) -> None:
        opened.append((Path(path), browser))

    monkeypatch.setattr(camlink.studio, "run", serve)
    problem = ROOT / "examples" / "synthesis_burmester_four.toml"
    out = tmp_path / "out"
    assert main(["synth", str(problem), "-o", str(out), "--studio", "--no-browser"]) == 0
    best = synth.solve(problem).solutions[0]
    assert opened == [(out / f"{best.name}.toml", False)]
    assert "→" in capsys.readouterr().out


def test_issue31_cli_no_browser_goes_with_studio(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    problem = ROOT / "examples" / "synthesis_two_positions.toml"
    assert main(["synth", str(problem), "-o", str(tmp_path), "--no-browser"]) == 2
    assert "--no-browser goes with --studio" in capsys.readouterr().err


def test_issue31_path_search_on_dask_equals_the_local_run(tmp_path: Path) -> None:
    distributed = pytest.importorskip("distributed")
    local = synth.solve(PATH)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=False, protocol="tcp://",
        dashboard_address=None, silence_logs=logging.CRITICAL,
    ) as cluster, distributed.Client(cluster) as client:
        on_dask = synth.solve(PATH, client=client)
        # A problem without a search is solved here, as without Dask.
        two = ROOT / "examples" / "synthesis_two_positions.toml"
        assert synth.solve(two, client=client) == synth.solve(two)
        # The command line sends the search to a scheduler by its address.
        out = tmp_path / "out"
        address = cluster.scheduler_address
        assert main(["synth", str(PATH), "-o", str(out), "-q", "--scheduler", address]) == 0
    written = sorted(out.glob("*.toml"))
    assert [p.read_text() for p in written] == [
        p.read_text() for p in sorted(synth.write(local, tmp_path / "local"))
    ]
    assert on_dask.kind == local.kind == "path"
    assert len(on_dask.solutions) == len(local.solutions)
    for d, s in zip(on_dask.solutions, local.solutions, strict=True):
        assert d.model_text == s.model_text
        assert d.report == s.report


def test_issue31_cli_synth_unreachable_scheduler_is_a_clear_error(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["synth", str(PATH), "-o", str(tmp_path), "--scheduler", "tcp://127.0.0.1:9"]) == 2
    assert "cannot reach the Dask scheduler" in capsys.readouterr().err
    assert not list(tmp_path.iterdir())


def test_issue31_ball_point_example_runs_straight_there(tmp_path: Path) -> None:
    """The Ball's point example's model, run by camlink: at t = 0 its
    coupler point is at the reported Ball's point and its velocity is
    parallel to its acceleration (zero curvature), 1e-9 relative."""
    import math

    import numpy as np

    import camlink

    result = synth.solve(ROOT / "examples" / "synthesis_ball_point.toml")
    (s,) = result.solutions
    (path,) = synth.write(result, tmp_path)
    res = camlink.load(path).kinematics(times=np.array([0.0, 0.5]), tol=1e-12)
    ball = s.report["instant"]["ball"]
    assert abs(res["coupler.P.x"][0] - ball[0]) < 1e-9 and abs(res["coupler.P.y"][0] - ball[1]) < 1e-9
    v = (res["coupler.P.vx"][0], res["coupler.P.vy"][0])
    a = (res["coupler.P.ax"][0], res["coupler.P.ay"][0])
    w = 2 * math.pi
    assert abs(v[0] * a[1] - v[1] * a[0]) < 1e-9 * math.hypot(*v) * w * w * s.links.coupler
