"""Sizing a cam's follower train: Hertz contact stress and bearing life,
camshaft torque, the helical return spring and the follower train's
vibration, read from the ``[contact]``, ``[spring]`` and ``[vibration]``
tables of a cam design file and checked as limits of the cam report.

The formulas are in the Rust core (``CamCore.stress``,
``CamCore.vibration``, the materials table ``cam_materials``); the tables
are read and checked, the spring installed and the contact modulus
computed by the design file's loader, and the checks made by the report
(the ``camlink-cam`` crate: ``report/sizing.rs``). This module holds what
the loader read. See
docs/cam-design.md, *Contact stress*, *Springs* and *Follower vibration*.
"""

from __future__ import annotations

from dataclasses import dataclass

from camlink._core import cam_design_limits, cam_materials

__all__ = [
    "LIFE_EXPONENT",
    "MATERIALS",
    "MAX_STEPS",
    "MAX_TURNS",
    "RPM",
    "SURGE_RATIO",
    "ContactSpec",
    "SpringSpec",
    "VibrationSpec",
]

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
