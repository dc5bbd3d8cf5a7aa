"""Machine design of a linkage (`docs/machine.md`): the report of a model
file's ``[machine]`` table — shaking force and moment, counterweights,
flywheel and motor — computed in the core, presented here as text, JSON,
a polar plot of the shaking force and a balanced model file.

Units: SI (N, N·m, J, kg·m², rad/s, W); angles in the report in rad,
printed in degrees.
"""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Any, TypedDict, cast

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import numpy.typing as npt
from matplotlib.figure import Figure

from camlink import _core

__all__ = [
    "MachineReport",
    "balanced_text",
    "counterweights_text",
    "format_report",
    "polar",
    "report",
    "save",
    "to_json",
]


class MachineShaking(TypedDict):
    fx: npt.NDArray[np.float64]
    fy: npt.NDArray[np.float64]
    moment: npt.NDArray[np.float64]
    point: list[float]
    peak_force: float
    peak_at: float
    peak_dynamic: float
    peak_moment: float
    weight: list[float]

class MachineCounterweight(TypedDict):
    body: str
    mass: float
    at: list[float]
    radius: float
    new_mass: float
    new_centroid: list[float]
    new_inertia: float

class MachineBalance(TypedDict, total=False):
    """Either ``error`` (why there is no balance) or the rest."""
    error: str
    linkage: str
    balanced: str
    counterweights: list[MachineCounterweight]
    balanced_peak_dynamic: float

class MachineFlywheel(TypedDict):
    """``law``: the forward run's motor — ``"curve"`` (the motor curve
    through its gear) or ``"mean_torque"`` (a constant T̄); the run settles
    for ``settle_cycles`` cycles, then the last is measured;
    ``motor_torque``: (least, greatest) torque at the motor shaft there."""
    mean_torque: float
    delta_e: float
    cs: float
    inertia: float
    theta_max: float
    theta_min: float
    law: str
    settle_cycles: int
    omega_min: float
    omega_max: float
    omega_mean: float
    cs_run: float
    motor_torque: tuple[float, float] | None

class MachineMotor(TypedDict, total=False):
    """At the motor shaft; ``curve`` and the ratings when the file gives a motor."""
    gear_ratio: float
    peak_torque: float
    peak_at: float
    rms_torque: float
    peak_power: float
    speed: npt.NDArray[np.float64]
    torque: npt.NDArray[np.float64]
    curve: list[tuple[float, float]]
    rated_torque: float | None
    rated_power: float | None

class MachineCheck(TypedDict):
    name: str
    value: float
    limit: float
    margin: float
    unit: str
    ok: bool

class MachineReport(TypedDict):
    """The machine report: SI units, angles in rad."""
    driver: str
    speed: float
    period: float
    theta: npt.NDArray[np.float64]
    torque: npt.NDArray[np.float64]
    shaking: MachineShaking
    balance: MachineBalance | None
    flywheel: MachineFlywheel | None
    motor: MachineMotor
    checks: list[MachineCheck]
    ok: bool


def report(path: str | Path) -> MachineReport:
    """The machine report of the model file at `path` (its ``[machine]``
    table); a `ModelError` names the file, line and field of bad input."""
    return cast(MachineReport, _core.machine_report(Path(path)))


def _deg(rad: float) -> float:
    return math.degrees(rad) % 360.0


