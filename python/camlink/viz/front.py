"""The data the browser front end (``web/camlink.js``) draws: a model's
scene in body frames, the motion, traces, springs, forces and channels.

Shared by the studio (`camlink.studio`) and the viewer file
(`camlink.viz.viewer`). Units: m, rad, s; arrays are float64 in base64
(``{"f64": …}``) unless noted.
"""

from __future__ import annotations

import base64
from collections.abc import Callable, Mapping, Sequence
from importlib import resources
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from camlink.viz.fourbar import marks
from camlink.viz.scene import GROUND, Scene

if TYPE_CHECKING:
    from camlink.model import Model

__all__ = ["asset", "default_plots", "extent", "frame_data", "scene_data"]

Array = npt.NDArray[np.float64]


def asset(name: str) -> str:
    """The text of a packaged front-end file (``web/NAME``)."""
    return resources.files("camlink.viz").joinpath("web", name).read_text(encoding="utf-8")


def b64(a: npt.ArrayLike, dtype: str = "f64") -> dict[str, str]:
    """A float array as little-endian float64 (or ``"f32"``) in base64."""
    little = np.ascontiguousarray(a, dtype="<f8" if dtype == "f64" else "<f4")
    return {dtype: base64.b64encode(little.tobytes()).decode("ascii")}


def _flat(points: npt.ArrayLike) -> list[float]:
    return [round(float(v), 12) for v in np.asarray(points, dtype=np.float64).ravel()]


def scene_data(model: Model, scene: Scene, size: float,
               flat: Callable[[Array], Any] | None = None) -> dict[str, Any]:
    """`scene` for the page: every shape in its body's frame (m), the
    points of links, outlines and curves (x and y interleaved) as `flat`
    gives them (a list of numbers by default); guides and faces drawn
    `size` (m) long at most."""
    half = 0.35 * size
    flat = flat or _flat
    return {
        "links": [{"body": lk.body, "points": flat(lk.points)} for lk in scene.links],
        "outlines": [{"body": b, "points": flat(p)} for b, p in scene.outlines.items()],
        "pins": [{"name": p.joint, "body_i": p.body_i, "s_i": list(p.s_i), "body_j": p.body_j,
                  "s_j": list(p.s_j), "grounded": p.grounded} for p in scene.pins],
        "guides": [{"name": g.joint, "body_i": g.body_i, "s_i": list(g.s_i), "v_i": _unit(g.v_i),
                    "body_j": g.body_j, "s_j": list(g.s_j), "half": half} for g in scene.guides],
        "curves": [{"name": c.joint, "body": c.body, "points": flat(c.points), "closed": c.closed,
                    "role": c.role} for c in scene.curves],
        "gears": [{"body": g.body, "centre": list(g.centre), "radius": g.radius} for g in scene.gears],
        "faces": [{"body": f.body, "s": list(f.s), "u": _unit(f.u), "half": 0.5 * half}
                  for f in scene.faces],
        "rods": [{"body_i": r.body_i, "s_i": list(r.s_i), "body_j": r.body_j, "s_j": list(r.s_j)}
                 for r in scene.rods],
    }


def _unit(v: Sequence[float]) -> list[float]:
    n = float(np.hypot(v[0], v[1])) or 1.0
    return [float(v[0]) / n, float(v[1]) / n]


def springs(model: Model, scene: Scene | None = None) -> list[dict[str, Any]]:
    """Spring–damper–actuators between two body points: a spring (a
    zigzag) and a damper (a dashpot) for each that has them; a torsion
    spring (a spiral) round the pin joining its two bodies."""
    out = []
    for f in model._core.forces:
        if f["kind"] == "rsda" and scene is not None:
            bi, bj = f["bodies"]
            pin = next((p for p in scene.pins if {p.body_i, p.body_j} == {bi, bj}), None)
            if pin is not None:
                out.append({"name": f["name"], "kind": "torsion", "body_i": pin.body_i,
                            "s_i": list(pin.s_i), "body_j": pin.body_i, "s_j": list(pin.s_i)})
            continue
        if f["kind"] != "tsda" or f["s_i"] is None or f["s_j"] is None:
            continue
        bi, bj = f["bodies"]
        k, c = float(f["stiffness"] or 0.0), float(f["damping"] or 0.0)
        kinds = ["spring"] * (k != 0.0 or c == 0.0) + ["damper"] * (c != 0.0)
        for kind in kinds:
            out.append({"name": f["name"], "kind": kind, "body_i": bi, "s_i": list(f["s_i"]),
                        "body_j": bj, "s_j": list(f["s_j"])})
    return out


