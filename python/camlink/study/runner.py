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

__all__ = [
    "BATCH",
    "ERROR",
    "KEY",
    "RESERVED",
    "STATUS",
    "STATUSES",
    "VARIANT",
    "check_size",
    "connect",
    "run_variants",
    "variant_key",
]

#: The study's own columns of every study table, besides its parameters
#: and outputs. A parameter name is an identifier, so no parameter is
#: named like them; an output may not be.
VARIANT = "study.variant"
STATUS = "study.status"
ERROR = "study.error"
KEY = "study.key"
BATCH = "study.batch"
RESERVED = (VARIANT, STATUS, ERROR, KEY, BATCH)

#: The same columns as batch files name them without the ``study.``
#: prefix (files written before it; read, and rewritten, on resuming).
_UNPREFIXED = {"variant": VARIANT, "status": STATUS, "error": ERROR, "key": KEY, "batch": BATCH}

#: Memory a study takes per variant (bytes): its parameter set, its key,
#: its row of the table and the frames that build it. Measured with
#: tracemalloc over 10⁴ to 3·10⁴ variants: about 660 bytes with one
#: parameter and one output, about 100 more per parameter; these allow
#: twice that.
BYTES_PER_VARIANT = 1024
#: More per parameter or output of each variant (bytes).
BYTES_PER_VALUE = 128

#: Seconds allowed to connect to a Dask scheduler, its handshake included.
CONNECT_TIMEOUT = 20.0

#: What a variant's ``status`` can be.
STATUSES: tuple[str, ...] = _core.STUDY_STATUSES

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
    on_batch: Callable[[int, int], object] | None = None,
) -> pd.DataFrame:
    """Runs each parameter set of `variants` on `model` (its file's
    ``[analysis]``) and reduces each run to `outputs`.

    Returns one row per variant, in order: ``study.variant`` (its index),
    the parameters, the outputs, ``study.status`` (one of `STATUSES`),
    ``study.error`` ("" when ok), ``study.key`` and ``study.batch``. With
    `output` (a folder, e.g. ``sweep.parquet``), each batch is written
    there as one Parquet file as it arrives, and the variants already
    there are not run again. `client` (a ``dask.distributed.Client``) or
    `scheduler` (an address such as ``tcp://host:8786``) sends the batches
    to Dask workers; otherwise they run on `threads` local cores (default
    all). `time_limit` (s) stops a variant that runs longer. Unless
    `check_outputs` is false, the model itself is run once first, so that
    an output naming a channel the run lacks is an error at once. A study
    whose table cannot fit in the memory available is refused
    (`check_size`). `on_batch(done, total)`, if given, is called with the
    variants done (those found in `output` included) before the first
    batch and after each; an exception it raises stops the study (the
    batches written to `output` stay, and a rerun resumes from them).
    """
    named = parse_outputs(outputs)
    check_size(len(variants), len(named) + (len(variants[0]) if len(variants) else 0), "study")
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

    columns = list(params)
    out_names = list(named)
    folder = None if output is None else _study_folder(Path(output))
    done = {}
    if folder is not None:
        index = {key: k for k, key in enumerate(keys)}
        done = _read_done(folder, index, variants, columns, out_names)
    todo = [k for k, key in enumerate(keys) if key not in done]
    size = batch_size or _default_batch_size(len(todo), threads)
    if size < 1:
        raise ModelError(f"batch_size must be at least 1 ({size})")
    batches = [todo[i : i + size] for i in range(0, len(todo), size)]

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
        if on_batch is not None:
            on_batch(progress.done, len(variants))

    with progress:
        if on_batch is not None:
            on_batch(progress.done, len(variants))
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
         [str(r[STATUS]) for r in rows], [str(r[ERROR]) for r in rows]),
        batch=[str(r[BATCH]) for r in rows],
    )
    parts = [f for f in [old, *frames] if len(f)]
    table = (pd.concat(parts, ignore_index=True) if parts
             else _frame([], [], [], columns, out_names, (np.empty((0, len(out_names))), [], [])))
    table = table.sort_values(VARIANT, kind="stable").reset_index(drop=True)
    return table[[VARIANT, *columns, *out_names, STATUS, ERROR, KEY, BATCH]]


