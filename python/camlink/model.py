"""Loading models and running analyses."""

from __future__ import annotations

import errno
import json
import math
import os
import warnings
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from camlink import _core
from camlink._core import AnalysisError, ModelError
from camlink.errors import warnings_from
from camlink.io.output import BackgroundWriter, check_not_input, open_writer
from camlink.records import (
    AnalysisSettings,
    BodyRecord,
    CheckReport,
    DesignFinding,
    ForceRecord,
    JointRecord,
    LoadWarningRecord,
)
from camlink.results import ImpactRecord, LiftOffRecord, Results, RunSummary, plain_summary
from camlink.settings import check_settings
from camlink.signals import stop_on_termination
from camlink.units import channel_units
from camlink.warn import (
    CourseFileWarning,
    issue_design_warnings,
    issue_load_warnings,
    issue_run_warnings,
)

__all__ = ["ANALYSES", "Model", "json_schema", "load", "loads"]

#: Rows computed between two writes of a run's ``output`` file.
CHUNK_ROWS = 1024

#: The analyses a model can run; ``[analysis] type`` names one.
ANALYSES: tuple[str, ...] = _core.ANALYSES



def load(
    path: str | os.PathLike[str],
    acf: str | os.PathLike[str] | None = None,
    *,
    allow_outside: bool = False,
) -> Model:
    """Loads a TOML or JSON model file (the format follows the suffix), or a
    simEngine2D ``.adm`` model with the analysis of `acf` (default: the
    ``.acf`` file beside it, if any; see docs/simengine2d.md).

    Data files the model names (a spline's CSV points) resolve against the
    model file's folder and must lie in it or below, symbolic links
    followed, unless `allow_outside`: opening a model from someone else
    cannot read your other files.

    Raises `FileNotFoundError` for a missing file and `ModelError` (a
    `ValueError`) naming the file, line and field for a file that is not a
    valid model.
    """
    path = Path(path)
    for p in (path, None if acf is None else Path(acf)):
        if p is not None and not p.is_file():
            if p.is_dir():
                raise IsADirectoryError(errno.EISDIR, "is a directory, not a model file", str(p))
            raise FileNotFoundError(errno.ENOENT, "no such model file", str(p))
    if path.suffix.lower() == ".adm":
        model = Model(_core.Model.load_adm(path, acf), source=path)
        for w in model.load_warnings:
            warnings.warn(w, CourseFileWarning, stacklevel=2)
        issue_load_warnings(model.warnings, path)
        return model
    if acf is not None:
        raise ModelError(f"{path}: an .acf analysis file goes with a simEngine2D .adm model only")
    model = Model(_core.Model.load(path, allow_outside), source=path)
    text = path.read_bytes().decode("utf-8", errors="surrogateescape").removeprefix("\ufeff")
    fmt = "json" if path.suffix.lower() == ".json" else "toml"
    model._recipe = (text, fmt, str(path), str(path.parent), allow_outside)
    issue_load_warnings(model.warnings, path)
    return model


def loads(
    text: str,
    format: str = "toml",
    source: str = "<string>",
    *,
    base_dir: str | os.PathLike[str] | None = None,
    allow_outside: bool = False,
) -> Model:
    """Loads a model from TOML or JSON text; `source` names it in errors.

    Data files resolve against `base_dir`, else the folder of `source`
    (the current folder for the default ``"<string>"``), and must lie in
    it or below unless `allow_outside`.
    """
    try:
        text.encode("utf-8")
    except UnicodeEncodeError as e:
        line = text.count("\n", 0, e.start) + 1
        raise ModelError(
            f"{source}:{line}: the text holds a lone surrogate "
            f"({text[e.start]!a}), which is not a character; fix how it was decoded"
        ) from None
    model = Model(_core.Model.from_str(text, format, source, base_dir, allow_outside))
    model._recipe = (
        text,
        format,
        source,
        None if base_dir is None else os.fspath(base_dir),
        allow_outside,
    )
    issue_load_warnings(model.warnings, source)
    return model


def json_schema() -> dict[str, Any]:
    """The JSON Schema of model files."""
    return json.loads(_core.json_schema())


