"""camlink against peer engines on the issue benchmarks, in one run.

    uv run --group bench python bench/compare.py [--quick] [--only NAME] [--no-cargo]

NAME is one of four_bar, cam_roller, slider_crank, chain, output (the cost of writing
results: the four-bar kinematics with no output, to CSV and to Parquet). Every figure in the table
comes from this run on this machine; ratios divide by camlink's core
figure from the same run (camlink from Python when --no-cargo). The
machine is shared: the load average is printed at the start and the end,
and figures taken under load are slower and noisier than on a quiet one.
"""

from __future__ import annotations

import argparse
import datetime
import importlib
import os
import platform
import re
import subprocess
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))

import camlink_models
import divan
import output_writing
import slider_crank as sc
import textbook_four_bar as tb

BENCHES = ("four_bar", "cam_roller", "slider_crank", "chain", "output")


@dataclass
class Row:
    bench: str
    engine: str
    computes: str
    us: float | None
    unit: str = "µs/step"
    note: str = ""
    base: bool = False


def load_average() -> str:
    one, five, fifteen = os.getloadavg()
    return f"{one:.2f}, {five:.2f}, {fifteen:.2f} (1, 5, 15 min; {os.cpu_count()} cores)"


def best_of(repeats: int, fn: Callable[[], Any]) -> tuple[float, Any]:
    """(smallest wall time of `repeats` calls, the last call's value)."""
    best, value = float("inf"), None
    for _ in range(repeats):
        start = time.perf_counter()
        value = fn()
        best = min(best, time.perf_counter() - start)
    return best, value


def peer(name: str) -> Any | None:
    """The peer module, or None with a line saying why."""
    try:
        return importlib.import_module(name)
    except ImportError as e:
        print(f"  {name.removeprefix('peer_')}: not installed ({e.name}); skipped")
        return None


def cargo(package: str, bench: str, filters: list[str]) -> dict[str, dict[str, float]]:
    print(f"  cargo bench -p {package} --bench {bench} -- {' '.join(filters)} …", flush=True)
    return divan.run(package, bench, filters)


# ---------------------------------------------------------------------------
# 1. Four-bar crank-rocker kinematics.


def four_bar(args: argparse.Namespace, rows: list[Row]) -> None:
    n = 1_000 if args.quick else 10_000
    print(f"four-bar crank-rocker kinematics, {n:,} steps of 1 ms (the core's bench: 10,000)")
    reps = 1 if args.quick else 3
    times = np.arange(n) * 1e-3

    if not args.no_cargo:
        core_kinematics_row("four_bar", "four_bar_10k_steps", rows)

    import camlink

    model = camlink.load(ROOT / "examples" / "four_bar.toml")
    t_end = float(times[-1])
    elapsed, results = best_of(reps, lambda: model.run(t_end=t_end, step=1e-3))
    assert len(results.t) == n, len(results.t)
    rows.append(
        Row(
            "four_bar",
            "camlink from Python (Model.run)",
            "pos, vel, acc + 2 points",
            elapsed / n * 1e6,
            note="whole call: set-up, solve, channels, Results",
        )
    )
    binding_kinematics_row("four_bar", model, times, reps, rows)

    # Textbook NumPy: the same grid (fewer steps: it is slow), checked
    # against camlink's results.
    m = min(n, 1_000 if args.quick else 2_000)
    elapsed, out = best_of(1, lambda: tb.run(times[:m]))
    names = ["crank", "coupler", "rocker"]
    diff = {"q": 0.0, "q̇": 0.0, "q̈": 0.0}
    suffix = {"q": ("x", "y", "phi"), "q̇": ("vx", "vy", "omega"), "q̈": ("ax", "ay", "alpha")}
    for block, key in enumerate(diff):
        for b, body in enumerate(names):
            for c, ch in enumerate(suffix[key]):
                col = out[:, 9 * block + 3 * b + c]
                diff[key] = max(diff[key], float(np.max(np.abs(col - results[f"{body}.{ch}"][:m]))))
    agree = ", ".join(f"{k} {v:.1e}" for k, v in diff.items())
    print(f"  textbook NumPy vs camlink over {m} steps, max |difference|: {agree}")
    rows.append(
        Row(
            "four_bar",
            "textbook NumPy (bench/textbook_four_bar.py)",
            "pos, vel, acc",
            elapsed / m * 1e6,
            note=f"{m} steps; max diff vs camlink {agree}",
        )
    )

    pe = peer("peer_exudyn")
    if pe is not None:
        try:
            elapsed, q = pe.four_bar(times)
            err = float(
                np.max(
                    np.abs(
                        q
                        - np.concatenate(
                            [[results[f"{b}.{c}"][-1] for c in ("x", "y", "phi")] for b in names]
                        )
                    )
                )
            )
            rows.append(
                Row(
                    "four_bar",
                    f"Exudyn {pe.VERSION} SolveStatic",
                    "pos only",
                    elapsed / n * 1e6,
                    note=f"one load step per time, driver offset by Python user function; "
                    f"final q vs camlink {err:.1e}",
                )
            )
        except Exception as e:  # a peer's failure is reported, not fatal
            print(f"  Exudyn: failed ({type(e).__name__}: {e})")


