"""Results of an analysis: named time series, and writers that save them
as the run goes."""

from __future__ import annotations

import csv
import dataclasses
import difflib
import io
import json
import os
from collections.abc import Iterator, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any, NotRequired, TypedDict

import numpy as np
import numpy.typing as npt

from camlink._core import ModelError
from camlink.errors import RunWarning, warnings_from
from camlink.io.output import (
    READ_SUFFIXES,
    SUFFIXES,
    kind_of,
    open_writer,
    read_arrow_stream,
    read_csv_metadata,
    sidecar_path,
)
from camlink.units import SI, Units, channel_units, parse_units, unit_of

if TYPE_CHECKING:
    from collections.abc import Sequence

    import pandas as pd
    from matplotlib.figure import Figure

    from camlink.io.results_file import ColumnSource
    from camlink.model import Model

__all__ = [
    "IMPACT_COLUMNS",
    "LIFT_OFF_COLUMNS",
    "SUFFIXES",
    "ImpactRecord",
    "LiftOffRecord",
    "Results",
    "ResultsMetadata",
    "RunSummary",
    "open_writer",
    "plain_summary",
]

#: Columns of `Results.lift_off`: names, then times (s), cam angles (rad),
#: the least normal force (N) of a bilateral contact and the greatest gap
#: (m) of a unilateral contact's simulated flight.
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
    "greatest_gap",
    "greatest_time",
    "greatest_cam_angle",
]

