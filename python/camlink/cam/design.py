"""Cam design files: a motion program and a follower in, a synthesised cam,
its design limits and a pass/fail report out.

A design file (TOML) holds ``[cam]``, ``[follower]``, ``[[segments]]`` and
optionally ``[limits]``, ``[dynamics]`` and ``[export]``; see
docs/cam-design.md. Angles in the file are in degrees (keys end in
``_deg``) and cam speeds in rev/min (``_rpm``); lengths are in metres.
Inside, everything is SI and radians; the mechanics run in the Rust core
(``camlink._core.CamCore``).
"""

from __future__ import annotations

import difflib
import math
import tomllib
import warnings
from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path, PureWindowsPath
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray

from camlink import _core
from camlink._core import CamCore, ModelError, cam_base_radius_question
from camlink.cam.export import MAX_CSV_ROWS, MIN_RELATIVE_TOLERANCE
from camlink.cam.sizing import SURGE_RATIO, ContactSpec, SpringSpec, VibrationSpec
from camlink.warn import LoadWarning

#: Each follower kind and the dimensions it takes (the core's table).
FOLLOWERS: dict[str, tuple[str, ...]] = {k: tuple(v) for k, v in _core.cam_followers()}
#: The motion laws of a segment (the core's names).
LAWS: tuple[str, ...] = tuple(_core.cam_laws())
RPM = 2.0 * math.pi / 60.0

#: Highest cam speed (rev/min) a design file may give.
MAX_RPM = 1e6

#: Most segments in a motion program (a real program has tens; each one
#: costs its share of every sample, report line and picture).
MAX_SEGMENTS = 1000

#: Least span (deg) of a segment.
MIN_SPAN_DEG = 1e-3

#: Largest length (m) a design file may give: base radius, follower
#: dimensions, lifts, limits, tool radius, search range.
MAX_LENGTH = 1e3


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


class _Table:
    """Typed reads from one TOML table with messages naming the field."""

    def __init__(self, path: Path, where: str, data: object) -> None:
        if not isinstance(data, dict):
            raise CamDesignError(f"{path}: {where} must be a table")
        self.path, self.where, self.data = path, where, data
        self.used: set[str] = set()

    def fail(self, key: str, message: str) -> CamDesignError:
        return CamDesignError(f"{self.path}: {self.where}.{key}: {message}")

    def number(
        self,
        key: str,
        default: float | None = None,
        *,
        positive: bool = False,
        most: float | None = None,
        unit: str = "",
    ) -> float:
        """The number at `key`; with `most`, |value| ≤ `most` (`unit`)."""
        self.used.add(key)
        v = self.data.get(key, default)
        if v is None:
            raise self.fail(key, "is required")
        if (
            isinstance(v, bool)
            or not isinstance(v, (int, float))
            or not math.isfinite(v)
        ):
            raise self.fail(key, f"must be a number, got {v!r}")
        if positive and v <= 0:
            raise self.fail(key, f"must be positive, got {v}")
        if most is not None and abs(v) > most:
            raise self.fail(key, f"must be at most {most:g}{unit} in size, got {v}")
        return float(v)

    def length(self, key: str, default: float | None = None, *, positive: bool = False) -> float:
        """A length (m) at `key`: at most `MAX_LENGTH` in size."""
        return self.number(key, default, positive=positive, most=MAX_LENGTH, unit=" m")

    def optional(
        self, key: str, *, positive: bool = False, most: float | None = None, unit: str = ""
    ) -> float | None:
        if key not in self.data:
            self.used.add(key)
            return None
        return self.number(key, positive=positive, most=most, unit=unit)

    def text(
        self, key: str, default: str | None = None, choices: tuple[str, ...] = ()
    ) -> str:
        self.used.add(key)
        v = self.data.get(key, default)
        if not isinstance(v, str):
            raise self.fail(
                key, "is required" if v is None else f"must be a string, got {v!r}"
            )
        if choices and v not in choices:
            raise self.fail(
                key, f"'{v}' is not one of {', '.join(choices)}{_did_you_mean(v, choices)}"
            )
        return v

    def finish(self) -> None:
        """Refuses a key no read asked for, suggesting the nearest known one."""
        extra = sorted(set(self.data) - self.used)
        if extra:
            known = sorted(k for k in self.used if not k.startswith("_"))
            raise self.fail(
                extra[0],
                f"unknown key{_did_you_mean(extra[0], known)}; "
                f"the keys here are {', '.join(known)}",
            )