class Model:
    """A validated, immutable mechanism and its file's ``[analysis]`` settings."""

    def __init__(self, core: _core.Model, source: Path | None = None) -> None:
        self._core = core
        #: The file the model came from, if any.
        self.source = source
        #: How to load the model again (text, format, source, base_dir,
        #: allow_outside), which is how it pickles; None for a model with a
        #: Python force, which cannot be pickled.
        self._recipe: tuple[str, str, str, str | None, bool] | None = None
        #: Parameters changed by `with_parameters` (name → value).
        self._overrides: dict[str, float | str] = {}

    def __reduce__(self) -> tuple[Any, ...]:
        """Pickles through the model's text (multiprocessing, joblib):
        the copy is loaded again from it, data files included."""
        if self._recipe is None:
            raise TypeError(
                f"model '{self.name}' cannot be pickled: it has a force computed "
                "in Python (with_force); pickle the model without it and add the "
                "force in the worker"
            )
        return (_unpickle, (*self._recipe, self.source, self._overrides))

    @property
    def name(self) -> str:
        return self._core.name

    @property
    def inputs(self) -> list[Path]:
        """The files the model was read from: its model file (if any) and
        the data files it names. A run refuses to write its output over one."""
        files = [self.source] if self.source is not None else []
        return files + list(self._core.data_files)

    @property
    def load_warnings(self) -> list[str]:
        """What loading read past, one line each naming the file, line and
        field: parts of a simEngine2D file that the course engine does not
        use either (empty for camlink's own files)."""
        return list(self._core.load_warnings)

    @property
    def bodies(self) -> list[BodyRecord]:
        """Moving bodies (the ground is implicit)."""
        return self._core.bodies

    @property
    def joints(self) -> list[JointRecord]:
        """Joints and drivers, with kind, bodies and equation count."""
        return self._core.joints

    @property
    def coordinates(self) -> list[str]:
        """The names of the coordinates q in their order: ``<body>.x``,
        ``.y``, ``.phi`` of every moving body, then ``<joint>.<own>`` for
        each joint's own coordinates (the kinematic channels of the same
        names hold their values)."""
        return self._core.coordinates

    @property
    def analysis(self) -> AnalysisSettings:
        """The file's ``[analysis]`` settings."""
        return self._core.analysis

    def check(self) -> CheckReport:
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
            step = _core.default_step(float(t_end))
        return _core.time_grid(float(t_end), float(step))

    @property
    def analysis_type(self) -> str:
        """The analysis the file asks for: one of `ANALYSES`."""
        return self._core.analysis["type"]

    @property
    def gravity(self) -> tuple[float, float]:
        """Gravity vector g (m/s²) in the global frame."""
        gx, gy = self._core.gravity
        return (gx, gy)

    @property
    def forces(self) -> list[ForceRecord]:
        """Applied forces, with kind and bodies."""
        return self._core.forces

    @property
    def warnings(self) -> list[LoadWarningRecord]:
        """What loading found worth a look (a value left out of the file
        and measured in a placement that the assembly moved): records with
        ``kind``, ``field``, ``message`` and ``text``; each was also issued
        as a `camlink.LoadWarning` by `load` and `loads`."""
        return self._core.warnings

    def design_check(self) -> list[DesignFinding]:
        """Design findings of the curve contacts (a flat follower on a
        concave profile, an undercut roller): `DesignFinding` records with
        ``severity``, ``joint``, ``message`` and ``text`` (one printable
        line)."""
        findings = self._core.design_check()
        issue_design_warnings(findings)
        return findings

    def with_force(
        self,
        name: str,
        body: str,
        f: Callable[[float, tuple[float, float, float], tuple[float, float, float]],
                    Sequence[float]],
    ) -> Model:
        """A copy of this model with a force computed in Python: the slow path.

        ``f(t, q, qd)`` gets the time (s), q = (x, y, φ) and
        qd = (ẋ, ẏ, φ̇) of `body`'s frame, and returns (fx, fy, torque):
        a force (N, global frame) at the body-frame origin and a torque
        (N·m, counter-clockwise); for a force F at a body point s′ add
        (A s′) × F to the torque. `f` is called at every Newton iteration of
        the dynamic analyses (kinematics ignores forces), so it costs far
        more than a ``[[forces]]`` entry. An exception raised by `f` (or a
        return value that is not three numbers) stops the run with an
        `AnalysisError` of kind ``force_failed`` naming the force and the
        time, the exception being its ``__cause__``.
        """
        if not callable(f):
            raise ModelError(f"force '{name}': f must be callable, not {type(f).__name__}")
        return Model(self._core.with_callback_force(name, body, f), source=self.source)

    @property
    def parameters(self) -> list[str]:
        """The names of the file's ``[parameters]``."""
        return list(self._core.parameter_names)

    def with_parameters(self, **values: float | str) -> Model:
        """A copy of this model with the file's ``[parameters]`` named in
        `values` set to those numbers or expressions (``w="3*pi"``,
        ``b="2*a"``: evaluated by camlink's expression evaluator, reading
        the other parameters with their new values, as the file's
        ``[parameters]`` do), and everything that depends on them (points,
        curves, drivers, forces, placements computed from them) resolved
        again in Rust, without reading the file.

        Raises `ModelError` for an unknown name (naming it), an expression
        that does not evaluate (naming the parameter) or a variant that is
        not a valid model (naming the file, line and field).
        """
        if self._recipe is None and self._core.parameter_names:
            raise ModelError(
                f"model '{self.name}' has a force computed in Python (with_force); "
                "change its parameters before adding the force"
            )
        for name, value in values.items():
            if isinstance(value, bool) or not isinstance(value, int | float | str):
                raise ModelError(
                    f"parameter '{name}' = {value!r} is not a number or an expression string"
                )
        given = {k: v if isinstance(v, str) else float(v) for k, v in values.items()}
        model = Model(self._core.with_parameters(given), source=self.source)
        model._recipe = self._recipe
        model._overrides = {**self._overrides, **given}
        return model

    def run(
        self,
        t_end: float | None = None,
        step: float | None = None,
        times: Sequence[float] | npt.ArrayLike | None = None,
        *,
        tol: float | None = None,
        points: Sequence[str] | None = None,
        output: str | os.PathLike[str] | None = None,
        max_iter: int | None = None,
        analysis: str | None = None,
        on_rows: Callable[[int], object] | None = None,
        **settings: Any,
    ) -> Results:
        """Runs the file's analysis (``[analysis] type``), or `analysis`.

        `analysis` is one of ``"kinematics"``, ``"inverse_dynamics"``,
        ``"equilibrium"``, ``"dynamics"``; the other arguments are those of
        `kinematics`, `inverse_dynamics`, `equilibrium` or `simulate`, and
        one that does not apply to the chosen analysis raises `ModelError`.
        `on_rows(n)`, if given, is called each time n more output rows are
        computed (a progress bar); an exception it raises stops the run,
        keeping the rows written to `output`.
        """
        kind = self.analysis_type if analysis is None else analysis
        if kind not in ANALYSES:
            raise ModelError(
                f"unknown analysis {kind!r} (expected one of {', '.join(ANALYSES)})"
            )
        given = {
            "t_end": t_end,
            "step": step,
            "times": times,
            "tol": tol,
            "points": points,
            "max_iter": max_iter,
            **settings,
        }
        # The settings each analysis takes are the core's (camlink_model::analysis).
        allowed = _core.analysis_settings()[kind]
        for key, value in given.items():
            if key not in allowed and value is not None:
                raise ModelError(_core.not_applicable(key, kind))
        kwargs = {k: v for k, v in given.items() if k in allowed}
        methods: dict[str, Callable[..., Results]] = {
            "kinematics": self.kinematics,
            "inverse_dynamics": self.inverse_dynamics,
            "equilibrium": self.equilibrium,
            "dynamics": self.simulate,
        }
        method = methods[kind]
        return method(output=output, on_rows=on_rows, **kwargs)

    def kinematics(
        self,
        t_end: float | None = None,
        step: float | None = None,
        times: Sequence[float] | npt.ArrayLike | None = None,
        *,
        tol: float | None = None,
        max_iter: int | None = None,
        points: Sequence[str] | None = None,
        output: str | os.PathLike[str] | None = None,
        on_rows: Callable[[int], object] | None = None,
        jerk: bool | None = None,
        start: Sequence[float] | npt.ArrayLike | None = None,
    ) -> Results:
        """Kinematic analysis: positions, velocities and accelerations.

        With `jerk` (default: the file's ``[analysis] jerk``), also the exact
        jerk from Φ_q q⃛ = η: channels ``<body>.jx``, ``.jy`` (m/s³),
        ``.jphi`` (rad/s³) and ``<point>.jx``, ``.jy`` for output points.

        `start`, if given, is the coordinate vector q (m, rad; in the order
        of `coordinates`) from which the first time is assembled instead of
        the model's placement: a solution of a similar model at that time
        keeps its assembly branch.

        Arguments left as None come from the file's ``[analysis]``. With
        `output` (``.csv`` or ``.parquet``), results are written as the run
        goes, so a run that stops early leaves every step it computed in the
        file, and the returned `Results` read their rows back from the file
        when asked for (memory stays flat however long the run).

        Raises `AnalysisError` when the mechanism cannot follow its drivers;
        the exception's ``results`` holds the steps before the failure.
        """
        check_settings(locals())
        grid = self.times(t_end, step, times)
        with_jerk = bool(self.analysis.get("jerk", False) if jerk is None else jerk)
        q0 = None if start is None else np.ascontiguousarray(start, dtype=np.float64).ravel()
        return self._run(
            "kinematics",
            output,
            lambda **kw: self._core.run_kinematics(
                grid, **_solver(tol, max_iter), jerk=with_jerk, start=q0, **kw
            ),
            points,
            on_rows,
        )

    def inverse_dynamics(
        self,
        t_end: float | None = None,
        step: float | None = None,
        times: Sequence[float] | npt.ArrayLike | None = None,
        *,
        tol: float | None = None,
        max_iter: int | None = None,
        points: Sequence[str] | None = None,
        output: str | os.PathLike[str] | None = None,
        on_rows: Callable[[int], object] | None = None,
    ) -> Results:
        """Inverse dynamics of a driven (zero-DOF) model: the kinematic
        channels, then joint reactions (``<joint>.fx``, ``.fy``,
        ``.torque`` …), driver efforts (``<driver>.effort``, ``.power``),
        energy and constraint drift. Arguments as `kinematics`."""
        check_settings(locals())
        grid = self.times(t_end, step, times)
        return self._run(
            "inverse_dynamics",
            output,
            lambda **kw: self._core.run_inverse_dynamics(grid, **_solver(tol, max_iter), **kw),
            points,
            on_rows,
        )

    def equilibrium(
        self,
        time: float | None = None,
        *,
        tol: float | None = None,
        max_iter: int | None = None,
        points: Sequence[str] | None = None,
        output: str | os.PathLike[str] | None = None,
        on_rows: Callable[[int], object] | None = None,
    ) -> Results:
        """The static equilibrium nearest the model's placement, with drivers
        and forces evaluated at `time` (s, default ``[analysis] time`` or 0):
        one row with the channels of `inverse_dynamics`."""
        check_settings(locals())
        time = float(self.analysis["time"] if time is None else time)
        return self._run(
            "equilibrium",
            output,
            lambda **kw: self._core.run_equilibrium(time, **_solver(tol, max_iter), **kw),
            points,
            on_rows,
        )

    def simulate(
        self,
        t_end: float | None = None,
        step: float | None = None,
        times: Sequence[float] | npt.ArrayLike | None = None,
        *,
        h: float | None = None,
        rho_inf: float | None = None,
        adaptive: bool | None = None,
        atol: float | None = None,
        rtol: float | None = None,
        h_min: float | None = None,
        projection_tol: float | None = None,
        tol: float | None = None,
        max_iter: int | None = None,
        points: Sequence[str] | None = None,
        output: str | os.PathLike[str] | None = None,
        on_rows: Callable[[int], object] | None = None,
    ) -> Results:
        """Forward dynamics (implicit index-3 generalized-α) from the model's
        placement and velocities, output at `times` or 0, `step`, … `t_end`.

        `h` is the integration step (s; default ``[analysis] h``, else the
        output step but at most 1 ms), the largest step when `adaptive`;
        `rho_inf` ∈ [0, 1] the numerical damping (1: none; default 0.8);
        `atol`, `rtol`, `h_min` the error control of the adaptive mode.
        Channels as `inverse_dynamics`; ``summary`` adds ``energy_drift``
        (J, largest change of ``energy.total``, which damping and
        time-dependent forces change too) and ``constraint_drift`` and
        ``velocity_drift`` (largest |Φ| and |Φ_q q̇ − ν|).
        """
        check_settings(locals())
        grid = self.times(t_end, step, times)
        # Settings left None take the file's, else the core's defaults:
        # h the output step but at most 1 ms; the error control only with
        # adaptive (camlink_model::analysis).
        settings = {
            "adaptive": None if adaptive is None else bool(adaptive),
            **_floats(
                step=step, h=h, rho_inf=rho_inf, atol=atol, rtol=rtol, h_min=h_min,
                projection_tol=projection_tol,
            ),
            **_solver(tol, max_iter),
        }

        def core(**kw: Any) -> Any:
            return self._core.run_dynamics(grid, **settings, **kw)

        return self._run("dynamics", output, core, points, on_rows)

    def _run(
        self,
        kind: str,
        output: str | os.PathLike[str] | None,
        core: Callable[
            ..., tuple[list[str], npt.NDArray[np.float64], dict[str, Any], list[str]]
        ],
        points: Sequence[str] | None,
        on_rows: Callable[[int], object] | None = None,
    ) -> Results:
        """Calls a core run with the output points and a chunk writer; wraps
        the outcome (or the partial results of a failure) as `Results`:
        held in memory without `output`, else read back from the file (the
        binding then keeps only the chunk being handed over)."""
        if points is None:
            points = self.analysis["points"]
        # One name is one point, not a sequence of characters.
        points = [points] if isinstance(points, str) else list(points)
        writer = None
        if output is not None:
            check_not_input(Path(output), self.inputs)
            head = {"camlink": _core.__version__, "model": self.name, "analysis": kind}
            writer = BackgroundWriter(open_writer(output, head=head))
        names: list[str] = []
        quantities: list[str] = []
        complete = False

        def on_chunk(
            chunk_names: list[str], rows: npt.NDArray[np.float64], chunk_quantities: list[str]
        ) -> None:
            names[:] = chunk_names
            quantities[:] = chunk_quantities
            if writer is not None:
                writer.write(chunk_names, rows, chunk_quantities)
            if on_rows is not None:
                on_rows(len(rows))

        metadata: dict[str, Any] | None = None
        try:
            # SIGTERM and SIGHUP, left at their defaults, stop the run as
            # Ctrl-C does (camlink.signals).
            with stop_on_termination(only_default=True):
                names, data, summary, quantities = core(
                    points=points,
                    on_chunk=on_chunk,
                    chunk_rows=CHUNK_ROWS,
                    keep_rows=writer is None,
                )
            complete = True
            # What a results file carries besides its rows (only a file needs it).
            metadata = None if writer is None else {
                "camlink": _core.__version__,
                "model": self.name,
                "analysis": kind,
                "units": channel_units(names, quantities),
                "quantities": dict(zip(names, quantities, strict=True)),
                # As `Results.save` writes it: one form of the summary in files.
                "summary": plain_summary(_summary(kind, summary)),
            }
        except AnalysisError as e:
            names = list(e.names)
            quantities = list(e.quantities)
            if writer is not None:
                e.output = writer.close(names, complete=False)
                e.results = Results._from_file(
                    writer.columns(), names, model=self.name, complete=False,
                    summary={"analysis": kind}, quantities=quantities or None,
                )
                writer = None
            else:
                e.output = None
                partial = e.data if e.data is not None else np.empty((0, len(names)))
                e.results = Results(
                    names, partial, model=self.name, complete=False, summary={"analysis": kind},
                    quantities=quantities or None,
                )
            e.results.mechanism = self
            raise
        except KeyboardInterrupt as e:
            # Ctrl-C, SIGTERM or SIGHUP: keep what was computed.
            if writer is not None:
                e.output = writer.close(names, complete=False)  # type: ignore[attr-defined]
                writer = None
            raise
        finally:
            if writer is not None:
                writer.close(names, complete=complete, metadata=metadata)
        typed = _summary(kind, summary)
        issue_run_warnings(typed)
        if writer is not None:
            results = Results._from_file(
                writer.columns(), names, model=self.name, summary=typed, quantities=quantities
            )
        else:
            results = Results(names, data, model=self.name, summary=typed, quantities=quantities)
        results.mechanism = self
        return results

    def draw(self, t: float | None = None, *, traces: Sequence[str] = ()) -> Any:
        """The mechanism at time `t` (s) as a matplotlib figure; see
        `camlink.draw`."""
        from camlink.viz.drawing import draw

        return draw(self, t, traces=traces)

    def _repr_html_(self) -> str:
        from camlink.viz.notebook import model_html

        return model_html(self)

    def __repr__(self) -> str:
        return repr(self._core)


