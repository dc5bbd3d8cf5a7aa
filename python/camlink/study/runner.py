"""Running many variants of a model: on local cores or on Dask, with every
result written as its batch arrives.

A variant is a set of parameter values; it is keyed by a hash of the model
text and all its parameter values (the model's own changes included), so a
study that stops — Ctrl-C, a killed worker, a crashed machine — resumes
from its output folder without recomputing a variant that is there. Each
batch of variants runs in Rust (`camlink._core.run_batch`): on all local
cores through rayon with the GIL released, or as one Dask task on a
worker. A variant that fails is recorded with its status and error; the
study goes on.
"""

from __future__ import annotations

import difflib
import functools
import hashlib
import json
import math
import os
import uuid
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt
import pandas as pd

from camlink import _core
from camlink._core import ModelError
from camlink.model import Model, loads
from camlink.progress import Progress
from camlink.study.outputs import Output, parse_outputs

if TYPE_CHECKING:
    from distributed import Client

__all__ = ["RESERVED", "STATUSES", "run_variants", "variant_key"]

#: Columns every study table has besides its parameters and outputs.
RESERVED = ("variant", "status", "error", "key", "batch")

#: What a variant's ``status`` can be.
STATUSES = ("ok", "model_error", "analysis_error", "output_error", "internal_error")

#: How a model loads again: (text, format, source, base_dir, allow_outside).
Recipe = tuple[str, str, str, str | None, bool]

_BatchResult = tuple[npt.NDArray[np.float64], list[str], list[str]]


def variant_key(text: str, values: Mapping[str, float]) -> str:
    """The key of a variant: SHA-256 (32 hex digits) of the model text and
    its parameter values, sorted by name, each as the shortest text that
    reads back to the same double."""
    h = hashlib.sha256(text.encode("utf-8", errors="surrogateescape"))
    h.update(b"\0")
    h.update(json.dumps(sorted((k, float(v)) for k, v in values.items())).encode())
    return h.hexdigest()[:32]


def run_variants(
    model: Model,
    variants: Sequence[Mapping[str, float]],
    outputs: Mapping[str, Output | Mapping[str, Any]],
    *,
    output: str | os.PathLike[str] | None = None,
    client: Client | None = None,
    scheduler: str | None = None,
    threads: int | None = None,
    batch_size: int | None = None,
    time_limit: float | None = None,
    quiet: bool = True,
    check_outputs: bool = True,
) -> pd.DataFrame:
    """Runs each parameter set of `variants` on `model` (its file's
    ``[analysis]``) and reduces each run to `outputs`.

    Returns one row per variant, in order: ``variant`` (its index), the
    parameters, the outputs, ``status`` (one of `STATUSES`), ``error``
    ("" when ok), ``key`` and ``batch``. With `output` (a folder, e.g.
    ``sweep.parquet``), each batch is written there as one Parquet file as
    it arrives, and the variants already there are not run again.
    `client` (a ``dask.distributed.Client``) or `scheduler` (an address
    such as ``tcp://host:8786``) sends the batches to Dask workers;
    otherwise they run on `threads` local cores (default all).
    `time_limit` (s) stops a variant that runs longer. Unless
    `check_outputs` is false, the model itself is run once first, so that
    an output naming a channel the run lacks is an error at once.
    """
    named = parse_outputs(outputs)
    recipe, overrides = _recipe_of(model)
    params = _parameter_names(model, variants)
    for name in named:
        if name in params or name in RESERVED:
            raise ModelError(f"outputs.{name}: the name is taken by a parameter or a study column")
    spec = [(name, o.to_json()) for name, o in named.items()]
    full = [{**overrides, **{k: float(v) for k, v in v.items()}} for v in variants]
    if check_outputs:
        _check_outputs(model, overrides, spec)
    keys = [variant_key(recipe[0], v) for v in full]

    folder = None if output is None else _study_folder(Path(output))
    done = _read_done(folder, set(keys), ["status", "error", "batch", *named]) if folder is not None else {}
    todo = [k for k, key in enumerate(keys) if key not in done]
    size = batch_size or _default_batch_size(len(todo), threads)
    if size < 1:
        raise ModelError(f"batch_size must be at least 1 ({size})")
    batches = [todo[i : i + size] for i in range(0, len(todo), size)]

    columns = list(params)
    out_names = list(named)
    frames: list[pd.DataFrame] = []
    progress = Progress(len(variants), "study", unit="variant", quiet=quiet)
    progress.update(len(variants) - len(todo))

    def arrived(batch: list[int], result: _BatchResult) -> None:
        frame = _frame(batch, [variants[k] for k in batch], [keys[k] for k in batch], columns,
                       out_names, result)
        if folder is not None:
            _write_batch(folder, frame)
        frames.append(frame)
        progress.update(len(batch))

    with progress:
        if client is not None or scheduler is not None:
            _run_dask(client, scheduler, recipe, full, batches, spec, time_limit, arrived)
        else:
            for batch in batches:
                arrived(batch, _core.run_batch(model._core, [variants[k] for k in batch], spec,
                                               threads=threads, time_limit=time_limit))
    # Variants found in the folder, each with its own index and values.
    todo_set = set(todo)
    found = [k for k in range(len(variants)) if k not in todo_set]
    rows = [done[keys[k]] for k in found]
    old = _frame(
        found, [variants[k] for k in found], [keys[k] for k in found], columns, out_names,
        (np.array([[float(r[o]) for o in out_names] for r in rows]).reshape(len(rows), len(out_names)),
         [str(r["status"]) for r in rows], [str(r["error"]) for r in rows]),
        batch=[str(r["batch"]) for r in rows],
    )
    parts = [f for f in [old, *frames] if len(f)]
    table = (pd.concat(parts, ignore_index=True) if parts
             else _frame([], [], [], columns, out_names, (np.empty((0, len(out_names))), [], [])))
    table = table.sort_values("variant", kind="stable").reset_index(drop=True)
    return table[["variant", *columns, *out_names, "status", "error", "key", "batch"]]


