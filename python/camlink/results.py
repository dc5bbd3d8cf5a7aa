"""Results of an analysis: named time series, and writers that save them
as the run goes."""

from __future__ import annotations

import difflib
import os
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypedDict

import numpy as np
import numpy.typing as npt

from camlink._core import ModelError
from camlink.errors import RunWarning

if TYPE_CHECKING:
    from collections.abc import Sequence

    import pandas as pd
    from matplotlib.figure import Figure

    from camlink.model import Model

__all__ = [
    "LIFT_OFF_COLUMNS",
    "SUFFIXES",
    "LiftOffRecord",
    "Results",
    "RunSummary",
    "open_writer",
]

#: File name suffixes `Results.save` and the `output=` of a run understand.
SUFFIXES = {".csv": "csv", ".parquet": "parquet", ".pq": "parquet"}

#: Columns of `Results.lift_off`: names, then times (s), cam angles (rad)
#: and the least normal force (N).
LIFT_OFF_COLUMNS = [
    "joint",
    "cam",
    "start_time",
    "start_cam_angle",
    "end_time",
    "end_cam_angle",
    "least_force",
    "least_time",
    "least_cam_angle",
]


class LiftOffRecord(TypedDict):
    """One interval of negative normal force (a row of `Results.lift_off`)."""

    joint: str
    cam: str
    start_time: float
    start_cam_angle: float
    end_time: float | None
    end_cam_angle: float | None
    least_force: float
    least_time: float
    least_cam_angle: float


class RunSummary(TypedDict, total=False):
    """How a run went; results read from a file have none of the keys."""

    #: The analysis run: one of `camlink.ANALYSES`.
    analysis: str
    steps: int
    newton_iterations: int
    factorizations: int
    halvings: int
    warnings: list[RunWarning]
    #: (body, (Δx, Δy, Δφ)) in m, m, rad for bodies that assembly moved.
    assembly_moves: list[tuple[str, tuple[float, float, float]]]
    lift_off: list[LiftOffRecord]
    #: Forward dynamics: largest |E − E(0)| (J), |Φ| and |Φ_q q̇ − ν|.
    energy_drift: float
    constraint_drift: float
    velocity_drift: float


