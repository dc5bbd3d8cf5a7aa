"""Follower jump: unilateral cam contacts seen from Python.

- `jump_plot`: the follower's lift against the cam angle with the flights
  shaded and the landings marked;
- `flight_summary`: the one-line summary of the flights and impacts the CLI
  prints;
- `jump_speed`: the lowest cam speed at which the follower leaves the cam
  in forward dynamics, beside the inverse dynamics' prediction.

The mechanics (gap, events, impact) are in the Rust core
(`docs/dynamics.md`, "Unilateral contacts"); this module converts and shows.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from camlink._core import ModelError
from camlink.results import Results
from camlink.warn import LiftOffWarning

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from camlink.model import Model
    from camlink.records import JointRecord

__all__ = ["JumpSpeed", "flight_summary", "jump_plot", "jump_speed"]


def jump_plot(results: Results, joint: str | None = None, *, width: float = 6.4) -> Figure:
    """The lift of the follower of cam contact `joint` (default: the first)
    against the cam angle θ (deg), with every simulated flight shaded and
    every landing marked (a dot at the located impact's cam angle and lift),
    and, dashed, the lift less the gap (``<joint>.gap``): where the follower
    would be on its cam, exact for a flat face square to the guide.
    """
    from matplotlib.figure import Figure

    from camlink.viz.plots import _axes, svaj_data

    d = svaj_data(results, joint)
    flights = results.lift_off
    flights = flights[(flights["joint"] == d.joint) & flights["greatest_gap"].notna()]
    impacts = results.impacts
    impacts = impacts[impacts["joint"] == d.joint]
    fig = Figure(figsize=(width, 3.4), dpi=100, layout="constrained")
    (ax,) = _axes(fig)
    scale, unit = (1e3, "mm") if d.units[0] == "m" else (1.0, d.units[0])
    ax.plot(d.angle, scale * d.s, linewidth=1.3, color="#1f4e79", gid=f"lift:{d.joint}",
            label="lift")
    gap = f"{d.joint}.gap"
    if gap in results and d.units[0] == "m":
        # Where the follower would be on the cam: its lift less the gap
        # (exact for a face square to the guide, where the gap is along it).
        ax.plot(d.angle, scale * (d.s - results[gap]), linewidth=0.9, linestyle="--",
                color="#555555", gid=f"cam:{d.joint}", label="lift − gap")
    # θ (deg) of a cam angle φ (rad) in the unwrapped scale of `d.angle`.
    phi0 = math.radians(float(d.angle[0]))
    for _, f in flights.iterrows():
        end = f["end_cam_angle"] if not math.isnan(f["end_cam_angle"]) else math.radians(
            float(d.angle[-1])
        )
        ax.axvspan(
            math.degrees(f["start_cam_angle"] - phi0) + float(d.angle[0]),
            math.degrees(end - phi0) + float(d.angle[0]),
            color="#f4a261",
            alpha=0.3,
            linewidth=0,
            gid="flight",
        )
    if len(impacts):
        theta = np.degrees(impacts["cam_angle"].to_numpy() - phi0) + float(d.angle[0])
        lift = np.interp(impacts["time"].to_numpy(), results.t, scale * d.s)
        ax.plot(theta, lift, "o", color="#c0392b", markersize=4, gid="landing", label="landing")
    ax.legend(fontsize=8, frameon=False, loc="upper right")
    ax.set_xlim(float(d.angle[0]), float(d.angle[-1]))
    ax.set_xlabel("cam angle θ (deg)", fontsize=9)
    ax.set_ylabel(f"lift ({unit})", fontsize=9)
    ax.set_title(f"{d.joint}: lift, flights shaded, landings marked", fontsize=10)
    return fig


def flight_summary(
    results: Results, joints: Sequence[JointRecord] | None = None
) -> str | None:
    """One line on the flights and impacts of the unilateral contacts and
    joint stops, or None when there were none: per joint, the number of
    flights and their greatest gap (mm), the number of impacts and the
    fastest approach (m/s; rad/s on a revolute's stop, whose gap is an
    angle), and when the follower came to rest on its cam
    or the joint on its stop."""
    flights = results.lift_off
    flights = flights[flights["greatest_gap"].notna()]
    impacts = results.impacts
    if flights.empty and impacts.empty:
        return None
    parts = []
    for joint in dict.fromkeys([*flights["joint"], *impacts["joint"]]):
        f = flights[flights["joint"] == joint]
        i = impacts[impacts["joint"] == joint]
        # A joint stop (`<joint>.lower`, `.upper`) has impacts, no flights.
        stop = joint.rpartition(".")[2] in ("lower", "upper")
        if stop:
            text = f"{joint}: {len(i)} impact{'s' * (len(i) != 1)}"
        else:
            text = f"{joint}: {len(f)} flight{'s' * (len(f) != 1)}"
            if len(f):
                text += f" (greatest gap {1e3 * f['greatest_gap'].max():.4g} mm)"
            text += f", {len(i)} impact{'s' * (len(i) != 1)}"
        if len(i):
            angle = results.quantities.get(f"{joint}.gap") == "angle"
            speed = "rad/s" if angle else "m/s"
            text += f" (fastest approach {i['approach_speed'].max():.4g} {speed})"
            closed = i[i["closed"]]
            if len(closed):
                rest = "on its stop" if stop else "on the cam again"
                text += f", {rest} from t = {closed['time'].iloc[-1]:.6g} s"
        parts.append(text)
    return "; ".join(parts)


@dataclass(frozen=True)
class JumpSpeed:
    """The result of `jump_speed`.

    `speeds` are the values tried (the parameter's unit, e.g. rpm), in
    increasing order; `flies[k]` is True when the follower left the cam in
    forward dynamics at `speeds[k]`; `forward` the lowest speed tried at
    which it did (None: at none); `inverse` the lowest speed tried at which
    the inverse dynamics of the bilateral model reports a negative normal
    force (None: at none).
    """

    joint: str
    speeds: tuple[float, ...]
    flies: tuple[bool, ...]
    forward: float | None
    inverse: float | None


def jump_speed(
    model: Model,
    joint: str,
    speeds: Sequence[float],
    *,
    parameter: str = "rpm",
    t_end: float | None = None,
) -> JumpSpeed:
    """The lowest of `speeds` at which the follower of unilateral contact
    `joint` leaves its cam in forward dynamics, beside the lowest at which
    the inverse dynamics (the contact held) reports a negative normal
    force.

    `model` is any model whose ``[parameters]`` table sets `parameter`
    (the cam speed, e.g. ``rpm = 6000``); each speed is one variant,
    `model.with_parameters(parameter=speed)`, resolved again in Rust.
    `t_end` overrides the runs' length (s). The inverse dynamics needs a
    driven cam (zero degrees of freedom).
    """
    if parameter not in model.parameters:
        raise ModelError(
            f"{model.source or model.name}: no parameter {parameter!r} to vary "
            f"(the [parameters] table has {', '.join(model.parameters) or 'none'})"
        )
    if joint not in {j["name"] for j in model.joints}:
        raise ModelError(f"{model.source or model.name}: no joint named {joint!r}")
    order = sorted(float(s) for s in speeds)
    if not order:
        raise ModelError("jump_speed needs at least one speed")
    flies: list[bool] = []
    inverse: float | None = None
    for speed in order:
        at = model.with_parameters(**{parameter: speed})
        res = at.run(t_end=t_end, analysis="dynamics")
        rows = res.lift_off
        flies.append(bool(((rows["joint"] == joint) & rows["greatest_gap"].notna()).any()))
        if inverse is None:
            # The inverse dynamics is a probe here: its lift-off is the answer,
            # not a warning.
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", LiftOffWarning)
                inv = at.run(t_end=t_end, analysis="inverse_dynamics")
            if bool((inv.lift_off["joint"] == joint).any()):
                inverse = speed
    forward = next((s for s, f in zip(order, flies, strict=True) if f), None)
    return JumpSpeed(joint, tuple(order), tuple(flies), forward, inverse)