def check_size(n: int, values: int, what: str) -> None:
    """`ModelError` when a study of `n` variants, each with `values`
    parameters and outputs, would need more memory than the machine has
    available: its parameter sets and its table are held in memory
    (`BYTES_PER_VARIANT`, `BYTES_PER_VALUE`). Called before the variants
    are built."""
    need = n * (BYTES_PER_VARIANT + BYTES_PER_VALUE * max(values, 1))
    have = _available_memory()
    if have is None or need <= have:
        return
    most = max(have // (BYTES_PER_VARIANT + BYTES_PER_VALUE * max(values, 1)), 1)
    raise ModelError(
        f"{what}: {n:,} variants need about {_bytes(need)} of memory for their parameter sets "
        f"and table, and {_bytes(have)} is available; split the study into parts of at most "
        f"{most:,} variants (parts written to one output folder read as one table)"
    )


def _available_memory() -> int | None:
    """Bytes of memory available to a new allocation (Linux's
    MemAvailable, else the physical memory), or None when unknown."""
    try:
        with open("/proc/meminfo", encoding="ascii") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    try:
        return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (AttributeError, ValueError, OSError):
        return None


def _bytes(n: float) -> str:
    for unit in ("B", "kB", "MB", "GB", "TB"):
        if n < 1000 or unit == "TB":
            return f"{n:.3g} {unit}"
        n /= 1000
    return f"{n:.3g} TB"


def _recipe_of(model: Model) -> tuple[Recipe, dict[str, float]]:
    recipe = model._recipe
    if recipe is None:
        raise ModelError(
            f"model '{model.name}' cannot be studied: it has a force computed in Python "
            "(with_force), which a variant cannot rebuild; use a [[forces]] entry"
        )
    text = [k for k, v in model._overrides.items() if isinstance(v, str)]
    if text:
        raise ModelError(
            f"model '{model.name}' cannot be studied with parameters set to expressions "
            f"({', '.join(text)}): give them as numbers in with_parameters"
        )
    return recipe, {k: float(v) for k, v in model._overrides.items()}


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
    data: dict[str, Any] = {VARIANT: np.asarray(indices, dtype=np.int64)}
    for c in columns:
        data[c] = np.array([float(v.get(c, np.nan)) for v in variants], dtype=np.float64)
    for j, name in enumerate(outputs):
        data[name] = np.asarray(values[:, j], dtype=np.float64)
    data[STATUS] = list(status)
    data[ERROR] = list(errors)
    data[KEY] = keys
    data[BATCH] = batch if batch is not None else [keys[0][:12]] * len(keys)
    return pd.DataFrame(data)


def _study_folder(path: Path) -> Path:
    if path.exists() and not path.is_dir():
        raise ModelError(
            f"{path}: a study writes a folder of Parquet files (one per batch), "
            "and this is a file; choose another name"
        )
    path.mkdir(parents=True, exist_ok=True)
    return path


def _read_done(
    folder: Path,
    index: Mapping[str, int],
    variants: Sequence[Mapping[str, float]],
    params: list[str],
    outputs: list[str],
) -> dict[str, dict[str, Any]]:
    """The rows already in `folder` for the keys of `index` (key → the
    variant's index in `variants`) that hold every one of `outputs` (a row
    of a study with other outputs runs again). A batch file without the
    ``study.`` prefix on its own columns is rewritten with it first. A
    file that cannot be read, or whose columns do not hold what a batch
    file holds, is a `ModelError` naming it."""
    done: dict[str, dict[str, Any]] = {}
    needed = {STATUS, ERROR, BATCH, *outputs}
    for f in sorted(folder.glob("batch-*.parquet")):
        try:
            frame = pd.read_parquet(f)
        except Exception as e:  # batch files are renamed whole: this one was damaged
            raise ModelError(
                f"{f}: cannot read this batch file ({e}); delete it to run its variants again"
            ) from None
        if KEY not in frame.columns and "key" in frame.columns:
            frame = _upgrade(f, frame, index, variants, params)
        if KEY not in frame.columns or not needed <= set(frame.columns):
            continue
        _check_batch_file(f, frame, outputs)
        for row in frame.to_dict("records"):
            if row[KEY] in index:
                done[str(row[KEY])] = {str(k): v for k, v in row.items()}
    return done


def _check_batch_file(f: Path, frame: pd.DataFrame, outputs: list[str]) -> None:
    """`ModelError` naming `f` and the column when a column a study reads
    back does not hold what it wrote: text for its own columns, a known
    status, numbers for the outputs."""

    def bad(column: str, what: str) -> ModelError:
        return ModelError(
            f"{f}: column '{column}' {what}: this is not a batch file of a study, or it was "
            "damaged; delete it to run its variants again"
        )

    for c in (KEY, STATUS, ERROR, BATCH):
        for v in frame[c]:
            if not isinstance(v, str):
                raise bad(c, f"holds {_plain(v)!r}, not text")
    for v in frame[STATUS]:
        if v not in STATUSES:
            raise bad(STATUS, f"holds {v!r}, not one of {', '.join(STATUSES)}")
    for o in outputs:
        dtype = frame[o].dtype
        if pd.api.types.is_bool_dtype(dtype) or not pd.api.types.is_numeric_dtype(dtype):
            first = next((v for v in frame[o] if not isinstance(v, float | int) or isinstance(v, bool)),
                         frame[o].iloc[0] if len(frame) else None)
            raise bad(o, f"holds {_plain(first)!r}, not a number")


def _plain(v: Any) -> Any:
    """A NumPy scalar as the Python value it holds (for messages)."""
    return v.item() if isinstance(v, np.generic) else v


def _upgrade(
    f: Path,
    frame: pd.DataFrame,
    index: Mapping[str, int],
    variants: Sequence[Mapping[str, float]],
    params: list[str],
) -> pd.DataFrame:
    """A batch file whose own columns lack the ``study.`` prefix, with it,
    written back over `f` (whole, as `_write_batch` writes). In such a file
    a parameter named like one of those columns lost its values to it (or,
    for ``variant``, the index to the parameter): the rows of variants of
    this study get their index and parameter values back from them."""
    frame = frame.rename(columns=_UNPREFIXED)
    if not all(isinstance(v, str) for v in frame[KEY]):
        return frame
    ks = [index.get(key) for key in frame[KEY]]
    if any(k is not None for k in ks):
        variant = frame[VARIANT] if VARIANT in frame.columns else pd.Series(np.nan, index=frame.index)
        frame[VARIANT] = [k if k is not None else v for k, v in zip(ks, variant, strict=True)]
        for p in params:
            have = frame[p] if p in frame.columns else pd.Series(np.nan, index=frame.index)
            frame[p] = [float(variants[k].get(p, np.nan)) if k is not None else v
                        for k, v in zip(ks, have, strict=True)]
    own = [c for c in RESERVED if c in frame.columns]
    first = [c for c in [VARIANT, *params] if c in frame.columns]
    frame = frame[first + [c for c in frame.columns if c not in own and c not in first]
                  + [c for c in own if c != VARIANT]]
    tmp = f.with_name(f".{f.name}.{uuid.uuid4().hex[:8]}.tmp")
    frame.to_parquet(tmp, index=False)
    os.replace(tmp, f)
    return frame


def _write_batch(folder: Path, frame: pd.DataFrame) -> None:
    """Writes one batch as ``batch-<id>.parquet``, whole or not at all
    (written under a temporary name, then renamed)."""
    name = f"batch-{frame[BATCH].iloc[0]}-{len(frame)}.parquet"
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
    from distributed import as_completed

    # Workers may run in other folders: data files resolve against an
    # absolute folder.
    text, fmt, source, base_dir, allow_outside = recipe
    folder = base_dir if base_dir is not None else os.path.dirname(source)
    recipe = (text, fmt, source, os.path.abspath(folder or "."), allow_outside)
    own = client is None
    if client is None:
        assert scheduler is not None
        client = connect(scheduler)
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


def connect(scheduler: str) -> Client:
    """A client of the Dask scheduler at `scheduler` (``tcp://host:8786``,
    ``tls://…``); `ModelError` naming ``--scheduler`` when the address is
    not one or nothing answers there within `CONNECT_TIMEOUT` seconds."""
    from distributed import Client

    connection = _connection_args(scheduler)
    _listening(scheduler)
    _probe_scheduler(scheduler, connection, CONNECT_TIMEOUT)
    try:
        return Client(scheduler, timeout=f"{CONNECT_TIMEOUT}s")
    except (OSError, TimeoutError, ValueError, TypeError) as e:
        raise ModelError(f"--scheduler {scheduler}: cannot reach the Dask scheduler ({e})") from None


def _connection_args(address: str) -> dict[str, Any]:
    """How a client connects to `address`: `ModelError` for an address
    that is not one, a scheme camlink cannot use, or TLS without
    certificates in Dask's configuration."""
    from distributed.comm import parse_address
    from distributed.security import Security

    where = f"--scheduler {address}"
    if not isinstance(address, str) or not address.strip():
        raise ModelError(f"{where}: give a Dask scheduler's address, such as tcp://host:8786")
    try:
        scheme, location = parse_address(address)
    except (ValueError, TypeError) as e:
        raise ModelError(f"{where}: not a Dask scheduler address ({e})") from None
    if scheme not in ("tcp", "tls", "ws", "wss"):
        raise ModelError(
            f"{where}: camlink connects to tcp:// (or tls://, ws://, wss://) schedulers, not "
            f"{scheme}://; for another transport, connect a dask.distributed.Client in Python "
            "and pass it as client="
        )
    if not location or ":" not in location:
        raise ModelError(f"{where}: give the scheduler's host and port, such as tcp://host:8786")
    try:
        args: dict[str, Any] = Security().get_connection_args("client")
    except (ValueError, TypeError, OSError) as e:
        raise ModelError(f"{where}: Dask's TLS configuration cannot be used ({e})") from None
    if scheme in ("tls", "wss") and args.get("ssl_context") is None:
        raise ModelError(
            f"{where}: a {scheme}:// scheduler needs certificates, and Dask's configuration "
            "(distributed.comm.tls) gives none; set them there, or connect a "
            "dask.distributed.Client with its Security in Python and pass it as client="
        )
    return args


def _listening(address: str) -> None:
    """`ModelError` at once when nothing listens at `address`: its host
    refuses a TCP connection on the port (Dask's own connect retries such
    an address until its timeout) or takes none within `CONNECT_TIMEOUT`
    seconds. An address that takes the connection is left to the probe,
    which asks whether a Dask scheduler answers there."""
    import socket

    from distributed.comm import parse_address, parse_host_port

    _, location = parse_address(address)
    try:
        host, port = parse_host_port(location)
    except (ValueError, TypeError):
        return
    why = None
    try:
        with socket.create_connection((host, port), timeout=CONNECT_TIMEOUT):
            pass
    except ConnectionRefusedError:
        why = f"connection refused: nothing listens on port {port} of {host}"
    except TimeoutError:
        why = f"no connection to port {port} of {host} within {CONNECT_TIMEOUT:g} s"
    except OSError:
        return
    if why is not None:
        raise ModelError(f"--scheduler {address}: cannot reach the Dask scheduler ({why})")


def _probe_scheduler(address: str, connection: dict[str, Any], timeout: float) -> None:
    """Connects to `address` and asks for its identity, all within
    `timeout` seconds (Dask bounds the connection but not its handshake, so
    an address that answers something else would hang the client):
    `ModelError` unless a Dask scheduler answers in time. Runs on a thread
    of its own, with its own event loop, so that it works where a loop
    runs already (Jupyter)."""
    import asyncio
    import threading

    from distributed.comm import connect

    async def identity() -> Any:
        # Dask's connect gives up on a connection not made in its timeout
        # (an OSError), before the bound of the whole: a timeout of the
        # whole is then an address that took the connection and did not
        # answer the handshake.
        comm = await connect(address, timeout=0.75 * timeout, **connection)
        try:
            await comm.write({"op": "identity", "reply": True})
            return await comm.read()
        finally:
            comm.abort()

    async def bounded() -> Any:
        return await asyncio.wait_for(identity(), timeout)

    outcome: dict[str, Any] = {}

    def probe() -> None:
        try:
            outcome["reply"] = asyncio.run(bounded())
        except BaseException as e:  # handed to the caller's thread below
            outcome["error"] = e

    thread = threading.Thread(target=probe, name="camlink-scheduler-probe", daemon=True)
    thread.start()
    thread.join(timeout + 5)
    where = f"--scheduler {address}"
    error = outcome.get("error")
    if thread.is_alive() or isinstance(error, asyncio.TimeoutError | TimeoutError):
        raise ModelError(
            f"{where}: cannot reach the Dask scheduler (no answer within {timeout:g} s: the address "
            "takes connections but does not answer as a Dask scheduler does; a dashboard's "
            "HTTP port, 8787 by default, is not the scheduler's, 8786 by default)"
        )
    if isinstance(error, Exception):
        raise ModelError(f"{where}: cannot reach the Dask scheduler ({error})") from None
    if error is not None:
        raise error
    reply = outcome.get("reply")
    if not isinstance(reply, dict) or reply.get("type") != "Scheduler":
        kind = reply.get("type") if isinstance(reply, dict) else None
        raise ModelError(
            f"{where}: cannot reach the Dask scheduler (what answers there is "
            f"{'a Dask ' + str(kind) if kind else 'not a Dask scheduler'})"
        )
