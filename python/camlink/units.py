"""Units of result channels and of what camlink shows, as the Rust core
states them.

Every channel carries its quantity from the core, where it is named
(``"crank.omega"`` is an ``"angular_velocity"``, a driver's ``effort`` a
``"torque"`` or a ``"force"`` by the coordinate it drives, a gear's
``theta`` an ``"angle"``); `unit_of` gives its SI unit, or its unit in the
units a user asks for (``"mm,deg"``) and the factor that converts it.
Lengths and angles and their rates follow the asked units; forces,
torques, energies and times stay SI.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import NamedTuple

from camlink import _core

__all__ = ["LENGTH_UNITS", "Units", "channel_units", "parse_units", "unit_of"]

#: Length units camlink knows: symbol → metres in one unit.
LENGTH_UNITS: dict[str, float] = dict(_core.length_units())


class Units(NamedTuple):
    """A length unit and an angle unit, e.g. ``Units("mm", "deg")``."""

    length: str
    angle: str

    def __str__(self) -> str:
        return f"{self.length},{self.angle}"


#: Metres and radians.
SI = Units("m", "rad")


def parse_units(text: str | Units | None) -> Units:
    """Units written ``"LENGTH,ANGLE"`` (``"mm,deg"``), either part alone
    (the other stays SI), or ``"si"``; None is SI. A `camlink.ModelError`
    names what is accepted."""
    if text is None:
        return SI
    if isinstance(text, Units):
        text = str(text)
    length, angle = _core.parse_units(text)
    return Units(length, angle)


def unit_of(quantity: str, units: str | Units | None = None) -> tuple[str, float]:
    """The unit of `quantity` (as the core names it, e.g. ``"velocity"``)
    in `units` (default SI) and the factor k that turns an SI value into it
    (value = k · SI value). ``""`` and 1 for an unknown quantity (a column
    of results read from a file written before channels carried theirs)."""
    if not quantity:
        return "", 1.0
    return _core.quantity_unit(quantity, str(parse_units(units)))


def channel_units(
    names: Sequence[str], quantities: Sequence[str] | Mapping[str, str],
    units: str | Units | None = None,
) -> dict[str, str]:
    """Each channel's unit in `units` (default SI) from its quantity:
    `quantities` in the order of `names`, or by name."""
    if isinstance(quantities, Mapping):
        by_name = quantities
    else:
        by_name = dict(zip(names, quantities, strict=True))
    asked = parse_units(units)
    # A model has many channels and few quantities: each looked up once.
    unit = {q: unit_of(q, asked)[0] for q in {*by_name.values(), ""}}
    return {n: unit[by_name.get(n, "")] for n in names}
