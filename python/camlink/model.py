"""Loading models and running analyses."""

from __future__ import annotations

import errno
import json
import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from camlink import _core
from camlink._core import AnalysisError, ModelError
from camlink.results import Results, open_writer

__all__ = ["Model", "load", "loads", "json_schema"]

#: Rows computed between two writes of a run's ``output`` file.
CHUNK_ROWS = 1024


def load(path: str | os.PathLike[str]) -> Model:
    """Loads a TOML or JSON model file (the format follows the suffix).

    Raises `FileNotFoundError` for a missing file and `ModelError` (a
    `ValueError`) naming the file, line and field for a file that is not a
    valid model.
    """
    path = Path(path)
    if not path.is_file():
        if path.is_dir():
            raise IsADirectoryError(errno.EISDIR, "is a directory, not a model file", str(path))
        raise FileNotFoundError(errno.ENOENT, "no such model file", str(path))
    return Model(_core.Model.load(path), source=path)


def loads(text: str, format: str = "toml", source: str = "<string>") -> Model:
    """Loads a model from TOML or JSON text; `source` names it in errors."""
    return Model(_core.Model.from_str(text, format, source))


def json_schema() -> dict[str, Any]:
    """The JSON Schema of model files."""
    return json.loads(_core.json_schema())


class Model:
    """A validated, immutable mechanism and its file's ``[analysis]`` settings."""

    def __init__(self, core: _core.Model, source: Path | None = None) -> None:
        self._core = core
        #: The file the model came from, if any.
        self.source = source

    @property
    def name(self) -> str:
        return self._core.name

    @property
    def bodies(self) -> list[dict[str, Any]]:
        """Moving bodies (the ground is implicit)."""
        return self._core.bodies

    @property
    def joints(self) -> list[dict[str, Any]]:
        """Joints and drivers, with kind, bodies and equation count."""
        return self._core.joints

    @property
    def analysis(self) -> dict[str, Any]:
        """The file's ``[analysis]`` settings."""
        return self._core.analysis

    def check(self) -> dict[str, Any]:
        """Counts of bodies, coordinates and equations, each constraint, and
        the degrees of freedom from the rank of Φ_q."""
        return self._core.check()

    def times(
        self,
        t_end: float | None = None,
        step: float | None = None,
        times: Sequence[float] | npt.ArrayLike | None = None,
    ) -> npt.NDArray[np.float64]:
        """The output times of a run: `times`, else 0, `step`, … `t_end`,
        each defaulting to the file's ``[analysis]``."""
        if times is not None:
            return _as_times(times)
        a = self.analysis
        if t_end is None and step is None and a.get("times") is not None:
            return _as_times(a["times"])
        t_end = a.get("t_end") if t_end is None else t_end
        step = a.get("step") if step is None else step
        if t_end is None:
            raise ModelError(
                f"model '{self.name}' gives no end time: pass t_end "
                "(or set [analysis] t_end in the file)"
            )
        if step is None:
            step = float(t_end) / 100 if t_end > 0 else 1.0
        return _core.time_grid(float(t_end), float(step))

    def run(
        self,
        t_end: float | None = None,
        step: float | None = None,
        times: Sequence[float] | npt.ArrayLike | None = None,
        tol: float | None = None,
        points: Sequence[str] | None = None,
        output: str | os.PathLike[str] | None = None,
        max_iter: int | None = None,
    ) -> Results:
        """Kinematic analysis: positions, velocities and accelerations.

        Arguments left as None come from the file's ``[analysis]``. With
        `output` (``.csv`` or ``.parquet``), results are written as the run
        goes, so a run that stops early leaves every step it computed in the
        file.

        Raises `AnalysisError` when the mechanism cannot follow its drivers;
        the exception's ``results`` holds the steps before the failure.
        """
        a = self.analysis
        grid = self.times(t_end, step, times)
        tol = a["tol"] if tol is None else float(tol)
        max_iter = a["max_iter"] if max_iter is None else int(max_iter)
        points = list(a["points"] if points is None else points)

        writer = open_writer(output) if output is not None else None
        names: list[str] = []

        def on_chunk(chunk_names: list[str], rows: npt.NDArray[np.float64]) -> None:
            names[:] = chunk_names
            if writer is not None:
                writer.write(chunk_names, rows)

        try:
            names, data, summary = self._core.run_kinematics(
                grid,
                tol=tol,
                max_iter=max_iter,
                points=points,
                on_chunk=on_chunk,
                chunk_rows=CHUNK_ROWS,
            )
        except AnalysisError as e:
            names = list(e.names)
            partial = e.data if e.data is not None else np.empty((0, len(names)))
            e.results = Results(names, partial, model=self.name, complete=False)
            e.output = writer.path if writer is not None else None
            raise
        finally:
            if writer is not None:
                writer.close(names)
        return Results(names, data, model=self.name, summary=summary)

    def __repr__(self) -> str:
        return repr(self._core)


def _as_times(times: Any) -> npt.NDArray[np.float64]:
    t = np.ascontiguousarray(times, dtype=np.float64)
    if t.ndim != 1 or t.size == 0:
        raise ModelError("times must be a non-empty list of numbers")
    if not np.all(np.isfinite(t)):
        raise ModelError("times must be finite numbers")
    if np.any(np.diff(t) <= 0):
        k = int(np.argmax(np.diff(t) <= 0))
        raise ModelError(f"times must increase, but {t[k + 1]:g} follows {t[k]:g}")
    return t