#: Columns of `Results.impacts`: the joint, time (s), cam angle (rad),
#: normal approach and separation speeds (m/s), impulse (N·s) and whether
#: the contact closed.
IMPACT_COLUMNS = [
    "joint",
    "time",
    "cam_angle",
    "approach_speed",
    "separation_speed",
    "impulse",
    "closed",
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
    #: A simulated flight's greatest gap (m) and where; NaN for an interval
    #: of negative normal force of a bilateral contact (whose ``least_*``
    #: are NaN for a flight).
    greatest_gap: NotRequired[float]
    greatest_time: NotRequired[float]
    greatest_cam_angle: NotRequired[float]


class ImpactRecord(TypedDict):
    """One impact of a unilateral contact (a row of `Results.impacts`)."""

    joint: str
    time: float
    cam_angle: float
    approach_speed: float
    separation_speed: float
    impulse: float
    closed: bool


class ResultsMetadata(TypedDict, total=False):
    """What a results file carries besides its rows (`Results.metadata`)."""

    #: The camlink version that wrote it.
    camlink: str
    #: The model's name.
    model: str
    #: The analysis: one of `camlink.ANALYSES`.
    analysis: str
    #: Each channel's unit (``""`` in files written before channels
    #: carried their quantity).
    units: dict[str, str]
    #: Each channel's quantity as the core names it (``"velocity"``…).
    quantities: dict[str, str]
    #: The length and angle units of the values (``"m,rad"`` unless the
    #: results were converted, `Results.in_units`).
    value_units: str
    #: The run summary as plain JSON values (warnings as dicts).
    summary: dict[str, Any]


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
    #: Forward dynamics with unilateral contacts: the impacts.
    impacts: list[ImpactRecord]
    #: Forward dynamics: largest |E − E(0)| (J), |Φ| and |Φ_q q̇ − ν|.
    energy_drift: float
    constraint_drift: float
    velocity_drift: float


def plain_summary(summary: Mapping[str, Any]) -> dict[str, Any]:
    """A run summary as results files store it, whoever writes the file
    (`Results.save` or a run with ``output=``): the same keys, warnings as
    plain dicts."""
    plain = dict(summary)
    if "warnings" in plain:
        plain["warnings"] = [dataclasses.asdict(w) for w in plain["warnings"]]
    return plain


class Results:
    """Time series of one run: ``t`` and one array per channel.

    ``results["crank.phi"]`` is a NumPy array over the time steps;
    ``results.channels`` lists the channel names (without ``t``).
    A run that stopped early has ``complete == False`` and keeps every step
    it computed. ``summary`` holds the solver's counts and warnings;
    ``lift_off`` the intervals where a cam follower would leave its cam.

    The results of a run that wrote an ``output`` file hold no rows: they
    read a channel from the file when it is first asked for (``data`` and
    `to_pandas` read every channel), and keep what they read. ``source``
    is then the file (None for results held in memory).
    """

    def __init__(
        self,
        names: list[str],
        data: npt.NDArray[np.float64],
        *,
        model: str = "",
        complete: bool = True,
        summary: RunSummary | None = None,
        quantities: Sequence[str] | None = None,
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
        self._data: npt.NDArray[np.float64] | None = data.view()
        self._data.flags.writeable = False
        # Results read lazily: the file, and the channels read from it.
        self._source: ColumnSource | None = None
        self._columns: dict[str, npt.NDArray[np.float64]] = {}
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
        #: file or converted to other units); drawings and animations take
        #: their geometry from it.
        self.mechanism: Model | None = None
        # Each channel's quantity as the core named it ("" when unknown).
        self._quantities: dict[str, str] = (
            dict(zip(self._names, quantities, strict=True)) if quantities is not None else {}
        )
        # Each channel's unit as a results file gave it, for files that
        # carry no quantities (None otherwise).
        self._file_units: dict[str, str] | None = None
        # The units of the values: SI unless converted (`in_units`).
        self._value_units: Units = SI

    @classmethod
    def _from_file(
        cls,
        source: ColumnSource,
        names: list[str],
        *,
        model: str = "",
        complete: bool = True,
        summary: RunSummary | None = None,
        quantities: Sequence[str] | None = None,
    ) -> Results:
        """Results whose rows stay in the file `source` until asked for."""
        res = cls(names, np.empty((0, len(names))), model=model, complete=complete,
                  summary=summary, quantities=quantities)
        res._data = None
        res._source = source
        return res

    def __getstate__(self) -> dict[str, Any]:
        """Pickles with the rows: results read lazily read them all first
        (an open file does not travel to another process)."""
        state = self.__dict__.copy()
        if self._source is not None:
            state["_data"] = self._rows()
            state["_source"] = None
            state["_columns"] = {}
        return state

    @property
    def source(self) -> Path | None:
        """The file these results read their rows from on access, or None
        when they hold them in memory."""
        return None if self._source is None else self._source.path

    def _read(self, names: list[str] | None, head: int | None = None) -> npt.NDArray[np.float64]:
        """Reads one channel (`names` of one) or every row (None) from the
        source file, or with `head` the first `head` rows of the channels
        `names`; `ModelError` naming the file when it cannot."""
        assert self._source is not None
        try:
            if head is not None:
                return self._source.head(self._names if names is None else names, head)
            if names is None:
                return self._source.table(self._names)
            return self._source.column(names[0])
        except (ValueError, OSError, EOFError) as e:
            if isinstance(e, ModelError):
                raise
            raise ModelError(f"cannot read results from '{self._source.path}': {e}") from None

    def _head(self, names: list[str], n: int) -> npt.NDArray[np.float64]:
        """The first `n` rows of the columns `names` (which exist), a new
        array; results read lazily read only those rows from the file."""
        if self._data is None:
            return self._read(names, head=n)
        return self._data[:n, [self._index[c] for c in names]]

    def _rows(self) -> npt.NDArray[np.float64]:
        """Every row, read from the source file the first time."""
        if self._data is None:
            data = self._read(None)
            data.flags.writeable = False
            self._data = data
            self._columns.clear()
        return self._data

    def _column(self, name: str) -> npt.NDArray[np.float64]:
        """The values of channel `name` (which exists), read-only."""
        if self._data is not None:
            return self._data[:, self._index[name]]
        column = self._columns.get(name)
        if column is None:
            column = self._read([name])
            column.flags.writeable = False
            self._columns[name] = column
        return column

    @property
    def t(self) -> npt.NDArray[np.float64]:
        """Times (s) of the steps."""
        if "t" not in self._index:
            return np.empty(0)
        return self._column("t")

    @property
    def channels(self) -> list[str]:
        """Channel names, in output order, without ``t``."""
        return [n for n in self._names if n != "t"]

    @property
    def data(self) -> npt.NDArray[np.float64]:
        """All values, one row per step, columns ``["t", *channels]``."""
        return self._rows()

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

        A unilateral contact (``unilateral = true``) in forward dynamics
        leaves its cam instead: its rows are the simulated flights, from the
        located lift-off (or a bounce) to the located impact, with
        ``greatest_gap`` (m) and where it is, ``greatest_time`` (s) and
        ``greatest_cam_angle`` (rad), at the step ends; ``least_*`` are NaN
        there, as ``greatest_*`` are for a bilateral contact's rows.

        Inverse and forward dynamics find these; the frame is empty (with
        the same columns) when the follower stays on its cam, for the other
        analyses, for a run that stopped early and for results read from a
        file.
        """
        import pandas as pd

        frame = pd.DataFrame(self.summary.get("lift_off", []), columns=LIFT_OFF_COLUMNS)
        return frame.astype({c: "float64" for c in LIFT_OFF_COLUMNS[2:]})

    @property
    def impacts(self) -> pd.DataFrame:
        """The impacts of the unilateral cam contacts in forward dynamics,
        in time order (`docs/dynamics.md`, "Unilateral contacts").

        Columns (`IMPACT_COLUMNS`): ``joint``; ``time`` (s) and
        ``cam_angle`` (rad, φ of the cam body) of the located impact;
        ``approach_speed`` −ġ⁻ and ``separation_speed`` ġ⁺ (m/s, along the
        contact normal; ġ⁺ = e (−ġ⁻) for a bounce, 0 when the contact
        closes); ``impulse`` (N·s, on the follower side along the normal);
        ``closed`` (True when the follower stayed on the cam). Empty, with
        the same columns, without unilateral contacts or impacts.
        """
        import pandas as pd

        frame = pd.DataFrame(self.summary.get("impacts", []), columns=IMPACT_COLUMNS)
        return frame.astype(
            {c: "float64" for c in IMPACT_COLUMNS[1:6]} | {"closed": "bool"}
        )

    def __getitem__(self, name: str) -> npt.NDArray[np.float64]:
        if not isinstance(name, str):
            raise TypeError(
                f"Results are indexed by channel name (res['crank.phi']), not by "
                f"{type(name).__name__}; for rows use res.data[{name!r}] "
                "(columns 't' and res.channels) or res.to_pandas()"
            )
        if name in self._index:
            return self._column(name)
        close = difflib.get_close_matches(name, self._names, n=3)
        hint = f" (did you mean {', '.join(repr(c) for c in close)}?)" if close else ""
        raise KeyError(f"no channel named {name!r}{hint}")

    def __iter__(self) -> Iterator[str]:
        raise TypeError(
            "Results are not iterable: loop over res.channels for the channel "
            "names, over res.data for the rows, or use res.to_pandas()"
        )

    def __contains__(self, name: object) -> bool:
        return name in self._index

    def __len__(self) -> int:
        """Number of time steps."""
        if self._data is None:
            assert self._source is not None
            return self._source.rows
        return self._data.shape[0]

    @property
    def units(self) -> dict[str, str]:
        """Each column's unit (``"t"`` first), as the core states it with
        the channel (a driver's effort in N·m or N by what it drives), in
        `value_units`; ``""`` only for a column of a file written before
        channels carried their quantity."""
        if not self._quantities and self._file_units is not None:
            return {n: self._file_units.get(n, "") for n in self._names}
        return channel_units(self._names, self._quantities, self._value_units)

    @property
    def quantities(self) -> dict[str, str]:
        """Each column's quantity as the core names it (``"t"``:
        ``"time"``, ``"crank.omega"``: ``"angular_velocity"``, a contact's
        ``normal_force``: ``"force"``…); ``""`` where a file did not say."""
        return {n: self._quantities.get(n, "") for n in self._names}

    @property
    def value_units(self) -> str:
        """The length and angle units of the values, ``"m,rad"`` unless
        the results were converted with `in_units`."""
        return str(self._value_units)

    def _like(self, names: list[str], data: npt.NDArray[np.float64]) -> Results:
        """Results of the columns `names` (of these) with the rows `data`:
        the same model, summary, units and mechanism (a thinned copy for a
        viewer)."""
        known = all(self._quantities.get(n) for n in names)
        out = Results(
            names, data, model=self.model, complete=self.complete, summary=self.summary,
            quantities=[self._quantities[n] for n in names] if known else None,
        )
        out._file_units = self._file_units
        out._value_units = self._value_units
        out.mechanism = self.mechanism
        return out

    def in_units(self, units: str | Units) -> Results:
        """These results with lengths and angles (and their rates) in
        `units`, e.g. ``"mm,deg"``: for tables, files and plots. Forces,
        torques, energies and times stay SI; residuals stay as computed.
        The copy has no `mechanism` (drawings need SI geometry). A
        `camlink.ModelError` names units camlink does not know, and a
        column whose quantity a file did not record."""
        target = parse_units(units)
        if target == self._value_units:
            return self
        factors = []
        for n in self._names:
            q = self._quantities.get(n, "")
            if not q:
                raise ModelError(
                    f"channel '{n}' has no recorded quantity (a results file of an earlier "
                    "version): its values cannot be converted"
                )
            # From the current units back to SI, then on to `target`.
            factors.append(unit_of(q, target)[1] / unit_of(q, self._value_units)[1])
        res = Results(
            self._names, self.data * np.asarray(factors), model=self.model,
            complete=self.complete, summary=self.summary,
            quantities=[self._quantities[n] for n in self._names],
        )
        res._value_units = target
        return res

    def __repr__(self) -> str:
        span = (
            f", t = {_number(self.t[0])} … {_number(self.t[-1])} s" if len(self) else ""
        )
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
        return pd.DataFrame(self.data[:, columns], index=index, columns=self.channels)

    def plot(self, y: str | Sequence[str], x: str = "t") -> Figure:
        """Channels `y` against time or the channel `x`; see `camlink.plot`."""
        from camlink.viz.plots import plot

        return plot(self, y, x)

    def svaj(self, joint: str | None = None) -> Figure:
        """The SVAJ diagram of a cam contact; see `camlink.viz.plots.svaj`."""
        from camlink.viz.plots import svaj

        return svaj(self, joint)

    def draw(
        self, t: float | None = None, *, traces: Sequence[str] = (), forces: Sequence[str] = ()
    ) -> Figure:
        """The mechanism at time `t` (s); see `camlink.draw`."""
        from camlink.viz.drawing import draw

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
        `camlink.viz.animate.animate`."""
        from camlink.viz.animate import animate

        return animate(self, path, fps=fps, speed=speed, traces=traces, width=width, dpi=dpi)

    def to_html(
        self, path: str | os.PathLike[str] | None = None, *, plots: Sequence[str] | None = None
    ) -> Path | str:
        """The self-contained browser viewer of the run, written to `path`
        (or returned as text); see `camlink.viz.viewer.to_html`."""
        from camlink.viz.viewer import to_html

        return to_html(self, path, plots=plots)

    def _repr_html_(self) -> str:
        from camlink.viz.notebook import results_html

        return results_html(self)

    def save(self, path: str | os.PathLike[str], *, units: str | Units | None = None) -> Path:
        """Writes the results as CSV or Parquet, chosen by the suffix, to a
        temporary file renamed over `path` once complete; with `units`
        (``"mm,deg"``) in those units (`in_units`), which the file's
        metadata records."""
        if units is not None and parse_units(units) != self._value_units:
            return self.in_units(units).save(path)
        meta = self.metadata()
        writer = open_writer(path, head=meta)
        complete = False
        try:
            known = [self._quantities[n] for n in self._names] if self._quantities else []
            writer.write(self._names, self.data, known)
            complete = True
        finally:
            writer.close(self._names, complete, metadata=meta)
        return writer.path

    def metadata(self) -> ResultsMetadata:
        """What a results file carries besides the rows: the ``camlink``
        version, the ``model`` name, the ``analysis``, each channel's
        ``units`` and the ``summary`` (warnings as plain dicts); the model,
        analysis and summary only when known."""
        from camlink import _core

        summary = plain_summary(self.summary)
        meta = ResultsMetadata(camlink=_core.__version__)
        if self.model:
            meta["model"] = self.model
        if "analysis" in summary:
            meta["analysis"] = summary["analysis"]
        meta["units"] = self.units
        if self._quantities:
            meta["quantities"] = self.quantities
        if self._value_units != SI:
            meta["value_units"] = self.value_units
        if summary:
            meta["summary"] = summary
        return meta

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> Results:
        """Reads results written by `save` or by a run with ``output=``,
        also the temporary file of a run that was killed (up to its last
        complete chunk). Raises `ModelError` for a file that is not
        results."""
        path = Path(path)
        kind = kind_of(path, "read", READ_SUFFIXES)
        try:
            if kind == "csv":
                names, data, meta = _read_csv(path)
            else:
                names, data, meta = _read_arrow(path, kind)
            model, summary = _file_metadata(meta, path)
            stored = meta.get("quantities")
            quantities = (
                [stored[n] for n in names]
                if isinstance(stored, dict) and all(isinstance(stored.get(n), str) for n in names)
                else None
            )
            res = cls(names, data, model=model, summary=summary, quantities=quantities)
            value_units = meta.get("value_units")
            res._value_units = parse_units(value_units) if isinstance(value_units, str) else SI
            units = meta.get("units")
            if isinstance(units, dict):
                res._file_units = {str(k): v for k, v in units.items() if isinstance(v, str)}
            return res
        except ModelError:
            raise
        except (ValueError, OSError, ImportError, EOFError, RecursionError) as e:
            # RecursionError: metadata nested deeper than JSON can be read.
            raise ModelError(f"cannot read results from '{path}': {e}") from None
        except Exception as e:
            import pyarrow as pa

            if isinstance(e, pa.ArrowException):
                raise ModelError(f"cannot read results from '{path}': {e}") from None
            raise


def _file_metadata(meta: Any, path: Path) -> tuple[str, RunSummary | None]:
    """The model name and run summary of a results file's ``camlink``
    metadata (the file's stem for a file without a model name);
    `ModelError` naming the field that does not hold what `save` writes."""

    def bad(field: str, what: str) -> ModelError:
        return ModelError(f"cannot read results from '{path}': its camlink metadata: {field}: {what}")

    if not isinstance(meta, dict):
        raise bad("camlink", f"expected a JSON object, got {type(meta).__name__}")
    model = meta.get("model", path.stem)
    if not isinstance(model, str):
        raise bad("model", f"expected a name, got {type(model).__name__}")
    summary = meta.get("summary")
    if summary is None:
        return model, None
    if not isinstance(summary, dict):
        raise bad("summary", f"expected a JSON object, got {type(summary).__name__}")
    if "warnings" in summary:
        raw = summary["warnings"]
        fields = ("kind", "time", "joints", "message")
        if not isinstance(raw, list) or not all(
            isinstance(w, dict) and all(f in w for f in fields)
            and isinstance(w["joints"], list) and _is_time(w["time"])
            for w in raw
        ):
            raise bad("summary.warnings", f"expected a list of warnings with {', '.join(fields)}")
        summary["warnings"] = warnings_from(raw)
    for key in ("lift_off", "impacts"):
        if key in summary and not (
            isinstance(summary[key], list) and all(isinstance(r, dict) for r in summary[key])
        ):
            raise bad(f"summary.{key}", "expected a list of JSON objects")
    return model, summary  # type: ignore[return-value]


def _number(v: float) -> str:
    """`v` as ``:g`` formats it, −0.0 as ``0``."""
    return f"{v + 0.0:g}"


def _is_time(v: Any) -> bool:
    return isinstance(v, int | float) and not isinstance(v, bool)


def _read_csv(path: Path) -> tuple[list[str], npt.NDArray[np.float64], dict[str, Any]]:
    """Names, rows and metadata of a results CSV: its sidecar
    (`camlink.io.output.sidecar_path`) or, in files of earlier versions, its
    comment lines; an unfinished last line (a run killed while writing) is
    dropped."""
    text = path.read_bytes().decode()
    if text and not text.endswith("\n"):
        text = text[: text.rfind("\n") + 1]
    lines = io.StringIO(text)
    comments = []
    line = lines.readline()
    while line.startswith("#"):
        comments.append(line)
        line = lines.readline()
    header = next(csv.reader([line]), [])
    rest = lines.read()
    tail = rest[rest.rfind("\n", 0, len(rest) - 1) + 1 :] if rest else ""
    if tail.startswith("#"):
        comments.append(tail)
    meta = read_csv_metadata(comments)
    if not rest.strip() or rest.lstrip().startswith("#"):
        data = np.empty((0, len(header)))
    else:
        data = np.loadtxt(io.StringIO(rest), delimiter=",", ndmin=2, comments="#")
    if data.shape[1] != len(header):
        raise ModelError(
            f"cannot read results from '{path}': {data.shape[1]} columns but "
            f"{len(header)} names"
        )
    side = sidecar_path(path)
    if side.exists():
        meta.update(_read_sidecar(side, path, header, len(data)))
    return header, data, meta


def _read_sidecar(side: Path, path: Path, header: list[str], rows: int) -> dict[str, Any]:
    """The metadata in the sidecar `side` of the results CSV `path`:
    `ModelError` when it is not a JSON object; none, with a
    `camlink.warn.CamlinkWarning`, when it describes other columns or
    another number of rows than the CSV's `header` and `rows` (the table
    was edited, or two runs wrote the same output at once)."""
    try:
        meta = json.loads(side.read_text(encoding="utf-8"))
    except ValueError as e:
        raise ModelError(f"cannot read the metadata of '{path}' from '{side}': {e}") from None
    if not isinstance(meta, dict):
        raise ModelError(
            f"cannot read the metadata of '{path}' from '{side}': expected a JSON object, "
            f"got {type(meta).__name__}"
        )
    columns = meta.pop("columns", header)
    count = meta.pop("rows", rows)
    if columns != header or count != rows:
        import warnings

        from camlink.warn import CamlinkWarning

        theirs = f"{len(columns) if isinstance(columns, list) else '?'} columns, {count} rows"
        warnings.warn(
            CamlinkWarning(
                f"'{side}' describes another file than '{path}' ({theirs}; the file has "
                f"{len(header)} columns, {rows} rows): '{path}' is read without it"
            ),
            stacklevel=4,
        )
        return {}
    return meta


def _read_arrow(path: Path, kind: str) -> tuple[list[str], npt.NDArray[np.float64], dict[str, Any]]:
    """Names, rows and camlink metadata (model name, camlink version,
    analysis, summary) of a results Parquet file or Arrow journal."""
    if kind == "parquet":
        import pyarrow.parquet as pq

        table = pq.read_table(path)
    else:
        table = read_arrow_stream(path)
    raw = (table.schema.metadata or {}).get(b"camlink")
    meta = json.loads(raw) if raw else {}
    names = list(table.column_names)
    import pyarrow as pa

    for name, field in zip(names, table.schema, strict=True):
        if not (pa.types.is_floating(field.type) or pa.types.is_integer(field.type)):
            raise ModelError(
                f"cannot read results from '{path}': column '{name}' holds {field.type}, not numbers"
            )
    if not table.num_rows:
        return names, np.empty((0, len(names))), meta
    data = np.column_stack([table.column(n).to_numpy() for n in names])
    return names, data, meta
