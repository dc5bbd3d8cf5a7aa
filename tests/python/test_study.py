"""Studies on local cores: model variants, sweeps against Freudenstein's
closed form, Monte Carlo against analytic propagation, optimisation to a
known optimum, failures recorded, resuming without recomputing, study
files and `camlink study`."""

from __future__ import annotations

import os
import pickle
import signal
import threading
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from scipy import stats

import camlink
from camlink import _core
from camlink.cli import main
from camlink.study import at, least_transmission_angle, max_abs, max_of, min_of, range_of, run_variants
from camlink.study.study_file import read_study
from conftest import ROOT

FOUR_BAR = ROOT / "examples" / "four_bar.toml"
B, C, D = 0.38, 0.3, 0.4  # coupler, rocker, ground of examples/four_bar.toml (m)


def rocker_limits(a):
    """Freudenstein: the rocker's extreme angles θ4 (rad, open branch), where
    crank and coupler line up, |O2B| = b + a and b − a."""
    extended = np.arccos(((B + a) ** 2 - D * D - C * C) / (2 * D * C))
    folded = np.arccos(((B - a) ** 2 - D * D - C * C) / (2 * D * C))
    return extended, folded


def fine_four_bar():
    """The example four-bar over one crank turn in 1000 steps (0.36° of crank)."""
    text = FOUR_BAR.read_text().replace("t_end = 2.0", "t_end = 1.0").replace("step = 0.005", "step = 0.001")
    return camlink.loads(text, "toml", str(FOUR_BAR))


SLIDER = """
[parameters]
x0 = 0.1     # start (m)
v = 0.5      # speed (m/s)

[[bodies]]
name = "block"
points = { P = [0, 0] }

[[joints]]
name = "level"
type = "absolute_y"
body = "block"
point = "P"

[[joints]]
name = "square"
type = "absolute_phi"
body = "block"

[[drivers]]
name = "push"
type = "absolute_x"
body = "block"
point = "P"
f = "x0 + v*t"

[analysis]
t_end = 2.0
step = 0.1
"""


# --- variants of a model ---------------------------------------------------


def test_with_parameters_re_resolves_points_and_drivers():
    base = camlink.load(FOUR_BAR)
    variant = base.with_parameters(a=0.1, theta0=0.5)
    crank = {b["name"]: b for b in variant.bodies}["crank"]
    assert crank["points"]["A"] == [0.1, 0.0]
    assert crank["angle"] == 0.5
    # The driver reads the new theta0: the crank starts there.
    assert variant.run(t_end=0.0)["crank.phi"][0] == pytest.approx(0.5, abs=1e-12)
    # The base model is unchanged.
    assert {b["name"]: b for b in base.bodies}["crank"]["points"]["A"] == [0.12, 0.0]
    # A pickled variant (Dask, multiprocessing) keeps its parameters.
    back = pickle.loads(pickle.dumps(variant))
    assert {b["name"]: b for b in back.bodies}["crank"]["points"]["A"] == [0.1, 0.0]


def test_with_parameters_names_an_unknown_parameter():
    with pytest.raises(camlink.ModelError, match=r"no parameter named 'aa' \(did you mean 'a'\?\)"):
        camlink.load(FOUR_BAR).with_parameters(aa=0.1)
    with pytest.raises(camlink.ModelError, match="is not a number"):
        camlink.load(FOUR_BAR).with_parameters(a=[0.1])  # type: ignore[arg-type]


# --- the checks ------------------------------------------------------------


def test_crank_sweep_matches_freudensteins_rocker_swing():
    a = np.linspace(0.06, 0.16, 11)
    table = camlink.sweep(
        fine_four_bar(), {"a": a},
        {"swing": range_of("rocker.phi"), "hi": max_of("rocker.phi"), "lo": min_of("rocker.phi"),
         "alpha": max_abs("rocker.alpha")},
    )
    assert list(table["study.status"]) == ["ok"] * len(a)
    extended, folded = rocker_limits(a)
    # Sampled every Δθ2 = 0.36° of crank, an extreme is missed by at most
    # ½·max|d²θ4/dθ2²|·(Δθ2/2)², with d²θ4/dθ2² = α4/ω2² (ω2 = 2π rad/s).
    bound = 0.5 * table["alpha"] / (2 * np.pi) ** 2 * (2 * np.pi * 0.001 / 2) ** 2
    assert (bound < 7e-6).all()
    assert (np.abs(table["hi"] - folded) <= bound).all()
    assert (np.abs(table["lo"] - extended) <= bound).all()
    assert (np.abs(table["swing"] - (folded - extended)) <= 2 * bound).all()


