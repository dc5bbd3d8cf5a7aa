"""Four-bars in a model: found by their joints, described by the Grashof
class and the transmission angle of camlink-synth's checks (in the core).

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
from typing import TYPE_CHECKING, Any

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


#: The quintic through (y, y′, y″) at both ends of a step of h, as
#: powers of the step's fraction s: row j holds the coefficients of s⁰…s⁵
#: of the weight of y₀, h y′₀, h² y″₀, y₁, h y′₁, h² y″₁ in turn.
_POWERS = np.arange(6.0)
_HERMITE5 = np.array([
    [1, 0, 0, -10, 15, -6],
    [0, 1, 0, -6, 8, -3],
    [0, 0, 0.5, -1.5, 1.5, -0.5],
    [0, 0, 0, 10, -15, 6],
    [0, 0, 0, -4, 7, -3],
    [0, 0, 0, 0.5, -1, 0.5],
])


def _quintics(h: float, rows: Array, k: int) -> Array:
    """The coefficients (channels × powers s⁰…s⁵) of each channel's
    quintic through its (y, y′, y″) at rows k and k + 1 of `rows`, whose
    columns are each channel's y, then every y′, then every y″ (three
    blocks of equal width), over a step of `h`."""
    m = rows.shape[1] // 3
    y0, v0, a0 = rows[k, :m], rows[k, m:2 * m], rows[k, 2 * m:]
    y1, v1, a1 = rows[k + 1, :m], rows[k + 1, m:2 * m], rows[k + 1, 2 * m:]
    weights = np.column_stack([y0, h * v0, h * h * a0, y1, h * v1, h * h * a1])
    return weights @ _HERMITE5


def marks(model: Model, scene: Scene, t: Array, names: list[str], values: Array,
          ok: npt.NDArray[np.bool_] | None = None) -> list[dict[str, object]]:
    """The four-bar's dead-centre positions (crank and coupler in line:
    the rocker at a limit of its swing) and toggle positions (coupler and
    rocker in line: μ = 0 or 180°) passed between two solved rows: the
    time (s), found where the cross product of the two links' vectors
    changes sign on the quintic through each row's pose, velocity and
    acceleration; the crank angle then (rad) and the pin that marks it
    (B for a dead centre, A for a toggle; global, m). Empty when the model
    is not a four-bar."""
    loop = find(model, scene)
    if loop is None or len(t) < 2:
        return []
    col = {n: i for i, n in enumerate(names)}
    if any(f"{b}.{c}" not in col for b in (loop.crank, loop.rocker)
           for c in ("x", "y", "phi", "vx", "vy", "omega", "ax", "ay", "alpha")):
        return []
    # The crank's and the rocker's (x, y, φ), then their velocities, then
    # their accelerations.
    motion = values[:, [col[f"{b}.{c}"] for trio in (("x", "y", "phi"), ("vx", "vy", "omega"),
                                                     ("ax", "ay", "alpha"))
                        for b in (loop.crank, loop.rocker) for c in trio]]
    solved = np.all(np.isfinite(motion), axis=1)
    if ok is not None:
        solved &= np.asarray(ok, dtype=bool)
    crank, rocker = motion[:, [0, 1, 2]], motion[:, [3, 4, 5]]
    (o2x, o2y), (o4x, o4y) = loop.o2, loop.o4
    step: dict[int, Array] = {}

    def pins(k: int, s: float) -> tuple[float, float, float, float, float]:
        """A, B (global, m) and the crank angle (rad) at row k + s."""
        if k not in step:
            step[k] = _quintics(float(t[k + 1] - t[k]), motion, k)
        cx, cy, cp, rx, ry, rp = (float(v) for v in step[k] @ (s ** _POWERS))
        sa, sb = loop.a_on_crank, loop.b_on_rocker
        ax = cx + math.cos(cp) * sa[0] - math.sin(cp) * sa[1]
        ay = cy + math.sin(cp) * sa[0] + math.cos(cp) * sa[1]
        bx = rx + math.cos(rp) * sb[0] - math.sin(rp) * sb[1]
        by = ry + math.sin(rp) * sb[0] + math.cos(rp) * sb[1]
        return ax, ay, bx, by, cp

    # The cross products, of a row's pins (floats) or of every row's (arrays).
    def dead(p: Any) -> Any:
        ax, ay, bx, by, _ = p
        return (ax - o2x) * (by - ay) - (ay - o2y) * (bx - ax)

    def toggle(p: Any) -> Any:
        ax, ay, bx, by, _ = p
        return (bx - ax) * (o4y - by) - (by - ay) * (o4x - bx)

    # Both cross products at every row, for the steps where one changes sign.
    sa, sb = loop.a_on_crank, loop.b_on_rocker
    cc, sc = np.cos(crank[:, 2]), np.sin(crank[:, 2])
    cr, sr = np.cos(rocker[:, 2]), np.sin(rocker[:, 2])
    rows = (crank[:, 0] + cc * sa[0] - sc * sa[1], crank[:, 1] + sc * sa[0] + cc * sa[1],
            rocker[:, 0] + cr * sb[0] - sr * sb[1], rocker[:, 1] + sr * sb[0] + cr * sb[1],
            crank[:, 2])
    out: list[dict[str, object]] = []
    both = solved[:-1] & solved[1:]
    for kind, f in (("dead centre", dead), ("toggle", toggle)):
        g = f(rows)
        for row in np.flatnonzero(both & (g[:-1] * g[1:] <= 0) & (g[1:] != 0)):
            k = int(row)
            f0, f1 = float(g[k]), float(g[k + 1])
            # Regula falsi (Illinois) on the step's quintic.
            a, b, fa, fb, side, s = 0.0, 1.0, f0, f1, 0, 0.0
            for _ in range(80):
                s = (a * fb - b * fa) / (fb - fa)
                fs = f(pins(k, s))
                if fs == 0.0 or b - a < 1e-14:
                    break
                if fs * fb > 0:
                    b, fb = s, fs
                    fa = fa / 2 if side == -1 else fa
                    side = -1
                else:
                    a, fa = s, fs
                    fb = fb / 2 if side == 1 else fb
                    side = 1
            p = pins(k, s)
            x, y = (p[2], p[3]) if kind == "dead centre" else (p[0], p[1])
            out.append({"t": float(t[k] + s * (t[k + 1] - t[k])), "kind": kind, "label": kind,
                        "crank": float(p[4]), "x": float(x), "y": float(y)})
    out.sort(key=lambda m: float(m["t"]))  # type: ignore[arg-type]
    return out
