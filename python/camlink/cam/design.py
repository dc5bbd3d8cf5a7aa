"""Cam design files: a motion program and a follower in, a synthesised cam,
its design limits and a pass/fail report out.

A design file (TOML) holds ``[cam]``, ``[follower]``, ``[[segments]]`` and
optionally ``[limits]``, ``[dynamics]`` and ``[export]``; see
docs/cam-design.md. Angles in the file are in degrees (keys end in
``_deg``) and cam speeds in rev/min (``_rpm``); lengths are in metres.
Inside, everything is SI and radians. The file is read and checked in
Rust (the ``camlink-cam`` crate, through ``camlink._core.cam_design_read``):
its rules, defaults and bounds are there, and its messages name the file,
line and field; the mechanics run in the Rust core
(``camlink._core.CamCore``). This module turns the checked design into
dataclasses and presents the report.
"""

from __future__ import annotations

import json
import math
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray

from camlink import _core
from camlink._core import CamCore, ModelError
from camlink.cam.sizing import SURGE_RATIO, ContactSpec, SpringSpec, VibrationSpec
from camlink.warn import LoadWarning

__all__ = [
    "FOLLOWERS",
    "LAWS",
    "MAX_LENGTH",
    "MAX_RPM",
    "MAX_SEGMENTS",
    "MIN_SPAN_DEG",
    "RPM",
    "BoundaryReport",
    "CamDesignError",
    "Check",
    "Design",
    "Dynamics",
    "Export",
    "FaceTravel",
    "FactorReport",
    "Limits",
    "Report",
    "Segment",
    "analyse",
    "format_report",
    "from_data",
    "in_units",
    "is_design",
    "json_safe",
    "load",
    "sample",
    "tool_undercut",
]

#: Each follower kind and the dimensions it takes (the core's table).
FOLLOWERS: dict[str, tuple[str, ...]] = {k: tuple(v) for k, v in _core.cam_followers()}
#: The motion laws of a segment (the core's names).
LAWS: tuple[str, ...] = tuple(_core.cam_laws())

_LIMITS = _core.cam_design_limits()
#: One rev/min in rad/s.
RPM: float = _LIMITS["rpm"]
#: Highest cam speed (rev/min) a design file may give.
MAX_RPM: float = _LIMITS["max_rpm"]
#: Most segments in a motion program.
MAX_SEGMENTS: int = _LIMITS["max_segments"]
#: Least span (deg) of a segment.
MIN_SPAN_DEG: float = _LIMITS["min_span_deg"]
#: Largest length (m) a design file may give.
MAX_LENGTH: float = _LIMITS["max_length"]


class CamDesignError(ModelError):
    """A design file that cannot be used; the message names file and field.

    A `camlink.ModelError` (so a `ValueError`), as every bad input is."""


@dataclass(frozen=True)
class Segment:
    """One segment of the motion program as the file gives it."""

    law: str
    span: float
    """Span (rad)."""
    lift: float
    """Lift (m), or swing (rad) for an oscillating follower."""
    start: tuple[float | None, float | None, float | None]
    end: tuple[float | None, float | None, float | None]


@dataclass(frozen=True)
class Dynamics:
    """Follower mass (kg, or kg·m² about the pivot), spring and speeds."""

    mass: float
    spring_rate: float
    preload: float
    damping: float
    speed: float
    """Running speed (rad/s)."""
    redline: float | None
    """Highest speed the cam must run at without jump (rad/s)."""


@dataclass(frozen=True)
class Limits:
    """User limits; None where not given."""

    max_pressure_angle: float | None
    """rad"""
    min_radius: float | None
    """Least convex radius of curvature of the cam surface (m)."""
    max_face_width: float | None
    """m"""
    base_radius_range: tuple[float, float] | None
    """Search range (m) for the smallest base circle."""
    max_contact_stress: float | None = None
    """Allowable Hertz contact stress (Pa)."""
    min_bearing_life_hours: float | None = None
    """Least roller bearing L10 life at the running speed (h)."""
    min_coil_clearance: float | None = None
    """Least gap between the spring's coils at the largest lift (m)."""
    min_surge_ratio: float = SURGE_RATIO
    """Least spring surge frequency over the forcing frequency."""
    max_residual_vibration: float | None = None
    """Largest residual vibration after a rise or return (m or rad)."""