def _recipe_of(model: Model) -> tuple[Recipe, dict[str, float]]:
    recipe = model._recipe
    if recipe is None:
        raise ModelError(
            f"model '{model.name}' cannot be studied: it has a force computed in Python "
            "(with_force), which a variant cannot rebuild; use a [[forces]] entry"
        )
    return recipe, dict(model._overrides)


def _parameter_names(model: Model, variants: Sequence[Mapping[str, float]]) -> list[str]:
    """The parameters the variants set, in first-seen order; an unknown
    name or a value that is not a number is an error naming it."""
    known = list(model._core.parameter_names)
    seen: dict[str, None] = {}
    for k, v in enumerate(variants):
        for name, value in v.items():
            if name not in known:
                close = difflib.get_close_matches(name, known, n=1)
                hint = f" (did you mean '{close[0]}'?)" if close else ""
                have = ", ".join(known) if known else "none"
                raise ModelError(
                    f"variant {k}: model '{model.name}' has no parameter named '{name}'{hint}; "
                    f"its [parameters] are: {have}"
                )
            if isinstance(value, bool) or not isinstance(value, int | float | np.floating | np.integer):
                raise ModelError(f"variant {k}: parameter '{name}' = {value!r} is not a number")
            seen[name] = None
    return list(seen)


def _check_outputs(model: Model, overrides: dict[str, float], spec: list[tuple[str, str]]) -> None:
    """Runs the model itself once: an output naming a channel the run
    lacks, or a time outside it, is an error before any variant runs."""
    _, status, errors = _core.run_batch(model._core, [overrides], spec)
    if status[0] == "output_error":
        raise ModelError(errors[0])


def _default_batch_size(n: int, threads: int | None) -> int:
    """Enough variants per batch to keep every core busy and the files
    few: at least 8 per core, at most about 200 batches."""
    cores = threads or os.cpu_count() or 1
    return max(8 * cores, math.ceil(n / 200), 1)


def _frame(
    indices: list[int],
    variants: list[Mapping[str, float]],
    keys: list[str],
    columns: list[str],
    outputs: list[str],
    result: _BatchResult,
    batch: list[str] | None = None,
) -> pd.DataFrame:
    """One row per variant of a batch: index, parameters, outputs, status,
    error, key and the batch's id (the start of its first key)."""
    values, status, errors = result
    data: dict[str, Any] = {"variant": np.asarray(indices, dtype=np.int64)}
    for c in columns:
        data[c] = np.array([float(v.get(c, np.nan)) for v in variants], dtype=np.float64)
    for j, name in enumerate(outputs):
        data[name] = np.asarray(values[:, j], dtype=np.float64)
    data["status"] = list(status)
    data["error"] = list(errors)
    data["key"] = keys
    data["batch"] = batch if batch is not None else [keys[0][:12]] * len(keys)
    return pd.DataFrame(data)