class Results:
    """Time series of one run: ``t`` and one array per channel.

    ``results["crank.phi"]`` is a NumPy array over the time steps;
    ``results.channels`` lists the channel names (without ``t``).
    A run that stopped early has ``complete == False`` and keeps every step
    it computed. ``summary`` holds the solver's counts and warnings;
    ``lift_off`` the intervals where a cam follower would leave its cam.
    """

    def __init__(
        self,
        names: list[str],
        data: npt.NDArray[np.float64],
        *,
        model: str = "",
        complete: bool = True,
        summary: RunSummary | None = None,
    ) -> None:
        data = np.asarray(data, dtype=np.float64)
        if data.ndim != 2 or (names and data.shape[1] != len(names)):
            raise ValueError(
                f"data of shape {data.shape} does not match {len(names)} names"
            )
        self._names = list(names)
        self._index = {n: k for k, n in enumerate(self._names)}
        # A read-only view: results are not edited in place (the caller's
        # array keeps its own flags).
        self._data = data.view()
        self._data.flags.writeable = False
        self.model = model
        self.complete = complete
        #: The ``analysis`` run, solver counts (steps, newton_iterations,
        #: factorizations, halvings), ``warnings`` as `camlink.RunWarning` records and
        #: ``assembly_moves`` as (body, (Δx, Δy, Δφ)) for bodies that
        #: assembly moved, ``lift_off`` as a list of dicts (the rows of
        #: `lift_off`); forward dynamics adds ``energy_drift``,
        #: ``constraint_drift`` and ``velocity_drift``. Empty for results
        #: read from a file.
        self.summary: RunSummary = summary if summary is not None else {}
        #: The model that produced these results (None when read from a
        #: file); drawings and animations take their geometry from it.
        self.mechanism: Model | None = None

    @property
    def t(self) -> npt.NDArray[np.float64]:
        """Times (s) of the steps."""
        if "t" not in self._index:
            return np.empty(0)
        return self._data[:, self._index["t"]]

    @property
    def channels(self) -> list[str]:
        """Channel names, in output order, without ``t``."""
        return [n for n in self._names if n != "t"]

    @property
    def data(self) -> npt.NDArray[np.float64]:
        """All values, one row per step, columns ``["t", *channels]``."""
        return self._data

    @property
    def lift_off(self) -> pd.DataFrame:
        """Intervals where a cam contact's normal force is negative: the
        follower would leave the cam (jump). One row per interval, by start
        time, each also one of the summary's warnings.

        Columns (`LIFT_OFF_COLUMNS`): ``joint`` and ``cam`` (names);
        ``start_time`` (s) and ``start_cam_angle`` (rad) where the normal
        force falls through zero; ``end_time`` (s) and ``end_cam_angle``
        (rad) where it rises again, NaN when the run ends in lift-off;
        ``least_force`` (N, negative) and where it is, ``least_time`` (s)
        and ``least_cam_angle`` (rad). The cam angle is φ of the cam body,
        not folded into one turn. Zeros are interpolated linearly between
        output times.

        Inverse and forward dynamics find these; the frame is empty (with
        the same columns) when the follower stays on its cam, for the other
        analyses, for a run that stopped early and for results read from a
        file.
        """
        import pandas as pd

        frame = pd.DataFrame(self.summary.get("lift_off", []), columns=LIFT_OFF_COLUMNS)
        return frame.astype({c: "float64" for c in LIFT_OFF_COLUMNS[2:]})

    def __getitem__(self, name: str) -> npt.NDArray[np.float64]:
        try:
            return self._data[:, self._index[name]]
        except KeyError:
            close = difflib.get_close_matches(name, self._names, n=3)
            hint = f" (did you mean {', '.join(repr(c) for c in close)}?)" if close else ""
            raise KeyError(f"no channel named {name!r}{hint}") from None

    def __contains__(self, name: object) -> bool:
        return name in self._index

    def __len__(self) -> int:
        """Number of time steps."""
        return self._data.shape[0]

    def __repr__(self) -> str:
        span = f", t = {self.t[0]:g} … {self.t[-1]:g} s" if len(self) else ""
        state = "" if self.complete else ", stopped early"
        name = f" of '{self.model}'" if self.model else ""
        return (
            f"<camlink Results{name}: {len(self)} steps, "
            f"{len(self.channels)} channels{span}{state}>"
        )

    def to_pandas(self) -> pd.DataFrame:
        """A DataFrame with one column per channel, indexed by ``t`` (by the
        step number when there is no ``t`` column)."""
        import pandas as pd

        columns = [k for k, n in enumerate(self._names) if n != "t"]
        index = (
            pd.Index(self.t, name="t") if "t" in self._index else pd.RangeIndex(len(self), name="step")
        )
        return pd.DataFrame(self._data[:, columns], index=index, columns=self.channels)

    def plot(self, y: str | Sequence[str], x: str = "t") -> Figure:
        """Channels `y` against time or the channel `x`; see `camlink.plot`."""
        from camlink.plots import plot

        return plot(self, y, x)

    def svaj(self, joint: str | None = None) -> Figure:
        """The SVAJ diagram of a cam contact; see `camlink.plots.svaj`."""
        from camlink.plots import svaj

        return svaj(self, joint)

    def draw(
        self, t: float | None = None, *, traces: Sequence[str] = (), forces: Sequence[str] = ()
    ) -> Figure:
        """The mechanism at time `t` (s); see `camlink.draw`."""
        from camlink.drawing import draw

        return draw(self, t, traces=traces, forces=forces)

    def animate(
        self,
        path: str | os.PathLike[str] | None = None,
        *,
        fps: float = 20.0,
        speed: float = 1.0,
        traces: Sequence[str] = (),
        width: float = 6.4,
        dpi: int = 80,
    ) -> Path | str:
        """An animation of the run: a GIF or MP4 file at `path` (by suffix),
        or, with no path, HTML of an inline animation for a notebook. See
        `camlink.animate.animate`."""
        from camlink.animate import animate

        return animate(self, path, fps=fps, speed=speed, traces=traces, width=width, dpi=dpi)

    def to_html(
        self, path: str | os.PathLike[str] | None = None, *, plots: Sequence[str] | None = None
    ) -> Path | str:
        """The self-contained browser viewer of the run, written to `path`
        (or returned as text); see `camlink.viewer.to_html`."""
        from camlink.viewer import to_html

        return to_html(self, path, plots=plots)

    def _repr_html_(self) -> str:
        from camlink.notebook import results_html

        return results_html(self)

    def save(self, path: str | os.PathLike[str]) -> Path:
        """Writes the results as CSV or Parquet, chosen by the suffix."""
        writer = open_writer(path)
        try:
            writer.write(self._names, self._data)
        finally:
            writer.close(self._names)
        return writer.path

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> Results:
        """Reads results written by `save` or by a run with ``output=``."""
        path = Path(path)
        kind = _kind(path)
        if kind == "csv":
            with path.open(newline="") as f:
                header = f.readline().strip()
                names = header.split(",") if header else []
                data = np.loadtxt(f, delimiter=",", ndmin=2)
            if data.size == 0:
                data = np.empty((0, len(names)))
        else:
            import pyarrow.parquet as pq

            table = pq.read_table(path)
            names = table.column_names
            data = np.column_stack(
                [table.column(n).to_numpy() for n in names]
            ) if table.num_rows else np.empty((0, len(names)))
        return cls(names, data, model=path.stem)


