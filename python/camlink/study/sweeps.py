"""`camlink.sweep`: a model run over a grid of parameter values, or over
lists of values taken together."""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterable, Mapping, Sized
from typing import Any, Literal

import pandas as pd

from camlink._core import ModelError
from camlink.model import Model
from camlink.study.outputs import Output
from camlink.study.runner import check_size, run_variants

__all__ = ["sweep", "sweep_variants"]


def sweep_variants(
    values: Mapping[str, Iterable[float]], mode: Literal["grid", "zip"] = "grid"
) -> list[dict[str, float]]:
    """The parameter sets of a sweep: every combination of the lists
    (``"grid"``, the last name varying fastest), or the i-th value of each
    list together (``"zip"``, lists of one length). A sweep too large for
    the memory available is refused before it is built
    (`camlink.study.runner.check_size`)."""
    if not values:
        raise ModelError("sweep: give at least one parameter and its values")
    sizes = [len(vs) for vs in values.values() if isinstance(vs, Sized)]
    if len(sizes) == len(values) and mode in ("grid", "zip"):
        # Before the lists are copied: one of 10⁹ values is itself too many.
        check_size(math.prod(sizes) if mode == "grid" else max(sizes), len(values) + 1, f"sweep ({mode})")
    lists: dict[str, list[float]] = {}
    for name, vs in values.items():
        try:
            lists[name] = [float(v) for v in vs]
        except (TypeError, ValueError):
            raise ModelError(f"sweep: the values of '{name}' must be a list of numbers") from None
        if not lists[name]:
            raise ModelError(f"sweep: '{name}' has no values")
    names = list(lists)
    if mode in ("grid", "zip"):
        n = math.prod(len(v) for v in lists.values()) if mode == "grid" else len(lists[names[0]])
        check_size(n, len(names) + 1, f"sweep ({mode})")
    if mode == "grid":
        return [dict(zip(names, combo, strict=True)) for combo in itertools.product(*lists.values())]
    if mode == "zip":
        lengths = {name: len(v) for name, v in lists.items()}
        if len(set(lengths.values())) != 1:
            raise ModelError(f"sweep: zipped lists must have one length, got {lengths}")
        return [dict(zip(names, combo, strict=True)) for combo in zip(*lists.values(), strict=True)]
    raise ModelError(f"sweep: mode must be 'grid' or 'zip', not {mode!r}")


def sweep(
    model: Model,
    values: Mapping[str, Iterable[float]],
    outputs: Mapping[str, Output | Mapping[str, Any]],
    *,
    mode: Literal["grid", "zip"] = "grid",
    **execution: Any,
) -> pd.DataFrame:
    """Runs `model` for each parameter set of `values` (see
    `sweep_variants`) and returns one row per variant: its parameters, its
    `outputs`, ``status`` and ``error`` (see `camlink.study.run_variants`,
    whose `execution` arguments — `output`, `client`, `scheduler`,
    `threads`, `batch_size`, `time_limit`, `quiet` — are passed on)."""
    return run_variants(model, sweep_variants(values, mode), outputs, **execution)
