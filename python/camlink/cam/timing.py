"""Timing diagrams and servo cam tables: the cams of one machine on one
master angle.

A timing file (TOML, see docs/cam-design.md, *Timing diagram and servo cam
tables*) names the machine's cams — each a cam design file with its phase
on the master angle — the positions of their followers in the machine, and
the least distances between followers. ``camlink cam TIMING.toml`` checks
the clearances over a master turn, draws the timing diagram and writes a
cam table for each axis for a servo drive: master angle against position,
velocity and acceleration at the machine's speed, plus a table of each
segment's extreme points and continuity class.

The file is read and checked in Rust (``camlink_cam::timing``, through
``camlink._core.cam_timing_read``): its rules, defaults and bounds are
there, with messages naming the file, line and field, and so are the
axes' motion, the clearances and the cam tables. This module presents
them: the diagram, the files and the report.

Axis k at master angle Θ runs its own program at θ = Θ − φ_k (φ_k its
phase); its follower's tip is at O_k + s_k(θ) (cos α_k, sin α_k) in the
machine's plane (O_k its ``origin``, α_k its ``direction_deg``).
"""

from __future__ import annotations

import csv
import math
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from camlink import _core
from camlink._core import ModelError, TimingCore
from camlink.cam import design as cam_design
from camlink.cam.design import CamDesignError
from camlink.units import LENGTH_UNITS as METRES
from camlink.warn import LoadWarning

__all__ = [
    "RPM",
    "Axis",
    "Clearance",
    "ClearanceReport",
    "Timing",
    "clearances",
    "diagram",
    "format_report",
    "is_timing",
    "load",
    "motion",
    "outputs",
    "segment_rows",
    "table_rows",
    "tip",
    "write",
]

RPM = cam_design.RPM

# METRES: metres per length unit; the core allows a timing file's `units`
# only among camlink_cam::timing::UNITS.


@dataclass(frozen=True)
class Axis:
    """One axis of a timing file, as read (see `Timing`: the analyses read
    `core`, not these fields)."""

    name: str
    design: cam_design.Design
    phase: float
    """Phase φ (rad) on the master angle."""
    origin: tuple[float, float]
    """The follower's tip at s = 0 (m)."""
    direction: float
    """Direction α (rad) in which s moves the tip."""
    index: int
    """Its place in the timing file's ``[[axes]]``."""
    core: TimingCore = field(repr=False, compare=False)
    """The checked timing file in the Rust core."""


@dataclass(frozen=True)
class Clearance:
    a: str
    b: str
    min_distance: float
    """m"""


@dataclass(frozen=True)
class Timing:
    """A timing file as the core read and checked it. The analyses
    (`motion`, `tip`, `clearances`, `table_rows`, `segment_rows`) read the
    file from `core`; these fields are what it holds, for display: a copy
    with other values (`dataclasses.replace`) is analysed as the file was
    read. To analyse other values, write them into the file and `load`
    it."""

    path: Path
    name: str
    speed: float
    """Machine speed (rad/s of the master)."""
    resolution: float
    """Master angle step of the cam tables (rad)."""
    units: str
    axes: tuple[Axis, ...]
    clearances: tuple[Clearance, ...]
    diagram: str | None
    tables: bool
    core: TimingCore = field(repr=False, compare=False)
    """The checked timing file in the Rust core."""


def is_timing(path: str | Path) -> bool:
    """True for a timing file (TOML with ``[[axes]]``)."""
    return _core.cam_is_timing(Path(path))


def load(path: str | Path) -> Timing:
    """Reads and checks a timing file and its cam design files (in the
    core, `camlink_cam::timing`); raises CamDesignError naming the file,
    line and field."""
    p = Path(path)
    try:
        core, d, notes = _core.cam_timing_read(p)
    except ModelError as e:
        raise CamDesignError(str(e)) from None
    for note in notes:
        warnings.warn(LoadWarning(note), stacklevel=2)
    axes = tuple(
        Axis(
            a["name"],
            cam_design._design(a["design"], Path(a["design_path"])),
            a["phase"],
            (a["origin"][0], a["origin"][1]),
            a["direction"],
            k,
            core,
        )
        for k, a in enumerate(d["axes"])
    )
    return Timing(
        p,
        d["name"],
        d["speed"],
        d["resolution"],
        d["units"],
        axes,
        tuple(Clearance(axes[a].name, axes[b].name, m) for a, b, m in d["clearances"]),
        d["diagram"],
        d["tables"],
        core,
    )