def test_monte_carlo_of_a_linear_response_matches_analytic_propagation():
    model = camlink.loads(SLIDER)
    x0, v = stats.norm(0.1, 0.002), stats.uniform(0.5, 0.1)
    n, t = 400, 1.5
    mc = camlink.monte_carlo(model, {"x0": x0, "v": v}, {"x": at("block.x", t)}, n=n, seed=7)
    # x(t) = x0 + v t: mean and variance propagate exactly.
    mean = x0.mean() + t * v.mean()
    std = np.hypot(x0.std(), t * v.std())
    s = mc.statistics.loc["x"]
    assert s["n"] == n
    # Within four standard errors: of the mean σ/√n, of the standard
    # deviation about σ/√(2(n−1)).
    assert abs(s["mean"] - mean) < 4 * std / np.sqrt(n)
    assert abs(s["std"] - std) < 4 * std / np.sqrt(2 * (n - 1))
    # Each row is exactly the linear response of its own inputs.
    np.testing.assert_allclose(mc.table["x"], mc.table["x0"] + t * mc.table["v"], rtol=1e-12)
    # Sensitivity: standardised coefficients σ_i·∂x/∂p_i / σ_x, v first.
    sens = mc.sensitivity.set_index("parameter")
    assert sens.loc["v", "rank"] == 1 and sens.loc["x0", "rank"] == 2
    assert sens.loc["v", "src"] == pytest.approx(t * v.std() / std, abs=0.02)
    assert sens.loc["x0", "src"] == pytest.approx(x0.std() / std, abs=0.02)


@pytest.mark.parametrize("sampling", ["sobol", "lhs"])
def test_quasi_random_sampling_converges_faster(sampling):
    x0, v = stats.norm(0.1, 0.002), stats.uniform(0.5, 0.1)
    mc = camlink.monte_carlo(camlink.loads(SLIDER), {"x0": x0, "v": v}, {"x": at("block.x", 1.0)},
                             n=256, seed=3, sampling=sampling)
    mean = x0.mean() + v.mean()
    std = np.hypot(x0.std(), v.std())
    # Far inside the pseudo-random sampling error (σ/√n ≈ 1.9e-3).
    assert abs(mc.statistics.loc["x", "mean"] - mean) < 2e-4
    assert abs(mc.statistics.loc["x", "std"] - std) < 0.02 * std


def test_optimisation_finds_the_crank_for_a_required_swing():
    extended, folded = rocker_limits(0.1)
    target = folded - extended
    best = camlink.optimize(
        camlink.load(FOUR_BAR),
        lambda row: (row["swing"] - target) ** 2,
        {"a": (0.06, 0.16)},
        {"swing": range_of("rocker.phi")},
        seed=1,
        options={"maxiter": 30},
    )
    # dswing/da ≈ 7; the swing sampled every 1.8° of crank is within 3e-5 rad.
    assert best.parameters["a"] == pytest.approx(0.1, abs=2e-5)
    assert best.outputs["swing"] == pytest.approx(target, abs=5e-5)
    assert best.objective == best.history["study.objective"].min()
    assert set(best.history["study.status"]) == {"ok"}


def test_optimisation_with_a_scipy_minimize_method():
    best = camlink.optimize(
        camlink.loads(SLIDER), lambda row: (row["x"] - 1.3) ** 2, {"v": (0.0, 2.0)},
        {"x": at("block.x", 2.0)}, method="Nelder-Mead", x0={"v": 0.2},
        options={"xatol": 1e-9, "fatol": 1e-14},
    )
    assert best.parameters["v"] == pytest.approx((1.3 - 0.1) / 2.0, abs=1e-6)


# --- failures, execution ---------------------------------------------------


def test_a_failing_variant_is_recorded_and_the_study_goes_on():
    # a = 0.3 breaks Grashof's condition: the crank cannot turn; a = inf is
    # not a model.
    table = camlink.sweep(camlink.load(FOUR_BAR), {"a": [0.1, 0.3, float("inf"), 0.12]},
                          {"swing": range_of("rocker.phi")})
    assert list(table["study.status"]) == ["ok", "analysis_error", "model_error", "ok"]
    assert table["study.error"][0] == "" and np.isnan(table["swing"][1])
    assert "t = " in table["study.error"][1] or "time" in table["study.error"][1], table["study.error"][1]
    assert "parameters.a" in table["study.error"][2] and "not a finite number" in table["study.error"][2]
    assert table["swing"][3] == pytest.approx(np.subtract(*rocker_limits(0.12)[::-1]), abs=5e-5)