def format_report(r: MachineReport, name: str = "") -> str:
    """The report as text: figures, then each check with its margin."""
    sh = r["shaking"]
    rpm = r["speed"] * 60.0 / (2.0 * math.pi)
    head = f"machine {name}".rstrip()
    lines = [f"{head}: driver '{r['driver']}' at {r['speed']:.6g} rad/s ({rpm:.6g} rpm)"]
    lines.append("shaking force on the frame (mechanism on ground, global frame):")
    lines.append(
        f"  peak |F_s| {sh['peak_force']:.6g} N at crank {_deg(sh['peak_at']):.1f}°, "
        f"including the weight ({sh['weight'][0]:.6g}, {sh['weight'][1]:.6g}) N"
    )
    lines.append(f"  peak |F_s − W| {sh['peak_dynamic']:.6g} N")
    px, py = sh["point"]
    lines.append(f"  peak |M| {sh['peak_moment']:.6g} N·m about ({px:.6g}, {py:.6g}) m")
    b = r["balance"]
    if b is not None:
        if "error" in b:
            lines.append(f"balance: not available: {b['error']}")
        else:
            lines.append(f"balance ({b['linkage']}): {b['balanced']}")
            for c in b["counterweights"]:
                lines.append(
                    f"  {c['body']}: counterweight {c['mass']:.6g} kg at ({c['at'][0]:.6g}, "
                    f"{c['at'][1]:.6g}) m in its frame (radius {c['radius']:.6g} m); body mass "
                    f"{c['new_mass']:.6g} kg, centroid ({c['new_centroid'][0]:.6g}, "
                    f"{c['new_centroid'][1]:.6g}) m, inertia {c['new_inertia']:.6g} kg·m²"
                )
            lines.append(f"  balanced: peak |F_s − W| {b['balanced_peak_dynamic']:.3g} N")
    f = r["flywheel"]
    if f is not None:
        lines.append("flywheel:")
        lines.append(
            f"  mean input torque {f['mean_torque']:.6g} N·m, energy fluctuation ΔE {f['delta_e']:.6g} J"
        )
        lines.append(
            f"  inertia I = ΔE/(C_s ω²) = {f['inertia']:.6g} kg·m² for C_s = {f['cs']:.6g}; "
            f"fastest at {_deg(f['theta_max']):.1f}°, slowest at {_deg(f['theta_min']):.1f}°"
        )
        law = "the motor curve through its gear" if f["law"] == "curve" else "constant torque T̄"
        lines.append(
            f"  forward run with it ({law}; cycle {f['settle_cycles'] + 1}): ω {f['omega_min']:.6g} to "
            f"{f['omega_max']:.6g} rad/s, mean {f['omega_mean']:.6g} rad/s, C_s {f['cs_run']:.6g}"
        )
        if f["motor_torque"] is not None:
            lo, hi = f["motor_torque"]
            lines.append(f"  motor torque over that cycle {lo:.6g} to {hi:.6g} N·m")
        # The core's `run_speed` check: the mean speed within the band
        # ½ C_s ω about the design speed.
        band = next((c for c in r["checks"] if c["name"] == "run_speed"), None)
        if band is not None and not band["ok"]:
            off = f["omega_mean"] - r["speed"]
            pct = 100.0 * off / r["speed"]
            if off < 0:
                lines.append(
                    f"  the motor cannot reach the design speed: the machine runs at "
                    f"{f['omega_mean']:.6g} rad/s, {-pct:.3g} % slow "
                    "(more torque at n ω, or another gear ratio)"
                )
            else:
                lines.append(
                    f"  the motor drives the machine past the design band: {f['omega_mean']:.6g} rad/s, "
                    f"{pct:.3g} % fast (another gear ratio)"
                )
    m = r["motor"]
    lines.append(f"motor (gear ratio {m['gear_ratio']:.6g}, torque at the motor shaft, no flywheel):")
    lines.append(
        f"  peak torque {m['peak_torque']:.6g} N·m at crank {_deg(m['peak_at']):.1f}°, "
        f"RMS torque {m['rms_torque']:.6g} N·m, peak power {m['peak_power']:.6g} W"
    )
    if r["checks"]:
        lines.append("checks:")
    for chk in r["checks"]:
        unit = f" {chk['unit']}" if chk["unit"] else ""
        verdict = "ok" if chk["ok"] else "FAIL"
        lines.append(
            f"  {chk['name']}: {chk['value']:.6g}{unit} (limit {chk['limit']:.6g}{unit}, "
            f"margin {chk['margin']:.6g}{unit}) {verdict}"
        )
    lines.append("all checks hold" if r["ok"] else "some checks fail")
    return "\n".join(lines)


def to_json(r: MachineReport) -> dict[str, Any]:
    """The report with arrays as lists, for JSON."""
    from camlink.cam.design import json_safe

    return cast(dict[str, Any], json_safe(dict(r)))