def motion(axis: Axis, master: NDArray[np.float64]) -> NDArray[np.float64]:
    """[s, s′, s″, s‴] of `axis` at master angles Θ (rad): its program at
    Θ − φ, derivatives per radian of the master."""
    return np.asarray(axis.core.motion(axis.index, np.asarray(master, dtype=np.float64)))


def tip(axis: Axis, s: NDArray[np.float64]) -> NDArray[np.float64]:
    """The follower's tip (m) for displacements s: (n, 2)."""
    return np.asarray(axis.core.tips(axis.index, np.asarray(s, dtype=np.float64)))


@dataclass(frozen=True)
class ClearanceReport:
    a: str
    b: str
    least: float
    """Least tip distance over a master turn (m)."""
    at_deg: float
    limit: float
    ok: bool


def clearances(t: Timing) -> list[ClearanceReport]:
    """The least distance between each pair of followers' tips over a
    master turn (the core's `Timing::clearances`: sampled at
    `camlink_cam::timing::SAMPLES` angles, the least refined by a parabola
    through it and its neighbours)."""
    names = [a.name for a in t.axes]
    return [
        ClearanceReport(names[a], names[b], least, at, limit, ok)
        for a, b, least, at, limit, ok in t.core.clearances()
    ]


def table_rows(t: Timing, axis: Axis) -> NDArray[np.float64]:
    """The cam table of `axis`: rows [master deg, position, velocity,
    acceleration, jerk] in the timing file's length unit and seconds at
    the machine speed, every `resolution` of the file over a turn, both
    ends included."""
    return np.asarray(t.core.table(axis.index, t.units))


def segment_rows(t: Timing, axis: Axis) -> list[dict[str, Any]]:
    """Each segment of `axis` on the master angle: start and end (deg),
    law, lift, the continuity class (C0…C3) at its start and end, and its
    extreme velocity and acceleration at the machine speed with the master
    angles where they occur (the core's `Timing::segments`)."""
    return list(t.core.segments(axis.index, t.units))


def diagram(t: Timing, report: list[ClearanceReport] | None = None) -> Any:
    """The timing diagram: one row per axis (displacement over the master
    angle, its segment boundaries as dotted lines) and, with clearances, a
    row of the tip distances against their limits."""
    import matplotlib.pyplot as plt

    rows = len(t.axes) + (1 if t.clearances else 0)
    fig, axs = plt.subplots(rows, 1, sharex=True, figsize=(8.0, 1.6 * rows + 0.8), squeeze=False)
    master = np.linspace(0.0, 2.0 * math.pi, 3601)
    deg = np.degrees(master)
    unit = t.units
    for ax, axis in zip(axs[:, 0], t.axes, strict=False):
        s = motion(axis, master)[:, 0]
        if axis.design.oscillating:
            ax.plot(deg, np.degrees(s), color="C0", lw=1.5)
            ax.set_ylabel(f"{axis.name}\n(deg)")
        else:
            ax.plot(deg, s / METRES[unit], color="C0", lw=1.5)
            ax.set_ylabel(f"{axis.name}\n({unit})")
        for st in axis.design.core().starts():
            ax.axvline(math.degrees(st + axis.phase) % 360.0, color="0.6", lw=0.8, ls=":")
        ax.grid(True, alpha=0.3)
    if t.clearances:
        ax = axs[-1, 0]
        by = {a.name: a for a in t.axes}
        for i, c in enumerate(t.clearances):
            pa = tip(by[c.a], motion(by[c.a], master)[:, 0])
            pb = tip(by[c.b], motion(by[c.b], master)[:, 0])
            d = np.hypot(*(pa - pb).T) / METRES[unit]
            ax.plot(deg, d, color=f"C{i + 1}", lw=1.5, label=f"{c.a}–{c.b}")
            ax.axhline(c.min_distance / METRES[unit], color=f"C{i + 1}", lw=1.0, ls="--")
        ax.set_ylabel(f"clearance\n({unit})")
        ax.legend(loc="best", fontsize=8)
        ax.grid(True, alpha=0.3)
    axs[-1, 0].set_xlabel("master angle (deg)")
    axs[-1, 0].set_xlim(0.0, 360.0)
    axs[-1, 0].set_xticks(np.arange(0, 361, 45))
    fig.suptitle(f"{t.name}: timing at {t.speed / RPM:g} rpm")
    fig.tight_layout()
    return fig