def test_a_variant_past_the_time_limit_is_stopped():
    table = camlink.sweep(fine_four_bar(), {"a": [0.1]}, {"swing": range_of("rocker.phi")},
                          time_limit=1e-6)
    assert table["study.status"][0] == "analysis_error"
    assert "time limit" in table["study.error"][0]


def test_outputs_are_checked_before_the_study_runs():
    model = camlink.load(FOUR_BAR)
    with pytest.raises(camlink.ModelError, match=r"output 'swing': the run has no channel 'rocker\.ph'"):
        camlink.sweep(model, {"a": [0.1]}, {"swing": range_of("rocker.ph")})
    with pytest.raises(camlink.ModelError, match=r"outputs.swing.kind: unknown output kind 'rnage'"):
        camlink.sweep(model, {"a": [0.1]}, {"swing": {"kind": "rnage", "channel": "rocker.phi"}})
    with pytest.raises(camlink.ModelError, match=r"has no parameter named 'aa' \(did you mean 'a'\?\)"):
        camlink.sweep(model, {"aa": [0.1]}, {"swing": range_of("rocker.phi")})
    with pytest.raises(camlink.ModelError, match="time 9 s is outside the run"):
        camlink.sweep(model, {"a": [0.1]}, {"x": at("rocker.phi", 9.0)})


def test_grid_and_zip_and_transmission_angle():
    model = camlink.load(FOUR_BAR)
    out = {"mu": least_transmission_angle("coupler", "rocker")}
    grid = camlink.sweep(model, {"a": [0.1, 0.12], "c": [0.3, 0.31]}, out)
    pairs = [(0.1, 0.3), (0.1, 0.31), (0.12, 0.3), (0.12, 0.31)]
    assert list(zip(grid["a"], grid["c"], strict=True)) == pairs
    zipped = camlink.sweep(model, {"a": [0.1, 0.12], "c": [0.3, 0.31]}, out, mode="zip")
    assert list(zip(zipped["a"], zipped["c"], strict=True)) == [(0.1, 0.3), (0.12, 0.31)]
    # The transmission angle by the cosine law, least where the crank
    # lines up with the ground: cos μ = (b² + c² − (d ∓ a)²) / (2bc).
    a = 0.12
    mu = [np.arccos((B**2 + C**2 - (D - s * a) ** 2) / (2 * B * C)) for s in (1, -1)]
    least = min(min(m, np.pi - m) for m in mu)
    assert grid["mu"][2] == pytest.approx(least, abs=2e-3)
    assert set(grid["study.status"]) == {"ok"}


def test_one_thread_and_all_cores_give_identical_results():
    model = camlink.load(FOUR_BAR)
    values = {"a": np.linspace(0.08, 0.14, 7)}
    out = {"swing": range_of("rocker.phi"), "mu": least_transmission_angle("coupler", "rocker")}
    one = camlink.sweep(model, values, out, threads=1, batch_size=3)
    many = camlink.sweep(model, values, out, threads=4, batch_size=100)
    pd.testing.assert_frame_equal(one.drop(columns="study.batch"), many.drop(columns="study.batch"))


# --- nothing lost ----------------------------------------------------------


def test_an_interrupted_study_resumes_without_recomputing(tmp_path, monkeypatch):
    model = camlink.load(FOUR_BAR)
    variants = [{"a": a} for a in np.linspace(0.08, 0.14, 10)]
    out = {"swing": range_of("rocker.phi")}
    folder = tmp_path / "sweep.parquet"
    real = _core.run_batch
    ran: list[float] = []

    def counting(model, variants, outputs, **kw):
        if len(ran) >= 6:
            raise KeyboardInterrupt  # Ctrl-C during the fourth batch
        ran.extend(v["a"] for v in variants)
        return real(model, variants, outputs, **kw)

    monkeypatch.setattr(_core, "run_batch", counting)
    with pytest.raises(KeyboardInterrupt):
        run_variants(model, variants, out, output=folder, batch_size=3, check_outputs=False)
    assert len(list(folder.glob("batch-*.parquet"))) == 2
    assert len(ran) == 6
    ran.clear()
    table = run_variants(model, variants, out, output=folder, batch_size=3, check_outputs=False)
    # Only the four variants not written were run.
    assert sorted(ran) == sorted(v["a"] for v in variants[6:])
    monkeypatch.setattr(_core, "run_batch", real)
    whole = run_variants(model, variants, out, check_outputs=False)
    pd.testing.assert_frame_equal(table.drop(columns="study.batch"), whole.drop(columns="study.batch"))
    # The folder reads back as one table.
    back = pd.read_parquet(folder).sort_values("study.variant", ignore_index=True)
    np.testing.assert_array_equal(back["swing"], whole["swing"])


