"""Building models in code.

`Mechanism` collects the same tables a model file has and loads them through
the same loader (as JSON), so a model built in code and the same model
written as a file are identical. Values may be numbers or expression strings
(``"r/2"``, ``"deg(60) + 2*pi*t"``) exactly as in a file.

    m = camlink.Mechanism("slider_crank")
    m.ground_point("O", (0, 0))
    m.body("crank", angle=0.0, points={"O": (0, 0), "A": (0.1, 0)})
    ...
    m.revolute("O", "ground", "O", "crank", "O")
    m.revolute_driver("motor", "O", f="2*pi*t")
    model = m.build()

Each call is checked as it is made, by the loader's own rules (the model
built so far is loaded through the binding): a call that the loader
refuses (an unknown body, point, curve or joint name, a wrong type, an
unknown joint kind, a bad expression) raises `ModelError` at once, naming
the Python file and line of the call, and leaves the model as it was. A
name must therefore be declared (by an earlier call) before it is used.
What only the whole model can tell (a body that no joint holds) is
reported by `build()`, again with the line of the call that added the
entry at fault.
"""

from __future__ import annotations

import json
import math
import numbers
import os
import sys
from collections.abc import Callable, Mapping, Sequence
from typing import Any, TypeAlias

from camlink import _core
from camlink._core import ModelError
from camlink.model import Model, loads
from camlink.results import Results

__all__ = ["Mechanism"]

Num: TypeAlias = float | int | str
Vec2: TypeAlias = tuple[Num, Num] | list[Num]
PointRef: TypeAlias = str | Vec2


def _value(v: Any) -> Any:
    """Plain JSON values: tuples and arrays to lists, NumPy scalars to floats."""
    if isinstance(v, str | bool) or v is None:
        return v
    if isinstance(v, numbers.Integral):
        return int(v)
    if isinstance(v, numbers.Real):
        return float(v)
    if isinstance(v, dict):
        return {str(k): _value(x) for k, x in v.items()}
    if hasattr(v, "tolist"):
        return _value(v.tolist())
    if isinstance(v, list | tuple):
        return [_value(x) for x in v]
    raise TypeError(f"cannot put a {type(v).__name__} ({v!r}) into a model")


def _fields(**kw: Any) -> dict[str, Any]:
    """Keyword arguments that were given, as model-file fields."""
    return {k: _value(v) for k, v in kw.items() if v is not None}


def _caller() -> str:
    """``file:line`` of the code that called into this module."""
    f = sys._getframe(1)
    while f.f_back is not None and f.f_code.co_filename == __file__:
        f = f.f_back
    return f"{f.f_code.co_filename}:{f.f_lineno}"


def _within(field: str, prefix: str) -> bool:
    """True when the field path `field` is `prefix` or inside it."""
    return field == prefix or (field.startswith(prefix) and field[len(prefix)] in ".[")