def traces(points: Sequence[str], names: Sequence[str]) -> list[dict[str, str]]:
    """The traced body points (``"coupler.P"``) whose ``.x``, ``.y``
    channels the run has."""
    have = set(names)
    return [{"name": p, "x": f"{p}.x", "y": f"{p}.y"} for p in points
            if f"{p}.x" in have and f"{p}.y" in have]


def forces(scene: Scene, names: Sequence[str]) -> list[dict[str, Any]]:
    """Pins whose force on body j (``<joint>.fx_j``, ``.fy_j``, N) the run
    has, drawn as arrows at the pin."""
    have = set(names)
    return [{"joint": p.joint, "fx": f"{p.joint}.fx_j", "fy": f"{p.joint}.fy_j",
             "body": p.body_i, "s": list(p.s_i)}
            for p in scene.pins if f"{p.joint}.fx_j" in have and f"{p.joint}.fy_j" in have]


def _column(names: Sequence[str], values: Array, name: str) -> Array:
    return values[:, list(names).index(name)]


def default_plots(bodies: Sequence[str], points: Sequence[str], t: Array,
                  names: Sequence[str], values: Array) -> list[str]:
    """Two channels worth seeing: the first traced point's y (a coupler
    trace coordinate), and the last body's angle or coordinate that is not
    a straight ramp in time (an output angle, a follower's lift)."""
    have = set(names)
    ok = np.all(np.isfinite(values), axis=1) if values.size else np.zeros(0, dtype=bool)
    out: list[str] = []

    def curved(name: str) -> float:
        v = _column(names, values, name)[ok]
        if v.size < 3:
            return 0.0
        tt = t[ok]
        fit = np.polyval(np.polyfit(tt, v, 1), tt)
        return float(np.ptp(v - fit))

    for p in points:
        pair = [c for c in (f"{p}.x", f"{p}.y") if c in have]
        if pair:
            out.append(max(pair, key=lambda c: float(np.ptp(_column(names, values, c)[ok]))
                           if ok.any() else 0.0))
            break
    traced = {c.split(".")[0] for c in out}
    for body in reversed(bodies):
        if body in traced:
            continue
        best = max((c for c in (f"{body}.phi", f"{body}.x", f"{body}.y") if c in have),
                   key=curved, default=None)
        if best is not None and curved(best) > 1e-9:
            out.append(best)
            break
    out += [c for c in names if c.endswith(".pressure_angle")][:1]
    if len(out) < 2:
        out += [c for c in names if c not in out and curved(c) > 1e-9][: 2 - len(out)]
    return out[:2] if len(out) >= 2 else [*out, *[c for c in names if c not in out]][:2]


