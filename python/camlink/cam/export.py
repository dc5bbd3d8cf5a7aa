"""Export of a synthesised cam for manufacture: points (CSV), DXF as a
closed polyline or as arcs fitted within a tolerance (through ezdxf), SVG,
and the centre path of a cutter or grinding wheel of a given radius.

All coordinates are in the cam frame, metres, the cam centre at the origin.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeAlias

import ezdxf
import numpy as np
from numpy.typing import NDArray

from camlink._core import CamCore, cam_design_limits
from camlink.units import LENGTH_UNITS as METRES

Points: TypeAlias = NDArray[np.float64]

#: Finest chord or arc-fit tolerance, relative to the size of the curve
#: (its largest distance from the cam centre): about 80,000 points for a
#: closed profile at the limit (the core's bound, which design files
#: are held to).
MIN_RELATIVE_TOLERANCE: float = cam_design_limits()["min_relative_tolerance"]

#: Most rows of a CSV export (a step of at least 0.00036°).
MAX_CSV_ROWS: int = cam_design_limits()["max_csv_rows"]

#: Most points `angles_by_chord` gives.
MAX_POINTS = 2_000_000

#: Length units of exports: name -> units per metre (of camlink's length
#: units, `camlink.units.LENGTH_UNITS`).
LENGTH_UNITS = {u: 1.0 / METRES[u] for u in ("m", "mm")}

#: DXF $INSUNITS codes of `LENGTH_UNITS`.
_DXF_UNITS = {"m": 6, "mm": 4}


@dataclass(frozen=True)
class Hub:
    """A bore, a keyway and a timing mark on the cam's drawing (cam frame,
    m and rad). The keyway is centred on the direction `keyway_angle`, its
    sides `keyway_width` apart, cut `keyway_depth` beyond the bore circle
    on its centreline (the hub's keyway depth t₂ of DIN 6885 measured from
    the bore). The timing mark is a radial line at `mark_angle` (the
    direction of the contact at θ = 0) from 0.6 to 0.9 of the least profile
    radius."""

    bore_radius: float
    keyway_width: float | None
    keyway_depth: float | None
    keyway_angle: float
    mark_angle: float | None

    def keyway(self) -> Points | None:
        """The keyway's open outline (4 points, m): from the bore circle
        out along one side, across, and back to the bore along the other."""
        if self.keyway_width is None or self.keyway_depth is None:
            return None
        r, w, d = self.bore_radius, self.keyway_width, self.keyway_depth
        u = np.array([math.cos(self.keyway_angle), math.sin(self.keyway_angle)])
        t = np.array([-u[1], u[0]])
        x0 = math.sqrt(r * r - 0.25 * w * w)
        return np.array(
            [x0 * u - 0.5 * w * t, (r + d) * u - 0.5 * w * t, (r + d) * u + 0.5 * w * t, x0 * u + 0.5 * w * t]
        )

    def mark(self, least_radius: float) -> Points | None:
        """The timing mark's two ends (m)."""
        if self.mark_angle is None:
            return None
        u = np.array([math.cos(self.mark_angle), math.sin(self.mark_angle)])
        return np.array([0.6 * least_radius * u, 0.9 * least_radius * u])


def angles_by_step(step: float) -> NDArray[np.float64]:
    """Cam angles θ (rad) over one turn at `step` (rad), the end excluded;
    at most `MAX_CSV_ROWS` of them (ValueError for a finer step)."""
    if not (step > 0 and math.isfinite(step)):
        raise ValueError(f"the step must be positive, got {step} rad")
    n = max(3, math.ceil(2.0 * math.pi / step - 1e-9))
    if n > MAX_CSV_ROWS:
        raise ValueError(
            f"a step of {math.degrees(step):g}° makes {n} rows; at most {MAX_CSV_ROWS} "
            f"(a step of at least {360.0 / MAX_CSV_ROWS:g}°)"
        )
    return np.linspace(0.0, 2.0 * math.pi, n, endpoint=False)


def check_tolerance(core: CamCore, tolerance: float, offset: float = 0.0) -> None:
    """Raises ValueError when `tolerance` (m) is not positive or is finer
    than `MIN_RELATIVE_TOLERANCE` of the size of the curve `offset` (m)
    outside the cam surface."""
    if not (tolerance > 0 and math.isfinite(tolerance)):
        raise ValueError(f"the tolerance must be positive, got {tolerance} m")
    size = float(core.geometry()["max_radius"]) + abs(offset)
    least = MIN_RELATIVE_TOLERANCE * size
    if tolerance < least:
        raise ValueError(
            f"a tolerance of {tolerance:g} m is finer than {MIN_RELATIVE_TOLERANCE:g} of the "
            f"profile's size ({size:.6g} m); use at least {least:.3g} m"
        )