@dataclass(frozen=True)
class Export:
    """Files to write, relative to the output directory; None to skip."""

    csv: str | None
    csv_step: float
    """Angular step (rad) of the CSV, or 0 with a chord tolerance."""
    csv_chord: float | None
    dxf: str | None
    dxf_mode: Literal["polyline", "arcs"]
    tolerance: float
    """Chord or arc-fit tolerance (m) of DXF and SVG."""
    svg: str | None
    tool_radius: float | None
    svaj: str | None
    profile: str | None
    given: frozenset[str] = frozenset()
    """The export keys whose file names the design file gives (the others
    are default names, never replaced without ``--force``)."""
    units: str = "m"
    """Length unit of reports, pictures and exports: "m" or "mm"."""
    svaj_time: str | None = None
    """SVAJ against time at the running speed (needs [dynamics])."""
    vibration: str | None = None
    """The follower train's deviation and dynamic contact force over a
    turn (needs [vibration])."""
    bore_radius: float | None = None
    """m"""
    keyway_width: float | None = None
    keyway_depth: float | None = None
    keyway_angle: float = 0.0
    """rad, from the timing mark."""
    timing_mark: bool = True


@dataclass(frozen=True)
class Design:
    """A parsed design file."""

    path: Path
    name: str
    follower: str
    dims: tuple[float, ...]
    base_radius: float
    ccw: bool
    segments: tuple[Segment, ...]
    limits: Limits
    dynamics: Dynamics | None
    export: Export
    contact: ContactSpec | None = None
    spring: SpringSpec | None = None
    vibration: VibrationSpec | None = None

    @property
    def oscillating(self) -> bool:
        return self.follower.startswith("oscillating")

    def core(self, base_radius: float | None = None) -> CamCore:
        """The synthesised cam (in the Rust core)."""
        segs = [
            (s.law, s.span, s.lift, list(s.start), list(s.end)) for s in self.segments
        ]
        try:
            return CamCore(
                segs,
                self.follower,
                list(self.dims),
                self.base_radius if base_radius is None else base_radius,
                self.ccw,
            )
        except ValueError as e:
            raise CamDesignError(f"{self.path}: {e}") from None


def _design(d: dict[str, Any], path: Path) -> Design:
    """The dataclasses of the core's checked design `d`."""
    lim = dict(d["limits"])
    if lim["base_radius_range"] is not None:
        lim["base_radius_range"] = tuple(lim["base_radius_range"])
    ex = dict(d["export"])
    ex["given"] = frozenset(ex["given"])
    c, sp, v = d["contact"], d["spring"], d["vibration"]
    return Design(
        path=path,
        name=d["name"],
        follower=d["follower"],
        dims=tuple(d["dims"]),
        base_radius=d["base_radius"],
        ccw=d["ccw"],
        segments=tuple(
            Segment(law, span, lift, (s0[0], s0[1], s0[2]), (s1[0], s1[1], s1[2]))
            for law, span, lift, s0, s1 in d["segments"]
        ),
        limits=Limits(**lim),
        dynamics=None if d["dynamics"] is None else Dynamics(**d["dynamics"]),
        export=Export(**ex),
        contact=None if c is None else ContactSpec(**{**c, "materials": tuple(c["materials"])}),
        spring=None if sp is None else SpringSpec(**sp),
        vibration=None
        if v is None
        else VibrationSpec(
            tuple(v["masses"]),
            tuple(v["stiffness"]),
            tuple(v["damping"]),
            v["steps"],
            v["turns"],
            v["polydyne"],
        ),
    )


def _checked(read: Any, path: Path) -> Design:
    """The design the core's `read()` returns, its warnings issued as
    `LoadWarning`; raises CamDesignError with the core's message."""
    try:
        d, notes = read()
    except ModelError as e:
        raise CamDesignError(str(e)) from None
    for note in notes:
        warnings.warn(LoadWarning(note), stacklevel=3)
    return _design(d, path)


def load(path: str | Path) -> Design:
    """Reads and checks a design file (in the core, `camlink_cam`); raises
    CamDesignError naming the file, line and field."""
    p = Path(path)
    return _checked(lambda: _core.cam_design_read(p), p)


def is_design(doc: dict[str, Any]) -> bool:
    """Whether the parsed TOML `doc` is a cam design file (a motion
    program: top-level ``[[segments]]`` and ``[follower]``) rather than a
    model file."""
    return bool(_core.cam_is_design(json.dumps(_plain(doc), default=str)))


