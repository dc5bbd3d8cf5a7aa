"""Four-bars in a model: found by their joints, described by the Grashof
class, the transmission angle and the dead-centre and toggle marks of
camlink-synth (in the core).

A model is a four-bar when it has three moving bodies joined in a loop
ground–crank–coupler–rocker–ground by four revolute joints (drivers
aside), the crank being the body a driver turns. Symbols as in
docs/synthesis.md: ground d = |O₄ − O₂|, crank a, coupler b, rocker c (m);
the transmission angle μ (rad) is the angle at B between the coupler and
the rocker, from the diagonal E = |O₄ − A| at each output row.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from camlink import _core
from camlink.viz.scene import GROUND, Pin, Scene

if TYPE_CHECKING:
    from camlink.model import Model

__all__ = ["FourBarLoop", "describe", "find", "summary", "transmission"]

Array = npt.NDArray[np.float64]


@dataclass(frozen=True)
class FourBarLoop:
    """The loop's bodies, the ground pivots O₂ (crank) and O₄ (rocker)
    (global, m), and the moving pivots A (crank–coupler) and B
    (coupler–rocker) in the crank's and the rocker's frames (m)."""

    crank: str
    coupler: str
    rocker: str
    o2: tuple[float, float]
    o4: tuple[float, float]
    a_on_crank: tuple[float, float]
    a_on_coupler: tuple[float, float]
    b_on_coupler: tuple[float, float]
    b_on_rocker: tuple[float, float]
    #: The crank's and the rocker's ground pivots in their own frames (m).
    o2_on_crank: tuple[float, float]
    o4_on_rocker: tuple[float, float]

    def lengths(self) -> tuple[float, float, float, float]:
        """(d, a, b, c) (m)."""
        return (
            math.dist(self.o2, self.o4),
            math.dist(self.a_on_crank, self.o2_on_crank),
            math.dist(self.a_on_coupler, self.b_on_coupler),
            math.dist(self.b_on_rocker, self.o4_on_rocker),
        )


def find(model: Model, scene: Scene) -> FourBarLoop | None:
    """The model's four-bar loop, or None when it is not one."""
    if len(scene.bodies) != 3 or len(scene.pins) != 4:
        return None
    drivers = [j for j in model.joints if j["driver"]]
    driven = {j["bodies"][1] for j in drivers} | {j["bodies"][0] for j in drivers}
    grounded = [p for p in scene.pins if p.grounded and p.body_i != p.body_j]
    moving = [p for p in scene.pins if not p.grounded and p.body_i != p.body_j]
    if len(grounded) != 2 or len(moving) != 2:
        return None

    def split(p: Pin) -> tuple[str, tuple[float, float], tuple[float, float]]:
        """The moving body of a grounded pin, the pin on the ground and on it."""
        if p.body_i == GROUND:
            return p.body_j, p.s_i, p.s_j
        return p.body_i, p.s_j, p.s_i

    ends = [split(p) for p in grounded]
    cranks = [e for e in ends if e[0] in driven]
    if len(cranks) != 1:
        return None
    crank, o2, crank_pivot = cranks[0]
    rocker, o4, rocker_pivot = next(e for e in ends if e[0] != crank)
    coupler = next((b for b in scene.bodies if b not in (crank, rocker)), None)
    if coupler is None:
        return None
    pa = next((p for p in moving if {p.body_i, p.body_j} == {crank, coupler}), None)
    pb = next((p for p in moving if {p.body_i, p.body_j} == {coupler, rocker}), None)
    if pa is None or pb is None:
        return None

    def on(pin: Pin, body: str) -> tuple[float, float]:
        return pin.s_i if pin.body_i == body else pin.s_j

    return FourBarLoop(crank, coupler, rocker, o2, o4, on(pa, crank), on(pa, coupler),
                       on(pb, coupler), on(pb, rocker), crank_pivot, rocker_pivot)


def transmission(loop: FourBarLoop, names: list[str], values: Array) -> Array:
    """μ (rad) at each row of `values` (rows × `names`), from the crank
    pin A's place at that row; NaN where a row is missing."""
    col = {n: i for i, n in enumerate(names)}
    x, y, phi = (values[:, col[f"{loop.crank}.{c}"]] for c in ("x", "y", "phi"))
    sx, sy = loop.a_on_crank
    ax = x + np.cos(phi) * sx - np.sin(phi) * sy
    ay = y + np.sin(phi) * sx + np.cos(phi) * sy
    diagonal = np.hypot(loop.o4[0] - ax, loop.o4[1] - ay)
    _, _, b, c = loop.lengths()
    return _core.fourbar_transmission(b, c, np.ascontiguousarray(diagonal))


