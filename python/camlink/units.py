"""Units of result channels, from the kind a channel's name ends with
(``"crank.omega"`` → ``"rad/s"``): for plot labels and result files."""

from __future__ import annotations

__all__ = ["UNITS", "unit"]

#: Units of channels by the last part of their name.
UNITS = {
    "t": "s",
    "x": "m", "y": "m", "cx": "m", "cy": "m",
    "phi": "rad", "alpha_i": "rad", "alpha_j": "rad", "pressure_angle": "rad",
    "vx": "m/s", "vy": "m/s", "omega": "rad/s",
    "ax": "m/s²", "ay": "m/s²", "alpha": "rad/s²",
    "jx": "m/s³", "jy": "m/s³", "jphi": "rad/s³",
    "fx": "N", "fy": "N", "fx_j": "N", "fy_j": "N", "fx_local": "N", "fy_local": "N",
    "fx_local_j": "N", "fy_local_j": "N", "normal": "N", "force": "N",
    "torque": "N·m", "torque_j": "N·m", "power": "W",
    "kinetic": "J", "potential": "J", "total": "J", "elastic": "J", "work": "J",
    "residual": "m", "velocity": "m/s", "gap": "m",
}


def unit(channel: str) -> str:
    """The unit of a channel from its kind (``"crank.omega"`` → ``"rad/s"``),
    or ``""`` when the kind does not fix it (a driver's effort is a force or
    a torque)."""
    return UNITS.get(channel.rsplit(".", 1)[-1], "")