def _plain(v: object) -> object:
    """`v` with its infinities and NaN as the words TOML writes them
    ('inf', 'nan'), which JSON cannot hold: the loader refuses them as
    numbers, naming the field."""
    if isinstance(v, float) and not math.isfinite(v):
        return repr(v)
    if isinstance(v, dict):
        return {k: _plain(x) for k, x in v.items()}
    if isinstance(v, list):
        return [_plain(x) for x in v]
    return v


def from_data(doc: dict[str, Any], path: str | Path) -> Design:
    """Checks the parsed TOML `doc` of the design file `path` (named in
    messages; its stem names the default exports) as `load` does; raises
    CamDesignError naming the field."""
    p = Path(path)
    text = json.dumps(_plain(doc), default=str)
    return _checked(lambda: _core.cam_design_load(text, str(p), json=True), p)


@dataclass(frozen=True)
class Check:
    """One design limit: its value, the user's limit, the margin, pass/fail."""

    name: str
    value: float
    limit: float | None
    margin: float | None
    """How far inside the limit (positive) or past it (negative), same unit."""
    unit: str
    at_deg: float | None
    ok: bool
    note: str = ""


@dataclass(frozen=True)
class BoundaryReport:
    theta_deg: float
    before: int
    after: int
    continuity: int
    jumps: tuple[float, float, float]
    text: str


@dataclass(frozen=True)
class FactorReport:
    segment: int
    law: str
    computed: tuple[float, float, float]
    textbook: tuple[float, float, float] | None


@dataclass(frozen=True)
class FaceTravel:
    """Where the contact runs along a flat face over a turn: its least and
    greatest position (m) from the stem axis (translating) or from the foot
    of the perpendicular from the pivot (oscillating), and the cam angles
    (deg) where it gets there; the face must span them."""

    lo: float
    hi: float
    lo_at_deg: float
    hi_at_deg: float

    @property
    def width(self) -> float:
        """The face width needed (m)."""
        return self.hi - self.lo


@dataclass(frozen=True)
class Report:
    """Everything `camlink cam` prints."""

    name: str
    follower: str
    base_radius: float
    boundaries: tuple[BoundaryReport, ...]
    factors: tuple[FactorReport, ...]
    checks: tuple[Check, ...]
    concave_deg: tuple[tuple[float, float], ...]
    undercut_deg: tuple[tuple[float, float], ...]
    tool_undercut_deg: tuple[tuple[float, float], ...]
    smallest_base_radius: float | None
    round_trip: tuple[float, float, float] | None
    """Largest relative errors of displacement, velocity, acceleration;
    None when the kinematics could not run the cam (a failing check says
    where)."""
    face_travel: FaceTravel | None = None
    """A flat face's contact travel; None for a roller."""
    files: tuple[str, ...] = field(default=())
    units: str = "m"
    """Length unit of the report's figures (``in_units``)."""
    sizing: dict[str, Any] = field(default_factory=dict)
    """Contact stress, bearing, spring and vibration figures (SI) behind
    their checks: keys ``contact``, ``bearing``, ``spring``, ``vibration``."""

    @property
    def ok(self) -> bool:
        return all(c.ok for c in self.checks)

    def to_dict(self) -> dict[str, Any]:
        from dataclasses import asdict

        d = asdict(self)
        d["ok"] = self.ok
        if self.face_travel is not None:
            d["face_travel"]["width"] = self.face_travel.width
        return d


def _pairs(r: list[tuple[float, float]]) -> tuple[tuple[float, float], ...]:
    return tuple((a, b) for a, b in r)


def _report(d: dict[str, Any], files: tuple[str, ...] = ()) -> Report:
    """The dataclasses of the core's report `d` (`_core.cam_design_report`)."""
    travel = d["face_travel"]
    return Report(
        name=d["name"],
        follower=d["follower"],
        base_radius=d["base_radius"],
        boundaries=tuple(BoundaryReport(**b) for b in d["boundaries"]),
        factors=tuple(FactorReport(**f) for f in d["factors"]),
        checks=tuple(Check(**c) for c in d["checks"]),
        concave_deg=_pairs(d["concave_deg"]),
        undercut_deg=_pairs(d["undercut_deg"]),
        tool_undercut_deg=_pairs(d["tool_undercut_deg"]),
        smallest_base_radius=d["smallest_base_radius"],
        round_trip=d["round_trip"],
        face_travel=None if travel is None else FaceTravel(**travel),
        files=files,
        units=d["units"],
        sizing=d["sizing"],
    )