class Mechanism:
    """A model under construction, with one method per model-file table."""

    def __init__(
        self,
        name: str,
        gravity: Vec2 | None = None,
        *,
        units: Mapping[str, str] | None = None,
        base_dir: str | os.PathLike[str] | None = None,
    ) -> None:
        """`gravity` (m/s², in the model's length unit per s²): the
        ``[model]`` table's; `units`: the units the model's values are
        written in, as the ``[model]`` table's ``units``, e.g.
        ``{"length": "mm", "angle": "deg"}`` (default metres and radians;
        docs/units.md); `base_dir`: the folder data files (a spline's
        ``file``) resolve against, and must lie in; default: the current
        folder."""
        self._model: dict[str, Any] = _fields(name=name, gravity=gravity, units=units)
        self._base_dir = base_dir
        self._curves: list[dict[str, Any]] = []
        self._parameters: dict[str, Any] = {}
        self._ground_points: dict[str, Any] = {}
        self._bodies: list[dict[str, Any]] = []
        self._joints: list[dict[str, Any]] = []
        self._drivers: list[dict[str, Any]] = []
        self._forces: list[dict[str, Any]] = []
        self._python_forces: list[tuple[str, str, Callable[..., Any]]] = []
        self._analysis: dict[str, Any] = {}
        #: Where each entry was added: field path prefix → ``file:line``.
        self._sites: dict[str, str] = {}

    @property
    def name(self) -> str:
        return self._model["name"]

    # -- parameters and bodies ------------------------------------------

    def parameter(self, name: str, value: Num) -> str:
        """A named parameter usable in expressions; returns its name."""
        self._keyed(self._parameters, name, _value(value), f"parameters.{name}")
        return name

    def ground_point(self, name: str, xy: Vec2) -> str:
        """A named point of the ground (m); returns its name."""
        self._keyed(self._ground_points, name, _value(xy), f"ground.points.{name}")
        return name

    def body(
        self,
        name: str,
        position: Vec2 | None = None,
        angle: Num | None = None,
        *,
        mass: Num | None = None,
        inertia: Num | None = None,
        centroid: Vec2 | None = None,
        velocity: Vec2 | None = None,
        omega: Num | None = None,
        points: dict[str, Vec2] | None = None,
        global_points: dict[str, Vec2] | None = None,
    ) -> str:
        """A rigid body: initial (or guessed) position (m) and angle (rad),
        mass (kg), inertia about the centroid (kg·m²), named points in the
        body frame (m), or `global_points` at their global positions at the
        initial instant (m; see `link`). Returns its name."""
        self._append(
            "bodies",
            self._bodies,
            _fields(
                name=name,
                position=position,
                angle=angle,
                mass=mass,
                inertia=inertia,
                centroid=centroid,
                velocity=velocity,
                omega=omega,
                points=dict(points) if points else None,
                global_points=dict(global_points) if global_points else None,
            ),
        )
        return name

    def link(
        self,
        name: str,
        /,
        *,
        mass: Num | None = None,
        inertia: Num | None = None,
        centroid: Vec2 | None = None,
        velocity: Vec2 | None = None,
        omega: Num | None = None,
        **points: Vec2,
    ) -> str:
        """A rigid body given as read off a drawing: its named points at
        their global positions at the initial instant (m), e.g.
        ``link("coupler", A=(0.1, 0.2), B=(0.5, 0.3))``. The body frame is
        at the mean of the points with angle 0, and `centroid` is global too
        (docs/model-files.md, "Bodies in global coordinates"). Returns its
        name."""
        if not points:
            raise ModelError(f"link {name!r}: give at least one point, e.g. A=(x, y)")
        return self.body(
            name,
            mass=mass,
            inertia=inertia,
            centroid=centroid,
            velocity=velocity,
            omega=omega,
            global_points=points,
        )

    def point(self, body: str, name: str, xy: Vec2) -> str:
        """Adds a named point to `body` (or to ``"ground"``): in the body
        frame (m), or global at the initial instant for a body given by
        global points (`link`); returns ``"body.name"``."""
        if body == "ground":
            self.ground_point(name, xy)
            return f"ground.{name}"
        for k, b in enumerate(self._bodies):
            if b["name"] == body:
                # A body given by global points takes more of them.
                key = "global_points" if "global_points" in b else "points"
                try:
                    self._keyed(b.setdefault(key, {}), name, _value(xy), f"bodies[{k}].{key}.{name}")
                finally:
                    if not b[key]:
                        del b[key]
                return f"{body}.{name}"
        known = ", ".join(b["name"] for b in self._bodies) or "none yet"
        raise KeyError(f"no body named {body!r} (bodies: {known})")

    # -- curves ---------------------------------------------------------

    def curve(self, name: str, body: str, source: str, **fields: Any) -> str:
        """A ``[[curves]]`` entry: a curve on `body` from `source`
        (``circle``, ``line``, ``arc``, ``expression``, ``fourier``,
        ``spline``) with the fields of model-files.md, e.g.
        ``curve("lobe", "cam", "expression", kind="polar", rho="1 + 0.2*cos(a)")``
        or ``curve("slot", "rocker", "spline", kind="parametric", file="slot.csv")``.
        Returns its name, for ``curve_i`` / ``curve_j`` of a contact joint."""
        self._append(
            "curves", self._curves, {"name": name, "body": body, "source": source, **_fields(**fields)}
        )
        return name

    # -- joints ---------------------------------------------------------

    def joint(self, name: str, type: str, **fields: Any) -> str:
        """Any joint of the model-file schema, e.g.
        ``joint("g", "gear", body_i=…, radius_i=…, …)``; returns its name."""
        self._append("joints", self._joints, {"name": name, "type": type, **_fields(**fields)})
        return name

    def revolute(
        self,
        name: str,
        body_i: str,
        point_i: PointRef | None,
        body_j: str,
        point_j: PointRef | None,
        *,
        limits: Mapping[str, Num] | None = None,
        friction: Mapping[str, Num] | None = None,
    ) -> str:
        """Point `point_i` of `body_i` coincides with `point_j` of `body_j`.
        `limits`: end stops on the angle of body j relative to body i, e.g.
        ``{"lower": "-pi/4", "upper": "pi/2", "restitution": 0.6}`` (rad);
        `friction`: Coulomb friction in the pin, e.g. ``{"mu": 0.1,
        "radius": 0.01}`` (radius in m); the fields of model-files.md."""
        return self.joint(
            name,
            "revolute",
            body_i=body_i,
            point_i=point_i,
            body_j=body_j,
            point_j=point_j,
            limits=limits,
            friction=friction,
        )

    def translational(
        self,
        name: str,
        body_i: str,
        point_i: PointRef | None,
        body_j: str,
        point_j: PointRef | None,
        axis: Vec2,
        angle: Num | None = None,
        *,
        limits: Mapping[str, Num] | None = None,
        friction: Mapping[str, Num] | None = None,
    ) -> str:
        """`point_j` slides on the line through `point_i` along `axis` (body i
        frame); the relative angle stays `angle` (default: its initial value).
        `limits`: end stops on the stroke along the axis, e.g. ``{"lower":
        -0.1, "upper": 0.1, "restitution": 0.5}`` (m); `friction`: Coulomb
        friction on the guide, e.g. ``{"mu": 0.3}``; the fields of
        model-files.md."""
        return self.joint(
            name,
            "translational",
            body_i=body_i,
            point_i=point_i,
            axis=axis,
            body_j=body_j,
            point_j=point_j,
            angle=angle,
            limits=limits,
            friction=friction,
        )

    def revolute_revolute(
        self,
        name: str,
        body_i: str,
        point_i: PointRef | None,
        body_j: str,
        point_j: PointRef | None,
        length: Num | None = None,
    ) -> str:
        """A massless link of `length` (m) between two body points."""
        return self.joint(
            name,
            "revolute_revolute",
            body_i=body_i,
            point_i=point_i,
            body_j=body_j,
            point_j=point_j,
            length=length,
        )

    # -- drivers --------------------------------------------------------

    def driver(self, name: str, type: str, **fields: Any) -> str:
        """Any driver of the model-file schema, e.g.
        ``driver("lift", "absolute_y", body="slider", f="0.1*sin(t)")``."""
        self._append("drivers", self._drivers, {"name": name, "type": type, **_fields(**fields)})
        return name

    def revolute_driver(self, name: str, joint: str, f: Num) -> str:
        """The angle of revolute `joint` = f(t) (rad)."""
        return self.driver(name, "revolute_angle", joint=joint, f=f)

    def translational_driver(self, name: str, joint: str, f: Num) -> str:
        """The travel along translational `joint` = f(t) (m)."""
        return self.driver(name, "translational_travel", joint=joint, f=f)

    # -- analysis and output ------------------------------------------

    # -- forces ---------------------------------------------------------

    def force(self, type: str, name: str | None = None, **fields: Any) -> str | None:
        """A ``[[forces]]`` entry: ``point_force``, ``torque``, ``tsda`` or
        ``rsda`` with the fields of model-files.md."""
        self._append("forces", self._forces, _fields(type=type, name=name, **fields))
        return name

    def python_force(
        self,
        name: str,
        body: str,
        f: Callable[[float, tuple[float, float, float], tuple[float, float, float]],
                    Sequence[float]],
    ) -> str:
        """A force computed in Python by ``f(t, q, qd) -> (fx, fy, torque)``
        on `body` (the slow path; see `Model.with_force`). It is added by
        `build()` and has no model-file form."""
        names = [b["name"] for b in self._bodies]
        if body not in names:
            known = ", ".join(names) or "none yet"
            raise ModelError(
                f"{_caller()}: python_force {name!r}: no moving body named {body!r} "
                f"(bodies: {known})"
            )
        self._python_forces.append((name, body, f))
        return name

    # -- analysis and output ------------------------------------------

    def analysis(
        self,
        t_end: Num | None = None,
        step: Num | None = None,
        *,
        type: str | None = None,
        times: list[Num] | None = None,
        time: Num | None = None,
        tol: Num | None = None,
        max_iter: int | None = None,
        points: list[str] | None = None,
        **dynamics: Any,
    ) -> None:
        """The analysis type, time grid, solver settings and output points;
        `dynamics` are the integrator keys of model-files.md (``h``,
        ``rho_inf``, ``adaptive``, ``atol``, ``rtol``, ``h_min``,
        ``projection_tol``). Each call adds to the table; a `type` other
        than the current one starts it afresh."""
        before = dict(self._analysis)
        if type is not None and type != self._analysis.get("type", "kinematics"):
            self._analysis.clear()
        self._analysis.update(
            _fields(
                type=type,
                t_end=t_end,
                step=step,
                times=times,
                time=time,
                tol=tol,
                max_iter=max_iter,
                points=points,
                **dynamics,
            )
        )
        self._sites["analysis"] = _caller()
        error = self._error_within("analysis")
        if error is not None:
            self._analysis.clear()
            self._analysis.update(before)
            raise error

    # -- checks at each call ----------------------------------------------

    def _append(self, section: str, items: list[dict[str, Any]], item: dict[str, Any]) -> None:
        """Adds `item` to `section`, or raises the loader's error about it
        and leaves the model as it was."""
        items.append(item)
        where = f"{section}[{len(items) - 1}]"
        self._sites[where] = _caller()
        error = self._error_within(where)
        if error is not None:
            items.pop()
            del self._sites[where]
            raise error

    def _keyed(self, table: dict[str, Any], key: str, value: Any, where: str) -> None:
        """Sets `table[key]`, or raises the loader's error about the entry
        at `where` and leaves the model as it was."""
        had, old = key in table, table.get(key)
        table[key] = value
        site = self._sites.get(where)
        self._sites[where] = _caller()
        error = self._error_within(where)
        if error is None:
            return
        if had:
            table[key] = old
        else:
            del table[key]
        if site is None:
            del self._sites[where]
        else:
            self._sites[where] = site
        raise error

    def _error_within(self, where: str) -> ModelError | None:
        """The loader's first error about the model so far, when it lies in
        the entry at `where` (a field path prefix)."""
        found = _core.model_error_of(json.dumps(self.to_dict()), "json", self._base_dir)
        if found is None or not _within(found["field"] or "", where):
            return None
        return self._located(found)

    def _located(self, found: dict[str, Any]) -> ModelError:
        """The error `found` (of `_core.model_error_of`) naming the Python
        line of the call that added the entry at fault."""
        field = found["field"] or ""
        sites = [(p, s) for p, s in self._sites.items() if _within(field, p)]
        site = max(sites, key=lambda ps: len(ps[0]))[1] if sites else f"<Mechanism '{self.name}'>"
        what = f"{field}: " if field else ""
        return ModelError(f"{site}: {what}{found['message']}")

    def to_dict(self) -> dict[str, Any]:
        """The model as the model-file tables (JSON-compatible)."""
        d: dict[str, Any] = {"model": dict(self._model)}
        if self._parameters:
            d["parameters"] = dict(self._parameters)
        if self._ground_points:
            d["ground"] = {"points": dict(self._ground_points)}
        for key, items in (
            ("bodies", self._bodies),
            ("curves", self._curves),
            ("joints", self._joints),
            ("drivers", self._drivers),
            ("forces", self._forces),
        ):
            if items:
                d[key] = [dict(x) for x in items]
        if self._analysis:
            d["analysis"] = dict(self._analysis)
        return d

    def to_json(self) -> str:
        return json.dumps(self.to_dict(), indent=2)

    def to_toml(self) -> str:
        """The model as a TOML model file."""
        d = self.to_dict()
        out: list[str] = []
        for key in ("model", "parameters"):
            if key in d:
                out.append(f"[{key}]")
                out += [f"{_key(k)} = {_toml(v)}" for k, v in d[key].items()]
                out.append("")
        if "ground" in d:
            out += ["[ground]", f"points = {_toml(d['ground']['points'])}", ""]
        for key in ("bodies", "curves", "joints", "drivers", "forces"):
            for item in d.get(key, []):
                out.append(f"[[{key}]]")
                out += [f"{_key(k)} = {_toml(v)}" for k, v in item.items()]
                out.append("")
        if "analysis" in d:
            out.append("[analysis]")
            out += [f"{_key(k)} = {_toml(v)}" for k, v in d["analysis"].items()]
            out.append("")
        return "\n".join(out)

    def build(self) -> Model:
        """Validates and loads the model; `ModelError` names the Python
        line of the call that added the entry at fault."""
        found = _core.model_error_of(json.dumps(self.to_dict()), "json", self._base_dir)
        if found is not None:
            raise self._located(found)
        model = loads(
            json.dumps(self.to_dict()),
            "json",
            f"<Mechanism '{self.name}'>",
            base_dir=self._base_dir,
        )
        for name, body, f in self._python_forces:
            model = model.with_force(name, body, f)
        return model

    def run(self, **kwargs: Any) -> Results:
        """`build()` then `Model.run(**kwargs)`."""
        return self.build().run(**kwargs)


def _key(k: str) -> str:
    bare = k and all(c.isalnum() or c in "_-" for c in k)
    return k if bare else json.dumps(k)


def _toml(v: Any) -> str:
    """A TOML value; JSON string escapes are valid TOML basic strings."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_key(k)} = {_toml(x)}" for k, x in v.items()) + " }"
    raise TypeError(f"cannot write {v!r} as TOML")
