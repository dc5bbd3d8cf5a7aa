"""The command of issue 9: forward dynamics of the slider-crank example at a
step of 1e-7 s with a Newton tolerance of 1e-10 runs (the Newton test stops
at the rounding level of the coordinates)."""

from __future__ import annotations

from pathlib import Path

from conftest import ROOT, run_cli


def test_tiny_step_slider_crank_runs(tmp_path: Path) -> None:
    out = tmp_path / "tiny.csv"
    proc = run_cli(
        "run",
        ROOT / "examples" / "dyn_slider_crank.toml",
        "-a",
        "dynamics",
        "--t-end",
        "0.0005",
        "--step",
        "0.0005",
        "--h",
        "1e-7",
        "--tol",
        "1e-10",
        "-o",
        out,
    )
    assert proc.returncode == 0, proc.stderr
    assert "Traceback" not in proc.stderr, proc.stderr
    rows = [r for r in out.read_text().splitlines() if r and not r.startswith("#")]
    assert float(rows[-1].split(",")[0]) == 0.0005, rows[-1][:80]