def tool_undercut(
    core: CamCore, tool_radius: float, n: int | None = None
) -> list[tuple[float, float]]:
    """θ ranges (rad) a tool of `tool_radius` (m) cannot cut, sampled at
    `n` angles (the core's default, every 0.1°): where the surface is
    concave tighter than the tool, or already cusped (the core's rule,
    ``camlink_cam::report::tool_undercut``)."""
    return list(_core.cam_tool_undercut(core, tool_radius, n))


def analyse(design: Design) -> Report:
    """Synthesises the cam and checks every limit (the core's report,
    ``camlink_cam::report``: which checks, their limits, margins and
    verdicts); lengths in metres."""
    try:
        return _report(_core.cam_design_report(design))
    except ModelError as e:
        raise CamDesignError(str(e)) from None


def json_safe(v: object) -> object:
    """`v` (a report's dict) with arrays as lists and infinities and NaN
    as None, for JSON."""
    if isinstance(v, np.ndarray):
        return json_safe(v.tolist())
    if isinstance(v, float) and not math.isfinite(v):
        return None
    if isinstance(v, dict):
        return {k: json_safe(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [json_safe(x) for x in v]
    return v


def in_units(r: Report, units: str) -> Report:
    """`r` with its lengths in `units` ("m" or "mm"): the checks in a
    length unit, the base circle, the smallest base circle and the face
    travel (angles are in degrees already; `sizing` stays SI). The rule is
    the core's (``Report::in_units``)."""
    if units == r.units:
        return r
    return _report(_core.cam_report_in_units(r, units), r.files)


def format_report(r: Report) -> str:
    """The report as text."""
    lines = [
        f"cam design '{r.name}': {r.follower} follower, base circle {r.base_radius:g} {r.units}",
        "",
    ]
    lines.append("motion program boundaries:")
    for b in r.boundaries:
        lines.append(f"  segment {b.before} -> {b.after}: {b.text}")
    lines.append("")
    lines.append("segment factors   Cv       Ca       Cj      (textbook Cv, Ca, Cj)")
    for f in r.factors:
        tb = (
            ""
            if f.textbook is None
            else "(" + ", ".join(f"{v:.4g}" for v in f.textbook) + ")"
        )
        lines.append(
            f"  {f.segment:2d} {f.law:18s} {f.computed[0]:7.4f} {f.computed[1]:8.4f} "
            f"{f.computed[2]:8.3f}  {tb}"
        )
    lines.append("")
    lines.append("design limits:")
    for c in r.checks:
        mark = "ok  " if c.ok else "FAIL"
        where = "" if c.at_deg is None else f" at {c.at_deg:.2f}°"
        unit = f" {c.unit}" if c.unit else ""
        lim = "" if c.limit is None else f" (limit {c.limit:.6g}{unit}"
        lim += (
            "" if c.margin is None or c.limit is None else f", margin {c.margin:.6g})"
        )
        lim += ")" if c.limit is not None and c.margin is None else ""
        value = "" if math.isnan(c.value) else f": {c.value:.6g}{unit}"
        note = "" if not c.note else f"; {c.note}" if value else f": {c.note}"
        lines.append(f"  {mark} {c.name}{value}{where}{lim}{note}")
    for label, ranges in (
        ("concave", r.concave_deg),
        ("undercut", r.undercut_deg),
        ("tool cannot cut", r.tool_undercut_deg),
    ):
        if ranges:
            txt = ", ".join(f"{a:.2f}°–{b:.2f}°" for a, b in ranges)
            lines.append(f"  {label}: {txt}")
    if r.smallest_base_radius is not None:
        lines.append(f"  smallest base circle: {r.smallest_base_radius:.6g} {r.units}")
    lines.append("")
    if r.round_trip is not None:
        d, v, a = r.round_trip
        lines.append(
            "round trip (camlink kinematics of the synthesised cam vs the program, "
            f"{_core.CAM_ROUND_TRIP_STEPS} steps):"
        )
        lines.append(
            f"  displacement {d:.2e}, velocity {v:.2e}, acceleration {a:.2e} (relative)"
        )
    for path in r.files:
        lines.append(f"wrote {path}")
    lines.append("")
    lines.append("all limits hold" if r.ok else "some limits fail")
    return "\n".join(lines)


def sample(
    core: CamCore, n: int = 1441
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(θ over a turn, [s, s′, s″, s‴] at each) for plots and exports."""
    th = np.linspace(0.0, 2.0 * math.pi, n)
    return th, np.asarray(core.motion(th))