def angles_by_chord(
    core: CamCore, tolerance: float, offset: float = 0.0
) -> NDArray[np.float64]:
    """Cam angles θ (rad) such that no curve point between two neighbours
    lies farther than `tolerance` (m) from their chord (checked at the
    middle and quarter points of every interval, halving where it fails).
    `tolerance` is at least `MIN_RELATIVE_TOLERANCE` of the curve's size
    (`check_tolerance`), which keeps the count below `MAX_POINTS`."""
    check_tolerance(core, tolerance, offset)
    return _chord_angles(core, tolerance, offset)


def _chord_angles(core: CamCore, tolerance: float, offset: float = 0.0) -> NDArray[np.float64]:
    """`angles_by_chord` without the check of the tolerance."""
    edges = np.linspace(0.0, 2.0 * math.pi, 73)
    done: list[NDArray[np.float64]] = []
    a, b = edges[:-1], edges[1:]
    # Breadth first: every interval of one level is probed in one call.
    while len(a):
        u = np.array([0.0, 1.0, 0.25, 0.5, 0.75])
        probe = a[:, None] + (b - a)[:, None] * u
        p = np.asarray(core.surface(probe.ravel(), offset)).reshape(len(a), 5, 2)
        d = p[:, 1] - p[:, 0]
        ln = np.hypot(d[:, 0], d[:, 1])
        r = p[:, 2:] - p[:, :1]
        cross = np.abs(d[:, None, 0] * r[:, :, 1] - d[:, None, 1] * r[:, :, 0])
        with np.errstate(divide="ignore", invalid="ignore"):
            dev = np.where(
                ln[:, None] > 0, cross / ln[:, None], np.hypot(r[:, :, 0], r[:, :, 1])
            ).max(axis=1)
        split = (dev > tolerance) & (b - a > 1e-9)
        done.append(b[~split])
        if sum(len(x) for x in done) + 2 * int(split.sum()) > MAX_POINTS:
            raise ValueError(
                f"more than {MAX_POINTS} points are needed to follow the curve within "
                f"{tolerance:g} m"
            )
        m = 0.5 * (a[split] + b[split])
        a, b = np.concatenate([a[split], m]), np.concatenate([m, b[split]])
    ends = np.sort(np.concatenate(done))
    return np.concatenate([[0.0], ends[:-1]])


def write_csv(
    core: CamCore,
    path: str | Path,
    theta: NDArray[np.float64],
    tool_radius: float | None = None,
    units: str = "m",
) -> None:
    """Writes θ (deg), the surface x, y (m, or mm with `units` "mm", the
    columns then named ``x_mm`` …) and, for a roller, the pitch curve;
    with `tool_radius`, the tool centre path too."""
    k = LENGTH_UNITS[units]
    tag = "" if units == "m" else f"_{units}"
    surf = np.asarray(core.surface(theta)) * k
    cols = [np.degrees(theta), surf[:, 0], surf[:, 1]]
    head = ["theta_deg", f"x{tag}", f"y{tag}"]
    pitch = core.pitch(theta)
    if pitch is not None:
        p = np.asarray(pitch) * k
        cols += [p[:, 0], p[:, 1]]
        head += [f"pitch_x{tag}", f"pitch_y{tag}"]
    if tool_radius is not None:
        t = np.asarray(core.surface(theta, tool_radius)) * k
        cols += [t[:, 0], t[:, 1]]
        head += [f"tool_x{tag}", f"tool_y{tag}"]
    with Path(path).open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow(head)
        for row in np.column_stack(cols):
            w.writerow([f"{v:.12g}" for v in row])


@dataclass(frozen=True)
class Arc:
    """A fitted arc: centre (m), radius (m), start and end angles (deg,
    counterclockwise from start to end), or a line when radius is inf."""

    centre: tuple[float, float]
    radius: float
    start: float
    end: float
    p0: tuple[float, float]
    p1: tuple[float, float]


def _circle(a: Points, b: Points, c: Points) -> tuple[Points, float] | None:
    """The circle through three points; None when they are collinear."""
    d = 2.0 * (a[0] * (b[1] - c[1]) + b[0] * (c[1] - a[1]) + c[0] * (a[1] - b[1]))
    if abs(d) < 1e-300:
        return None
    aa, bb, cc = a @ a, b @ b, c @ c
    ux = (aa * (b[1] - c[1]) + bb * (c[1] - a[1]) + cc * (a[1] - b[1])) / d
    uy = (aa * (c[0] - b[0]) + bb * (a[0] - c[0]) + cc * (b[0] - a[0])) / d
    centre = np.array([ux, uy])
    return centre, float(np.linalg.norm(a - centre))


