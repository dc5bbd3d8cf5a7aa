"""Issue 32: `camlink machine` — shaking force and its polar plot,
counterweights written into a new model file, flywheel and motor checks
with exit codes 0/1/2 like `camlink cam`."""

from __future__ import annotations

import itertools
import json
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from camlink import machine
from camlink.cli import main
from conftest import ROOT

EXAMPLE = ROOT / "examples" / "machine_slider_crank.toml"


def _variant(tmp_path: Path, old: str, new: str) -> Path:
    text = EXAMPLE.read_text(encoding="utf-8")
    assert old in text
    p = tmp_path / "variant.toml"
    p.write_text(text.replace(old, new), encoding="utf-8")
    return p


def test_issue32_machine_example_one_command(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    plot, balanced = tmp_path / "polar.png", tmp_path / "balanced.toml"
    code = main(["machine", str(EXAMPLE), "--plot", str(plot), "--balanced", str(balanced)])
    out = capsys.readouterr().out
    assert code == 0, out
    for words in (
        "peak |F_s|",
        "counterweight",
        "inertia I = ΔE/(C_s ω²)",
        "the motor curve",
        "all checks hold",
    ):
        assert words in out, out
    assert plot.stat().st_size > 10_000
    # The balanced copy keeps its comments and shakes the frame with its weight only.
    text = balanced.read_text(encoding="utf-8")
    assert "# A slider-crank press" in text and "with the counterweight" in text
    before = machine.report(EXAMPLE)
    after = machine.report(balanced)
    assert before["shaking"]["peak_dynamic"] > 100.0
    assert after["shaking"]["peak_dynamic"] <= 1e-9 * before["shaking"]["peak_dynamic"]


def test_issue32_machine_json(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["machine", str(EXAMPLE), "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    names = [c["name"] for c in r["checks"]]
    assert names == ["speed_band", "run_speed", "mean_torque", "rms_torque", "peak_power"]
    f = r["flywheel"]
    # The forward run drives the press by the motor's curve and holds the design speed.
    assert f["law"] == "curve"
    assert abs(f["omega_mean"] - r["speed"]) <= 0.5 * f["cs"] * r["speed"]
    # I = ΔE / (C_s ω²) and the forward run inside the band.
    assert f["inertia"] == pytest.approx(f["delta_e"] / (f["cs"] * r["speed"] ** 2), rel=1e-12)
    assert f["cs_run"] <= f["cs"]
    assert len(r["shaking"]["fx"]) == len(r["theta"]) == 361


def test_issue32_polar_plot_draws_the_shaking_force(tmp_path: Path) -> None:
    r = machine.report(EXAMPLE)
    fig = machine.polar(r)
    ax = fig.axes[0]
    line = ax.lines[0]
    assert np.array_equal(line.get_xdata(), r["shaking"]["fx"])
    assert np.array_equal(line.get_ydata(), r["shaking"]["fy"])
    fig.canvas.draw()
    canvas: Any = fig.canvas
    img = np.asarray(canvas.buffer_rgba())
    h = canvas.get_width_height()[1]
    # The tip of F_s at its peak is drawn at its pixel; the origin of the
    # force plane, far from the locus (which is offset by the weight), is
    # marked by the black cross.
    fx, fy = np.asarray(r["shaking"]["fx"]), np.asarray(r["shaking"]["fy"])
    k = int(np.argmax(np.hypot(fx, fy)))
    x, y = ax.transData.transform((fx[k], fy[k]))
    patch = img[round(h - y) - 1 : round(h - y) + 2, round(x) - 1 : round(x) + 2, :3]
    assert patch.min() < 200, patch
    machine.save(fig, tmp_path / "p.png")


def test_issue32_flywheel_band_of_zero_exit_2(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    p = _variant(tmp_path, "speed_band = 0.02 ", "speed_band = 0 ")
    assert main(["machine", str(p)]) == 2
    err = capsys.readouterr().err
    assert "variant.toml:" in err and "machine.speed_band" in err and "Traceback" not in err


def test_issue32_motor_curve_short_of_the_speed_exit_2(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    p = _variant(tmp_path, "[60, 45], [85, 40], [95, 0]]", "[60, 45], [80, 0]]")
    assert main(["machine", str(p)]) == 2
    err = capsys.readouterr().err
    assert "machine.motor.curve" in err and "never reaches the motor speed" in err


def test_issue32_motor_too_small_exit_1(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    p = _variant(tmp_path, "rated_torque = 12 ", "rated_torque = 1 ")
    assert main(["machine", str(p)]) == 1
    out = capsys.readouterr().out
    assert "rms_torque" in out and "FAIL" in out and "some checks fail" in out


def test_issue32_no_machine_table_exit_2(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["machine", str(ROOT / "examples" / "four_bar.toml")]) == 2
    assert "no [machine] table" in capsys.readouterr().err


def test_issue32_motor_that_cannot_reach_the_speed_exit_1(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # A tenth of the torque: the curve gives less than the press needs at n ω.
    p = _variant(tmp_path, "[[0, 40], [60, 45], [85, 40], [95, 0]]", "[[0, 4], [60, 4.5], [85, 4], [95, 0]]")
    code = main(["machine", str(p)])
    out = capsys.readouterr().out
    assert code == 1, out
    assert "the motor cannot reach the design speed" in out, out
    assert "run_speed" in out and "FAIL" in out


def test_issue32_partial_balance_weight_sweep(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """As the weight of the shaking force grows (the others 1), the optimum
    shakes the frame less and twists it more; each optimum scores below
    both the unbalanced machine and the full balance."""
    from camlink.study import partial_balance

    sweep = [partial_balance(EXAMPLE, (wf, 1.0, 1.0)) for wf in (1.0, 10.0, 30.0)]
    for p in sweep:
        print(p.weights, p.factors, p.figures)
        assert p.figures.objective < p.unbalanced.objective
        assert p.figures.objective < p.full.objective
        assert p.unbalanced.objective == pytest.approx(sum(p.weights), rel=1e-12)
        assert len(p.history) > 50
    for a, b in itertools.pairwise(sweep):
        assert b.figures.force < a.figures.force
        assert b.figures.moment > a.figures.moment
    # The CLI writes the partial counterweights into a copy of the model.
    out_file = tmp_path / "partial.toml"
    code = main(["machine", str(EXAMPLE), "--partial", "1,1,1", "--balanced", str(out_file)])
    out = capsys.readouterr().out
    assert code == 0, out
    assert "partial balance (slider_crank)" in out and "factor" in out
    after = machine.report(out_file)["shaking"]["peak_dynamic"]
    assert after == pytest.approx(sweep[0].figures.force, rel=1e-9)


def test_issue32_partial_balance_bad_weights_exit_2(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["machine", str(EXAMPLE), "--partial", "1,1"]) == 2
    assert "--partial: give three weights" in capsys.readouterr().err
    assert main(["machine", str(EXAMPLE), "--partial", "0,0,0"]) == 2
    assert "not all zero" in capsys.readouterr().err
