"""Plots of results: channels against time or each other, several runs
overlaid, a joint's reactions, and a cam's SVAJ diagram and pressure angle
against the cam angle in degrees.

Every function returns a matplotlib `Figure`; labels carry the channel's
unit as the results state it (`camlink.Results.units`: from the core, in
the units of results converted with `camlink.Results.in_units`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from camlink._core import ModelError
from camlink.results import Results
from camlink.units import unit_of

__all__ = ["Svaj", "cam_contacts", "plot", "pressure_angle", "reactions", "svaj", "svaj_data"]

Array = npt.NDArray[np.float64]


def label(channel: str, units: Mapping[str, str]) -> str:
    """An axis label: the channel and its unit (from `units`, a results'
    `camlink.Results.units`) in parentheses."""
    u = units.get(channel, "")
    return f"{channel} ({u})" if u else channel


def _axes(fig: Figure, rows: int = 1) -> list[Axes]:
    axes = [fig.add_subplot(rows, 1, k + 1) for k in range(rows)]
    for ax in axes:
        ax.grid(True, linewidth=0.4, color="#dddddd")
        ax.tick_params(labelsize=8, direction="in")
        for side in ("top", "right"):
            ax.spines[side].set_visible(False)
    return axes


def plot(
    runs: Results | Sequence[Results],
    y: str | Sequence[str],
    x: str = "t",
    *,
    labels: Sequence[str] | None = None,
    width: float = 6.4,
    height: float = 3.6,
) -> Figure:
    """One or several channels `y` against `x` (time by default, or another
    channel for an x–y plot; two lengths get one scale), for one run or
    several overlaid. `labels` names the runs in the legend (default: each
    run's model name)."""
    if isinstance(runs, Results):
        runs = [runs]
    names = [y] if isinstance(y, str) else list(y)
    if not runs or not names:
        raise ModelError("plot needs at least one run and one channel")
    if labels is not None and len(labels) != len(runs):
        raise ModelError(f"{len(labels)} labels for {len(runs)} runs")
    run_labels = list(labels) if labels is not None else [
        r.model or f"run {k + 1}" for k, r in enumerate(runs)
    ]
    units = runs[0].units
    quantities = runs[0].quantities
    fig = Figure(figsize=(width, height), dpi=100, layout="constrained")
    (ax,) = _axes(fig)
    for r, run_label in zip(runs, run_labels, strict=True):
        xs = r.t if x == "t" else r[x]
        for name in names:
            tag = [run_label] * (len(runs) > 1) + [name] * (len(names) > 1)
            ax.plot(xs, r[name], linewidth=1.3, label=", ".join(tag) or None, gid=f"{run_label}:{name}")
    ax.set_xlabel(label(x, units), fontsize=9)
    shown = {units.get(n, "") for n in names}
    ax.set_ylabel(label(names[0], units) if len(names) == 1 else
                  (f"({shown.pop()})" if len(shown) == 1 else "value"), fontsize=9)
    if len(runs) > 1 or len(names) > 1:
        ax.legend(fontsize=8, frameon=False)
    if x != "t" and all(quantities.get(n) == "length" for n in [x, *names]):
        ax.set_aspect("equal", adjustable="datalim")
    return fig


def reactions(results: Results, joint: str, *, width: float = 6.4) -> Figure:
    """The force of `joint` on body i, ``<joint>.fx`` and ``.fy`` (N), and
    its torque (N·m) when it has one, against time."""
    parts = [f"{joint}.fx", f"{joint}.fy"]
    if parts[0] not in results:
        raise ModelError(
            f"no reaction channels for joint {joint!r}: run inverse dynamics or dynamics"
        )
    torque = f"{joint}.torque"
    fig = Figure(figsize=(width, 4.2 if torque in results else 3.2), dpi=100, layout="constrained")
    axes = _axes(fig, 2 if torque in results else 1)
    for name in parts:
        axes[0].plot(results.t, results[name], linewidth=1.3, label=name)
    axes[0].set_ylabel(f"force on body i ({results.units[parts[0]]})", fontsize=9)
    axes[0].legend(fontsize=8, frameon=False)
    if torque in results:
        axes[1].plot(results.t, results[torque], linewidth=1.3, color="C2")
        axes[1].set_ylabel(label(torque, results.units), fontsize=9)
    axes[-1].set_xlabel("t (s)", fontsize=9)
    axes[0].set_title(f"reactions of {joint}", fontsize=10)
    return fig


def cam_contacts(results: Results) -> list[tuple[str, str, str]]:
    """(joint, cam body, follower body) of each cam contact of the model."""
    model = results.mechanism
    if model is None:
        return []
    return [
        (j["name"], j["bodies"][0], j["bodies"][1])
        for j in model.joints
        if j["kind"] in ("cam-follower", "flat-follower")
    ]


@dataclass(frozen=True)
class Svaj:
    """A follower's motion against the cam angle.

    `angle` is the cam's angle θ (deg, unwrapped from its first value);
    `s` the follower's lift from its lowest position, `v`, `a`, `j` its
    velocity, acceleration and jerk (time derivatives): along the guide
    (m, m/s, m/s², m/s³) for a translating follower, of its angle
    (rad, rad/s, rad/s², rad/s³) for an oscillating one. `j` is None when
    the run has no jerk channels (run kinematics with ``jerk=True``).
    """

    joint: str
    angle: Array
    s: Array
    v: Array
    a: Array
    j: Array | None
    units: tuple[str, str, str, str]


def svaj_data(results: Results, joint: str | None = None) -> Svaj:
    """The SVAJ of the cam contact `joint` (default: the model's first)."""
    contacts = cam_contacts(results)
    if not contacts:
        raise ModelError("these results have no cam contact (or carry no model)")
    if joint is None:
        joint = contacts[0][0]
    try:
        _, cam, follower = next(c for c in contacts if c[0] == joint)
    except StopIteration:
        names = ", ".join(c[0] for c in contacts)
        raise ModelError(f"no cam contact named {joint!r} (cam contacts: {names})") from None
    assert results.mechanism is not None
    angle = np.degrees(np.unwrap(results[f"{cam}.phi"])) if cam != "ground" else np.zeros(len(results))
    guide = _follower_guide(results, follower)

    def jerk(parts: Sequence[str]) -> list[Array] | None:
        return [results[p] for p in parts] if all(p in results for p in parts) else None

    if guide is not None:
        u = np.asarray(guide) / np.hypot(*guide)
        pos = u[0] * results[f"{follower}.x"] + u[1] * results[f"{follower}.y"]
        v = u[0] * results[f"{follower}.vx"] + u[1] * results[f"{follower}.vy"]
        a = u[0] * results[f"{follower}.ax"] + u[1] * results[f"{follower}.ay"]
        jj = jerk([f"{follower}.jx", f"{follower}.jy"])
        j = None if jj is None else u[0] * jj[0] + u[1] * jj[1]
        kinds = ("length", "velocity", "acceleration", "jerk")
    else:
        pos = results[f"{follower}.phi"]
        v, a = results[f"{follower}.omega"], results[f"{follower}.alpha"]
        jj = jerk([f"{follower}.jphi"])
        j = None if jj is None else jj[0]
        kinds = ("angle", "angular_velocity", "angular_acceleration", "angular_jerk")
    units = tuple(unit_of(q, results.value_units)[0] for q in kinds)
    return Svaj(joint, angle, pos - pos.min(), v, a, j, units)  # type: ignore[arg-type]


def _follower_guide(results: Results, follower: str) -> tuple[float, float] | None:
    """The global axis of the ground guide a translating follower slides on,
    or None for a follower that turns."""
    from camlink.viz.scene import Scene

    assert results.mechanism is not None
    scene = Scene.of(results.mechanism, tol=1e-2)
    for g in scene.guides:
        if g.body_j == follower and g.body_i == "ground":
            return g.v_i
        if g.body_i == follower and g.body_j == "ground":
            phi = float(results[f"{follower}.phi"][0])
            c, s = np.cos(phi), np.sin(phi)
            return (c * g.v_i[0] - s * g.v_i[1], s * g.v_i[0] + c * g.v_i[1])
    return None


def svaj(results: Results, joint: str | None = None, *, width: float = 6.4) -> Figure:
    """The SVAJ diagram of a cam contact: the follower's lift, velocity,
    acceleration and jerk against the cam angle θ (deg). Without jerk
    channels the fourth panel says how to get them."""
    d = svaj_data(results, joint)
    fig = Figure(figsize=(width, 6.4), dpi=100, layout="constrained")
    axes = _axes(fig, 4)
    names = ("S", "V", "A", "J")
    values = (d.s, d.v, d.a, d.j)
    for ax, name, val, u in zip(axes, names, values, d.units, strict=True):
        ax.set_ylabel(f"{name} ({u})", fontsize=9)
        if val is None:
            ax.text(0.5, 0.5, "jerk: run kinematics with jerk=True", transform=ax.transAxes,
                    ha="center", va="center", fontsize=9, color="#666666")
            continue
        ax.plot(d.angle, val, linewidth=1.3, color="#1f4e79", gid=f"svaj:{name}")
        ax.axhline(0.0, color="#999999", linewidth=0.6)
    for ax in axes[:-1]:
        ax.tick_params(labelbottom=False)
    for ax in axes:
        ax.set_xlim(float(d.angle[0]), float(d.angle[-1]))
    axes[-1].set_xlabel("cam angle θ (deg)", fontsize=9)
    axes[0].set_title(f"SVAJ of {d.joint}", fontsize=10)
    return fig


def pressure_angle(results: Results, joint: str | None = None, *, width: float = 6.4) -> Figure:
    """The pressure angle (deg) of a cam contact against the cam angle
    θ (deg)."""
    d = svaj_data(results, joint)
    channel = f"{d.joint}.pressure_angle"
    if channel not in results:
        raise ModelError(
            f"no {channel} channel: the follower of {d.joint!r} has neither a ground guide "
            "nor a fixed pivot"
        )
    fig = Figure(figsize=(width, 3.0), dpi=100, layout="constrained")
    (ax,) = _axes(fig)
    ax.plot(d.angle, np.degrees(results[channel]), linewidth=1.3, color="#7b2d26",
            gid=f"pressure:{d.joint}")
    ax.set_xlim(float(d.angle[0]), float(d.angle[-1]))
    ax.set_xlabel("cam angle θ (deg)", fontsize=9)
    ax.set_ylabel("pressure angle (deg)", fontsize=9)
    return fig
