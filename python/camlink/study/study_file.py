"""Study files: a ``[study]`` table naming a model, the parameters and
their values or distributions, the outputs and how to run.

```toml
[study]
model = "four_bar.toml"      # resolved against this file's folder
kind = "sweep"               # or "monte_carlo"
mode = "grid"                # sweep: "grid" (every combination) or "zip"

[study.parameters]
a = { start = 0.08, stop = 0.16, num = 9 }   # or a list: [0.08, 0.1]

[study.outputs]
swing = { kind = "range", channel = "rocker.phi" }
```

A Monte Carlo study gives each parameter a scipy.stats distribution by
name with its keyword arguments (``{ dist = "norm", loc = 0.12, scale =
0.0005 }``) and ``n``, ``seed``, ``sampling``. Errors name the file, the
line and the field.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from camlink import _core
from camlink._core import ModelError
from camlink.study.outputs import Output, parse_outputs
from camlink.study.runner import check_size

__all__ = ["StudyFile", "read_study"]

_KEYS = {"model", "kind", "mode", "n", "seed", "sampling", "batch_size", "threads", "time_limit",
         "scheduler", "parameters", "outputs"}
_SPACED = {"start", "stop", "num"}


@dataclass(frozen=True)
class StudyFile:
    """A study file, validated. `values` holds a sweep's lists;
    `distributions` a Monte Carlo study's frozen scipy.stats
    distributions."""

    path: Path
    model: Path
    kind: str
    outputs: dict[str, Output]
    values: dict[str, list[float]] = field(default_factory=dict)
    distributions: dict[str, Any] = field(default_factory=dict)
    mode: str = "grid"
    n: int = 0
    seed: int | None = None
    sampling: str = "random"
    batch_size: int | None = None
    threads: int | None = None
    time_limit: float | None = None
    scheduler: str | None = None


class _Where:
    """Names the file, line and field of an error."""

    def __init__(self, path: Path, text: str) -> None:
        self.path, self.text = path, text

    def error(self, fieldpath: str, message: str) -> ModelError:
        pos = _core.toml_position(self.text, fieldpath)
        at = f":{pos[0]}:{pos[1]}" if pos else ""
        return ModelError(f"{self.path}{at}: {fieldpath}: {message}")


def read_study(path: str | Path) -> StudyFile:
    """Reads and checks a study file."""
    path = Path(path)
    text = path.read_text(encoding="utf-8")
    where = _Where(path, text)
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise ModelError(f"{path}: syntax error: {e}") from None
    study = doc.get("study")
    if not isinstance(study, dict):
        raise ModelError(f"{path}: no [study] table; a study file names its model in [study] model = \"...\"")
    for key in study:
        if key not in _KEYS:
            keys = ", ".join(sorted(_KEYS))
            raise where.error(f"study.{key}", f"unknown key (the keys of [study]: {keys})")
    model = study.get("model")
    if not isinstance(model, str) or not model:
        raise where.error("study.model", "give the model file, e.g. model = \"four_bar.toml\"")
    kind = study.get("kind", "sweep")
    if kind not in ("sweep", "monte_carlo"):
        raise where.error("study.kind", f"expected \"sweep\" or \"monte_carlo\", not {kind!r}")
    opts: dict[str, Any] = {
        "batch_size": _whole(study, "batch_size", where),
        "threads": _whole(study, "threads", where),
        "time_limit": _positive(study, "time_limit", where),
        "scheduler": _text(study, "scheduler", where),
    }
    params = study.get("parameters")
    if not isinstance(params, dict) or not params:
        raise where.error("study.parameters", "give each parameter its values (sweep) or distribution")
    outputs = _outputs(study.get("outputs"), where)
    common = {"path": path, "model": path.parent / model, "kind": kind, "outputs": outputs, **opts}
    if kind == "sweep":
        for key in ("n", "seed", "sampling"):
            if key in study:
                raise where.error(f"study.{key}", "applies to kind = \"monte_carlo\" only")
        mode = study.get("mode", "grid")
        if mode not in ("grid", "zip"):
            raise where.error("study.mode", f"expected \"grid\" or \"zip\", not {mode!r}")
        counts = [c for c in (_count(spec) for spec in params.values()) if c is not None]
        if len(counts) == len(params):
            total = math.prod(counts) if mode == "grid" else max(counts)
            check_size(total, len(params) + len(outputs), f"{path}: study.parameters")
        values = {name: _values(name, spec, where) for name, spec in params.items()}
        if mode == "zip" and len({len(v) for v in values.values()}) > 1:
            raise where.error("study.parameters", "with mode = \"zip\" every list must have one length")
        return StudyFile(**common, values=values, mode=mode)
    if "mode" in study:
        raise where.error("study.mode", "applies to kind = \"sweep\" only")
    n = _whole(study, "n", where)
    if n is None:
        raise where.error("study.n", "a Monte Carlo study needs n, the number of variants")
    sampling = study.get("sampling", "random")
    if sampling not in ("random", "sobol", "lhs"):
        raise where.error("study.sampling", f"expected \"random\", \"sobol\" or \"lhs\", not {sampling!r}")
    seed = study.get("seed")
    if seed is not None and (isinstance(seed, bool) or not isinstance(seed, int) or seed < 0):
        raise where.error("study.seed", f"expected a whole number ≥ 0, not {seed!r}")
    check_size(n, len(params) + len(outputs), f"{path}: study.n")
    dists = {name: _distribution(name, spec, where) for name, spec in params.items()}
    return StudyFile(**common, distributions=dists, n=n, seed=seed, sampling=sampling)


def _outputs(spec: Any, where: _Where) -> dict[str, Output]:
    if not isinstance(spec, dict) or not spec:
        raise where.error("study.outputs", "give at least one output, e.g. swing = { kind = \"range\", "
                          "channel = \"rocker.phi\" }")
    try:
        return parse_outputs(spec, "study.outputs")
    except ModelError as e:
        fieldpath, _, message = str(e).partition(": ")
        raise where.error(fieldpath, message) from None


def _count(spec: Any) -> int | None:
    """How many values a parameter of a sweep gives, before they are made
    (None when `spec` is not valid; `_values` says why)."""
    if isinstance(spec, list):
        return len(spec)
    if isinstance(spec, dict):
        num = spec.get("num")
        if isinstance(num, int) and not isinstance(num, bool) and num >= 1:
            return num
    return None


def _values(name: str, spec: Any, where: _Where) -> list[float]:
    f = f"study.parameters.{name}"
    if isinstance(spec, list):
        if not spec or not all(_is_number(v) for v in spec):
            raise where.error(f, "expected a list of numbers")
        return [float(v) for v in spec]
    if isinstance(spec, dict):
        for key in spec:
            if key not in _SPACED:
                raise where.error(f"{f}.{key}", "unknown key (a range has start, stop, num)")
        if set(spec) != _SPACED or not _is_number(spec["start"]) or not _is_number(spec["stop"]):
            raise where.error(f, "a range needs start and stop (numbers) and num")
        num = spec["num"]
        if isinstance(num, bool) or not isinstance(num, int) or num < 1:
            raise where.error(f"{f}.num", f"expected a whole number ≥ 1, not {num!r}")
        return [float(v) for v in np.linspace(spec["start"], spec["stop"], num)]
    raise where.error(f, "expected a list of values or { start, stop, num }")


def _distribution(name: str, spec: Any, where: _Where) -> Any:
    """A frozen scipy.stats distribution looked up by name among the
    continuous distributions only (nothing from the file is evaluated)."""
    from scipy import stats

    f = f"study.parameters.{name}"
    if not isinstance(spec, dict) or not isinstance(spec.get("dist"), str):
        raise where.error(f, "expected a distribution, e.g. { dist = \"norm\", loc = 0.12, scale = 0.001 }")
    dist = getattr(stats, spec["dist"], None) if spec["dist"].isidentifier() else None
    if not isinstance(dist, stats.rv_continuous):
        raise where.error(f"{f}.dist", f"{spec['dist']!r} is not a continuous scipy.stats distribution "
                          "(such as norm, uniform, truncnorm, lognorm, triang)")
    args = {k: v for k, v in spec.items() if k != "dist"}
    for key, value in args.items():
        if not _is_number(value):
            raise where.error(f"{f}.{key}", f"expected a number, not {value!r}")
    try:
        frozen = dist(**args)
        mean = frozen.mean()
    except (TypeError, ValueError) as e:
        raise where.error(f, f"{spec['dist']}: {e}") from None
    if not np.isfinite(mean) and not np.isfinite(frozen.median()):
        raise where.error(f, f"{spec['dist']} with these arguments is not a valid distribution")
    return frozen


def _is_number(v: Any) -> bool:
    return isinstance(v, int | float) and not isinstance(v, bool) and bool(np.isfinite(v))


def _whole(study: dict[str, Any], key: str, where: _Where) -> int | None:
    v = study.get(key)
    if v is not None and (isinstance(v, bool) or not isinstance(v, int) or v < 1):
        raise where.error(f"study.{key}", f"expected a whole number ≥ 1, not {v!r}")
    return v


def _positive(study: dict[str, Any], key: str, where: _Where) -> float | None:
    v = study.get(key)
    if v is not None and not (_is_number(v) and v > 0):
        raise where.error(f"study.{key}", f"expected a positive number of seconds, not {v!r}")
    return None if v is None else float(v)


def _text(study: dict[str, Any], key: str, where: _Where) -> str | None:
    v = study.get(key)
    if v is not None and not isinstance(v, str):
        raise where.error(f"study.{key}", f"expected a string, not {v!r}")
    return v