# ---------------------------------------------------------------------------
# 2. Slider-crank forward dynamics.


def core_kinematics_row(bench: str, divan_name: str, rows: list[Row]) -> None:
    """The core's divan benchmark `divan_name` (10,000 kinematic steps of an
    example file) as the base row of `bench`."""
    try:
        res = cargo("camlink-bench", "examples", [divan_name])[divan_name]
    except (RuntimeError, KeyError, OSError) as e:
        print(f"  camlink core: failed ({e})")
        return
    rows.append(
        Row(
            bench,
            "camlink core (Rust, divan)",
            "pos, vel, acc",
            res["median"] / 1e4 * 1e6,
            note=f"fastest {res['fastest'] / 1e4 * 1e6:.2f}",
            base=True,
        )
    )


def binding_kinematics_row(
    bench: str, model: Any, times: np.ndarray, reps: int, rows: list[Row]
) -> None:
    """The binding alone (`_core.run_kinematics`: no point channels, no chunk
    callback) over `times`, best of `reps`."""
    import camlink

    tol, max_iter = camlink._core.Model.analysis_defaults()["kinematics"]
    tol = model.analysis["tol"] or tol
    elapsed, _ = best_of(
        reps, lambda: model._core.run_kinematics(times, tol=tol, max_iter=max_iter, points=[])
    )
    rows.append(
        Row(
            bench,
            "camlink binding (_core.run_kinematics)",
            "pos, vel, acc",
            elapsed / len(times) * 1e6,
            note="one call into Rust, arrays back",
        )
    )


def cam_roller(args: argparse.Namespace, rows: list[Row]) -> None:
    """The seed's Example 3.4.3 (a cam with a roller follower): the core's
    divan benchmark and the binding's run, no peer."""
    n = 1_000 if args.quick else 10_000
    print(f"cam with roller follower kinematics, {n:,} steps of 1 ms (the core's bench: 10,000)")
    if not args.no_cargo:
        core_kinematics_row("cam_roller", "cam_roller_10k_steps", rows)

    import camlink

    model = camlink.load(ROOT / "examples" / "cam_seed_example_3_4_3.toml")
    reps = 1 if args.quick else 3
    binding_kinematics_row("cam_roller", model, np.arange(n) * 1e-3, reps, rows)


def camlink_slider_error() -> float | None:
    """camlink's slider error at t = 1 s from its accuracy test (same model,
    same RK4 reference), printed by the test."""
    cmd = [
        "cargo",
        "test",
        "-q",
        "--release",
        "-p",
        "camlink-core",
        "--test",
        "integration",
        "dynamics_forward::slider_crank_matches_minimal_coordinates",
        "--",
        "--nocapture",
    ]
    print(f"  {' '.join(cmd)} …", flush=True)
    proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, check=False)
    m = re.search(r"\(error ([0-9.eE+-]+) m\)", proc.stderr + proc.stdout)
    return float(m.group(1)) if m else None


def camlink_simulate(text: str, t_end: float, reps: int) -> tuple[float, float, Any] | None:
    """(seconds with output every 1 ms, seconds with output at the end
    only, the first run's results) of `Model.simulate` with h = 1 ms, or
    None when this camlink has no Python forward dynamics."""
    import camlink

    if not hasattr(camlink.Model, "simulate"):
        print("  camlink: forward dynamics has no Python entry here; its figures come from cargo")
        return None
    model = camlink.loads(text)
    every, res = best_of(reps, lambda: model.simulate(t_end=t_end, step=1e-3, h=1e-3, rho_inf=0.8))
    end, _ = best_of(reps, lambda: model.simulate(t_end=t_end, step=t_end, h=1e-3, rho_inf=0.8))
    return every, end, res


