"""`camlink.monte_carlo`: a model run over random parameter values drawn
from scipy.stats distributions, with statistics of the outputs and a
ranking of the inputs by how much each moves each output."""

from __future__ import annotations

import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
import numpy.typing as npt
import pandas as pd

from camlink._core import ModelError
from camlink.model import Model
from camlink.study.outputs import Output
from camlink.study.runner import BATCH, ERROR, KEY, STATUS, VARIANT, check_size, run_variants

__all__ = ["MonteCarlo", "monte_carlo", "sample", "sensitivity", "statistics"]

Sampling = Literal["random", "sobol", "lhs"]


@dataclass(frozen=True)
class MonteCarlo:
    """The outcome of a Monte Carlo study.

    `table`: one row per variant (parameters, outputs, ``study.status``,
    ``study.error``, …; see `camlink.study.run_variants`).
    `statistics`: one row per output, over the variants that ran (``n``):
    ``mean``, ``std`` (with n − 1), ``sem`` (standard error of the mean,
    std/√n), ``min``, ``p05``, ``median``, ``p95``, ``max``.
    `sensitivity`: one row per (output, parameter): ``src`` (standardised
    regression coefficient: the change of the output, in its standard
    deviations, per standard deviation of the parameter, the others held),
    ``spearman`` (rank correlation) and ``rank`` (1 = largest |src|).
    """

    table: pd.DataFrame
    statistics: pd.DataFrame
    sensitivity: pd.DataFrame


def sample(
    distributions: Mapping[str, Any], n: int, *, seed: int | None = None, sampling: Sampling = "random"
) -> pd.DataFrame:
    """`n` parameter sets drawn from `distributions` (name → frozen
    scipy.stats distribution, e.g. ``scipy.stats.norm(0.12, 0.0005)``),
    each independent: points of the unit cube — pseudo-random, scrambled
    Sobol or Latin hypercube (scipy.stats.qmc) — mapped through each
    distribution's inverse CDF."""
    from scipy.stats import qmc

    if isinstance(n, bool) or not isinstance(n, int) or n < 1:
        raise ModelError(f"monte_carlo: n must be a whole number of at least 1 ({n!r})")
    if not distributions:
        raise ModelError("monte_carlo: give at least one parameter and its distribution")
    for name, dist in distributions.items():
        if not callable(getattr(dist, "ppf", None)):
            raise ModelError(
                f"monte_carlo: '{name}' needs a scipy.stats distribution "
                f"(such as scipy.stats.norm(0.12, 0.0005)), not {type(dist).__name__}"
            )
    d = len(distributions)
    check_size(n, d + 1, "monte_carlo")
    if sampling == "random":
        u = np.random.default_rng(seed).random((n, d))
    elif sampling == "sobol":
        with warnings.catch_warnings():
            # Sobol points balance best at n a power of two; any n is valid.
            warnings.simplefilter("ignore", UserWarning)
            u = qmc.Sobol(d, scramble=True, seed=seed).random(n)
    elif sampling == "lhs":
        u = qmc.LatinHypercube(d, seed=seed).random(n)
    else:
        raise ModelError(f"monte_carlo: sampling must be 'random', 'sobol' or 'lhs', not {sampling!r}")
    columns = {name: np.asarray(dist.ppf(u[:, k]), dtype=np.float64)
               for k, (name, dist) in enumerate(distributions.items())}
    for name, x in columns.items():
        if not np.all(np.isfinite(x)):
            raise ModelError(f"monte_carlo: the distribution of '{name}' gives values that are not finite")
    return pd.DataFrame(columns)


def statistics(table: pd.DataFrame, outputs: list[str]) -> pd.DataFrame:
    """Statistics of each output over the variants whose status is ok."""
    ok = table[table[STATUS] == "ok"]
    rows = []
    for name in outputs:
        x = ok[name].to_numpy(dtype=np.float64)
        n = len(x)
        std = float(np.std(x, ddof=1)) if n > 1 else float("nan")
        q = np.quantile(x, [0.05, 0.5, 0.95]) if n else [np.nan] * 3
        rows.append({
            "output": name, "n": n, "mean": float(np.mean(x)) if n else np.nan, "std": std,
            "sem": std / np.sqrt(n) if n > 1 else np.nan,
            "min": float(np.min(x)) if n else np.nan, "p05": float(q[0]), "median": float(q[1]),
            "p95": float(q[2]), "max": float(np.max(x)) if n else np.nan,
        })
    return pd.DataFrame(rows).set_index("output")


def sensitivity(table: pd.DataFrame, params: list[str], outputs: list[str]) -> pd.DataFrame:
    """The inputs ranked by their effect on each output: standardised
    regression coefficients of a least-squares linear fit, and Spearman
    rank correlations, over the variants whose status is ok."""
    from scipy.stats import spearmanr

    ok = table[table[STATUS] == "ok"]
    rows = []
    x = ok[params].to_numpy(dtype=np.float64)
    for name in outputs:
        y = ok[name].to_numpy(dtype=np.float64)
        src = _src(x, y)
        ranks = np.argsort(np.argsort(-np.abs(np.nan_to_num(src, nan=-1.0))))
        for k, p in enumerate(params):
            rho = float("nan")
            if len(y) > 2 and np.std(x[:, k]) > 0 and np.std(y) > 0:
                rho = float(spearmanr(x[:, k], y).statistic)
            rows.append({"output": name, "parameter": p, "src": float(src[k]), "spearman": rho,
                         "rank": int(ranks[k]) + 1})
    return pd.DataFrame(rows)


def _src(x: npt.NDArray[np.float64], y: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    """Standardised regression coefficients of y on the columns of x."""
    n, d = x.shape
    sx, sy = np.std(x, axis=0), np.std(y)
    if n <= d or sy == 0:
        return np.full(d, np.nan)
    a = np.column_stack([np.ones(n), x - x.mean(axis=0)])
    coef, *_ = np.linalg.lstsq(a, y, rcond=None)
    out: npt.NDArray[np.float64] = coef[1:] * sx / sy
    return out


def monte_carlo(
    model: Model,
    distributions: Mapping[str, Any],
    outputs: Mapping[str, Output | Mapping[str, Any]],
    *,
    n: int,
    seed: int | None = None,
    sampling: Sampling = "random",
    **execution: Any,
) -> MonteCarlo:
    """Runs `model` for `n` parameter sets drawn from `distributions` (see
    `sample`) and returns the table, the statistics of each output and a
    sensitivity ranking of the inputs (`MonteCarlo`). `execution`
    arguments are those of `camlink.study.run_variants`."""
    drawn = sample(distributions, n, seed=seed, sampling=sampling)
    params = list(drawn.columns)
    variants = [{p: float(row[k]) for k, p in enumerate(params)} for row in drawn.to_numpy()]
    table = run_variants(model, variants, outputs, **execution)
    names = [c for c in table.columns if c not in (*params, VARIANT, STATUS, ERROR, KEY, BATCH)]
    return MonteCarlo(table, statistics(table, names), sensitivity(table, params, names))
