"""Studies: many variants of a model — sweeps, Monte Carlo, optimisation —
each run reduced to the outputs named, on local cores or on Dask
(docs/studies.md)."""

from camlink.study.balance import PartialBalance, partial_balance
from camlink.study.optimization import Optimum, optimize
from camlink.study.outputs import (
    Output,
    at,
    first_lift_off,
    least_transmission_angle,
    max_abs,
    max_of,
    max_pressure_angle,
    min_of,
    peak_effort,
    range_of,
)
from camlink.study.runner import run_variants, variant_key
from camlink.study.sampling import MonteCarlo, monte_carlo
from camlink.study.sweeps import sweep, sweep_variants

__all__ = [
    "MonteCarlo",
    "Optimum",
    "Output",
    "PartialBalance",
    "at",
    "first_lift_off",
    "least_transmission_angle",
    "max_abs",
    "max_of",
    "max_pressure_angle",
    "min_of",
    "monte_carlo",
    "optimize",
    "partial_balance",
    "peak_effort",
    "range_of",
    "run_variants",
    "sweep",
    "sweep_variants",
    "variant_key",
]
