"""The studio's editable model: the file's text as a document, its edits,
undo and redo, the re-solved cycle of each edit, and saving.

A TOML file is held as a tomlkit document, so that an edit changes one
value and keeps every comment and the layout; a JSON file as plain data,
saved with two-space indents. Every edit rebuilds the model from the
document's text through the binding (`camlink.loads`), exactly as the CLI
reads the saved file.

Edits (all lengths m, angles rad, global frame):

- a *handle* (a named body point, or a joint's point on each of its
  bodies) moved to the global point (x, y) at output row k: the point's
  body-frame coordinates become s′ = A(φ_k)ᵀ (r − r_k), with the body's
  pose (r_k, φ_k) at row k of the last solved cycle (the file's placement
  when the cycle has no row k); a point of a ``global_points`` body (or a
  joint's [x, y] on one) becomes its global position in the placement,
  position₀ + A(φ₀) s′; a ground point becomes (x, y);
- a ``[parameters]`` number set to a value.

The cycle is the kinematic run over the file's ``[analysis]`` times (361
times over one second when the file gives none). A time at which the
mechanism does not assemble leaves its row missing (NaN) and the run goes
on from the next time at which it assembles again from the placement.
"""

from __future__ import annotations

import base64
import json
import math
import os
import shutil
import tempfile
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
import tomlkit
import tomlkit.items

import camlink
from camlink._core import AnalysisError, ModelError
from camlink.model import Model
from camlink.units import unit_of
from camlink.viz.scene import GROUND, Scene

__all__ = ["Document", "Handle", "Solution", "solve"]

Array = npt.NDArray[np.float64]

#: Decimal places of a dragged coordinate written to the file (m): a
#: nanometre, far below a pixel at any zoom a mechanism is edited at.
DIGITS = 9
#: Times of the cycle when the file gives none: 361 over one second.
DEFAULT_TIMES = np.linspace(0.0, 1.0, 361)
#: Most restarts tried past a time at which the mechanism does not assemble.
RESTARTS = 180


def b64(a: npt.ArrayLike) -> dict[str, str]:
    """A float array as little-endian float64 in base64, as the page reads it."""
    little = np.ascontiguousarray(a, dtype="<f8")
    return {"f64": base64.b64encode(little.tobytes()).decode("ascii")}


@dataclass(frozen=True)
class Target:
    """One place in the file a handle writes: ``kind`` is ``"ground"``
    (``[ground] points.NAME``), ``"points"`` / ``"global_points"`` (a
    body's named point) or ``"joint"`` (a joint's inline ``point_i`` /
    ``point_j``); `body` is the body the point is on."""

    kind: str
    body: str
    index: int  # the body's or the joint's index in its array (−1 for the ground)
    key: str  # the point's name, or "point_i" / "point_j"


@dataclass(frozen=True)
class Handle:
    """A draggable point: on `body` at `local` (body frame, m), writing
    each of `targets` when moved."""

    id: str
    label: str
    body: str
    local: tuple[float, float]
    targets: tuple[Target, ...]


@dataclass
class Solution:
    """A re-solved cycle: the model, its scene, the full time grid `t`,
    the results' channels over it (NaN on missing rows) and the handles."""

    model: Model
    scene: Scene
    t: Array
    names: list[str]
    values: Array  # rows × channels, NaN where the mechanism did not assemble
    ok: npt.NDArray[np.bool_]
    handles: list[Handle]
    error: str | None = None
    #: Each channel's unit, as the core states it.
    units: dict[str, str] = field(default_factory=dict)

    def pose(self, body: str, row: int) -> tuple[float, float, float]:
        """(x, y, φ) of `body` at `row` (m, m, rad): the nearest solved row,
        else the file's placement."""
        if body == GROUND:
            return (0.0, 0.0, 0.0)
        solved = np.flatnonzero(self.ok)
        if solved.size:
            k = int(solved[np.argmin(np.abs(solved - row))])
            col = {n: i for i, n in enumerate(self.names)}
            return tuple(float(self.values[k, col[f"{body}.{c}"]]) for c in ("x", "y", "phi"))  # type: ignore[return-value]
        return self.scene.placement[body]


def _times(model: Model) -> Array:
    try:
        return np.asarray(model.times(), dtype=np.float64)
    except ModelError:
        return DEFAULT_TIMES.copy()


