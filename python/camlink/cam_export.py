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
from typing import TypeAlias

import ezdxf
import numpy as np
from numpy.typing import NDArray

from camlink._core import CamCore

Points: TypeAlias = NDArray[np.float64]


def angles_by_step(step: float) -> NDArray[np.float64]:
    """Cam angles θ (rad) over one turn at `step` (rad), the end excluded."""
    n = max(3, math.ceil(2.0 * math.pi / step - 1e-9))
    return np.linspace(0.0, 2.0 * math.pi, n, endpoint=False)


def angles_by_chord(
    core: CamCore, tolerance: float, offset: float = 0.0
) -> NDArray[np.float64]:
    """Cam angles θ (rad) such that no curve point between two neighbours
    lies farther than `tolerance` (m) from their chord (checked at the
    middle and quarter points of every interval, halving where it fails)."""
    th = list(np.linspace(0.0, 2.0 * math.pi, 73))
    out = [th[0]]
    stack = [(th[i], th[i + 1]) for i in range(len(th) - 2, -1, -1)]
    while stack:
        a, b = stack.pop()
        probe = np.array([a, b, 0.25 * (3 * a + b), 0.5 * (a + b), 0.25 * (a + 3 * b)])
        p = np.asarray(core.surface(probe, offset))
        d = p[1] - p[0]
        ln = float(np.hypot(d[0], d[1]))
        dev = 0.0
        for q in p[2:]:
            r = q - p[0]
            dev = max(
                dev,
                abs(float(d[0] * r[1] - d[1] * r[0])) / ln
                if ln > 0
                else float(np.hypot(*r)),
            )
        if dev > tolerance and b - a > 1e-9:
            m = 0.5 * (a + b)
            stack.append((m, b))
            stack.append((a, m))
        else:
            out.append(b)
    return np.array(out[:-1])


def write_csv(
    core: CamCore,
    path: str | Path,
    theta: NDArray[np.float64],
    tool_radius: float | None = None,
) -> None:
    """Writes θ (deg), the surface x, y (m) and, for a roller, the pitch
    curve; with `tool_radius`, the tool centre path too."""
    surf = np.asarray(core.surface(theta))
    cols = [np.degrees(theta), surf[:, 0], surf[:, 1]]
    head = ["theta_deg", "x", "y"]
    pitch = core.pitch(theta)
    if pitch is not None:
        p = np.asarray(pitch)
        cols += [p[:, 0], p[:, 1]]
        head += ["pitch_x", "pitch_y"]
    if tool_radius is not None:
        t = np.asarray(core.surface(theta, tool_radius))
        cols += [t[:, 0], t[:, 1]]
        head += ["tool_x", "tool_y"]
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


def fit_arcs(points: Points, tolerance: float) -> list[Arc]:
    """Arcs (through both ends of each run and its middle point) covering
    the closed polygon `points`, each run as long as every point of it
    stays within `tolerance` (m) of its arc. Neighbouring arcs share their
    end points."""
    n = len(points)
    pts = np.vstack([points, points[:1]])
    arcs: list[Arc] = []
    i = 0
    while i < n:
        best = i + 1
        j = i + 2
        while j <= n:
            run = pts[i : j + 1]
            c = _circle(run[0], run[len(run) // 2], run[-1])
            if c is None:
                ok = True
            else:
                centre, r = c
                ok = r < 1e6 * tolerance and bool(
                    np.all(
                        np.abs(np.linalg.norm(run - centre, axis=1) - r) <= tolerance
                    )
                )
            if not ok:
                break
            best = j
            j += 1
        run = pts[i : best + 1]
        c = _circle(run[0], run[len(run) // 2], run[-1]) if len(run) >= 3 else None
        p0 = (float(run[0][0]), float(run[0][1]))
        p1 = (float(run[-1][0]), float(run[-1][1]))
        if c is None or c[1] >= 1e6 * tolerance:
            arcs.append(Arc((math.nan, math.nan), math.inf, 0.0, 0.0, p0, p1))
        else:
            centre, r = c
            a0 = math.degrees(math.atan2(run[0][1] - centre[1], run[0][0] - centre[0]))
            a1 = math.degrees(
                math.atan2(run[-1][1] - centre[1], run[-1][0] - centre[0])
            )
            mid = run[len(run) // 2]
            # Orientation of the run: ezdxf arcs run counterclockwise.
            cross = (mid[0] - run[0][0]) * (run[-1][1] - run[0][1]) - (
                mid[1] - run[0][1]
            ) * (run[-1][0] - run[0][0])
            if cross < 0:  # clockwise run: swap ends
                a0, a1 = a1, a0
            arcs.append(Arc((float(centre[0]), float(centre[1])), r, a0, a1, p0, p1))
        i = best
    return arcs


def write_dxf(
    core: CamCore,
    path: str | Path,
    tolerance: float,
    mode: str = "polyline",
    tool_radius: float | None = None,
) -> int:
    """Writes the cam surface (layer CAM) as a closed polyline within the
    chord `tolerance` or as fitted arcs, and with `tool_radius` the tool
    centre path (layer TOOL); returns the number of entities on CAM."""
    doc = ezdxf.new("R2010", units=6)  # 6: metres
    msp = doc.modelspace()
    doc.layers.add("CAM", color=7)
    th = angles_by_chord(core, tolerance)
    pts = np.asarray(core.surface(th))
    count = 0
    if mode == "arcs":
        dense = np.asarray(core.surface(angles_by_chord(core, 0.1 * tolerance)))
        for a in fit_arcs(dense, tolerance):
            if math.isinf(a.radius):
                msp.add_line(a.p0, a.p1, dxfattribs={"layer": "CAM"})
            else:
                msp.add_arc(
                    a.centre, a.radius, a.start, a.end, dxfattribs={"layer": "CAM"}
                )
            count += 1
    else:
        msp.add_lwpolyline(
            [tuple(p) for p in pts], close=True, dxfattribs={"layer": "CAM"}
        )
        count = 1
    if tool_radius is not None:
        doc.layers.add("TOOL", color=1)
        tp = np.asarray(
            core.surface(angles_by_chord(core, tolerance, tool_radius), tool_radius)
        )
        msp.add_lwpolyline(
            [tuple(p) for p in tp], close=True, dxfattribs={"layer": "TOOL"}
        )
    doc.saveas(path)
    return count


def write_svg(
    core: CamCore, path: str | Path, tolerance: float, tool_radius: float | None = None
) -> None:
    """Writes the cam surface as one closed SVG path, in millimetres, y up
    (the drawing's y axis is flipped), centre marked."""
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
    out += ["</g>", "</svg>", ""]
    Path(path).write_text("\n".join(out))