def _unpickle(
    text: str,
    format: str,
    source: str,
    base_dir: str | None,
    allow_outside: bool,
    path: Path | None,
    overrides: dict[str, float | str] | None = None,
) -> Model:
    model = loads(text, format, source, base_dir=base_dir, allow_outside=allow_outside)
    model.source = path
    return model.with_parameters(**overrides) if overrides else model


def _floats(**given: float | None) -> dict[str, float | None]:
    """The settings given as floats for the core, None kept (not given)."""
    return {k: None if v is None else float(v) for k, v in given.items()}


def _solver(tol: float | None, max_iter: int | None) -> dict[str, Any]:
    """Newton settings for the core, None where not given: the core takes
    the file's, else the analysis' defaults."""
    return {"tol": None if tol is None else float(tol),
            "max_iter": None if max_iter is None else int(max_iter)}


def _summary(kind: str, raw: dict[str, Any]) -> RunSummary:
    """The binding's summary dict as a `RunSummary`."""
    typed = RunSummary(
        analysis=kind,
        steps=int(raw["steps"]),
        newton_iterations=int(raw["newton_iterations"]),
        factorizations=int(raw["factorizations"]),
        halvings=int(raw["halvings"]),
        warnings=warnings_from(raw["warnings"]),
        assembly_moves=[(str(b), (dx, dy, dphi)) for b, (dx, dy, dphi) in raw["assembly_moves"]],
        lift_off=[_lift_off(r) for r in raw["lift_off"]]
        + [_flight(r) for r in raw.get("flights", [])],
        impacts=[_impact(r) for r in raw.get("impacts", [])],
    )
    for key in ("energy_drift", "constraint_drift", "velocity_drift"):
        if key in raw:
            typed[key] = float(raw[key])
    return typed


