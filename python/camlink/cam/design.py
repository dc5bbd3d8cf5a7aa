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


def _deg_ranges(r: list[tuple[float, float]]) -> tuple[tuple[float, float], ...]:
    return tuple((math.degrees(a), math.degrees(b)) for a, b in r)


def tool_undercut(
    core: CamCore, tool_radius: float, n: int = 3600
) -> list[tuple[float, float]]:
    """θ ranges (rad) a tool of `tool_radius` (m) cannot cut: where the
    surface is concave tighter than the tool, or already cusped."""
    th = np.linspace(0.0, 2.0 * math.pi, n, endpoint=False)
    rho = np.asarray(core.contact(th)["rho"])
    bad = (rho < 0) & (-rho < tool_radius) | ~np.isfinite(rho)
    out: list[tuple[float, float]] = []
    start: float | None = None
    for i in range(n + 1):
        b = bool(bad[i % n])
        if b and start is None:
            start = float(th[i % n]) + (2 * math.pi if i >= n else 0.0)
        elif not b and start is not None:
            out.append((start, float(th[i - 1]) + 2 * math.pi / n))
            start = None
    if start is not None:
        out.append((start, 2 * math.pi))
    return out


def analyse(design: Design) -> Report:
    """Synthesises the cam and checks every limit."""
    core = design.core()
    g = core.geometry()
    checks: list[Check] = []
    deg = math.degrees
    lim = design.limits
    for key, label in (
        ("pressure_rise", "pressure angle, rise"),
        ("pressure_return", "pressure angle, return"),
    ):
        e = g[key]
        if e is None or design.follower == "translating-flat":
            continue
        value, at = e
        limit = lim.max_pressure_angle
        margin = None if limit is None else deg(limit - abs(value))
        checks.append(
            Check(
                label,
                deg(value),
                None if limit is None else deg(limit),
                margin,
                "deg",
                deg(at),
                margin is None or margin >= 0,
            )
        )
    rmin, at = g["min_convex_radius"]
    margin = None if lim.min_radius is None else rmin - lim.min_radius
    checks.append(
        Check(
            "least radius of curvature (convex)",
            rmin,
            lim.min_radius,
            margin,
            "m",
            deg(at),
            margin is None or margin >= 0,
        )
    )
    if g["min_pitch_radius"] is not None:
        rp, at = g["min_pitch_radius"]
        rr = design.dims[-1]
        checks.append(
            Check(
                "least convex pitch-curve radius vs roller radius",
                rp,
                rr,
                rp - rr,
                "m",
                deg(at),
                rp > rr,
            )
        )
    und = g["undercut"]
    checks.append(
        Check("undercut ranges", float(len(und)), None, None, "", None, not und)
    )
    travel = None
    if design.follower.endswith("flat"):
        (lo, lo_at), (hi, hi_at) = g["face_travel"]
        travel = FaceTravel(lo, hi, deg(lo_at), deg(hi_at))
        width = hi - lo
        limit = lim.max_face_width
        margin = None if limit is None else limit - width
        checks.append(
            Check(
                "face width needed",
                width,
                limit,
                margin,
                "m",
                None,
                margin is None or margin >= 0,
                f"contact travels from {lo:.6g} to {hi:.6g} m along the face",
            )
        )
        conc = g["concave"]
        if conc:
            checks.append(
                Check(
                    "concave ranges under a flat face",
                    float(len(conc)),
                    None,
                    None,
                    "",
                    None,
                    False,
                )
            )
    if design.dynamics is not None:
        d = design.dynamics
        f = core.force((d.mass, d.spring_rate, d.preload, d.damping), d.speed)
        fmin, at = f["min_normal"]
        checks.append(
            Check(
                f"least contact force at {d.speed / RPM:.6g} rpm",
                fmin,
                0.0,
                fmin,
                "N",
                deg(at),
                fmin > 0,
            )
        )
        jump = f["jump"]
        jump_rpm = math.inf if jump is None else jump[0] / RPM
        if d.redline is not None:
            red = d.redline / RPM
            checks.append(
                Check(
                    "jump speed vs redline",
                    jump_rpm,
                    red,
                    jump_rpm - red,
                    "rpm",
                    None if jump is None else deg(jump[1]),
                    jump_rpm > red,
                )
            )
        else:
            checks.append(
                Check(
                    "jump speed",
                    jump_rpm,
                    None,
                    None,
                    "rpm",
                    None if jump is None else deg(jump[1]),
                    jump_rpm > d.speed / RPM,
                )
            )
    tool = []
    if design.export.tool_radius is not None:
        tool = tool_undercut(core, design.export.tool_radius)
    smallest = None
    if lim.base_radius_range is not None:
        smallest = core.smallest_base_radius(
            lim.max_pressure_angle, lim.min_radius, *lim.base_radius_range
        )
        limit = design.base_radius
        checks.append(
            Check(
                "smallest base circle meeting the limits",
                math.nan if smallest is None else smallest,
                limit,
                None if smallest is None else limit - smallest,
                "m",
                None,
                smallest is not None and smallest <= limit,
            )
        )
    from camlink.cam import sizing as cam_sizing

    more, sizing = cam_sizing.checks(design, core)
    checks.extend(more)
    try:
        rt: tuple[float, float, float] | None = core.round_trip(1.0, 720)
    except ValueError as e:
        rt = None
        checks.append(
            Check("round trip", math.nan, None, None, "", None, False, str(e))
        )
    return Report(
        name=design.name,
        follower=design.follower,
        base_radius=design.base_radius,
        boundaries=tuple(
            BoundaryReport(
                deg(b[0]), b[1], b[2], b[3], (b[4][0], b[4][1], b[4][2]), b[5]
            )
            for b in core.boundaries()
        ),
        factors=tuple(
            FactorReport(
                k, law, (c[0], c[1], c[2]), None if t is None else (t[0], t[1], t[2])
            )
            for k, law, c, t in core.factors()
        ),
        checks=tuple(checks),
        concave_deg=_deg_ranges(g["concave"]),
        undercut_deg=_deg_ranges(und),
        tool_undercut_deg=_deg_ranges(tool),
        smallest_base_radius=smallest,
        round_trip=rt,
        face_travel=travel,
        sizing=sizing,
    )


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
    """`r` with its lengths in `units` ("m" or "mm"): the checks in m, the
    base circle, the smallest base circle and the face travel (angles are
    in degrees already)."""
    if units == "m":
        return r
    from dataclasses import replace

    k = 1000.0

    def conv(c: Check) -> Check:
        if c.unit != "m":
            return c
        f = lambda v: None if v is None else v * k  # noqa: E731
        note = c.note
        if r.face_travel is not None and c.name == "face width needed":
            lo, hi = r.face_travel.lo * k, r.face_travel.hi * k
            note = f"contact travels from {lo:.6g} to {hi:.6g} mm along the face"
        return replace(
            c, value=c.value * k, limit=f(c.limit), margin=f(c.margin), unit="mm", note=note
        )

    travel = r.face_travel
    if travel is not None:
        travel = replace(travel, lo=travel.lo * k, hi=travel.hi * k)
    return replace(
        r,
        base_radius=r.base_radius * k,
        checks=tuple(conv(c) for c in r.checks),
        smallest_base_radius=None
        if r.smallest_base_radius is None
        else r.smallest_base_radius * k,
        face_travel=travel,
        units=units,
    )


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
            "round trip (camlink kinematics of the synthesised cam vs the program, 720 steps):"
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
