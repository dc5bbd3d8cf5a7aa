"""Analyses and studies started from the studio page: kinematics,
inverse dynamics, equilibrium or dynamics of the model being edited, or a
study of it, run by the core in a thread of their own (never on the
server's event loop, nor in the thread that solves edits), with progress
and a stop.

A run is `Model.run(analysis=…)` of the model as the page shows it, which
is the model `camlink run` reads from the saved file. Its rows are counted
as the core hands them over (`on_rows`, every `camlink.model.CHUNK_ROWS`
rows and at the end); the stop is seen there too, so a run stops within a
chunk of rows. A run stopped, or failed, keeps the rows it computed, as
`camlink run` keeps what it computed: the rows go to a results file
(``output=``) in a private folder beside the model file (the studio writes
nothing outside the model's folder), read back when the run ends and
removed; the message of a stopped run names the time it stopped at. Where
that folder cannot be made (a read-only folder), the run keeps its rows in
memory only when it ends. A study is the one of a study file
beside the model that names it, run on the model as edited, as `camlink
study` runs it but writing no files; its variants are counted as each
batch comes back (`run_variants`' ``on_batch``), and it stops between
batches.

Messages to the page (``type = "run"``): ``state`` is ``running``,
``done``, ``stopped`` or ``failed``; ``done`` and ``total`` count output
rows (variants for a study); ``id`` numbers the run and ``n`` its
messages (the page keeps the highest: they may arrive out of order); a
finished run adds its channels' names and units, its time column and
channels worth seeing (`camlink.viz.front.default_plots` of the run)
then those the page asked for (float64, base64), a finished study its
table (``columns``, ``rows``: the first `MAX_TABLE`), and ``message``.
"""

from __future__ import annotations

import itertools
import math
import tempfile
import threading
import time
import tomllib
from collections.abc import Callable, Iterator
from concurrent.futures import ThreadPoolExecutor
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from camlink._core import AnalysisError, ModelError
from camlink.io.output import partial_path
from camlink.model import ANALYSES, Model
from camlink.results import Results
from camlink.viz.front import b64, default_plots

if TYPE_CHECKING:
    import pandas as pd

    from camlink.study.study_file import StudyFile

__all__ = ["ANALYSES", "Run", "Runs", "studies_of"]

#: Most rows of a study's table sent to the page.
MAX_TABLE = 500

#: Least time (s) between two progress messages of a run.
INTERVAL = 0.05

#: Numbers the runs of a server and the messages of a run: the page keeps
#: the message of the highest number (they may arrive out of order).
_RUNS = itertools.count(1)


class Stopped(Exception):
    """Raised in a run's row callback when the page asked it to stop."""


class Run:
    """One analysis of `model` (`analysis`: one of `ANALYSES`), or the
    study of the file `study` (`analysis` = ``"study"``) on `model`."""

    def __init__(self, model: Model, analysis: str, study: Path | None = None,
                 folder: Path | None = None) -> None:
        if analysis not in ANALYSES and not (analysis == "study" and study is not None):
            raise ModelError(f"unknown analysis {analysis!r} (one of {', '.join(ANALYSES)})")
        self.model = model
        self.analysis = analysis
        #: Where the run's rows are written as they come (a private folder
        #: made in it, removed at the end); None: kept in memory only.
        self.folder = folder
        self.study: StudyFile | None = None
        if study is not None:
            from camlink.study.study_file import read_study

            self.study = read_study(study)
        self.table: pd.DataFrame | None = None
        self.total = (1 if analysis == "equilibrium" else 0 if study is not None
                      else len(model.times()))
        self.done = 0
        self.state = "running"
        self.message = ""
        self.results: Results | None = None
        self.stop = threading.Event()
        self.id = next(_RUNS)
        self._messages = itertools.count(1)

    def status(self, channels: list[str] | None = None) -> dict[str, Any]:
        """The page's message for this run; a finished run's carries its
        time column and `channels` (those it has)."""
        out: dict[str, Any] = {"type": "run", "id": self.id, "n": next(self._messages),
                               "analysis": self.analysis, "state": self.state,
                               "done": self.done, "total": self.total, "message": self.message}
        res = self.results
        if self.table is not None and self.state != "running":
            out["table"] = _table(self.table)
        if res is not None and self.state != "running" and len(res):
            names = list(res.channels)
            out["names"] = names
            out["units"] = dict(res.units)
            out["t"] = b64(res["t"])
            first = default_plots([str(b["name"]) for b in self.model.bodies],
                                  [str(p) for p in self.model.analysis.get("points") or []],
                                  np.asarray(res["t"]), names,
                                  np.column_stack([np.asarray(res[c]) for c in names]))
            wanted = dict.fromkeys([*first, *(channels or [])])
            out["channels"] = {c: b64(res[c]) for c in wanted if c in names}
        return out

    def channel(self, name: str) -> dict[str, Any]:
        """The values of channel `name` of the finished run."""
        res = self.results
        if res is None or name not in res.channels:
            raise KeyError(f"the run has no channel {name!r}")
        return {"type": "runchannel", "name": name, "values": b64(np.asarray(res[name]))}

    def execute(self, report: Callable[[Run], None]) -> None:
        """Runs the analysis (in the calling thread), calling `report(self)`
        at most every `INTERVAL` s while it runs and once at the end."""
        last = 0.0

        def on_rows(n: int) -> None:
            nonlocal last
            self.done += n
            if self.stop.is_set():
                raise Stopped()
            now = time.monotonic()
            if now - last >= INTERVAL:
                last = now
                report(self)

        def on_batch(done: int, total: int) -> None:
            self.done, self.total = done, total
            report(self)
            if self.stop.is_set():
                raise Stopped()

        unit = "variants" if self.study is not None else "rows"
        try:
            if self.study is not None:
                from camlink.study.runner import STATUS

                self.table = _run_study(self.model, self.study, on_batch)
                ok = int((self.table[STATUS] == "ok").sum())
                self.message = (f"study {self.study.path.name}: {len(self.table)} variants, {ok} ok"
                                + ("" if len(self.table) <= MAX_TABLE else
                                   f" (the first {MAX_TABLE} shown)"))
            else:
                with _scratch(self.folder) as output:
                    try:
                        self.results = self.model.run(analysis=self.analysis, on_rows=on_rows,
                                                      output=output)
                    finally:
                        if output is not None:
                            self.results = _written(output, self.model)
                self.message = (f"{self.analysis}: "
                                f"{0 if self.results is None else len(self.results)} rows")
            self.state = "done"
        except Stopped:
            self.state = "stopped"
            self.message = f"{self.analysis} stopped after {self.done} of {self.total} {unit}"
            res = self.results
            if res is not None and len(res):
                self.message += (f", at t = {float(res['t'][-1]):.6g} s: the {len(res)} rows "
                                 "computed are kept")
        except AnalysisError as e:
            if self.results is None:
                self.results = e.results
            self.state = "failed"
            self.message = str(e)
        except (ModelError, ValueError) as e:
            self.state = "failed"
            self.message = str(e)
        report(self)