def _lift_off(r: dict[str, Any]) -> LiftOffRecord:
    end_time, end_angle = r["end_time"], r["end_cam_angle"]
    return LiftOffRecord(
        joint=str(r["joint"]),
        cam=str(r["cam"]),
        start_time=float(r["start_time"]),
        start_cam_angle=float(r["start_cam_angle"]),
        end_time=None if end_time is None else float(end_time),
        end_cam_angle=None if end_angle is None else float(end_angle),
        least_force=float(r["least_force"]),
        least_time=float(r["least_time"]),
        least_cam_angle=float(r["least_cam_angle"]),
    )


def _flight(r: dict[str, Any]) -> LiftOffRecord:
    """A simulated flight of a unilateral contact as a lift-off row: no
    least force, the greatest gap instead."""
    nan = {"least_force": math.nan, "least_time": math.nan, "least_cam_angle": math.nan}
    row = _lift_off({**r, **nan})
    row["greatest_gap"] = float(r["greatest_gap"])
    row["greatest_time"] = float(r["greatest_time"])
    row["greatest_cam_angle"] = float(r["greatest_cam_angle"])
    return row


def _impact(r: dict[str, Any]) -> ImpactRecord:
    return ImpactRecord(
        joint=str(r["joint"]),
        time=float(r["time"]),
        cam_angle=float(r["cam_angle"]),
        approach_speed=float(r["approach_speed"]),
        separation_speed=float(r["separation_speed"]),
        impulse=float(r["impulse"]),
        closed=bool(r["closed"]),
    )


def _as_times(times: Any) -> npt.NDArray[np.float64]:
    t = np.ascontiguousarray(times, dtype=np.float64)
    if t.ndim != 1:
        raise ModelError("times must be a non-empty list of numbers")
    # Non-empty, finite, increasing: the core's rule (camlink_core::run::check_times).
    _core.check_times(t)
    return t