def polar(r: MachineReport, title: str = "") -> Figure:
    """The polar plot of the shaking force: the locus of the tip of F_s
    (N, global frame) over the cycle, the crank angle of a few points
    marked, the weight W as a cross; equal scales on both axes."""
    sh = r["shaking"]
    fx, fy = np.asarray(sh["fx"]), np.asarray(sh["fy"])
    fig, ax = plt.subplots(figsize=(6, 6), layout="constrained")
    ax.plot(fx, fy, color="C0", lw=1.5, label="F_s over the cycle")
    ax.plot([0.0], [0.0], "k+", ms=10)
    w = sh["weight"]
    ax.plot([w[0]], [w[1]], "x", color="C3", ms=8, label="weight W")
    th = np.asarray(r["theta"])
    n = len(th) - 1
    for k in range(0, n, max(1, n // 8)):
        label = f"{_deg(float(th[k])):.0f}°"
        ax.annotate(label, (fx[k], fy[k]), textcoords="offset points", xytext=(4, 4), fontsize=8)
        ax.plot([fx[k]], [fy[k]], "o", color="C0", ms=3)
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, lw=0.4)
    ax.set_xlabel("shaking force x (N)")
    ax.set_ylabel("shaking force y (N)")
    ax.set_title(title or "shaking force on the frame")
    ax.legend(loc="best", fontsize=8)
    return fig


def save(fig: Figure, path: str | Path, dpi: int = 120) -> None:
    """Writes the figure as PNG and closes it."""
    fig.savefig(path, dpi=dpi)
    plt.close(fig)


_BODY = re.compile(r"^\s*\[\[bodies\]\]\s*(#.*)?$")
_TABLE = re.compile(r"^\s*\[\[?[A-Za-z_][\w.]*\]\]?\s*(#.*)?$")
_KEY = re.compile(r"^\s*(mass|inertia|centroid)\s*=")
_NAME = re.compile(r"^\s*name\s*=\s*\"([^\"]*)\"")


def balanced_text(text: str, r: MachineReport) -> str:
    """The model file `text` with the counterweights of the report's full
    force balance (see `counterweights_text`)."""
    b = r["balance"]
    if b is None or "error" in b:
        why = b["error"] if b is not None else "[machine] balance = false"
        raise _core.ModelError(f"the model has no counterweights to write: {why}")
    return counterweights_text(text, b["counterweights"])


def counterweights_text(text: str, counterweights: list[MachineCounterweight]) -> str:
    """The model file `text` with each counterweighted body's ``mass``,
    ``centroid`` and ``inertia`` set to those of the body with its
    counterweight (the other lines, comments included, kept). The
    ``[[bodies]]`` tables must be written as TOML tables (as in the
    examples), one key a line."""
    new = {c["body"]: c for c in counterweights if c["mass"] > 0.0}
    lines = text.splitlines(keepends=True)
    # Split into [[bodies]] blocks: the lines from one header to the next table header.
    out: list[str] = []
    k = 0
    while k < len(lines):
        if not _BODY.match(lines[k]):
            out.append(lines[k])
            k += 1
            continue
        end = k + 1
        while end < len(lines) and not _TABLE.match(lines[end]):
            end += 1
        block = lines[k:end]
        name = next((m.group(1) for ln in block if (m := _NAME.match(ln))), None)
        c = new.get(name or "")
        if c is None:
            out.extend(block)
        else:
            cx, cy = c["new_centroid"]
            values = {
                "mass": f"{c['new_mass']!r}",
                "inertia": f"{c['new_inertia']!r}",
                "centroid": f"[{cx!r}, {cy!r}]",
            }
            note = f"  # with the counterweight of `camlink machine` ({c['mass']:.6g} kg)\n"
            kept = [ln for ln in block if not _KEY.match(ln)]
            while kept and not kept[-1].strip():
                kept.pop()
            out.extend(kept)
            out.extend(f"{key} = {v}{note}" for key, v in values.items())
            out.append("\n")
        k = end
    return "".join(out)