def describe(model: Model, t: Array, names: list[str], values: Array,
             scene: Scene | None = None) -> list[str]:
    """Lines for the page: the class and the range of μ over the cycle (no
    lines when the model is not a four-bar); `scene` is the model's when
    the caller has it."""
    loop = find(model, Scene.of(model, tol=1e-2) if scene is None else scene)
    if loop is None:
        return []
    d, a, b, c = loop.lengths()
    kind = _core.fourbar_class(d, a, b, c)
    lines = [f"four-bar: d = {d:.6g} m, a = {a:.6g} m, b = {b:.6g} m, c = {c:.6g} m; Grashof class: {kind}"]
    mu = transmission(loop, names, values)
    if np.any(np.isfinite(mu)):
        lo, hi = float(np.nanmin(mu)), float(np.nanmax(mu))
        worst = max(abs(90 - math.degrees(lo)), abs(90 - math.degrees(hi)))
        lines.append(f"transmission angle μ: {math.degrees(lo):.2f}° to {math.degrees(hi):.2f}° "
                     f"(worst {worst:.2f}° from 90°)")
    return lines


def summary(model: Model) -> dict[str, object] | None:
    """The four-bar loop of `model` for `camlink check`, or None when the
    model is not one: its bodies, lengths d, a, b, c (m), Grashof class,
    and the range of the transmission angle μ (rad) over every position
    the loop can take. μ grows with the diagonal E = |O₄ − A|
    (cos μ = (b² + c² − E²)/(2bc)), and E spans [max(|d − a|, |b − c|),
    min(d + a, b + c)] over the crank's reach, so the ends of that span
    give the extremes; no motion is run."""
    loop = find(model, Scene.of(model, tol=1e-2))
    if loop is None:
        return None
    d, a, b, c = loop.lengths()
    lo, hi = max(abs(d - a), abs(b - c)), min(d + a, b + c)
    mu = _core.fourbar_transmission(b, c, np.array([lo, hi]))
    return {
        "crank": loop.crank,
        "coupler": loop.coupler,
        "rocker": loop.rocker,
        "lengths": {"ground": d, "crank": a, "coupler": b, "rocker": c},
        "grashof": _core.fourbar_class(d, a, b, c),
        "transmission": [float(mu[0]), float(mu[1])] if lo <= hi else None,
    }


def marks(model: Model, scene: Scene, t: Array, names: list[str], values: Array,
          ok: npt.NDArray[np.bool_] | None = None) -> list[dict[str, object]]:
    """The four-bar's dead-centre positions (crank and coupler in line:
    the rocker at a limit of its swing) and toggle positions (coupler and
    rocker in line: μ = 0 or 180°) passed between two solved rows: the
    time (s), found by camlink-synth where the cross product of the two
    links' vectors changes sign on the quintic through each row's pose,
    velocity and acceleration; the crank body's angle φ then (rad) and the pin that
    marks it (B for a dead centre, A for a toggle; global, m). Empty when
    the model is not a four-bar."""
    loop = find(model, scene)
    if loop is None or len(t) < 2:
        return []
    col = {n: i for i, n in enumerate(names)}
    if any(f"{b}.{c}" not in col for b in (loop.crank, loop.rocker)
           for c in ("x", "y", "phi", "vx", "vy", "omega", "ax", "ay", "alpha")):
        return []
    # The crank's and the rocker's (x, y, φ), then their velocities, then
    # their accelerations: the rows camlink-synth's marks read.
    motion = values[:, [col[f"{b}.{c}"] for trio in (("x", "y", "phi"), ("vx", "vy", "omega"),
                                                     ("ax", "ay", "alpha"))
                        for b in (loop.crank, loop.rocker) for c in trio]]
    solved = np.ones(len(t), dtype=bool) if ok is None else np.asarray(ok, dtype=bool)
    found = _core.fourbar_marks(np.ascontiguousarray(t, dtype=np.float64),
                                np.ascontiguousarray(motion, dtype=np.float64),
                                np.ascontiguousarray(solved), loop.o2, loop.o4,
                                loop.a_on_crank, loop.b_on_rocker)
    return [{"t": tm, "kind": kind, "label": kind, "crank": crank, "x": x, "y": y}
            for tm, kind, crank, x, y in found]
