"""Sizing a cam's follower train: Hertz contact stress and bearing life,
camshaft torque, the helical return spring and the follower train's
vibration, read from the ``[contact]``, ``[spring]`` and ``[vibration]``
tables of a cam design file and checked as limits of the cam report.

The formulas are in the Rust core (``CamCore.stress``,
``CamCore.vibration``, the materials table ``cam_materials``); the tables
are read and checked, the spring installed and the contact modulus
computed by the design file's loader (the ``camlink-cam`` crate). This
module holds what it read and presents the checks. See
docs/cam-design.md, *Contact stress*, *Springs* and *Follower vibration*.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from camlink._core import CamCore, cam_design_limits, cam_materials

if TYPE_CHECKING:
    from camlink.cam.design import Check, Design

#: Materials by name: (E Pa, ν, G Pa, density kg/m³), Shigley's
#: *Mechanical Engineering Design*, 10th ed., Table A-5 (in the core).
MATERIALS: dict[str, tuple[float, float, float, float]] = {
    n: (e, nu, g, rho) for n, e, nu, g, rho in cam_materials()
}

_LIMITS = cam_design_limits()

#: Life exponent of a bearing type (ISO 281).
LIFE_EXPONENT: dict[str, float] = dict(_LIMITS["life_exponents"])

#: Default least ratio of spring surge frequency to the forcing (cam)
#: frequency: Norton, *Machine Design*, ch. 13 ("at least 13 times").
SURGE_RATIO: float = _LIMITS["surge_ratio"]

#: One rev/min in rad/s.
RPM: float = _LIMITS["rpm"]

#: Most integration steps per turn and turns of `[vibration]` (seconds of work).
MAX_STEPS: int = _LIMITS["max_steps"]
MAX_TURNS: int = _LIMITS["max_turns"]


@dataclass(frozen=True)
class ContactSpec:
    width: float
    """Contact length along the cam axis (m)."""
    modulus: float
    """Contact modulus E* (Pa)."""
    materials: tuple[str, str]
    rating: float | None
    """Bearing dynamic rating C (N)."""
    exponent: float
    crown: float | None = None
    """A crowned roller's crown radius (m)."""


@dataclass(frozen=True)
class SpringSpec:
    wire: float
    mean_diameter: float
    active_coils: float
    total_coils: float
    free_length: float
    installed_length: float
    shear_modulus: float
    density: float
    figures: dict[str, float]
    """rate, preload, solid, shortest, clash_margin, mass, surge, index."""


@dataclass(frozen=True)
class VibrationSpec:
    masses: tuple[float, ...]
    stiffness: tuple[float, ...]
    damping: tuple[float, ...]
    steps: int
    turns: int
    polydyne: bool


