"""Partial balance of a machine (`docs/machine.md`): the counterweights of
the full force balance, each scaled by a factor k ≥ 0, with the factors
chosen by the study optimiser to minimise

    J = w_F F/F₀ + w_M M/M₀ + w_T ΔT/ΔT₀,

F the peak shaking force less the weight (N), M the peak shaking moment
about the `[machine]` table's point (N·m) and ΔT the swing of the input
torque (N·m), each relative to the unbalanced machine's (F₀, M₀, ΔT₀), so
that the unbalanced machine scores w_F + w_M + w_T. The figures and J are
computed in the core (`_core.MachineCycle`, one inverse-dynamics cycle
per point, on all cores); this module hands them to
`camlink.study.optimization.minimise_batch`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any, cast

import numpy as np
import numpy.typing as npt
import pandas as pd

from camlink import _core
from camlink._core import ModelError
from camlink.machine import MachineCounterweight
from camlink.study.optimization import minimise_batch

__all__ = ["BalanceFigures", "PartialBalance", "partial_balance"]

#: Differential evolution's settings unless `options` says otherwise: a
#: small population, for a problem of one or two factors.
DEFAULT_OPTIONS: dict[str, Any] = {"popsize": 8, "maxiter": 40, "tol": 1e-4, "polish": False}


@dataclass(frozen=True)
class BalanceFigures:
    """A machine's balance figures: peak |F_s − W| (N), peak |M_P| (N·m),
    the input torque's swing max T − min T (N·m) and the objective J."""

    force: float
    moment: float
    torque_swing: float
    objective: float


@dataclass(frozen=True)
class PartialBalance:
    """The best factors found and what they give.

    `factors` maps each counterweighted body to its factor k (1: the full
    balance's counterweight, 0: none); `counterweights` are those
    counterweights (as in the machine report); `figures` the machine with
    them, `unbalanced` and `full` the machine as it is and fully balanced,
    all scored with `weights`. `history` has one row per point run:
    ``k.<body>`` for each factor, ``force``, ``moment``, ``torque_swing``,
    ``objective``. `result` is scipy's ``OptimizeResult``.
    """

    linkage: str
    weights: tuple[float, float, float]
    factors: dict[str, float]
    counterweights: list[MachineCounterweight]
    figures: BalanceFigures
    unbalanced: BalanceFigures
    full: BalanceFigures
    history: pd.DataFrame
    result: Any


def _weights(weights: Sequence[float]) -> tuple[float, float, float]:
    try:
        w = tuple(float(x) for x in weights)
    except (TypeError, ValueError):
        raise ModelError("partial balance: weights must be three numbers (force, moment, torque)") from None
    if len(w) != 3 or not all(math.isfinite(x) and x >= 0.0 for x in w) or sum(w) <= 0.0:
        raise ModelError(
            "partial balance: weights must be three numbers ≥ 0 (force, moment, torque), not all zero; "
            f"got {list(weights)}"
        )
    return (w[0], w[1], w[2])


def partial_balance(
    path: str | Path,
    weights: Sequence[float] = (1.0, 1.0, 1.0),
    *,
    bounds: tuple[float, float] = (0.0, 1.5),
    method: str = "differential_evolution",
    seed: int | None = 0,
    options: dict[str, Any] | None = None,
) -> PartialBalance:
    """The partial balance of the machine in the model file at `path` (its
    ``[machine]`` table; a four-bar or slider-crank) for `weights`
    (w_F, w_M, w_T), each factor within `bounds`. `method`, `seed` and
    `options` go to `minimise_batch` (differential evolution by default,
    with `DEFAULT_OPTIONS`). The answer is the best point run, the
    unbalanced (every k = 0) and fully balanced (every k = 1) machines
    among them. A `ModelError` names bad input."""
    w = _weights(weights)
    lo_b, hi_b = (float(b) for b in bounds)
    if not (0.0 <= lo_b < hi_b and math.isfinite(hi_b)):
        raise ModelError(f"partial balance: bounds must satisfy 0 ≤ low < high, got {bounds}")
    cycle = _core.MachineCycle(Path(path))
    bodies = cycle.bodies
    n = len(bodies)
    rows: list[tuple[float, ...]] = []

    def evaluate(x: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        """Objectives of the points in the columns of x (or of one point)."""
        pts = np.atleast_2d(np.asarray(x, dtype=np.float64).T)
        got = cycle.evaluate([list(map(float, p)) for p in pts], w)
        rows.extend(tuple(p) + r for p, r in zip(pts, got, strict=True))
        values = np.array([r[3] for r in got], dtype=np.float64)
        return np.where(np.isfinite(values), values, np.inf)

    # The two ends first: the unbalanced and the fully balanced machine.
    evaluate(np.array([[0.0] * n, [1.0] * n]).T)
    unbalanced, full = (BalanceFigures(*rows[k][n:]) for k in (0, 1))
    opts = {**DEFAULT_OPTIONS, **(options or {})} if method == "differential_evolution" else options
    lo, hi = np.full(n, lo_b), np.full(n, hi_b)
    result = minimise_batch(evaluate, lo, hi, method=method, seed=seed, options=opts)
    columns = [*(f"k.{b}" for b in bodies), "force", "moment", "torque_swing", "objective"]
    history = pd.DataFrame(rows, columns=columns)
    best = history.iloc[int(np.nanargmin(history["objective"].to_numpy(dtype=np.float64)))]
    k = [float(best[f"k.{b}"]) for b in bodies]
    return PartialBalance(
        linkage=cycle.linkage,
        weights=w,
        factors=dict(zip(bodies, k, strict=True)),
        counterweights=cast(list[MachineCounterweight], cycle.counterweights(k)),
        figures=BalanceFigures(*(float(best[c]) for c in ("force", "moment", "torque_swing", "objective"))),
        unbalanced=unbalanced,
        full=full,
        history=history,
        result=result,
    )