def outputs(t: Timing, out: Path) -> list[Path]:
    """The files `write` writes into `out`: the diagram, then each axis's
    cam table and segment table."""
    paths = [] if t.diagram is None else [out / t.diagram]
    if t.tables:
        for axis in t.axes:
            paths += [out / f"{t.path.stem}_{axis.name}.csv", out / f"{t.path.stem}_{axis.name}_segments.csv"]
    return paths


def write(t: Timing, out: Path, report: list[ClearanceReport], force: bool = False) -> list[str]:
    """Writes the diagram and the cam tables into `out`; the paths. None is
    the timing file or an axis's design file (nor a link to one), and none
    that exists is replaced unless `force`; each is written to a temporary
    name and renamed."""
    from camlink.cam import plots as cam_plots
    from camlink.io.output import check_not_input, replacing

    targets = outputs(t, out)
    inputs = [t.path, *(a.design.path for a in t.axes)]
    try:
        for path in targets:
            check_not_input(path, inputs)
    except ModelError as e:
        raise CamDesignError(str(e)) from None
    existing = [str(p) for p in targets if p.exists()]
    if existing and not force:
        raise CamDesignError(
            f"{', '.join(existing)} {'exists' if len(existing) == 1 else 'exist'}; pass --force "
            "to replace, or choose another --out"
        )
    out.mkdir(parents=True, exist_ok=True)
    written = []
    if t.diagram is not None:
        path = out / t.diagram
        with replacing(path) as temp:
            cam_plots.save(diagram(t, report), temp)
        written.append(str(path))
    if t.tables:
        u = t.units
        for axis in t.axes:
            lu = "rad" if axis.design.oscillating else u
            path = out / f"{t.path.stem}_{axis.name}.csv"
            rows = table_rows(t, axis)
            with replacing(path) as temp, open(temp, "w", newline="") as f:
                w = csv.writer(f)
                w.writerow(
                    [
                        "master_deg",
                        f"position_{lu}",
                        f"velocity_{lu}_per_s",
                        f"acceleration_{lu}_per_s2",
                        f"jerk_{lu}_per_s3",
                    ]
                )
                for r in rows:
                    w.writerow([repr(float(x)) for x in r])
            written.append(str(path))
            path = out / f"{t.path.stem}_{axis.name}_segments.csv"
            segs = segment_rows(t, axis)
            with replacing(path) as temp, open(temp, "w", newline="") as f:
                dw = csv.DictWriter(f, fieldnames=list(segs[0]))
                dw.writeheader()
                dw.writerows(segs)
            written.append(str(path))
    return written


def format_report(t: Timing, report: list[ClearanceReport], files: list[str]) -> str:
    lines = [f"timing '{t.name}': {len(t.axes)} axes at {t.speed / RPM:g} rpm", ""]
    for a in t.axes:
        lines.append(
            f"  {a.name}: {a.design.path.name}, phase {math.degrees(a.phase):g}°, "
            f"{a.design.follower}"
        )
    if report:
        lines.append("")
        lines.append("clearances:")
    scale = METRES[t.units]
    for c in report:
        mark = "ok  " if c.ok else "FAIL"
        lines.append(
            f"  {mark} {c.a}–{c.b}: least {c.least / scale:.6g} {t.units} at {c.at_deg:.2f}° "
            f"(limit {c.limit / scale:.6g} {t.units}, margin {(c.least - c.limit) / scale:.6g})"
        )
    for f in files:
        lines.append(f"wrote {f}")
    lines.append("")
    lines.append("all clearances hold" if all(c.ok for c in report) else "some clearances fail")
    return "\n".join(lines)