def _did_you_mean(name: str, candidates: Iterable[str]) -> str:
    """`` (did you mean 'x'?)`` for the candidate closest to `name`, if any is close."""
    close = difflib.get_close_matches(name, list(candidates), n=1, cutoff=0.6)
    return f" (did you mean '{close[0]}'?)" if close else ""


def _ends(
    t: _Table, key: str, scale: float
) -> tuple[float | None, float | None, float | None]:
    t.used.add(key)
    if key not in t.data:
        return (None, None, None)
    e = _Table(t.path, f"{t.where}.{key}", t.data[key])
    out = tuple(
        None if k not in e.data else e.number(k) * scale
        for k in ("velocity", "acceleration", "jerk")
    )
    e.used.update(("velocity", "acceleration", "jerk"))
    e.finish()
    return (out[0], out[1], out[2])


def load(path: str | Path) -> Design:
    """Reads and checks a design file; raises CamDesignError naming the field."""
    p = Path(path)
    try:
        with p.open("rb") as f:
            doc = tomllib.load(f)
    except tomllib.TOMLDecodeError as e:
        raise CamDesignError(f"{p}: {e}") from None
    return from_data(doc, p)


def is_design(doc: dict[str, Any]) -> bool:
    """Whether the parsed TOML `doc` is a cam design file (a motion
    program: top-level ``[[segments]]`` and ``[follower]``) rather than a
    model file."""
    return isinstance(doc.get("segments"), list) and "follower" in doc and "bodies" not in doc