def _study_folder(path: Path) -> Path:
    if path.exists() and not path.is_dir():
        raise ModelError(
            f"{path}: a study writes a folder of Parquet files (one per batch), "
            "and this is a file; choose another name"
        )
    path.mkdir(parents=True, exist_ok=True)
    return path


def _read_done(folder: Path, wanted: set[str], needed: list[str]) -> dict[str, dict[str, Any]]:
    """The rows already in `folder` for the keys in `wanted` that hold the
    `needed` columns (a row of a study with other outputs runs again)."""
    done: dict[str, dict[str, Any]] = {}
    for f in sorted(folder.glob("batch-*.parquet")):
        try:
            frame = pd.read_parquet(f)
        except Exception as e:  # batch files are renamed whole: this one was damaged
            raise ModelError(
                f"{f}: cannot read this batch file ({e}); delete it to run its variants again"
            ) from None
        if "key" not in frame.columns or not set(needed) <= set(frame.columns):
            continue
        for row in frame.to_dict("records"):
            if row["key"] in wanted:
                done[str(row["key"])] = {str(k): v for k, v in row.items()}
    return done


def _write_batch(folder: Path, frame: pd.DataFrame) -> None:
    """Writes one batch as ``batch-<id>.parquet``, whole or not at all
    (written under a temporary name, then renamed)."""
    name = f"batch-{frame['batch'].iloc[0]}-{len(frame)}.parquet"
    tmp = folder / f".{name}.{uuid.uuid4().hex[:8]}.tmp"
    frame.to_parquet(tmp, index=False)
    os.replace(tmp, folder / name)


@functools.lru_cache(maxsize=4)
def _load(recipe: Recipe) -> Model:
    text, fmt, source, base_dir, allow_outside = recipe
    return loads(text, fmt, source, base_dir=base_dir, allow_outside=allow_outside)


def run_batch_task(
    recipe: Recipe, variants: list[dict[str, float]], spec: list[tuple[str, str]], time_limit: float | None
) -> _BatchResult:
    """One batch on a Dask worker: the model loaded from its text (once per
    worker process), each variant on one thread; Dask runs as many
    batches at once as the worker has threads."""
    return _core.run_batch(_load(recipe)._core, variants, spec, threads=1, time_limit=time_limit)


def _run_dask(
    client: Client | None,
    scheduler: str | None,
    recipe: Recipe,
    full: list[dict[str, float]],
    batches: list[list[int]],
    spec: list[tuple[str, str]],
    time_limit: float | None,
    arrived: Callable[[list[int], _BatchResult], None],
) -> None:
    """Sends each batch to the cluster as one task and hands each result
    to `arrived` as it completes. A worker that dies has its tasks run
    again on another (Dask's own recovery)."""
    from distributed import Client, as_completed

    # Workers may run in other folders: data files resolve against an
    # absolute folder.
    text, fmt, source, base_dir, allow_outside = recipe
    folder = base_dir if base_dir is not None else os.path.dirname(source)
    recipe = (text, fmt, source, os.path.abspath(folder or "."), allow_outside)
    own = client is None
    if client is None:
        try:
            client = Client(scheduler, timeout="20s")
        except (OSError, TimeoutError, ValueError) as e:
            raise ModelError(f"--scheduler {scheduler}: cannot reach the Dask scheduler ({e})") from None
    try:
        futures = {}
        for batch in batches:
            keys = ",".join(variant_key(recipe[0], full[k]) for k in batch)
            name = "camlink-batch-" + hashlib.sha256(keys.encode()).hexdigest()[:24]
            f = client.submit(run_batch_task, recipe, [full[k] for k in batch], spec, time_limit,
                              key=name)
            futures[f.key] = (f, batch)
        try:
            for f in as_completed([f for f, _ in futures.values()]):
                arrived(futures[f.key][1], f.result())
        except BaseException:
            client.cancel([f for f, _ in futures.values()])
            raise
    finally:
        if own:
            client.close()