@contextmanager
def _scratch(folder: Path | None) -> Iterator[Path | None]:
    """A results file (Parquet) in a private folder made in `folder`,
    removed with what is in it on leaving; None when there is no `folder`
    or the folder cannot be made there."""
    if folder is None:
        yield None
        return
    try:
        tmp = tempfile.TemporaryDirectory(prefix=".camlink-run-", dir=folder)
    except OSError:
        yield None
        return
    with tmp as name:
        yield Path(name) / "run.parquet"


def _written(output: Path, model: Model) -> Results | None:
    """The rows a run of `model` wrote to `output`, or, stopped or
    failed, to its partial file (`partial_path`), read into memory and
    marked incomplete; None when it wrote none."""
    if output.is_file():
        res = Results.load(output)
    elif (partial := partial_path(output)).is_file():
        res = Results.load(partial)
        res.complete = False
    else:
        return None
    res.mechanism = model
    return res


def _run_study(model: Model, sf: StudyFile,
               on_batch: Callable[[int, int], None]) -> pd.DataFrame:
    """The study `sf` on `model` (the model as edited, not its file), as
    `camlink study` runs it but writing no files, on local cores."""
    from camlink.study.sampling import monte_carlo
    from camlink.study.sweeps import sweep
    execution: dict[str, Any] = {"threads": sf.threads, "batch_size": sf.batch_size,
                                 "time_limit": sf.time_limit, "quiet": True,
                                 "on_batch": on_batch}
    if sf.kind == "sweep":
        return sweep(model, sf.values, sf.outputs, mode="zip" if sf.mode == "zip" else "grid",
                     **execution)
    mc = monte_carlo(model, sf.distributions, sf.outputs, n=sf.n or 0, seed=sf.seed,
                     sampling="sobol" if sf.sampling == "sobol" else
                     "lhs" if sf.sampling == "lhs" else "random", **execution)
    return mc.table


def _table(table: pd.DataFrame) -> dict[str, Any]:
    """A study's table for the page: its columns but the key and batch,
    and its first `MAX_TABLE` rows (numbers, NaN as None, and text)."""
    from camlink.study.runner import BATCH, KEY
    columns = [c for c in table.columns if c not in (KEY, BATCH)]
    rows = []
    for row in table[columns].head(MAX_TABLE).itertuples(index=False):
        rows.append([None if isinstance(v, float) and not math.isfinite(v) else
                     v.item() if isinstance(v, np.generic) else v for v in row])
    return {"columns": columns, "rows": rows}


def studies_of(path: Path) -> list[str]:
    """The study files beside the model file `path` that name it
    (``[study] model``), by file name."""
    out = []
    for f in sorted(path.parent.glob("*.toml")):
        try:
            data = tomllib.loads(f.read_text(encoding="utf-8"))
        except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError):
            continue
        study = data.get("study")
        if isinstance(study, dict) and study.get("model") == path.name:
            out.append(f.name)
    return out


class Runs:
    """The studio's runs: one at a time, in a thread of their own."""

    def __init__(self) -> None:
        self.executor = ThreadPoolExecutor(max_workers=1, thread_name_prefix="camlink-run")
        self.current: Run | None = None

    def start(self, model: Model, analysis: str, report: Callable[[Run], None],
              study: Path | None = None, folder: Path | None = None) -> Run:
        """Starts `analysis` of `model` (the study `study` when `analysis`
        is ``"study"``), its rows written as they come in a private folder
        made in `folder` (`Run`); raises ValueError while a run is going."""
        if self.current is not None and self.current.state == "running":
            raise ValueError("a run is going: stop it first")
        run = Run(model, analysis, study, folder)
        self.current = run
        self.executor.submit(run.execute, report)
        return run

    def stop(self) -> None:
        """Asks the current run to stop (at its next chunk of rows)."""
        if self.current is not None:
            self.current.stop.set()

    def close(self) -> None:
        self.stop()
        self.executor.shutdown(wait=False, cancel_futures=True)
