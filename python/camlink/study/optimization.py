"""`camlink.optimize`: the parameter values that minimise a function of a
run's outputs (scipy.optimize)."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt
import pandas as pd

from camlink._core import ModelError
from camlink.model import Model
from camlink.study.outputs import Output
from camlink.study.runner import BATCH, ERROR, KEY, STATUS, VARIANT, run_variants

__all__ = ["OBJECTIVE", "Optimum", "minimise_batch", "optimize"]

#: The column of `Optimum.history` that holds each variant's objective.
OBJECTIVE = "study.objective"

#: The objective: a variant's row (each parameter and output by name) → a number.
Objective = Callable[[Mapping[str, float]], float]


@dataclass(frozen=True)
class Optimum:
    """The best variant found.

    `parameters` and `outputs` are its values by name, `objective` its
    objective; `history` has one row per variant run (parameters,
    outputs, ``study.status``, ``study.error``, ``study.objective``), in
    the order run; `result` is
    scipy's ``OptimizeResult`` (``success``, ``message``, ``nfev``, …).
    """

    parameters: dict[str, float]
    outputs: dict[str, float]
    objective: float
    history: pd.DataFrame
    result: Any


def optimize(
    model: Model,
    objective: Objective,
    bounds: Mapping[str, tuple[float, float]],
    outputs: Mapping[str, Output | Mapping[str, Any]],
    *,
    method: str = "differential_evolution",
    x0: Mapping[str, float] | None = None,
    seed: int | None = None,
    options: Mapping[str, Any] | None = None,
    **execution: Any,
) -> Optimum:
    """Minimises ``objective(row)`` over the parameters in `bounds` (name →
    (low, high)), where `row` maps each parameter and each of `outputs` to
    its value for one variant. A variant that fails counts as +∞.

    ``method="differential_evolution"`` (default) evaluates each
    generation's whole population as one batch, in parallel; any method of
    ``scipy.optimize.minimize`` (``"Nelder-Mead"``, ``"Powell"``,
    ``"L-BFGS-B"``, …) starts from `x0` (default: the middle of the
    bounds) and runs one variant at a time. `options` go to the scipy
    function; `execution` arguments to `camlink.study.run_variants`
    (``output`` is not allowed: an optimisation keeps its `history`).
    Variants run are not cached: a point scipy asks for twice runs twice.
    """
    if "output" in execution:
        raise ModelError("optimize: `output` does not apply; the variants run are in Optimum.history")
    if not callable(objective):
        raise ModelError(f"optimize: objective must be callable, not {type(objective).__name__}")
    names = list(bounds)
    if not names:
        raise ModelError("optimize: give at least one parameter and its bounds")
    lo = np.empty(len(names))
    hi = np.empty(len(names))
    for k, name in enumerate(names):
        try:
            lo[k], hi[k] = (float(b) for b in bounds[name])
        except (TypeError, ValueError):
            raise ModelError(f"optimize: the bounds of '{name}' must be two numbers (low, high)") from None
        if not (np.isfinite(lo[k]) and np.isfinite(hi[k]) and lo[k] < hi[k]):
            raise ModelError(f"optimize: the bounds of '{name}' must be finite with low < high")
    history: list[pd.DataFrame] = []
    first = [True]

    def evaluate(x: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        """Objectives of the points in the columns of x (or of one point)."""
        pts = np.atleast_2d(np.asarray(x, dtype=np.float64).T)
        variants = [dict(zip(names, map(float, p), strict=True)) for p in pts]
        table = run_variants(model, variants, outputs, check_outputs=first[0], **execution)
        first[0] = False
        values = np.full(len(table), np.inf)
        for k, row in enumerate(table.to_dict("records")):
            if row[STATUS] == "ok":
                v = float(objective({str(c): x for c, x in row.items()}))
                values[k] = v if np.isfinite(v) else np.inf
        table = table.drop(columns=[VARIANT, KEY, BATCH]).assign(**{OBJECTIVE: values})
        history.append(table)
        return values

    start = np.array([float(x0[n]) for n in names]) if x0 is not None else None
    result = minimise_batch(evaluate, lo, hi, method=method, x0=start, seed=seed, options=options)
    hist = pd.concat(history, ignore_index=True)
    ok = hist[np.isfinite(hist[OBJECTIVE])]
    if ok.empty:
        raise ModelError("optimize: no variant ran; see the errors of Optimum.history")
    best = ok.loc[ok[OBJECTIVE].idxmin()]
    out_names = [c for c in hist.columns if c not in (*names, STATUS, ERROR, OBJECTIVE)]
    return Optimum(
        parameters={n: float(best[n]) for n in names},
        outputs={n: float(best[n]) for n in out_names},
        objective=float(best[OBJECTIVE]),
        history=hist,
        result=result,
    )



def minimise_batch(
    evaluate: Callable[[npt.NDArray[np.float64]], npt.NDArray[np.float64]],
    lo: npt.NDArray[np.float64],
    hi: npt.NDArray[np.float64],
    *,
    method: str = "differential_evolution",
    x0: npt.NDArray[np.float64] | None = None,
    seed: int | None = None,
    options: Mapping[str, Any] | None = None,
) -> Any:
    """The optimiser of `optimize`, for any batch objective: minimises
    over the box `lo` ≤ x ≤ `hi`, where ``evaluate(x)`` gives the
    objectives of the points in the columns of `x` (or of one point) as an
    array (+∞ for a failed point). ``differential_evolution`` (default)
    hands each generation's whole population to `evaluate` at once; any
    method of ``scipy.optimize.minimize`` starts from `x0` (default: the
    middle of the box) and evaluates one point at a time. Returns scipy's
    ``OptimizeResult``."""
    from scipy import optimize as so

    opts = dict(options or {})
    box = list(zip(lo, hi, strict=True))
    if method == "differential_evolution":
        return so.differential_evolution(
            lambda x: evaluate(x) if np.ndim(x) > 1 else float(evaluate(x)[0]),
            box, vectorized=True, updating="deferred", seed=seed, **opts,
        )
    start = x0 if x0 is not None else (lo + hi) / 2
    return so.minimize(lambda x: float(evaluate(x)[0]), start, method=method, bounds=box, options=opts)