def test_variants_are_keyed_by_model_text_and_parameters():
    model = camlink.load(FOUR_BAR)
    text = FOUR_BAR.read_text()
    table = camlink.sweep(model, {"a": [0.1]}, {"swing": range_of("rocker.phi")})
    assert table["study.key"][0] == camlink.study.variant_key(text, {"a": 0.1})
    # A model changed by with_parameters keys its own changes too.
    other = camlink.sweep(model.with_parameters(c=0.31), {"a": [0.1]}, {"swing": range_of("rocker.phi")})
    assert other["study.key"][0] == camlink.study.variant_key(text, {"a": 0.1, "c": 0.31})
    assert other["study.key"][0] != table["study.key"][0]


# --- study files and the command -------------------------------------------


def test_the_example_study_runs_from_the_command_line(tmp_path, capsys):
    out = tmp_path / "sweep.parquet"
    assert main(["study", str(ROOT / "examples" / "study_four_bar.toml"), "-o", str(out)]) == 0
    assert "9 variants of four_bar on local cores: 9 ok, 0 failed" in capsys.readouterr().out
    table = pd.read_parquet(out).sort_values("study.variant", ignore_index=True)
    a = np.linspace(0.08, 0.16, 9)
    np.testing.assert_allclose(table["a"], a)
    extended, folded = rocker_limits(a)
    # The example samples every 1.8° of crank: within 1e-4 rad.
    np.testing.assert_allclose(table["swing"], folded - extended, atol=1e-4)
    assert (table["least_transmission"] > 0).all() and (table["least_transmission"] < np.pi / 2).all()
    assert len(list(out.glob("batch-*.parquet"))) == 3


def test_a_monte_carlo_study_file(tmp_path, capsys):
    (tmp_path / "slider.toml").write_text(SLIDER)
    study = tmp_path / "mc.toml"
    study.write_text(
        '[study]\nmodel = "slider.toml"\nkind = "monte_carlo"\nn = 64\nseed = 2\nsampling = "sobol"\n'
        '[study.parameters]\nv = { dist = "norm", loc = 0.5, scale = 0.01 }\n'
        '[study.outputs]\nx = { kind = "at", channel = "block.x", time = 1.0 }\n'
    )
    assert main(["study", str(study), "-o", str(tmp_path / "mc.parquet")]) == 0
    printed = capsys.readouterr().out
    assert "64 variants of slider" in printed and "mean" in printed
    table = pd.read_parquet(tmp_path / "mc.parquet")
    np.testing.assert_allclose(table["x"], 0.1 + table["v"], rtol=1e-12)


@pytest.mark.parametrize(
    ("body", "where"),
    [
        ('[study.outputs]\nswing = { kind = "rnage", channel = "rocker.phi" }\n',
         r"study.toml:8:\d+: study.outputs.swing.kind: unknown output kind 'rnage'"),
        ('[study.outputs]\nswing = { kind = "range", chanel = "rocker.phi" }\n',
         r"study.toml:8:\d+: study.outputs.swing.chanel: not a field of a range output"),
        ('[study.outputs]\nswing = { kind = "range" }\n',
         r"study.toml:8:\d+: study.outputs.swing: a range output needs `channel`"),
    ],
)
def test_study_file_errors_name_the_line_and_field(tmp_path, body, where):
    study = tmp_path / "study.toml"
    head = f'[study]\nmodel = "{FOUR_BAR}"\nkind = "sweep"\n\n[study.parameters]\na = [0.1]\n'
    study.write_text(head + body)
    with pytest.raises(camlink.ModelError, match=where):
        read_study(study)


def test_study_file_errors_in_parameters(tmp_path, capsys):
    study = tmp_path / "study.toml"
    study.write_text(
        f'[study]\nmodel = "{FOUR_BAR}"\nkind = "monte_carlo"\nn = 4\n[study.parameters]\n'
        'a = { dist = "__import__", loc = 1 }\n'
        '[study.outputs]\ns = { kind = "range", channel = "rocker.phi" }\n'
    )
    where = r"study.toml:6:\d+: study.parameters.a.dist: '__import__' is not"
    with pytest.raises(camlink.ModelError, match=where):
        read_study(study)
    study.write_text(f'[study]\nmodel = "{FOUR_BAR}"\nthreads = 0\n')
    assert main(["study", str(study), "-o", str(tmp_path / "x")]) == 2
    assert "study.toml:3:" in capsys.readouterr().err


