"""The atlas of a path-generation (or cognates) result: each candidate's
coupler curve against the target points, one panel per candidate.

The curves and the numbers are the report's (computed in Rust); this module
draws them with matplotlib (Agg)::

    from camlink import synth
    from camlink.synth import atlas as synth_atlas
    result = synth.solve("examples/synthesis_path.toml")
    fig = synth_atlas.atlas(result)
    synth_atlas.save(fig, "atlas.png")

Lengths are drawn in mm.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")

from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from camlink._core import ModelError
from camlink.synth import Synthesis

__all__ = ["CURVE_COLOUR", "TARGET_COLOUR", "atlas", "curve_mm", "save"]

#: Marker colour of the target points and line colour of the coupler curves.
TARGET_COLOUR = "#d62728"
CURVE_COLOUR = "#1f77b4"
MM = 1000.0


def curve_mm(report: Any) -> tuple[list[float], list[float]]:
    """The report's coupler curve in mm, NaN where the linkage does not
    assemble (so the line breaks there)."""
    xs: list[float] = []
    ys: list[float] = []
    for p in report.get("curve", ()):
        if p is None:
            xs.append(math.nan)
            ys.append(math.nan)
        else:
            xs.append(p[0] * MM)
            ys.append(p[1] * MM)
    return xs, ys


def atlas(result: Synthesis, columns: int = 3) -> Figure:
    """One panel per solution: its coupler curve (blue), the targets (red
    dots, when the problem has them), the ground pivots (black triangles)
    where they fall in the frame, titled with the name, the RMS distance and
    the defects. Each panel is framed on its curve and targets."""
    with_curves = [s for s in result.solutions if "curve" in s.report]
    if not with_curves:
        raise ModelError(
            f"a {result.kind} problem has no coupler curves to draw; the atlas is for "
            "path and cognates problems"
        )
    n = len(with_curves)
    cols = min(columns, n)
    rows = math.ceil(n / cols)
    fig = Figure(figsize=(4.2 * cols, 4.0 * rows), layout="constrained")
    FigureCanvasAgg(fig)
    for k, s in enumerate(with_curves):
        ax = fig.add_subplot(rows, cols, k + 1)
        r = s.report
        xs, ys = curve_mm(r)
        ax.plot(xs, ys, color=CURVE_COLOUR, lw=1.5, label="coupler curve")
        if "targets" in r:
            tx = [p[0] * MM for p in r["targets"]]
            ty = [p[1] * MM for p in r["targets"]]
            ax.plot(tx, ty, "o", color=TARGET_COLOUR, ms=3.5, label="targets", zorder=3)
        # The ground pivots (a slider-crank has no rocker pivot).
        pivots = [p for p in (s.links.o2, s.links.o4) if p is not None]
        ax.plot([p[0] * MM for p in pivots], [p[1] * MM for p in pivots], "^", color="black", ms=7)
        title = s.name
        if "error" in r:
            title += f"\nRMS {r['error']['rms'] * MM:.3g} mm, {s.grashof}"
        else:
            title += f"\n{s.grashof}"
        title += "; " + (", ".join(d.kind for d in s.defects) if s.defects else "no defects")
        ax.set_title(title, fontsize=9)
        # Framed on the curve and the targets; pivots outside are left out.
        fx = [v for v in xs if not math.isnan(v)] + [p[0] * MM for p in r.get("targets", ())]
        fy = [v for v in ys if not math.isnan(v)] + [p[1] * MM for p in r.get("targets", ())]
        if fx:
            half = 0.6 * max(max(fx) - min(fx), max(fy) - min(fy), 1e-9)
            cx, cy = 0.5 * (max(fx) + min(fx)), 0.5 * (max(fy) + min(fy))
            ax.set_xlim(cx - half, cx + half)
            ax.set_ylim(cy - half, cy + half)
        ax.set_aspect("equal", adjustable="box")
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm)")
        ax.grid(True, lw=0.3)
    return fig


def save(fig: Figure, path: str | Path, dpi: int = 110) -> None:
    """Writes `fig` as a PNG."""
    fig.savefig(path, dpi=dpi)