def _kind(path: Path) -> str:
    try:
        return SUFFIXES[path.suffix.lower()]
    except KeyError:
        known = ", ".join(sorted(SUFFIXES))
        raise ModelError(
            f"cannot write results to '{path}': unknown file type "
            f"'{path.suffix or '(none)'}' (use one of {known})"
        ) from None


class _CsvWriter:
    """Appends rows to a CSV file with a header line, flushing each chunk."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self._file = path.open("w", newline="")
        self._header = False

    def write(self, names: list[str], rows: npt.NDArray[np.float64]) -> None:
        if not self._header:
            self._file.write(",".join(names) + "\n")
            self._header = True
        if len(rows):
            # %.17g keeps every bit of a double; adding 0.0 turns −0.0 into
            # 0.0, so a value at rest reads "0" rather than "-0".
            np.savetxt(self._file, rows + 0.0, delimiter=",", fmt="%.17g")
        self._file.flush()

    def close(self, names: list[str]) -> None:
        if not self._header and names:
            self.write(names, np.empty((0, len(names))))
        self._file.close()


class _ParquetWriter:
    """Writes one Parquet row group per chunk; `close` leaves a valid file."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self._writer: Any = None
        # Fail now, not after the run, if the file cannot be written.
        path.open("wb").close()

    def _table(self, names: list[str], rows: npt.NDArray[np.float64]) -> Any:
        import pyarrow as pa

        return pa.table({n: rows[:, k] for k, n in enumerate(names)})

    def write(self, names: list[str], rows: npt.NDArray[np.float64]) -> None:
        import pyarrow.parquet as pq

        table = self._table(names, rows)
        if self._writer is None:
            self._writer = pq.ParquetWriter(self.path, table.schema)
        self._writer.write_table(table)

    def close(self, names: list[str]) -> None:
        if self._writer is None and names:
            self.write(names, np.empty((0, len(names))))
        if self._writer is not None:
            self._writer.close()
            self._writer = None


def open_writer(path: str | os.PathLike[str]) -> _CsvWriter | _ParquetWriter:
    """A writer for `path` (CSV or Parquet by suffix), created now so that an
    unwritable path fails before any work is done."""
    path = Path(path)
    kind = _kind(path)
    return _CsvWriter(path) if kind == "csv" else _ParquetWriter(path)