def slider_crank(args: argparse.Namespace, rows: list[Row]) -> None:
    print("slider-crank forward dynamics, 1,000 steps of 1 ms")
    steps = 1000
    h_ref = 1e-3 if args.quick else 1e-4
    _, x_ref = sc.reference(1.0, h_ref)
    print(
        f"  reference: RK4 on Lagrange's equation in θ, h = {h_ref:g} s: slider x(1 s) = {x_ref:.9f} m"
    )

    if not args.no_cargo:
        try:
            res = cargo("camlink-bench", "dynamics", ["slider_crank_1000_steps"])[
                "slider_crank_1000_steps"
            ]
            err = camlink_slider_error()
            acc = f"slider error {err:.1e} m (its test)" if err is not None else "error not read"
            rows.append(
                Row(
                    "slider_crank",
                    "camlink core (Rust, divan) gen-α ρ∞=0.8",
                    "index-3, Newton",
                    res["median"] / steps * 1e6,
                    base=True,
                    note=f"{acc}; fastest {res['fastest'] / steps * 1e6:.2f}",
                )
            )
        except (RuntimeError, KeyError, OSError) as e:
            print(f"  camlink core: failed ({e})")

    py = camlink_simulate(camlink_models.slider_crank(), 1.0, 1 if args.quick else 3)
    if py is not None:
        every, end, res = py
        x = float(res["slider.x"][-1])
        rows.append(
            Row(
                "slider_crank",
                "camlink from Python (Model.simulate)",
                "index-3, Newton",
                every / steps * 1e6,
                note=f"slider error {abs(x - x_ref):.1e} m; output at the end only {end / steps * 1e6:.2f}",
            )
        )

    pe = peer("peer_exudyn")
    if pe is not None:
        try:
            t1, x = pe.slider_crank(steps, 1.0)
            t2, _ = pe.slider_crank(2 * steps, 2.0)
            rows.append(
                Row(
                    "slider_crank",
                    f"Exudyn {pe.VERSION} gen-α ρ∞=0.8",
                    "index-3, modified Newton",
                    t1 / steps * 1e6,
                    note=f"slider error {abs(x - x_ref):.1e} m; marginal {(t2 - t1) / steps * 1e6:.1f}",
                )
            )
        except Exception as e:
            print(f"  Exudyn: failed ({type(e).__name__}: {e})")

    pm = peer("peer_mujoco")
    if pm is not None:
        try:
            t, x = pm.slider_crank(steps)
            rows.append(
                Row(
                    "slider_crank",
                    f"MuJoCo {pm.VERSION} Euler",
                    "joint coords, soft loop",
                    t / steps * 1e6,
                    note=f"slider error {abs(x - x_ref):.1e} m",
                )
            )
        except Exception as e:
            print(f"  MuJoCo: failed ({type(e).__name__}: {e})")


# ---------------------------------------------------------------------------
# 3. Pendulum chain.