def _points(model: Model) -> list[str]:
    pts = model.analysis.get("points") or []
    return [str(p) for p in pts]


def _kinematics(
    model: Model, times: Array, points: list[str]
) -> tuple[list[str], Array, dict[str, str]]:
    """Names, rows and units of the kinematic run at `times`, up to the
    first time at which the mechanism does not assemble (no rows when it
    does not at the first)."""
    try:
        res = model.kinematics(times=times, points=points)
    except AnalysisError as e:
        res = e.results
    names = list(res.channels)
    if len(res) == 0:
        return names, np.empty((0, len(names))), res.units
    return names, np.column_stack([res[c] for c in names]), res.units


def solve(
    model: Model,
) -> tuple[Array, list[str], Array, npt.NDArray[np.bool_], dict[str, str]]:
    """The cycle of `model`: times, channel names, rows (NaN where the
    mechanism does not assemble), the mask of solved rows and each
    channel's unit."""
    t = _times(model)
    points = _points(model)
    n = len(t)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        names, rows, units = _kinematics(model, t, points)
        if not names:
            names, _, units = _kinematics(model, t[:1], points)
        values = np.full((n, len(names)), np.nan)
        ok = np.zeros(n, dtype=bool)
        values[: len(rows)] = rows
        ok[: len(rows)] = True
        start = len(rows)
        stride = max(1, n // RESTARTS)
        while start < n:
            # Past a row that does not assemble: the next time that does.
            found = False
            for j in range(start + 1, n, stride):
                part_names, part, _ = _kinematics(model, t[j:], points)
                if len(part) and part_names == names:
                    values[j : j + len(part)] = part
                    ok[j : j + len(part)] = True
                    start = j + len(part)
                    found = True
                    break
            if not found:
                break
    return t, names, values, ok, units


def _handles(model: Model, scene: Scene, data: Any) -> list[Handle]:
    """The draggable points of the model: each joint with a point on two
    bodies (revolute), then each named body point not at such a joint."""
    bodies = list(data.get("bodies") or [])
    index = {str(b.get("name")): k for k, b in enumerate(bodies)}
    glob = {str(b.get("name")) for b in bodies if "global_points" in b}

    def named(body: str, name: str) -> Target | None:
        if body == GROUND:
            pts = (data.get("ground") or {}).get("points") or {}
            return Target("ground", GROUND, -1, name) if name in pts else None
        k = index.get(body)
        if k is None:
            return None
        kind = "global_points" if body in glob else "points"
        return Target(kind, body, k, name) if name in (bodies[k].get(kind) or {}) else None

    handles: list[Handle] = []
    taken: set[tuple[str, str]] = set()
    geometry = {j["name"]: j for j in model._core.geometry(1e-3)}
    for k, spec in enumerate(data.get("joints") or []):
        if spec.get("type") != "revolute":
            continue
        name = str(spec.get("name") or f"revolute_{k}")
        geo = geometry.get(name)
        if geo is None:
            continue
        targets = []
        for side in ("i", "j"):
            body = str(spec.get(f"body_{side}"))
            ref = spec.get(f"point_{side}")
            if isinstance(ref, str):
                tgt = named(body, ref)
                if tgt is None:
                    break
                targets.append(tgt)
                taken.add((body, ref))
            else:
                targets.append(Target("joint", body, k, f"point_{side}"))
        else:
            bi = str(spec.get("body_i"))
            s = geo["s_i"]
            handles.append(Handle(f"joint:{name}", name, bi, (float(s[0]), float(s[1])), tuple(targets)))
    for body, pts in scene.points.items():
        for pname, s in pts.items():
            if (body, pname) in taken:
                continue
            tgt = named(body, pname)
            if tgt is not None:
                handles.append(Handle(f"point:{body}.{pname}", f"{body}.{pname}", body, s, (tgt,)))
    return handles


def _number(v: float) -> float:
    r = round(float(v), DIGITS)
    return 0.0 if r == 0 else r


def _keep_comment(old: tomlkit.items.Item, new: tomlkit.items.Item) -> None:
    """Gives `new` the comment of `old`, in the same column when it fits."""
    ws = old.trivia.comment_ws
    if old.trivia.comment and ws.strip(" ") == "":
        ws = " " * max(1, len(ws) + len(old.as_string()) - len(new.as_string()))
    new.trivia.comment_ws = ws
    new.trivia.comment = old.trivia.comment
    new.trivia.trail = old.trivia.trail


def _set_pair(container: Any, key: str, xy: tuple[float, float]) -> None:
    """`container[key] = [x, y]`, keeping a TOML value's comment."""
    value = [_number(xy[0]), _number(xy[1])]
    old = container.get(key) if hasattr(container, "get") else None
    if isinstance(old, tomlkit.items.Array):
        new = tomlkit.array()
        new.extend(value)
        _keep_comment(old, new)
        container[key] = new
    else:
        container[key] = value


def _set_number(container: Any, key: str, v: float) -> None:
    old = container.get(key)
    if isinstance(old, tomlkit.items.Item):
        new = tomlkit.item(float(v))
        _keep_comment(old, new)
        container[key] = new
    else:
        container[key] = float(v)


class Document:
    """A model file open for editing. `solution` is the cycle of the
    current text; `edit_*` change the text and re-solve; `undo`, `redo`
    and `save` as their names say."""

    def __init__(self, path: str | os.PathLike[str]) -> None:
        self.path = Path(path).resolve()
        if not self.path.is_file():
            raise FileNotFoundError(f"no such model file: {path}")
        self.format = "json" if self.path.suffix.lower() == ".json" else "toml"
        if self.path.suffix.lower() not in (".toml", ".json"):
            raise ModelError(f"{path}: the studio edits .toml and .json model files")
        text = self.path.read_text(encoding="utf-8")
        self._data: Any = self._parse(text)
        self._undo: list[str] = []
        self._redo: list[str] = []
        self._gesture: object = None
        self.saved_text = text
        self.current_text = text
        self.solution = self._solve()

    # -- text -------------------------------------------------------------

    def _parse(self, text: str) -> Any:
        if self.format == "json":
            return json.loads(text)
        return tomlkit.parse(text)

    def text(self) -> str:
        """The document's current text."""
        if self.format == "json":
            return json.dumps(self._data, indent=2, ensure_ascii=False) + "\n"
        return tomlkit.dumps(self._data)

    @property
    def dirty(self) -> bool:
        """Whether the text differs from the file's."""
        return self.current_text != self.saved_text

    def _plain(self) -> Any:
        return self._data.unwrap() if self.format == "toml" else self._data

    # -- solving ----------------------------------------------------------

    def model(self, text: str | None = None) -> Model:
        """The model of the current text, read as the CLI reads the file."""
        text = self.text() if text is None else text
        return camlink.loads(text, self.format, str(self.path), base_dir=self.path.parent)

    def _solve(self) -> Solution:
        """Rebuilds the model from the text and solves its cycle. A drag is
        many edits and one undo step: the text before the first edit of a
        gesture is kept for undo."""
        text = self.text()
        self.current_text = text
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            model = self.model(text)
        scene = Scene.of(model, tol=1e-4)
        t, names, values, ok, units = solve(model)
        error = None
        if not names:
            # No kinematic run at all (a model that is not fully driven):
            # the placement, as one time.
            error = (f"model '{model.name}' has no kinematic motion (is every degree of freedom "
                     "driven?): the studio shows its placement")
            t = np.zeros(1)
            pose = (("x", "length"), ("y", "length"), ("phi", "angle"))
            names = [f"{b}.{c}" for b in scene.bodies for c, _ in pose]
            units = {f"{b}.{c}": unit_of(q)[0] for b in scene.bodies for c, q in pose}
            values = np.array([[v for b in scene.bodies for v in scene.placement[b]]])
            ok = np.ones(1, dtype=bool)
        self._plain_data = self._plain()
        return Solution(model, scene, t, names, values, ok, _handles(model, scene, self._plain_data),
                        error, units)

    # -- edits ------------------------------------------------------------

    def _apply(self, gesture: object, change: Any) -> Solution:
        """Applies `change` to the document and re-solves; on an error the
        document, undo and redo are as before and the error is raised."""
        before = self.current_text
        undo, redo, last = list(self._undo), list(self._redo), self._gesture
        if gesture is None or gesture != self._gesture:
            self._undo.append(before)
            self._redo.clear()
        self._gesture = gesture
        try:
            change()
            self.solution = self._solve()
        except (ModelError, ValueError, KeyError, TypeError):
            self._data = self._parse(before)
            self._undo, self._redo, self._gesture = undo, redo, last
            raise
        return self.solution

    def move(self, handle_id: str, row: int, x: float, y: float, gesture: object = None) -> Solution:
        """Moves the handle `handle_id` to the global point (x, y) (m) at
        output row `row`, and re-solves."""
        sol = self.solution
        handle = next((h for h in sol.handles if h.id == handle_id), None)
        if handle is None:
            raise KeyError(f"no handle {handle_id!r}")

        def change() -> None:
            data = self._data
            for tgt in handle.targets:
                if tgt.kind == "ground":
                    _set_pair(data["ground"]["points"], tgt.key, (x, y))
                    continue
                px, py, phi = sol.pose(tgt.body, row)
                c, s = math.cos(phi), math.sin(phi)
                local = (c * (x - px) + s * (y - py), -s * (x - px) + c * (y - py))
                if tgt.body != GROUND and "global_points" in self._body(tgt.body):
                    x0, y0, phi0 = sol.scene.placement[tgt.body]
                    c0, s0 = math.cos(phi0), math.sin(phi0)
                    local = (x0 + c0 * local[0] - s0 * local[1], y0 + s0 * local[0] + c0 * local[1])
                if tgt.kind == "joint":
                    _set_pair(data["joints"][tgt.index], tgt.key, local)
                else:
                    _set_pair(data["bodies"][tgt.index][tgt.kind], tgt.key, local)

        return self._apply(gesture, change)

    def _body(self, name: str) -> Any:
        for b in self._data.get("bodies") or []:
            if str(b.get("name")) == name:
                return b
        raise KeyError(name)

    def parameters(self) -> list[dict[str, Any]]:
        """The file's numeric ``[parameters]``: name, value and a slider
        range (half to twice a positive value, the mirror for a negative
        one, ±1 around zero)."""
        out = []
        for name, v in (self._plain_data.get("parameters") or {}).items():
            if isinstance(v, bool) or not isinstance(v, int | float):
                continue
            v = float(v)
            lo, hi = (0.5 * v, 2.0 * v) if v > 0 else (2.0 * v, 0.5 * v) if v < 0 else (-1.0, 1.0)
            out.append({"name": str(name), "value": v, "min": lo, "max": hi})
        return out

    def set_parameter(self, name: str, value: float, gesture: object = None) -> Solution:
        """Sets the ``[parameters]`` number `name` to `value`, and re-solves."""
        params = self._data.get("parameters")
        if params is None or name not in params:
            raise KeyError(f"no parameter {name!r}")
        if not math.isfinite(value):
            raise ValueError(f"parameter {name!r}: {value} is not a finite number")
        return self._apply(gesture, lambda: _set_number(params, name, value))

    def undo(self) -> Solution | None:
        """Goes back one edit (a whole drag); None when there is none."""
        if not self._undo:
            return None
        self._redo.append(self.current_text)
        self._data = self._parse(self._undo.pop())
        self._gesture = None
        self.solution = self._solve()
        return self.solution

    def redo(self) -> Solution | None:
        """Does again the edit last undone; None when there is none."""
        if not self._redo:
            return None
        self._undo.append(self.current_text)
        self._data = self._parse(self._redo.pop())
        self._gesture = None
        self.solution = self._solve()
        return self.solution

    def end_gesture(self) -> None:
        """Ends a drag or a slider move: the next edit is a new undo step."""
        self._gesture = None

    # -- saving -----------------------------------------------------------

    def save(self) -> Path:
        """Writes the text over the model file: into a temporary file in
        its folder, the old file kept as ``NAME.bak`` beside it, then the
        temporary file renamed over the file. Nothing is written outside
        the file's folder."""
        text = self.current_text
        folder = self.path.parent
        fd, tmp = tempfile.mkstemp(prefix=f".{self.path.name}.", suffix=".tmp", dir=folder)
        try:
            with os.fdopen(fd, "w", encoding="utf-8", newline="") as f:
                f.write(text)
            if self.path.exists():
                shutil.copy2(self.path, self.path.with_name(self.path.name + ".bak"))
            os.replace(tmp, self.path)
        except BaseException:
            Path(tmp).unlink(missing_ok=True)
            raise
        self.saved_text = text
        return self.path
