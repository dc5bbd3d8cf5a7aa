"""The benchmark slider-crank and its minimal-coordinate reference solution.

The model is the one of camlink's accuracy test
(``crates/camlink-core/tests/dynamics_forward.rs``): crank 0.1 m, rod 0.3 m,
in line, gravity −9.81 m/s² along y, a spring from the ground point
(0.6, 0.1) to the slider pin (200 N/m, free length 0.25 m), started at crank
angle 0.3 rad turning at 10 rad/s with consistent velocities.

Frames: the crank's at the ground pivot O (x along O→B), the rod's at its
middle (x along B→C), the slider's at its pin C on the x axis.
"""

from __future__ import annotations

import math

CRANK = 0.1
ROD = 0.3
MASS = (1.0, 2.0, 0.5)
INERTIA = (1.0e-3, 1.5e-2, 1.0e-3)
CRANK_CENTROID = (0.05, 0.0)
ROD_CENTROID = (0.03, 0.0)
G = 9.81
SPRING_POINT = (0.6, 0.1)
SPRING_K = 200.0
SPRING_L0 = 0.25
TH0 = 0.3
W0 = 10.0


class J2:
    """A value with its first two derivatives with respect to θ."""

    __slots__ = ("d1", "d2", "v")

    def __init__(self, v: float, d1: float = 0.0, d2: float = 0.0) -> None:
        self.v, self.d1, self.d2 = v, d1, d2

    def __add__(self, o: J2) -> J2:
        return J2(self.v + o.v, self.d1 + o.d1, self.d2 + o.d2)

    def __sub__(self, o: J2) -> J2:
        return J2(self.v - o.v, self.d1 - o.d1, self.d2 - o.d2)

    def __mul__(self, o: J2 | float) -> J2:
        if not isinstance(o, J2):
            return J2(self.v * o, self.d1 * o, self.d2 * o)
        return J2(
            self.v * o.v,
            self.d1 * o.v + self.v * o.d1,
            self.d2 * o.v + 2.0 * self.d1 * o.d1 + self.v * o.d2,
        )

    def chain(self, g: float, g1: float, g2: float) -> J2:
        """g(self) from g, g', g'' at self.v."""
        return J2(g, g1 * self.d1, g2 * self.d1 * self.d1 + g1 * self.d2)

    def sin(self) -> J2:
        return self.chain(math.sin(self.v), math.cos(self.v), -math.sin(self.v))

    def cos(self) -> J2:
        return self.chain(math.cos(self.v), -math.sin(self.v), -math.cos(self.v))

    def asin(self) -> J2:
        s = 1.0 - self.v * self.v
        return self.chain(math.asin(self.v), 1.0 / math.sqrt(s), self.v / s**1.5)

    def sqrt(self) -> J2:
        r = math.sqrt(self.v)
        return self.chain(r, 0.5 / r, -0.25 / (r * r * r))


def rod_angle(th: float) -> float:
    """ψ of the rod for crank angle θ (sin ψ = −a sin θ / b)."""
    return math.asin(-CRANK * math.sin(th) / ROD)


def slider_x(th: float) -> float:
    return CRANK * math.cos(th) + ROD * math.cos(rod_angle(th))


def bodies(th: float) -> list[tuple[tuple[J2, J2], J2]]:
    """Each body's centroid (x, y) and angle as jets of θ."""
    t = J2(th, 1.0)
    c1, s1 = t.cos(), t.sin()

    def rot(c: J2, s: J2, v: tuple[float, float]) -> tuple[J2, J2]:
        return (c * v[0] - s * v[1], s * v[0] + c * v[1])

    crank = rot(c1, s1, CRANK_CENTROID)
    psi = (s1 * (-CRANK / ROD)).asin()
    c2, s2 = psi.cos(), psi.sin()
    bx, by = c1 * CRANK, s1 * CRANK
    r = rot(c2, s2, (ROD / 2 + ROD_CENTROID[0], ROD_CENTROID[1]))
    rod = (bx + r[0], by + r[1])
    xs = bx + c2 * ROD
    return [(crank, t), (rod, psi), ((xs, J2(0.0)), J2(0.0))]


def rhs(th: float, w: float) -> tuple[float, float]:
    """(θ̇, θ̈) from Lagrange's equation m(θ) θ̈ + ½ m'(θ) θ̇² = Q(θ)."""
    mass = quad = q = 0.0
    bs = bodies(th)
    for k, (r, phi) in enumerate(bs):
        m, j = MASS[k], INERTIA[k]
        mass += m * (r[0].d1 ** 2 + r[1].d1 ** 2) + j * phi.d1**2
        quad += m * (r[0].d1 * r[0].d2 + r[1].d1 * r[1].d2) + j * phi.d1 * phi.d2
        q += -m * G * r[1].d1
    # Spring from its ground point to the slider pin: Q = −k (l − l₀) l'.
    dx = bs[2][0][0] - J2(SPRING_POINT[0])
    length = (dx * dx + J2(SPRING_POINT[1] ** 2)).sqrt()
    q += -SPRING_K * (length.v - SPRING_L0) * length.d1
    return w, (q - quad * w * w) / mass


def reference(t_end: float, h: float) -> tuple[float, float]:
    """(θ, slider x) at t_end by RK4 with step h."""
    th, w = TH0, W0
    for _ in range(round(t_end / h)):
        k1, l1 = rhs(th, w)
        k2, l2 = rhs(th + 0.5 * h * k1, w + 0.5 * h * l1)
        k3, l3 = rhs(th + 0.5 * h * k2, w + 0.5 * h * l2)
        k4, l4 = rhs(th + h * k3, w + h * l3)
        th += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        w += h / 6 * (l1 + 2 * l2 + 2 * l3 + l4)
    return th, slider_x(th)


def initial_state() -> dict[str, tuple[float, float, float, float, float, float]]:
    """Per body: centroid (x, y, φ) and its velocity at θ₀, ω₀."""
    out = {}
    for name, (r, phi) in zip(("crank", "rod", "slider"), bodies(TH0)):
        out[name] = (
            r[0].v,
            r[1].v,
            phi.v,
            r[0].d1 * W0,
            r[1].d1 * W0,
            phi.d1 * W0,
        )
    return out