def chain(args: argparse.Namespace, rows: list[Row]) -> None:
    sizes = (10, 100) if args.quick else (10, 100, 1000)
    steps = 100
    print(f"pendulum chain, N = {', '.join(map(str, sizes))}; {steps} steps of 1 ms")
    unit = "µs/body/step"

    if not args.no_cargo:
        try:
            res = cargo("camlink-bench", "dynamics", ["chain_100_steps"])
            for n in sizes:
                r = res[f"chain_100_steps/{n}"]
                rows.append(
                    Row(
                        f"chain N={n}",
                        "camlink core (Rust, divan) gen-α",
                        "index-3, Newton",
                        r["median"] / (steps * n) * 1e6,
                        unit,
                        base=True,
                        note=f"fastest {r['fastest'] / (steps * n) * 1e6:.3f}",
                    )
                )
        except (RuntimeError, KeyError, OSError) as e:
            print(f"  camlink core: failed ({e})")

    for n in sizes:
        py = camlink_simulate(camlink_models.chain(n), steps * 1e-3, 1)
        if py is None:
            break
        every, end, _ = py
        rows.append(
            Row(
                f"chain N={n}",
                "camlink from Python (Model.simulate)",
                "index-3, Newton",
                every / (steps * n) * 1e6,
                unit,
                note=f"output at the end only {end / (steps * n) * 1e6:.3g}",
            )
        )

    pe = peer("peer_exudyn")
    if pe is not None:
        for n in sizes:
            try:
                t1 = pe.chain(n, steps)
                t2 = pe.chain(n, 2 * steps)
                solver = "sparse" if n > 20 else "dense"
                rows.append(
                    Row(
                        f"chain N={n}",
                        f"Exudyn {pe.VERSION} gen-α ρ∞=0.8",
                        "index-3, modified Newton",
                        t1 / (steps * n) * 1e6,
                        unit,
                        note=f"{solver} solver; marginal {(t2 - t1) / (steps * n) * 1e6:.2g}",
                    )
                )
            except Exception as e:
                print(f"  Exudyn N={n}: failed ({type(e).__name__}: {e})")

    pm = peer("peer_mujoco")
    if pm is not None:
        for n in sizes:
            for maximal, what in ((True, "maximal coords, soft connect"), (False, "hinge tree")):
                try:
                    t = pm.chain(n, steps, maximal)
                    rows.append(
                        Row(
                            f"chain N={n}",
                            f"MuJoCo {pm.VERSION} Euler",
                            what,
                            t / (steps * n) * 1e6,
                            unit,
                        )
                    )
                except Exception as e:
                    print(f"  MuJoCo N={n} ({what}): failed ({type(e).__name__}: {e})")


# ---------------------------------------------------------------------------


def output(args: argparse.Namespace, rows: list[Row]) -> None:
    """The cost of writing results: the base is the same run with no
    output (targets: CSV within 2×, Parquet within 1.3×)."""
    steps = 20_000 if args.quick else 200_000
    reps = 1 if args.quick else 3
    print(f"writing results: four-bar kinematics, {steps:,} steps of 10 µs")
    for label, us in output_writing.measure(steps, reps).items():
        target = {"CSV": "target ≤ 2×", "Parquet": "target ≤ 1.3×"}.get(label, "")
        rows.append(
            Row("output", "camlink from Python", f"kinematics, {label}", us,
                note=target, base=label == "no output")
        )


def ratio(x: float) -> str:
    return f"{x:.2f}" if x < 10 else f"{x:.0f}"


def table(rows: list[Row]) -> None:
    # The base of each benchmark: camlink's core, else its first row.
    base: dict[str, float] = {}
    for r in sorted(rows, key=lambda r: not r.base):
        if r.us is not None:
            base.setdefault(r.bench, r.us)
    order = {b: k for k, b in reversed(list(enumerate(r.bench for r in rows)))}
    rows = sorted(rows, key=lambda r: order[r.bench])
    head = ("benchmark", "engine", "computes", "time", "× camlink", "notes")
    lines = [
        (
            r.bench,
            r.engine,
            r.computes,
            f"{r.us:.3g} {r.unit}" if r.us is not None else "—",
            ratio(r.us / base[r.bench]) if r.us is not None and r.bench in base else "—",
            r.note,
        )
        for r in rows
    ]
    widths = [max(len(h), *(len(l[i]) for l in lines)) for i, h in enumerate(head)]
    print()
    print(" | ".join(h.ljust(w) for h, w in zip(head, widths)).rstrip())
    print("-|-".join("-" * w for w in widths))
    for l in lines:
        print(" | ".join(c.ljust(w) for c, w in zip(l, widths)).rstrip())


def main() -> None:
    p = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    p.add_argument("--quick", action="store_true", help="fewer steps and repeats, N up to 100")
    p.add_argument(
        "--only", choices=BENCHES, action="append", help="run only this benchmark (repeatable)"
    )
    p.add_argument(
        "--no-cargo", action="store_true", help="skip the cargo bench figures of the core"
    )
    args = p.parse_args()

    print(f"camlink benchmark comparison, {datetime.datetime.now().isoformat(timespec='minutes')}")
    print(
        f"machine: {platform.machine()} {platform.processor() or ''}, Python {platform.python_version()}, NumPy {np.__version__}"
    )
    print(f"load average at start: {load_average()}")
    print(
        "(a shared machine: figures under load are slow and noisy; compare ratios within one run)"
    )
    rows: list[Row] = []
    for name in args.only or BENCHES:
        globals()[name](args, rows)
    table(rows)
    print(f"\nload average at end: {load_average()}")


if __name__ == "__main__":
    main()
