"""Pictures of a cam design: the SVAJ diagram and the cam profile.

Both take a synthesised cam (``camlink._core.CamCore``), draw with
matplotlib (Agg) and return the figure; ``save`` writes a PNG. Titles are
shown literally (a ``$`` in a design's name is not mathtext).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection
from matplotlib.figure import Figure
from matplotlib.patches import Circle
from matplotlib.text import Text

from camlink._core import CamCore

__all__ = [
    "UNDERCUT_COLOUR",
    "core_ccw",
    "profile",
    "save",
    "svaj",
    "svaj_time",
    "vibration",
]

#: The colour undercut ranges are drawn in.
UNDERCUT_COLOUR = "#ff2d2d"

#: Unit vectors to a circle's leftmost, rightmost, lowest and highest points.
_COMPASS = np.array([[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0]])


def _literal(text: str) -> str:
    """`text` as matplotlib shows it literally: a ``$`` would start
    mathtext (and an unmatched one fails to draw)."""
    return text.replace("$", r"\$")


def svaj(
    core: CamCore,
    *,
    oscillating: bool = False,
    title: str = "",
    n: int = 1441,
    units: str = "m",
) -> Figure:
    """S, V, A, J against cam angle θ (deg), derivatives per radian of cam
    angle, with the segment boundaries marked by vertical lines; lengths in
    `units` ("m" or "mm")."""
    th = np.linspace(0.0, 2.0 * math.pi, n)
    m = np.asarray(core.motion(th))
    unit = "rad" if oscillating else units
    if not oscillating and units == "mm":
        m = m * 1000.0
    labels = [
        f"s ({unit})",
        f"v = s′ ({unit}/rad)",
        f"a = s″ ({unit}/rad²)",
        f"j = s‴ ({unit}/rad³)",
    ]
    fig, axes = plt.subplots(4, 1, sharex=True, figsize=(8, 9), layout="constrained")
    deg = np.degrees(th)
    for k, ax in enumerate(axes):
        ax.plot(deg, m[:, k], color="C0", lw=1.4)
        ax.axhline(0.0, color="0.6", lw=0.6)
        for b in core.starts():
            ax.axvline(math.degrees(b), color="C3", lw=0.8, ls="--")
        ax.set_ylabel(labels[k])
        ax.grid(True, lw=0.3)
    axes[-1].set_xlabel("cam angle θ (deg)")
    axes[-1].set_xlim(0.0, 360.0)
    axes[-1].set_xticks(np.arange(0, 361, 30))
    if title:
        axes[0].set_title(_literal(title))
    return fig


def svaj_time(
    core: CamCore,
    omega: float,
    *,
    oscillating: bool = False,
    title: str = "",
    n: int = 1441,
    units: str = "m",
) -> Figure:
    """S, V, A, J over one turn against time t = θ/ω (s) at cam speed
    `omega` (rad/s): s, ṡ = ω s′, s̈ = ω² s″, jerk ω³ s‴, in `units` ("m"
    or "mm"; an oscillating follower's swing in deg), with the segment
    boundaries as vertical lines."""
    th = np.linspace(0.0, 2.0 * math.pi, n)
    m = np.asarray(core.motion(th)) * omega ** np.arange(4)
    if oscillating:
        m = np.degrees(m)
        unit = "deg"
    else:
        unit = units
        m = m * (1000.0 if units == "mm" else 1.0)
    labels = [
        f"s ({unit})",
        f"v ({unit}/s)",
        f"a ({unit}/s²)",
        f"j ({unit}/s³)",
    ]
    t = th / omega
    fig, axes = plt.subplots(4, 1, sharex=True, figsize=(8, 9), layout="constrained")
    for k, ax in enumerate(axes):
        ax.plot(t, m[:, k], color="C0", lw=1.4)
        ax.axhline(0.0, color="0.6", lw=0.6)
        for b in core.starts():
            ax.axvline(b / omega, color="C3", lw=0.8, ls="--")
        ax.set_ylabel(labels[k])
        ax.grid(True, lw=0.3)
    axes[-1].set_xlabel(f"time t (s) at {omega * 60.0 / (2.0 * math.pi):g} rpm")
    axes[-1].set_xlim(0.0, 2.0 * math.pi / omega)
    if title:
        axes[0].set_title(_literal(title))
    return fig


def vibration(core: CamCore, design: Any, *, title: str = "") -> Figure:
    """The follower train of `design` ([vibration], [dynamics]) over the
    last turn computed: the last mass's deviation from its quasi-static
    position (top) and the dynamic contact force against the rigid
    train's (bottom), against cam angle θ (deg); lengths in the design's
    export units."""
    d, v = design.dynamics, design.vibration
    r = core.vibration(
        list(v.masses), list(v.stiffness), list(v.damping), d.spring_rate, d.preload, d.speed,
        v.steps, v.turns, False,
    )
    th = np.asarray(r["theta"])
    deg = np.degrees(th)
    osc = design.oscillating
    k = 1.0 if osc else (1000.0 if design.export.units == "mm" else 1.0)
    unit = "rad" if osc else design.export.units
    rigid = np.asarray(core.force((d.mass, d.spring_rate, d.preload, d.damping), d.speed)["generalised"])
    rth = np.linspace(0.0, 360.0, len(rigid), endpoint=False)
    fig, axes = plt.subplots(2, 1, sharex=True, figsize=(8, 6), layout="constrained")
    axes[0].plot(deg, np.asarray(r["deviation"]) * k, color="C0", lw=1.2)
    axes[0].set_ylabel(f"deviation ({unit})")
    axes[1].plot(deg, np.asarray(r["contact"]), color="C0", lw=1.2, label="dynamic")
    axes[1].plot(rth, rigid, color="C1", lw=1.0, ls="--", label="rigid train")
    axes[1].axhline(0.0, color="C3", lw=0.8)
    axes[1].set_ylabel("N·m" if osc else "contact force (N)")
    axes[1].legend(loc="best", fontsize=8)
    for ax in axes:
        for b in core.starts():
            ax.axvline(math.degrees(b), color="0.6", lw=0.8, ls=":")
        ax.grid(True, lw=0.3)
    axes[-1].set_xlabel("cam angle θ (deg)")
    axes[-1].set_xlim(0.0, 360.0)
    axes[-1].set_xticks(np.arange(0, 361, 30))
    if title:
        axes[0].set_title(_literal(title))
    return fig


def profile(
    core: CamCore,
    *,
    base_radius: float,
    colour_by: str = "pressure_angle",
    followers: int = 4,
    title: str = "",
    n: int = 1441,
) -> Figure:
    """The cam in its own frame (m): the surface coloured by pressure angle
    (deg) or radius of curvature (m), the base circle (dashed), a roller's
    pitch curve (dotted), the undercut ranges over the surface in
    `UNDERCUT_COLOUR`, and the follower drawn at `followers` cam angles
    (where it touches the cam when the cam has turned by that angle), each
    labelled with that angle. The frame holds all of them."""
    th = np.linspace(0.0, 2.0 * math.pi, n)
    surf = np.asarray(core.surface(th))
    c = core.contact(th)
    if colour_by == "pressure_angle":
        values = np.degrees(np.asarray(c["pressure_angle"]))
        label = "pressure angle φ (deg)"
    else:
        values = np.clip(np.asarray(c["rho"]), -10 * base_radius, 10 * base_radius)
        label = "radius of curvature ρ (m)"
    fig, ax = plt.subplots(figsize=(7, 7), layout="constrained")
    seg = np.stack([surf[:-1], surf[1:]], axis=1)
    lc = LineCollection(
        list(seg),
        array=0.5 * (values[:-1] + values[1:]),
        cmap="viridis",
        linewidths=2.5,
    )
    ax.add_collection(lc)
    fig.colorbar(lc, ax=ax, label=label, shrink=0.8)
    ax.add_patch(
        Circle((0.0, 0.0), base_radius, fill=False, ls="--", color="0.5", lw=0.8)
    )
    pitch = core.pitch(th)
    if pitch is not None:
        p = np.asarray(pitch)
        ax.plot(p[:, 0], p[:, 1], ls=":", color="C1", lw=1.0, label="pitch curve")
    ax.plot([0.0], [0.0], "k+", ms=10)
    # Undercut ranges, over the surface in a highlight colour.
    for k, (a, b) in enumerate(core.geometry()["undercut"]):
        end = b if b > a else b + 2.0 * math.pi
        span = np.linspace(a, end, max(2, int(n * (end - a) / (2.0 * math.pi)) + 2))
        u = np.asarray(core.surface(span))
        ax.plot(
            u[:, 0], u[:, 1], color=UNDERCUT_COLOUR, lw=6.0, alpha=0.6,
            solid_capstyle="round", label="undercut" if k == 0 else None, gid="undercut",
        )
    # What the frame holds: the surface, the base circle, the pitch curve,
    # the followers (and their labels, by `_fit`).
    reach = [surf, base_radius * _COMPASS]
    if pitch is not None:
        reach.append(p)
    # The follower at a few cam angles, drawn in the cam frame, each
    # labelled with its cam angle beyond its outer side.
    ts = np.linspace(0.0, 2.0 * math.pi, followers, endpoint=False)
    outer = []  # (where the follower reaches farthest out, the outward direction)
    if pitch is not None:
        pts = np.asarray(core.pitch(ts))
        roller = float(np.linalg.norm(pts[0] - np.asarray(core.surface(ts[:1]))[0]))
        for q in pts:
            ax.add_patch(
                Circle((q[0], q[1]), roller, fill=False, color="C3", lw=1.0, gid="follower")
            )
            out = q / max(float(np.linalg.norm(q)), 1e-300)
            reach.append(np.array([q + roller * d for d in _COMPASS]))
            outer.append((q + roller * out, out))
    else:
        cc = core.contact(ts)
        pts = np.asarray(core.surface(ts))
        for t, q, nrm in zip(ts, pts, np.asarray(cc["normal"]), strict=True):
            # The face's direction in the cam frame: the ground normal turned back.
            a = -float(t) if core_ccw(core) else float(t)
            ca, sa = math.cos(a), math.sin(a)
            nn = np.array([ca * nrm[0] - sa * nrm[1], sa * nrm[0] + ca * nrm[1]])
            d = np.array([-nn[1], nn[0]]) * 0.6 * base_radius
            ends = np.array([q - d, q + d])
            ax.plot(ends[:, 0], ends[:, 1], color="C3", lw=1.2, gid="follower")
            reach.append(ends)
            out = q / max(float(np.linalg.norm(q)), 1e-300)
            outer.append((q, out))
    r = float(np.max(np.abs(np.concatenate(reach))))
    gap = 0.06 * r
    labels = []
    for t, (q, out) in zip(ts, outer, strict=True):
        at = q + gap * out
        labels.append(
            ax.annotate(
                f"θ = {math.degrees(float(t)):.0f}°",
                (float(at[0]), float(at[1])),
                ha="left" if out[0] > 0.3 else "right" if out[0] < -0.3 else "center",
                va="bottom" if out[1] > 0.3 else "top" if out[1] < -0.3 else "center",
                fontsize=8,
                color="C3",
                gid="follower label",
            )
        )
    ax.set_aspect("equal")
    if pitch is not None or core.geometry()["undercut"]:
        fig.legend(loc="outside lower center", ncols=2, fontsize=8, frameon=False)
    ax.set_xlabel("x (m, cam frame)")
    ax.set_ylabel("y (m, cam frame)")
    ax.grid(True, lw=0.3)
    if title:
        ax.set_title(_literal(title))
    _fit(fig, ax, 1.08 * r, labels)
    return fig


def _fit(fig: Figure, ax: Axes, half: float, texts: Sequence[Text]) -> None:
    """Square limits ±`half` (m) or wider, so that the `texts` lie inside
    the axes too: the text keeps its size in points while the limits
    change, so a few rounds of layout and measuring settle."""
    for _ in range(4):
        ax.set_xlim(-half, half)
        ax.set_ylim(-half, half)
        fig.draw_without_rendering()
        renderer = fig.canvas.get_renderer()  # type: ignore[attr-defined]
        to_data = ax.transData.inverted()
        need = half
        for text in texts:
            box = text.get_window_extent(renderer)
            corners = to_data.transform([[box.x0, box.y0], [box.x1, box.y1]])
            need = max(need, float(np.max(np.abs(corners))))
        if need <= half:
            return
        half = 1.02 * need


def core_ccw(core: CamCore) -> bool:
    """True when the cam turns counterclockwise: its pitch or surface runs
    clockwise in the cam frame (the signed area is negative)."""
    th = np.linspace(0.0, 2.0 * math.pi, 361)
    p = np.asarray(core.surface(th))
    area = 0.5 * float(np.sum(p[:-1, 0] * p[1:, 1] - p[1:, 0] * p[:-1, 1]))
    return area < 0


def save(fig: Figure, path: str | Path, dpi: int = 120) -> None:
    """Writes the figure as PNG and closes it."""
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
