"""`camlink run`'s error-control options (--atol, --rtol, --h-min) reach the
integrator exactly as the Python arguments do; "atol and rtol both 0" is
refused the same way from the command line, Python and a model file; the
`-p` help says one thing."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

import camlink
from camlink.results import Results
from conftest import ROOT, run_cli

PENDULUM = ROOT / "examples" / "dyn_pendulum.toml"


@pytest.fixture
def pendulum_file(tmp_path: Path) -> Path:
    return Path(shutil.copy(PENDULUM, tmp_path / "pendulum.toml"))


def _cli_and_python(model_file: Path, tmp_path: Path, **settings: float) -> tuple[Results, Results]:
    """An adaptive run of `model_file` with `settings` through `camlink run`
    (each as ``--key value``) and through `Model.simulate`."""
    out = tmp_path / "cli.csv"
    options = [str(a) for k, v in settings.items() for a in (f"--{k.replace('_', '-')}", v)]
    proc = run_cli("run", model_file, "-o", out, "--adaptive", *options)
    assert proc.returncode == 0, proc.stderr
    py = camlink.load(model_file).simulate(adaptive=True, **settings)  # type: ignore[arg-type]
    return Results.load(out), py


def test_atol_rtol_h_min_on_the_command_line_match_python(pendulum_file: Path, tmp_path: Path) -> None:
    # Largest step 0.25 s, so that the tolerances, not h, set the steps.
    grid = {"t_end": 1, "step": 0.25, "h": 0.25}
    cli, py = _cli_and_python(pendulum_file, tmp_path, **grid, atol=1e-9, rtol=1e-7, h_min=1e-9)
    np.testing.assert_array_equal(cli["arm.phi"], py["arm.phi"])
    # The options change the answer: the default tolerances give another.
    loose = camlink.load(pendulum_file).simulate(adaptive=True, **grid)  # type: ignore[arg-type]
    assert np.max(np.abs(loose["arm.phi"] - py["arm.phi"])) > 1e-9


def test_h_min_on_the_command_line_is_used(pendulum_file: Path, tmp_path: Path) -> None:
    # Tight tolerances want steps far below 0.01 s; h_min = 0.01 s holds
    # them there, and the CLI answer is Python's with the same h_min.
    tight = {"t_end": 0.2, "step": 0.1, "h": 0.1, "atol": 1e-12, "rtol": 1e-12}
    cli, held = _cli_and_python(pendulum_file, tmp_path, **tight, h_min=0.01)
    np.testing.assert_array_equal(cli["arm.phi"], held["arm.phi"])
    free = camlink.load(pendulum_file).simulate(adaptive=True, **tight)  # type: ignore[arg-type]
    assert held.summary["steps"] < free.summary["steps"]


def test_atol_and_rtol_both_zero_are_refused_everywhere(pendulum_file: Path, tmp_path: Path) -> None:
    message = "atol and rtol are both 0: no step would pass"
    proc = run_cli(
        "run", pendulum_file, "-o", tmp_path / "o.csv", "--t-end", "0.1",
        "--adaptive", "--atol", "0", "--rtol", "0",
    )
    assert proc.returncode == 2, proc.stderr
    assert message in proc.stderr and "Traceback" not in proc.stderr
    assert not (tmp_path / "o.csv").exists()
    with pytest.raises(camlink.ModelError, match=message):
        camlink.load(pendulum_file).simulate(t_end=0.1, adaptive=True, atol=0, rtol=0)
    text = PENDULUM.read_text().replace("[analysis]", "[analysis]\nadaptive = true\natol = 0\nrtol = 0")
    with pytest.raises(camlink.ModelError, match=f"analysis.atol: {message}"):
        camlink.loads(text)


def test_point_option_help_says_one_thing() -> None:
    proc = run_cli("run", "--help")
    assert proc.returncode == 0
    text = " ".join(proc.stdout.split())
    start = text.index("-p BODY.POINT, --point BODY.POINT")
    help_text = text[start : text.index(" -q, --quiet")]
    assert "instead of the model's [analysis] points" in help_text
    assert "also" not in help_text