def extent(scene: Scene, bodies: Sequence[str], poses: dict[str, Array],
           extra: Sequence[Array] = ()) -> tuple[float, float, float, float]:
    """(x0, x1, y0, y1) (m) framing every point of the scene at every row,
    with a margin."""
    xs: list[Array] = []
    ys: list[Array] = []
    for e in extra:
        pair = np.asarray(e).reshape(-1, 2)
        xs.append(pair[:, 0])
        ys.append(pair[:, 1])
    local: dict[str, list[Array]] = {}
    for body, named in scene.points.items():
        if named:
            local.setdefault(body, []).append(np.asarray(list(named.values())))
    for curve in scene.curves:
        local.setdefault(curve.body, []).append(curve.points[:: max(1, len(curve.points) // 64)])
    for body, arrs in local.items():
        sl = np.vstack(arrs)
        q = poses.get(body) if body != GROUND else np.zeros((1, 3))
        if q is None:
            continue
        q = q[np.isfinite(q[:, 0]) & np.isfinite(q[:, 1]) & np.isfinite(q[:, 2])]
        q = q[:: max(1, len(q) // 90)]
        cq, sq = np.cos(q[:, 2:3]), np.sin(q[:, 2:3])
        xs.append((q[:, 0:1] + cq * sl[:, 0] - sq * sl[:, 1]).ravel())
        ys.append((q[:, 1:2] + sq * sl[:, 0] + cq * sl[:, 1]).ravel())
    # Each coordinate apart (a reduction along a long axis, not across pairs).
    x = np.concatenate(xs) if xs else np.zeros(1)
    y = np.concatenate(ys) if ys else np.zeros(1)
    ok = np.isfinite(x) & np.isfinite(y)
    if not ok.any():
        x, y, ok = np.zeros(1), np.zeros(1), np.ones(1, dtype=bool)
    x, y = x[ok], y[ok]
    lo, hi = (float(x.min()), float(y.min())), (float(x.max()), float(y.max()))
    size = float(np.hypot(hi[0] - lo[0], hi[1] - lo[1])) or 1.0
    pad = 0.12 * size
    return (lo[0] - pad, hi[0] + pad, lo[1] - pad, hi[1] + pad)


def frame_data(
    model: Model,
    scene: Scene,
    t: Array,
    names: Sequence[str],
    values: Array,
    ok: npt.NDArray[np.bool_] | None,
    *,
    points: Sequence[str] = (),
    plots: Sequence[str] | None = None,
    pose_dtype: str = "f64",
    channels: Sequence[str] | None = None,
    all_names: bool = False,
    units: Mapping[str, str] | None = None,
    encode: Callable[[Array, str], Any] = b64,
    flat: Callable[[Array], Any] | None = None,
) -> dict[str, Any]:
    """Everything the page draws for a run: `values` (rows × `names`,
    NaN on rows where `ok` is false) over the times `t`; `channels` limits
    the channels sent (default all); with `all_names`, every channel is
    named and only those sent have values (the others null). Each array
    is given as `encode(array, dtype)`: base64 text by default (`b64`);
    the scene's shapes as `flat` gives them (`scene_data`)."""
    bodies = list(scene.bodies)
    index = {n: i for i, n in enumerate(names)}

    def column(name: str) -> Array:
        return values[:, index[name]]

    poses: dict[str, Array] = {}
    for b in bodies:
        poses[b] = values[:, [index[f"{b}.{c}"] for c in ("x", "y", "phi")]]
    tr = traces(points, names)
    extra = [np.column_stack([column(x["x"]), column(x["y"])]) for x in tr]
    box = extent(scene, bodies, poses, extra)
    size = float(np.hypot(box[1] - box[0], box[3] - box[2]))
    chosen = list(plots) if plots else default_plots(bodies, points, t, names, values)
    sent = list(names) if channels is None else list(dict.fromkeys([*channels, *chosen]))
    base: dict[str, Any] = {
        "title": model.name,
        "t": encode(t, "f64"),
        "ok": None if ok is None else np.asarray(ok, dtype=np.int64).tolist(),
        "bodies": [GROUND, *bodies],
        "poses": [encode(poses[b].ravel(), pose_dtype) for b in bodies],
        "scene": scene_data(model, scene, size, flat),
        "traces": tr,
        "springs": springs(model, scene),
        "forces": forces(scene, names),
        "cams": scene.cam_bodies(),
        "box": list(box),
        "plots": chosen,
        "marks": marks(model, scene, t, list(names), values, ok),
    }
    units = units or {}
    if all_names:
        # Every name, values for those in `sent` only (null for the rest).
        have = set(sent)
        return {**base, "channels": {
            "names": list(names), "units": [units.get(c, "") for c in names],
            "values": [encode(_column(names, values, c), pose_dtype) if c in have else None
                       for c in names]}}
    return {**base, "channels": {
        "names": sent, "units": [units.get(c, "") for c in sent],
        "values": [encode(_column(names, values, c), pose_dtype) for c in sent]}}
