"""Units of result channels, from the kind a channel's name ends with
(``"crank.omega"`` → ``"rad/s"``): for plot labels and result files.

A driver's effort is a torque or a force by the coordinate it drives, and
a joint stop's gap an angle or a length; `unit` tells them apart when it
is given the model's joints.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from camlink.records import JointRecord

__all__ = ["UNITS", "effort_unit", "unit"]

#: Units of channels by the last part of their name.
UNITS = {
    "t": "s",
    "x": "m", "y": "m", "cx": "m", "cy": "m",
    "phi": "rad", "alpha_i": "rad", "alpha_j": "rad", "pressure_angle": "rad",
    "theta": "rad",
    "vx": "m/s", "vy": "m/s", "omega": "rad/s",
    "ax": "m/s²", "ay": "m/s²", "alpha": "rad/s²",
    "jx": "m/s³", "jy": "m/s³", "jphi": "rad/s³",
    "fx": "N", "fy": "N", "fx_j": "N", "fy_j": "N", "fx_local": "N", "fy_local": "N",
    "fx_local_j": "N", "fy_local_j": "N", "normal": "N", "force": "N",
    "normal_force": "N", "tangential_force": "N", "friction_force": "N",
    "friction_torque": "N·m", "friction_power": "W",
    "torque": "N·m", "torque_j": "N·m", "moment": "N·m", "power": "W",
    "kinetic": "J", "potential": "J", "total": "J", "elastic": "J", "work": "J",
    "residual": "m", "velocity": "m/s", "gap": "m",
}

#: Equations of a driver whose effort is a torque: it drives an angle.
ANGLE_EQUATIONS = frozenset({"phi"})


def effort_unit(driver: JointRecord) -> str:
    """The unit of a driver's effort: ``"N·m"`` when it drives an angle,
    ``"N"`` when it drives a length (x, y, a distance, travel along a
    guide)."""
    names = driver.get("equation_names") or []
    return "N·m" if any(n in ANGLE_EQUATIONS for n in names) else "N"


def unit(channel: str, joints: Sequence[JointRecord] | None = None) -> str:
    """The unit of a channel from its kind (``"crank.omega"`` → ``"rad/s"``).

    A driver's ``<driver>.effort`` is in N·m or N by what it drives: given
    the model's `joints` (`Model.joints`), the driver's; without them ``""``.
    A revolute's stop ``<joint>.lower.gap`` is in rad given the joints.
    """
    owner, _, kind = channel.rpartition(".")
    if kind == "effort":
        driver = next((j for j in joints or () if j["name"] == owner and j["driver"]), None)
        return effort_unit(driver) if driver is not None else ""
    if kind == "gap" and stop_of_revolute(owner, joints or ()):
        return "rad"
    return UNITS.get(kind, "")


def stop_of_revolute(owner: str, joints: Sequence[JointRecord]) -> bool:
    """True when `owner` is an end stop (``<joint>.lower`` or
    ``<joint>.upper``) of a revolute joint, whose gap is an angle."""
    joint, _, side = owner.rpartition(".")
    return side in ("lower", "upper") and any(
        j["name"] == joint and j["kind"] == "revolute" for j in joints
    )
