"""Analyses started from the studio page: kinematics, inverse dynamics,
equilibrium or dynamics of the model being edited, run by the core in a
thread of their own (never on the server's event loop, nor in the thread
that solves edits), with progress and a stop.

A run is `Model.run(analysis=…)` of the model as the page shows it, which
is the model `camlink run` reads from the saved file. Its rows are counted
as the core hands them over (`on_rows`, every `camlink.model.CHUNK_ROWS`
rows and at the end); the stop is seen there too, so a run stops within a
chunk of rows (a stopped run keeps no rows: run it from the command line
with ``-o`` for partial output).

Messages to the page (``type = "run"``): ``state`` is ``running``,
``done``, ``stopped`` or ``failed``; ``done`` and ``total`` count output
rows; ``id`` numbers the run and ``n`` its messages (the page keeps the
highest: they may arrive out of order); a finished run adds its channels' names and units, its time column
and channels worth seeing (`camlink.viz.front.default_plots` of the run)
then those the page asked for (float64, base64), and ``message``.
"""

from __future__ import annotations

import itertools
import threading
import time
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from typing import Any

import numpy as np

from camlink._core import AnalysisError, ModelError
from camlink.model import ANALYSES, Model
from camlink.results import Results
from camlink.viz.front import b64, default_plots

__all__ = ["ANALYSES", "Run", "Runs"]

#: Least time (s) between two progress messages of a run.
INTERVAL = 0.05

#: Numbers the runs of a server and the messages of a run: the page keeps
#: the message of the highest number (they may arrive out of order).
_RUNS = itertools.count(1)


class Stopped(Exception):
    """Raised in a run's row callback when the page asked it to stop."""


class Run:
    """One analysis of `model` (`analysis`: one of `ANALYSES`)."""

    def __init__(self, model: Model, analysis: str) -> None:
        if analysis not in ANALYSES:
            raise ModelError(f"unknown analysis {analysis!r} (one of {', '.join(ANALYSES)})")
        self.model = model
        self.analysis = analysis
        self.total = 1 if analysis == "equilibrium" else len(model.times())
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

        try:
            self.results = self.model.run(analysis=self.analysis, on_rows=on_rows)
            self.state = "done"
            self.message = f"{self.analysis}: {len(self.results)} rows"
        except Stopped:
            self.state = "stopped"
            self.message = f"{self.analysis} stopped after {self.done} of {self.total} rows"
        except AnalysisError as e:
            self.results = e.results
            self.state = "failed"
            self.message = str(e)
        except (ModelError, ValueError) as e:
            self.state = "failed"
            self.message = str(e)
        report(self)


class Runs:
    """The studio's runs: one at a time, in a thread of their own."""

    def __init__(self) -> None:
        self.executor = ThreadPoolExecutor(max_workers=1, thread_name_prefix="camlink-run")
        self.current: Run | None = None

    def start(self, model: Model, analysis: str, report: Callable[[Run], None]) -> Run:
        """Starts `analysis` of `model`; raises ValueError while a run is going."""
        if self.current is not None and self.current.state == "running":
            raise ValueError("a run is going: stop it first")
        run = Run(model, analysis)
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