def _fit(run: Points, tolerance: float) -> Arc | None:
    """The line (when every point of `run` lies within `tolerance` (m) of
    the chord between its ends) or else the arc through its ends and middle
    point covering `run` (when every point lies within `tolerance` of it,
    less the arc's largest sagitta over the edges between neighbouring
    points, so that the edges stay within `tolerance` too); None when
    neither does."""
    p0 = (float(run[0][0]), float(run[0][1]))
    p1 = (float(run[-1][0]), float(run[-1][1]))
    d = run[-1] - run[0]
    ln = float(np.hypot(d[0], d[1]))
    r = run - run[0]
    off = (
        float(np.max(np.abs(d[0] * r[:, 1] - d[1] * r[:, 0]))) / ln
        if ln > 0
        else float(np.max(np.hypot(r[:, 0], r[:, 1])))
    )
    if off <= tolerance:
        return Arc((math.nan, math.nan), math.inf, 0.0, 0.0, p0, p1)
    c = _circle(run[0], run[len(run) // 2], run[-1])
    if c is None:
        return None
    centre, radius = c
    half = 0.5 * np.hypot(*np.diff(run, axis=0).T)
    sagitta = radius - math.sqrt(max(radius * radius - float(np.max(half)) ** 2, 0.0))
    if not np.all(np.abs(np.linalg.norm(run - centre, axis=1) - radius) <= tolerance - sagitta):
        return None
    a0 = math.degrees(math.atan2(run[0][1] - centre[1], run[0][0] - centre[0]))
    a1 = math.degrees(math.atan2(run[-1][1] - centre[1], run[-1][0] - centre[0]))
    mid = run[len(run) // 2]
    # Orientation of the run: ezdxf arcs run counterclockwise.
    cross = (mid[0] - run[0][0]) * (run[-1][1] - run[0][1]) - (mid[1] - run[0][1]) * (
        run[-1][0] - run[0][0]
    )
    if cross < 0:  # clockwise run: swap ends
        a0, a1 = a1, a0
    return Arc((float(centre[0]), float(centre[1])), radius, a0, a1, p0, p1)


def fit_arcs(points: Points, tolerance: float, slack: float = 0.0) -> list[Arc]:
    """Lines and arcs (each arc through both ends of its run of points and
    its middle point) covering the closed polygon `points`, each run as
    long as every point and every edge of it stays within `tolerance` −
    `slack` (m) of its line or arc (run lengths found by doubling, then
    bisection). A curve that leaves each edge of the polygon by at most
    `slack` stays within `tolerance` of the pieces. Neighbouring pieces
    share their end points."""
    n = len(points)
    pts = np.vstack([points, points[:1]])
    arcs: list[Arc] = []
    i = 0
    while i < n:
        # A run of two points is its own chord. The run ends at `lo`, which
        # fits; `hi` is the least end known not to (n + 1 until one fails).
        lo, fit, hi, step = i + 1, _fit(pts[i : i + 2], tolerance - slack), n + 1, 1
        while lo + 1 < hi:
            j = min(lo + step, n) if hi > n else (lo + hi) // 2
            f = _fit(pts[i : j + 1], tolerance - slack)
            if f is None:
                hi = j
            else:
                lo, fit, step = j, f, 2 * step
        assert fit is not None
        arcs.append(fit)
        i = lo
    return arcs


def _polyline(msp: Any, points: Points, layer: str) -> None:
    """A closed LWPOLYLINE through `points` on `layer`, its vertex array
    set in one step (ezdxf's own appending copies the array per point)."""
    poly = msp.add_lwpolyline([], close=True, dxfattribs={"layer": layer})
    poly.lwpoints.set(np.column_stack([points, np.zeros((len(points), 3))]))


def _least_radius(core: CamCore) -> float:
    th = np.linspace(0.0, 2.0 * math.pi, 3600, endpoint=False)
    return float(np.min(np.hypot(*np.asarray(core.surface(th)).T)))


def write_dxf(
    core: CamCore,
    path: str | Path,
    tolerance: float,
    mode: str = "polyline",
    tool_radius: float | None = None,
    units: str = "m",
    hub: Hub | None = None,
) -> int:
    """Writes the cam surface (layer CAM) as a closed polyline within the
    chord `tolerance` or as fitted arcs, and with `tool_radius` the tool
    centre path (layer TOOL); in metres, or millimetres with `units` "mm"
    ($INSUNITS set to match). With `hub`: the bore circle (layer BORE), the
    keyway's outline (layer KEYWAY, an open polyline) and the timing mark
    (layer MARK, a line). Returns the number of entities on CAM."""
    doc = ezdxf.new("R2010", units=_DXF_UNITS[units])
    k = LENGTH_UNITS[units]
    msp = doc.modelspace()
    doc.layers.add("CAM", color=7)
    count = 0
    if mode == "arcs":
        # Between the points the curve leaves their chord by at most 0.1
        # of the tolerance: the fit keeps the polygon within the rest.
        check_tolerance(core, tolerance)
        dense = np.asarray(core.surface(_chord_angles(core, 0.1 * tolerance)))
        for a in fit_arcs(dense, tolerance, slack=0.1 * tolerance):
            if math.isinf(a.radius):
                p0 = (a.p0[0] * k, a.p0[1] * k)
                p1 = (a.p1[0] * k, a.p1[1] * k)
                msp.add_line(p0, p1, dxfattribs={"layer": "CAM"})
            else:
                c = (a.centre[0] * k, a.centre[1] * k)
                msp.add_arc(c, a.radius * k, a.start, a.end, dxfattribs={"layer": "CAM"})
            count += 1
    else:
        pts = np.asarray(core.surface(angles_by_chord(core, tolerance))) * k
        _polyline(msp, pts, "CAM")
        count = 1
    if tool_radius is not None:
        doc.layers.add("TOOL", color=1)
        tp = np.asarray(
            core.surface(angles_by_chord(core, tolerance, tool_radius), tool_radius)
        )
        _polyline(msp, tp * k, "TOOL")
    if hub is not None:
        doc.layers.add("BORE", color=3)
        msp.add_circle((0.0, 0.0), hub.bore_radius * k, dxfattribs={"layer": "BORE"})
        key = hub.keyway()
        if key is not None:
            doc.layers.add("KEYWAY", color=3)
            msp.add_lwpolyline((key * k).tolist(), dxfattribs={"layer": "KEYWAY"})
        mark = hub.mark(_least_radius(core))
        if mark is not None:
            doc.layers.add("MARK", color=5)
            msp.add_line(tuple(mark[0] * k), tuple(mark[1] * k), dxfattribs={"layer": "MARK"})
    doc.saveas(path)
    return count


def write_svg(
    core: CamCore,
    path: str | Path,
    tolerance: float,
    tool_radius: float | None = None,
    hub: Hub | None = None,
) -> None:
    """Writes the cam surface as one closed SVG path, in millimetres, y up
    (the drawing's y axis is flipped), centre marked; with `hub` the bore
    (``<circle id="bore">``), the keyway (``<path id="keyway">``) and the
    timing mark (``<path id="mark">``)."""
    th = angles_by_chord(core, tolerance)
    pts = np.asarray(core.surface(th)) * 1000.0
    paths = [pts]
    if tool_radius is not None:
        paths.append(
            np.asarray(
                core.surface(angles_by_chord(core, tolerance, tool_radius), tool_radius)
            )
            * 1000.0
        )
    r = max(float(np.max(np.abs(p))) for p in paths) * 1.05
    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        (
            f'<svg xmlns="http://www.w3.org/2000/svg" width="{2 * r:.4f}mm" height="{2 * r:.4f}mm" '
            f'viewBox="{-r:.6f} {-r:.6f} {2 * r:.6f} {2 * r:.6f}">'
        ),
        '<g transform="scale(1,-1)" fill="none" stroke-width="0.2">',
    ]
    for k, p in enumerate(paths):
        d = "M " + " L ".join(f"{x:.6f} {y:.6f}" for x, y in p) + " Z"
        colour = "black" if k == 0 else "red"
        out.append(
            f'<path id="{"cam" if k == 0 else "tool"}" stroke="{colour}" d="{d}"/>'
        )
    out.append('<path stroke="blue" d="M -2 0 L 2 0 M 0 -2 L 0 2"/>')
    if hub is not None:
        out.append(
            f'<circle id="bore" stroke="green" cx="0" cy="0" r="{hub.bore_radius * 1000.0:.6f}"/>'
        )
        key = hub.keyway()
        if key is not None:
            d = "M " + " L ".join(f"{x * 1000.0:.6f} {y * 1000.0:.6f}" for x, y in key)
            out.append(f'<path id="keyway" stroke="green" d="{d}"/>')
        mark = hub.mark(_least_radius(core))
        if mark is not None:
            (x0, y0), (x1, y1) = mark * 1000.0
            out.append(
                f'<path id="mark" stroke="blue" d="M {x0:.6f} {y0:.6f} L {x1:.6f} {y1:.6f}"/>'
            )
    out += ["</g>", "</svg>", ""]
    Path(path).write_text("\n".join(out))
