"""The geometry of a mechanism, in body frames, as the drawings, animations
and the browser viewer show it.

`Scene.of(model)` collects, from the model alone, every shape a picture
needs: links through each body's joint and named points, pins, guides,
sliders, cam and follower curves, flat faces, slots and gear pitch circles.
Every shape is a set of points in its body's frame (m); `poses` places the
bodies at each output row of a run, and `place` moves local points to the
global frame. Units: m, rad.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

if TYPE_CHECKING:
    from camlink.model import Model
    from camlink.results import Results

__all__ = ["CurveShape", "Face", "GearCircle", "Guide", "Link", "Pin", "Rod", "Scene", "place"]

Array = npt.NDArray[np.float64]

GROUND = "ground"


@dataclass(frozen=True)
class Link:
    """A body's link shape: the attachment points `points` (k × 2, body
    frame, m) it runs through. Two points make a bar with rounded ends,
    more a rounded polygon round them, one a hub."""

    body: str
    points: Array


@dataclass(frozen=True)
class Pin:
    """A pin joining two bodies: `s_i` on `body_i`, `s_j` on `body_j`
    (body frames, m); `grounded` when either body is the ground."""

    joint: str
    body_i: str
    s_i: tuple[float, float]
    body_j: str
    s_j: tuple[float, float]
    grounded: bool


@dataclass(frozen=True)
class Guide:
    """A translational joint: the guide line through `s_i` along `v_i` on
    `body_i`, and the slider block of `body_j` centred at `s_j` (m)."""

    joint: str
    body_i: str
    s_i: tuple[float, float]
    v_i: tuple[float, float]
    body_j: str
    s_j: tuple[float, float]


@dataclass(frozen=True)
class CurveShape:
    """A curve carried by `body`: `points` (n × 2, body frame, m) within the
    sampling tolerance of the exact curve; `role` is ``"cam"`` (a closed
    profile, filled), ``"roller"`` (a follower's closed curve), ``"slot"``
    (drawn as a double line) or ``"curve"`` (an open profile)."""

    joint: str
    body: str
    points: Array
    closed: bool
    role: str


@dataclass(frozen=True)
class GearCircle:
    """A gear's pitch circle on `body`: centre (body frame, m) and radius
    (m); `internal` for a ring gear."""

    joint: str
    body: str
    centre: tuple[float, float]
    radius: float
    internal: bool


@dataclass(frozen=True)
class Face:
    """A flat follower face (or a rack's pitch line) on `body`: the line
    through `s` along the unit vector `u` (body frame)."""

    joint: str
    body: str
    s: tuple[float, float]
    u: tuple[float, float]


@dataclass(frozen=True)
class Rod:
    """A massless distance link (revolute–revolute joint) from `s_i` on
    `body_i` to `s_j` on `body_j` (body frames, m)."""

    joint: str
    body_i: str
    s_i: tuple[float, float]
    body_j: str
    s_j: tuple[float, float]


@dataclass(frozen=True)
class Scene:
    """Every shape of a model, in body frames. `bodies` lists the moving
    bodies; the ground is ``"ground"``."""

    name: str
    bodies: list[str]
    points: dict[str, dict[str, tuple[float, float]]]
    links: list[Link] = field(default_factory=list)
    pins: list[Pin] = field(default_factory=list)
    guides: list[Guide] = field(default_factory=list)
    curves: list[CurveShape] = field(default_factory=list)
    gears: list[GearCircle] = field(default_factory=list)
    faces: list[Face] = field(default_factory=list)
    rods: list[Rod] = field(default_factory=list)
    #: Outlines the model file gives (``outline``), by body: closed
    #: polylines (n × 2, body frame, m) drawn instead of the derived link.
    outlines: dict[str, Array] = field(default_factory=dict)
    #: Bodies and placements (x, y, φ) of the model file (m, m, rad).
    placement: dict[str, tuple[float, float, float]] = field(default_factory=dict)

    @classmethod
    def of(cls, model: Model, tol: float = 1e-4) -> Scene:
        """The scene of `model`, curves sampled within `tol` (m)."""
        core = model._core
        points: dict[str, dict[str, tuple[float, float]]] = {
            GROUND: {k: (float(v[0]), float(v[1])) for k, v in core.ground_points.items()}
        }
        placement: dict[str, tuple[float, float, float]] = {GROUND: (0.0, 0.0, 0.0)}
        for b in model.bodies:
            points[b["name"]] = {k: (float(v[0]), float(v[1])) for k, v in b["points"].items()}
            placement[b["name"]] = (float(b["position"][0]), float(b["position"][1]), float(b["angle"]))
        scene = cls(model.name, [b["name"] for b in model.bodies], points, placement=placement,
                    outlines={k: np.asarray(v, dtype=np.float64) for k, v in core.outlines(tol).items()})
        attach: dict[str, list[tuple[float, float]]] = {
            name: list(p.values()) for name, p in points.items()
        }

        def pt(v: list[float]) -> tuple[float, float]:
            return (float(v[0]), float(v[1]))

        # Each joint's sketch: generic marks in body frames (Model.geometry).
        for j in core.geometry(tol):
            if j["driver"]:
                continue
            name = j["name"]
            bi, bj = j["bodies"]
            for m in j["marks"]:
                shape = m["shape"]
                if shape == "pin":
                    pin = Pin(name, bi, pt(m["s_i"]), bj, pt(m["s_j"]), GROUND in (bi, bj))
                    scene.pins.append(pin)
                    attach[bi].append(pin.s_i)
                    attach[bj].append(pin.s_j)
                elif shape == "slider":
                    body, s = m["body"], pt(m["s"])
                    scene.pins.append(Pin(name, body, s, body, s, False))
                    attach[body].append(s)
                elif shape == "rod":
                    scene.rods.append(Rod(name, bi, pt(m["s_i"]), bj, pt(m["s_j"])))
                elif shape == "guide":
                    scene.guides.append(Guide(name, bi, pt(m["s_i"]), pt(m["v_i"]), bj, pt(m["s_j"])))
                elif shape == "face":
                    scene.faces.append(Face(name, m["body"], pt(m["s"]), pt(m["u"])))
                elif shape == "circle":
                    scene.gears.append(
                        GearCircle(name, m["body"], pt(m["s"]), m["radius"], bool(m["internal"]))
                    )
                elif shape == "curve":
                    scene.curves.append(
                        CurveShape(name, m["body"], np.asarray(m["points"]), bool(m["closed"]), m["role"])
                    )
        for body in scene.bodies:
            unique = _unique(attach[body])
            if len(unique) >= 2 and body not in scene.outlines:
                scene.links.append(Link(body, np.asarray(unique)))
        return scene

    def poses(self, results: Results | None) -> dict[str, Array]:
        """Each body's (x, y, φ) per output row (rows × 3; m, m, rad); one
        row of the file's placement when there are no results."""
        out: dict[str, Array] = {}
        n = len(results) if results is not None else 1
        out[GROUND] = np.zeros((n, 3))
        for b in self.bodies:
            if results is not None:
                out[b] = np.column_stack([results[f"{b}.x"], results[f"{b}.y"], results[f"{b}.phi"]])
            else:
                out[b] = np.asarray([self.placement[b]])
        return out

    def point_path(self, name: str, poses: dict[str, Array]) -> Array:
        """Global path (rows × 2, m) of the body point ``"body.point"``."""
        body, _, point = name.partition(".")
        if body not in poses or point not in self.points.get(body, {}):
            known = [f"{b}.{p}" for b in self.points for p in self.points[b]]
            raise KeyError(
                f"no body point {name!r} (points: {', '.join(known) or 'none'})"
            )
        s = np.asarray(self.points[body][point])
        pose = poses[body]
        return np.stack([place(s[None, :], q)[0] for q in pose])

    def cam_bodies(self) -> list[str]:
        """Bodies that carry a cam profile."""
        return list(dict.fromkeys(c.body for c in self.curves if c.role == "cam"))


def place(local: npt.ArrayLike, q: npt.ArrayLike) -> Array:
    """Body-frame points (k × 2, m) in the global frame for the pose
    q = (x, y, φ): r + A(φ) s′."""
    s = np.asarray(local, dtype=np.float64).reshape(-1, 2)
    x, y, phi = (float(v) for v in np.asarray(q).ravel()[:3])
    c, si = np.cos(phi), np.sin(phi)
    return np.column_stack([x + c * s[:, 0] - si * s[:, 1], y + si * s[:, 0] + c * s[:, 1]])


def _unique(pts: list[tuple[float, float]], tol: float = 1e-9) -> list[tuple[float, float]]:
    out: list[tuple[float, float]] = []
    for p in pts:
        if all(abs(p[0] - q[0]) > tol or abs(p[1] - q[1]) > tol for q in out):
            out.append(p)
    return out