def test_study_output_that_is_a_file_is_refused(tmp_path):
    f = tmp_path / "out.parquet"
    f.write_text("x")
    with pytest.raises(camlink.ModelError, match="a study writes a folder"):
        camlink.sweep(camlink.load(FOUR_BAR), {"a": [0.1]}, {"s": range_of("rocker.phi")}, output=f)


def test_a_model_with_a_python_force_cannot_be_studied():
    model = camlink.load(FOUR_BAR).with_force("f", "crank", lambda t, q, qd: (0.0, 0.0, 0.0))
    with pytest.raises(camlink.ModelError, match="force computed in Python"):
        camlink.sweep(model, {"a": [0.1]}, {"s": range_of("rocker.phi")})


def test_study_files_are_found(tmp_path):
    assert Path(ROOT / "examples" / "study_four_bar.toml").is_file()


def test_ctrl_c_stops_a_running_batch_at_once(tmp_path):
    # 400 slow variants (20,000 steps each) in one batch on one thread: many
    # seconds of work; Ctrl-C after 0.3 s stops the runs at their next step.
    text = FOUR_BAR.read_text().replace("step = 0.005", "step = 0.0001")
    model = camlink.loads(text, "toml", str(FOUR_BAR))
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        camlink.sweep(model, {"a": np.linspace(0.08, 0.14, 400)}, {"s": range_of("rocker.phi")},
                      threads=1, batch_size=400, output=tmp_path / "s.parquet")
    elapsed = time.monotonic() - start
    timer.join()
    assert elapsed < 2.0, elapsed
    # Nothing of the stopped batch was written.
    assert list((tmp_path / "s.parquet").glob("batch-*")) == []


def test_with_parameters_recomputes_defaults_from_the_initial_placement():
    # `absolute_x` without a value holds the point where the file places
    # it: a variant that moves the body moves the constraint with it.
    text = """
[parameters]
x0 = 0.1

[[bodies]]
name = "block"
position = ["x0", 0]

[[joints]]
name = "hold_x"
type = "absolute_x"
body = "block"
point = [0, 0]

[[joints]]
name = "hold_y"
type = "absolute_y"
body = "block"
point = [0, 0]

[[joints]]
name = "square"
type = "absolute_phi"
body = "block"
"""
    base = camlink.loads(text)
    assert base.run(t_end=0.0)["block.x"][0] == pytest.approx(0.1, abs=1e-12)
    moved = base.with_parameters(x0=0.3)
    assert moved.run(t_end=0.0)["block.x"][0] == pytest.approx(0.3, abs=1e-12)


def test_cam_outputs_agree_with_the_full_results():
    # The valve example under inverse dynamics: below and above its jump
    # speed (4554 rpm). Each reduction, computed as the rows go, equals the
    # same number taken from the run's whole table.
    path = ROOT / "examples" / "cam_valve_spring.toml"
    text = path.read_text().replace("[analysis]", '[analysis]\ntype = "inverse_dynamics"')
    model = camlink.loads(text, "toml", str(path))
    outputs = {
        "lift": camlink.study.first_lift_off(),
        "lift_bucket": camlink.study.first_lift_off("bucket"),
        "torque": camlink.study.peak_effort("motor"),
        "force": at("bucket.normal_force", 0.003),
    }
    table = camlink.sweep(model, {"rpm": [3000.0, 5000.0]}, outputs)
    assert set(table["study.status"]) == {"ok"}
    with pytest.warns(camlink.LiftOffWarning):
        full = [model.with_parameters(rpm=rpm).run() for rpm in (3000.0, 5000.0)]
    assert np.isnan(table["lift"][0]) and full[0].lift_off.empty
    assert table["lift"][1] == full[1].lift_off["start_time"].min() == table["lift_bucket"][1]
    for k in range(2):
        assert table["torque"][k] == np.max(np.abs(full[k]["motor.effort"]))
        assert table["force"][k] == pytest.approx(np.interp(0.003, full[k].t, full[k]["bucket.normal_force"]),
                                                  rel=1e-12)


def test_pressure_angle_output_agrees_with_the_full_results():
    model = camlink.load(ROOT / "examples" / "cam_circle_roller.toml")
    table = camlink.sweep(model, {"e": [0.15, 0.2]}, {"p": camlink.study.max_pressure_angle("contact")})
    for k, e in enumerate([0.15, 0.2]):
        assert table["p"][k] == np.max(model.with_parameters(e=e).run()["contact.pressure_angle"])
    assert table["p"][0] != table["p"][1]
