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

from camlink import _core
from camlink._core import CamCore, cam_design_limits
from camlink.units import LENGTH_UNITS as METRES

__all__ = [
    "LENGTH_UNITS",
    "MAX_CSV_ROWS",
    "MAX_POINTS",
    "MIN_RELATIVE_TOLERANCE",
    "Arc",
    "Hub",
    "angles_by_chord",
    "angles_by_step",
    "check_tolerance",
    "fit_arcs",
    "write_csv",
    "write_dxf",
    "write_svg",
]

Points: TypeAlias = NDArray[np.float64]

#: Finest chord or arc-fit tolerance, relative to the size of the curve
#: (its largest distance from the cam centre): about 80,000 points for a
#: closed profile at the limit (the core's bound, which design files
#: are held to).
MIN_RELATIVE_TOLERANCE: float = cam_design_limits()["min_relative_tolerance"]

#: Most rows of a CSV export (a step of at least 0.00036°).
MAX_CSV_ROWS: int = cam_design_limits()["max_csv_rows"]

#: Most points `angles_by_chord` gives (the core's
#: `camlink_cam::export::MAX_POINTS`).
MAX_POINTS: int = _core.cam_export_limits()["max_points"]

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
    at most `MAX_CSV_ROWS` of them (ValueError for a finer step). The
    core's `camlink_cam::export::angles_by_step`."""
    return np.asarray(_core.cam_angles_by_step(step))


def check_tolerance(core: CamCore, tolerance: float, offset: float = 0.0) -> None:
    """Raises ValueError when `tolerance` (m) is not positive or is finer
    than `MIN_RELATIVE_TOLERANCE` of the size of the curve `offset` (m)
    outside the cam surface (the core's
    `camlink_cam::export::check_tolerance`)."""
    _core.cam_check_tolerance(core, tolerance, offset)


def angles_by_chord(
    core: CamCore, tolerance: float, offset: float = 0.0
) -> NDArray[np.float64]:
    """Cam angles θ (rad) such that no curve point between two neighbours
    lies farther than `tolerance` (m) from their chord (checked at the
    middle and quarter points of every interval, halving where it fails;
    the core's `camlink_cam::export::chord_angles`). `tolerance` is at
    least `MIN_RELATIVE_TOLERANCE` of the curve's size
    (`check_tolerance`), which keeps the count below `MAX_POINTS`."""
    return np.asarray(_core.cam_angles_by_chord(core, tolerance, offset))


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


def fit_arcs(points: Points, tolerance: float, slack: float = 0.0) -> list[Arc]:
    """Lines and arcs (each arc through both ends of its run of points and
    its middle point) covering the closed polygon `points`, each run as
    long as every point and every edge of it stays within `tolerance` −
    `slack` (m) of its line or arc (the core's
    `camlink_cam::export::fit_arcs`). A curve that leaves each edge of the
    polygon by at most `slack` stays within `tolerance` of the pieces.
    Neighbouring pieces share their end points."""
    rows = _core.cam_fit_arcs(np.asarray(points, dtype=np.float64), tolerance, slack)
    return [
        Arc((c[0], c[1]), r, a0, a1, (p0[0], p0[1]), (p1[0], p1[1]))
        for c, r, a0, a1, p0, p1 in rows
    ]


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
        fine = _core.cam_angles_by_chord(core, 0.1 * tolerance, check=False)
        dense = np.asarray(core.surface(fine))
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