def checks(design: Design, core: CamCore) -> tuple[list[Check], dict[str, Any]]:
    """The limits of contact stress, bearing life, spring and vibration,
    and the figures behind them (SI) for the report."""
    from camlink.cam.design import Check

    out: list[Check] = []
    info: dict[str, Any] = {}
    d = design.dynamics
    lim = design.limits
    if d is None:
        return out, info
    deg = math.degrees
    rpm = d.speed / RPM
    top = (d.redline or d.speed) / RPM
    c = design.contact
    if c is not None:
        s = core.stress(
            (d.mass, d.spring_rate, d.preload, d.damping),
            d.speed,
            c.width,
            c.modulus,
            c.rating,
            c.exponent,
            c.crown,
        )
        p, at = s["max_pressure"]
        limit = lim.max_contact_stress
        margin = None if limit is None else (limit - p) / 1e6
        out.append(
            Check(
                f"Hertz contact stress at {rpm:.6g} rpm",
                p / 1e6,
                None if limit is None else limit / 1e6,
                margin,
                "MPa",
                deg(at),
                margin is None or margin >= 0,
                (
                    f"contact half-width {s['half_width_at_max'] * 1e3:.4g} mm over "
                    f"{c.width * 1e3:.4g} mm"
                    if c.crown is None
                    else f"crowned roller (crown radius {c.crown * 1e3:.4g} mm): contact "
                    f"ellipse semi-axis {s['half_width_at_max'] * 1e3:.4g} mm along the profile"
                )
                + f", {c.materials[0]} on {c.materials[1]}",
            )
        )
        tq, tat = s["peak_torque"]
        out.append(
            Check(
                f"camshaft torque at {rpm:.6g} rpm",
                tq,
                None,
                None,
                "N·m",
                deg(tat),
                True,
                f"RMS {s['rms_torque']:.6g} N·m",
            )
        )
        info["contact"] = {
            "max_pressure": p,
            "max_pressure_at_deg": deg(at),
            "half_width": s["half_width_at_max"],
            "modulus": c.modulus,
            "peak_torque": tq,
            "peak_torque_at_deg": deg(tat),
            "rms_torque": s["rms_torque"],
        }
        b = s["bearing"]
        if b is not None:
            hours = b["l10_turns"] / (rpm * 60.0)
            limit = lim.min_bearing_life_hours
            margin = None if limit is None else hours - limit
            out.append(
                Check(
                    f"roller bearing L10 life at {rpm:.6g} rpm",
                    hours,
                    limit,
                    margin,
                    "h",
                    None,
                    margin is None or margin >= 0,
                    f"equivalent load {b['equivalent_load']:.6g} N, "
                    f"{b['l10_revolutions'] / 1e6:.6g} million roller revolutions, "
                    f"{b['roller_turns']:.4g} roller turns per cam turn",
                )
            )
            info["bearing"] = {**b, "l10_hours": hours}
    sp = design.spring
    if sp is not None:
        f = sp.figures
        limit = lim.min_coil_clearance
        margin = f["clash_margin"] - (limit or 0.0)
        out.append(
            Check(
                "spring coil-clash margin at the largest lift",
                f["clash_margin"],
                limit if limit is not None else 0.0,
                margin,
                "m",
                None,
                margin >= 0,
                f"shortest {f['shortest'] * 1e3:.6g} mm, solid height {f['solid'] * 1e3:.6g} mm",
            )
        )
        ratio = f["surge"] / (top / 60.0)
        need = lim.min_surge_ratio
        out.append(
            Check(
                f"spring surge / forcing frequency at {top:.6g} rpm",
                ratio,
                need,
                ratio - need,
                "",
                None,
                ratio >= need,
                f"surge {f['surge']:.6g} Hz, rate {f['rate']:.6g} N/m, preload "
                f"{f['preload']:.6g} N, active mass {f['mass']:.4g} kg, index {f['index']:.3g}",
            )
        )
        info["spring"] = {**f, "surge_ratio": ratio}
    v = design.vibration
    if v is not None:
        r = core.vibration(
            list(v.masses),
            list(v.stiffness),
            list(v.damping),
            d.spring_rate,
            d.preload,
            d.speed,
            v.steps,
            v.turns,
            False,
        )
        th = np.asarray(r["theta"])
        contact = np.asarray(r["contact"])
        k = int(np.argmin(contact))
        out.append(
            Check(
                f"least dynamic contact force at {rpm:.6g} rpm ({len(v.masses)}-mass train)",
                float(contact[k]),
                0.0,
                float(contact[k]),
                "N",
                deg(float(th[k])),
                bool(contact[k] > 0),
            )
        )
        limit = lim.max_residual_vibration
        lunit = "rad" if design.oscillating else "m"
        residual = []
        for seg, amp, at in r["residual"]:
            margin = None if limit is None else limit - amp
            out.append(
                Check(
                    f"residual vibration after segment {seg}",
                    amp,
                    limit,
                    margin,
                    lunit,
                    deg(at),
                    margin is None or margin >= 0,
                )
            )
            residual.append({"segment": seg, "amplitude": amp, "at_deg": deg(at)})
        dev = np.asarray(r["deviation"])
        info["vibration"] = {
            "max_deviation": float(np.max(np.abs(dev))),
            "residual": residual,
            "min_contact": float(contact[k]),
        }
        if v.polydyne:
            q = core.vibration(
                list(v.masses),
                list(v.stiffness),
                list(v.damping),
                d.spring_rate,
                d.preload,
                d.speed,
                v.steps,
                v.turns,
                True,
            )
            x = np.asarray(q["position"])[-1]
            ks, k1 = d.spring_rate, v.stiffness[0]
            s_prog = np.asarray(core.motion(np.asarray(q["theta"]) % (2 * math.pi)))[:, 0]
            err = float(np.max(np.abs(x + d.preload / (k1 + ks) - s_prog)))
            y = np.asarray(q["input"])
            correction = float(np.max(np.abs(y - s_prog)))
            info["vibration"]["polydyne"] = {
                "max_departure": err,
                "max_correction": correction,
            }
            out.append(
                Check(
                    f"polydyne program at {rpm:.6g} rpm: follower's departure from s",
                    err,
                    None,
                    None,
                    lunit,
                    None,
                    True,
                    "cam displacement corrected by up to "
                    + (
                        f"{correction:.4g} rad"
                        if design.oscillating
                        else f"{correction * 1e3:.4g} mm"
                    ),
                )
            )
    return out, info