def from_data(doc: dict[str, Any], path: str | Path) -> Design:
    """Checks the parsed TOML `doc` of the design file `path` (named in
    messages; its stem names the default exports) as `load` does; raises
    CamDesignError naming the field."""
    p = Path(path)
    top = _Table(p, "design", doc)
    name = top.text("name", p.stem)
    cam = _Table(p, "cam", doc.get("cam", {}))
    top.used.add("cam")
    base = cam.length("base_radius", positive=True)
    question = cam_base_radius_question(base)
    if question is not None:
        warnings.warn(
            LoadWarning(f"{p}: [cam] base_radius: {question} (design files are in metres)"),
            stacklevel=2,
        )
    rotation = cam.text("rotation", "ccw", ("ccw", "cw"))
    cam.finish()
    fol = _Table(p, "follower", doc.get("follower", {}))
    top.used.add("follower")
    kind = fol.text("type", None, tuple(FOLLOWERS))
    dims = []
    for k in FOLLOWERS[kind]:
        dims.append(
            fol.length(
                k,
                0.0 if k in ("offset", "face_offset") else None,
                positive=k not in ("offset", "face_offset"),
            )
        )
    fol.finish()
    oscillating = kind.startswith("oscillating")
    raw = doc.get("segments")
    top.used.add("segments")
    if not isinstance(raw, list) or not raw:
        raise CamDesignError(
            f"{p}: [[segments]]: the motion program needs at least one segment"
        )
    if len(raw) > MAX_SEGMENTS:
        raise CamDesignError(
            f"{p}: [[segments]]: {len(raw)} segments; a motion program has at most "
            f"{MAX_SEGMENTS}"
        )
    segments = []
    for i, r in enumerate(raw):
        s = _Table(p, f"segments[{i}]", r)
        law = s.text("law", None, LAWS)
        span_deg = s.number("span_deg", positive=True, most=360.0, unit="°")
        if span_deg < MIN_SPAN_DEG:
            raise s.fail("span_deg", f"must be at least {MIN_SPAN_DEG:g}°, got {span_deg:g}")
        span = math.radians(span_deg)
        if oscillating:
            lift = math.radians(s.number("swing_deg", 0.0, most=180.0, unit="°"))
            scale = 1.0
        else:
            lift = s.length("lift", 0.0)
            scale = 1.0
        start, end = _ends(s, "start", scale), _ends(s, "end", scale)
        s.finish()
        segments.append(Segment(law, span, lift, start, end))
    lim = _Table(p, "limits", doc.get("limits", {}))
    top.used.add("limits")
    phi = lim.optional("max_pressure_angle_deg", positive=True, most=90.0, unit="°")
    rng = None
    lim.used.add("base_radius_search")
    if "base_radius_search" in lim.data:
        v = lim.data["base_radius_search"]
        if not (
            isinstance(v, list)
            and len(v) == 2
            and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in v)
            and 0 < v[0] < v[1] <= MAX_LENGTH
        ):
            raise lim.fail(
                "base_radius_search",
                f"must be [lo, hi] with 0 < lo < hi ≤ {MAX_LENGTH:g} (m), got {v!r}",
            )
        rng = (float(v[0]), float(v[1]))
    limits = Limits(
        max_pressure_angle=None if phi is None else math.radians(phi),
        min_radius=lim.optional("min_radius", positive=True, most=MAX_LENGTH, unit=" m"),
        max_face_width=lim.optional("max_face_width", positive=True, most=MAX_LENGTH, unit=" m"),
        base_radius_range=rng,
        max_contact_stress=lim.optional("max_contact_stress", positive=True, unit=" Pa"),
        min_bearing_life_hours=lim.optional("min_bearing_life_hours", positive=True, unit=" h"),
        min_coil_clearance=lim.optional(
            "min_coil_clearance", positive=True, most=MAX_LENGTH, unit=" m"
        ),
        min_surge_ratio=lim.number("min_surge_ratio", SURGE_RATIO, positive=True),
        max_residual_vibration=lim.optional("max_residual_vibration", positive=True),
    )
    lim.finish()
    dynamics = None
    dynamics_given: frozenset[str] = frozenset()
    if "dynamics" in doc:
        top.used.add("dynamics")
        d = _Table(p, "dynamics", doc["dynamics"])
        red = d.optional("redline_rpm", positive=True, most=MAX_RPM, unit=" rpm")
        dynamics = Dynamics(
            mass=d.number("mass", positive=True),
            spring_rate=d.number("spring_rate", 0.0),
            preload=d.number("preload", 0.0),
            damping=d.number("damping", 0.0),
            speed=d.number("speed_rpm", positive=True, most=MAX_RPM, unit=" rpm") * RPM,
            redline=None if red is None else red * RPM,
        )
        for k in ("spring_rate", "preload", "damping"):
            if getattr(dynamics, k) < 0:
                raise d.fail(k, "must not be negative")
        d.finish()
        dynamics_given = frozenset(d.data)
    sizing: dict[str, Any] = {k: doc[k] for k in ("contact", "spring", "vibration") if k in doc}
    top.used.update(sizing)
    ex = _Table(p, "export", doc.get("export", {}))
    top.used.add("export")
    stem = p.stem

    names: dict[str, str] = {}
    given: set[str] = set()

    def out(key: str, default: str) -> str | None:
        ex.used.add(key)
        v = ex.data.get(key, default)
        if v is False:
            return None
        if not isinstance(v, str) or not v:
            raise ex.fail(key, f"must be a file name or false, got {v!r}")
        problem = _not_plain(v)
        if problem:
            raise ex.fail(
                key, f"'{v}' {problem}; an export is a plain file name inside the output folder"
            )
        if v == p.name:
            raise ex.fail(key, f"'{v}' is the design file's name; choose another file name")
        if v in names:
            raise ex.fail(key, f"'{v}' is also export.{names[v]}; each export needs its own file")
        names[v] = key
        if key in ex.data:
            given.add(key)
        return v

    chord = ex.optional("csv_chord_tolerance", positive=True, most=MAX_LENGTH, unit=" m")
    step_deg = None if chord is not None else ex.number("csv_step_deg", 1.0, positive=True)
    if step_deg is not None and 360.0 / step_deg > MAX_CSV_ROWS:
        raise ex.fail(
            "csv_step_deg",
            f"{step_deg:g}° makes {360.0 / step_deg:.3g} rows; the CSV holds at most "
            f"{MAX_CSV_ROWS} (a step of at least {360.0 / MAX_CSV_ROWS:g}°)",
        )
    export = Export(
        csv=out("csv", f"{stem}.csv"),
        csv_step=0.0 if step_deg is None else math.radians(step_deg),
        csv_chord=chord,
        dxf=out("dxf", f"{stem}.dxf"),
        dxf_mode="arcs"
        if ex.text("dxf_mode", "polyline", ("polyline", "arcs")) == "arcs"
        else "polyline",
        tolerance=ex.number("tolerance", 1e-5, positive=True, most=MAX_LENGTH, unit=" m"),
        svg=out("svg", f"{stem}.svg"),
        tool_radius=ex.optional("tool_radius", positive=True, most=MAX_LENGTH, unit=" m"),
        svaj=out("svaj_plot", f"{stem}_svaj.png"),
        profile=out("profile_plot", f"{stem}_profile.png"),
        given=frozenset(given),
        units=ex.text("units", "m", ("m", "mm")),
        svaj_time=out("svaj_time_plot", f"{stem}_svaj_time.png") if dynamics else None,
        vibration=out("vibration_plot", f"{stem}_vibration.png") if "vibration" in doc else None,
    )
    bore = ex.optional("bore_diameter", positive=True, most=MAX_LENGTH, unit=" m")
    kw = ex.optional("keyway_width", positive=True, most=MAX_LENGTH, unit=" m")
    kd = ex.optional("keyway_depth", positive=True, most=MAX_LENGTH, unit=" m")
    ka = ex.number("keyway_angle_deg", 0.0, most=360.0, unit="°")
    ex.used.add("timing_mark")
    mark = ex.data.get("timing_mark", True)
    if not isinstance(mark, bool):
        raise ex.fail("timing_mark", f"must be true or false, got {mark!r}")
    for key, v in (("keyway_width", kw), ("keyway_depth", kd)):
        if v is not None and bore is None:
            raise ex.fail(key, "needs export.bore_diameter")
    if (kw is None) != (kd is None):
        raise ex.fail("keyway_width" if kw is None else "keyway_depth", "a keyway needs both width and depth")
    if bore is not None and kw is not None and kw >= bore:
        raise ex.fail("keyway_width", f"{kw} m must be narrower than the bore {bore} m")
    from dataclasses import replace as _replace

    export = _replace(
        export,
        bore_radius=None if bore is None else bore / 2.0,
        keyway_width=kw,
        keyway_depth=kd,
        keyway_angle=math.radians(ka),
        timing_mark=mark,
    )
    ex.finish()
    top.finish()
    design = Design(
        p,
        name,
        kind,
        tuple(dims),
        base,
        rotation == "ccw",
        tuple(segments),
        limits,
        dynamics,
        export,
    )
    core = design.core()  # checks the program and the follower's geometry
    if sizing:
        from camlink.cam import sizing as cam_sizing

        design = cam_sizing.complete(design, sizing, dynamics_given)
    th = np.linspace(0.0, 2.0 * math.pi, 3600, endpoint=False)
    bad = ~np.all(np.isfinite(np.asarray(core.surface(th))), axis=1)
    if bad.any():
        raise CamDesignError(
            f"{p}: the synthesised profile is not finite at θ = "
            f"{math.degrees(th[np.argmax(bad)]):.2f}° (check the base radius, the follower's "
            "dimensions, the lifts and the end conditions)"
        )
    if export.bore_radius is not None:
        th_all = np.linspace(0.0, 2.0 * math.pi, 3600, endpoint=False)
        least = float(np.min(np.hypot(*np.asarray(core.surface(th_all)).T)))
        outer = export.bore_radius + (export.keyway_depth or 0.0)
        if outer >= least:
            raise ex.fail(
                "bore_diameter",
                f"the bore and keyway reach {outer:.6g} m from the centre, beyond the "
                f"profile's least radius {least:.6g} m",
            )
    size = float(core.geometry()["max_radius"]) + (export.tool_radius or 0.0)
    for key, tol in (("tolerance", export.tolerance), ("csv_chord_tolerance", export.csv_chord)):
        least = MIN_RELATIVE_TOLERANCE * size
        if tol is not None and tol < least:
            raise ex.fail(
                key,
                f"{tol:g} m is finer than {MIN_RELATIVE_TOLERANCE:g} of the profile's size "
                f"({size:.6g} m); use at least {least:.3g} m",
            )
    return design


def _not_plain(name: str) -> str:
    """Why `name` is not a plain file name ("" when it is)."""
    if "/" in name or "\\" in name:
        return "holds a path separator"
    if name in (".", ".."):
        return "is a folder"
    if any(ord(c) < 32 for c in name):
        return "holds a control character"
    if Path(name).is_absolute() or PureWindowsPath(name).drive:
        return "is an absolute path"
    return ""


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
