"""The dynamics benchmark models as camlink model files (TOML text).

The same mechanisms as ``peer_exudyn.py`` and ``peer_mujoco.py``; body
frames sit where the initial velocities are simplest to state (a frame's
`velocity` is that of its origin).
"""

from __future__ import annotations

import slider_crank as sc


def slider_crank() -> str:
    """Crank frame at the pivot O, rod frame at its centroid, slider frame
    at its pin C; started at θ₀ with consistent velocities."""
    init = sc.initial_state()
    a, b = sc.CRANK, sc.ROD
    rx = b / 2 + sc.ROD_CENTROID[0]
    rod, slider = init["rod"], init["slider"]
    return f"""
[model]
name = "bench slider-crank"
gravity = [0, {-sc.G}]

[ground]
points = {{ O = [0, 0], S = [{sc.SPRING_POINT[0]}, {sc.SPRING_POINT[1]}] }}

[[bodies]]
name = "crank"
angle = {sc.TH0}
omega = {sc.W0}
mass = {sc.MASS[0]}
inertia = {sc.INERTIA[0]}
centroid = [{sc.CRANK_CENTROID[0]}, {sc.CRANK_CENTROID[1]}]
points = {{ O = [0, 0], B = [{a}, 0] }}

[[bodies]]
name = "rod"
position = [{rod[0]!r}, {rod[1]!r}]
angle = {rod[2]!r}
velocity = [{rod[3]!r}, {rod[4]!r}]
omega = {rod[5]!r}
mass = {sc.MASS[1]}
inertia = {sc.INERTIA[1]}
points = {{ B = [{-rx!r}, 0], C = [{b - rx!r}, 0] }}

[[bodies]]
name = "slider"
position = [{slider[0]!r}, 0]
velocity = [{slider[3]!r}, 0]
mass = {sc.MASS[2]}
inertia = {sc.INERTIA[2]}
points = {{ C = [0, 0] }}

[[joints]]
name = "O"
type = "revolute"
body_i = "ground"
point_i = "O"
body_j = "crank"
point_j = "O"

[[joints]]
name = "B"
type = "revolute"
body_i = "crank"
point_i = "B"
body_j = "rod"
point_j = "B"

[[joints]]
name = "C"
type = "revolute"
body_i = "rod"
point_i = "C"
body_j = "slider"
point_j = "C"

[[joints]]
name = "guide"
type = "translational"
body_i = "ground"
point_i = "O"
axis = [1, 0]
body_j = "slider"
point_j = "C"

[[forces]]
name = "spring"
type = "tsda"
body_i = "ground"
point_i = "S"
body_j = "slider"
point_j = "C"
stiffness = {sc.SPRING_K}
free_length = {sc.SPRING_L0}
"""


def chain(n: int, length: float = 0.1) -> str:
    """n links of 1 kg hanging from the origin, horizontal along +x, each
    frame at the link's middle."""
    parts = [
        f"""
[model]
name = "bench chain {n}"
gravity = [0, -9.81]

[ground]
points = {{ O = [0, 0] }}
"""
    ]
    for k in range(n):
        parts.append(
            f"""
[[bodies]]
name = "l{k}"
position = [{(k + 0.5) * length!r}, 0]
mass = 1
inertia = {length**2 / 12!r}
points = {{ A = [{-length / 2}, 0], B = [{length / 2}, 0] }}

[[joints]]
name = "J{k}"
type = "revolute"
body_i = "{"ground" if k == 0 else f"l{k - 1}"}"
point_i = "{"O" if k == 0 else "B"}"
body_j = "l{k}"
point_j = "A"
"""
        )
    return "".join(parts)
