"""The studio's editable model: the file's text as a document, its edits,
undo and redo, the re-solved cycle of each edit, and saving.

The file is held as plain data (dicts, lists, numbers, strings), which
edits change; every edit rebuilds the model from that data through the
binding (`camlink.loads` of its JSON, the same schema as the file) and
solves its cycle. Text is made only when it is asked for (`text`, `save`):
a TOML file as the tomlkit document of the file as opened with the values
that differ set, so every comment and the layout stay; a JSON file with
two-space indents.

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
times over one second when the file gives none). An edit's run starts
from the last cycle's coordinates at the first time (and a restart from
its coordinates at that time), not from the file's placement, so an edit
keeps the assembly branch. A time at which the mechanism does not
assemble leaves its row missing (NaN) and the run goes on from the next
time at which it assembles again.
"""

from __future__ import annotations

import json
import math
import os
import shutil
import tempfile
import tomllib
import warnings
from abc import ABC, abstractmethod
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
from camlink.viz.front import default_plots
from camlink.viz.scene import GROUND, Scene

__all__ = ["Document", "Editable", "Floats", "Handle", "Solution", "raw", "solve"]

Array = npt.NDArray[np.float64]

#: Decimal places of a dragged coordinate written to the file (m): a
#: nanometre, far below a pixel at any zoom a mechanism is edited at.
DIGITS = 9
#: Times of the cycle when the file gives none: 361 over one second.
DEFAULT_TIMES = np.linspace(0.0, 1.0, 361)
#: Most restarts tried past a time at which the mechanism does not assemble.
RESTARTS = 180


class Floats:
    """A float array as its little-endian float64 bytes (`data`), as a
    binary reply carries it (`camlink.studio.pack`)."""

    __slots__ = ("data",)

    def __init__(self, a: npt.ArrayLike) -> None:
        self.data = np.ascontiguousarray(a, dtype="<f8").tobytes()


def raw(a: npt.ArrayLike, dtype: str = "f64") -> Floats:
    """`a` for a binary reply (`Floats`); the studio sends float64 only."""
    if dtype != "f64":
        raise ValueError(f"the studio sends float64 arrays, not {dtype}")
    return Floats(a)


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
    #: Whether the cycle kept the last cycle's assembly branch where the
    #: file's placement assembles on another (the CLI would follow that).
    kept_branch: bool = False
    #: Each channel's unit, as the core states it.
    units: dict[str, str] = field(default_factory=dict)

    def coordinates(self, names: list[str]) -> Array | None:
        """The coordinates `names` (a model's `coordinates`) at every row
        (rows × names, NaN on missing rows); None when a name is not a
        channel of this cycle."""
        col = {n: i for i, n in enumerate(self.names)}
        if any(n not in col for n in names):
            return None
        return self.values[:, [col[n] for n in names]]

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


def _kinematics(model: Model, times: Array, points: list[str], start: Array | None = None,
                units: bool = True) -> tuple[list[str], Array, dict[str, str]]:
    """Names, rows and (with `units`, else none) units of the kinematic run
    at `times` (assembled from the coordinates `start` when given and
    finite, else from the placement), up to the first time at which the
    mechanism does not assemble (no rows when it does not at the first)."""
    if start is not None and not np.all(np.isfinite(start)):
        start = None
    try:
        res = model.kinematics(times=times, points=points, start=start)
    except AnalysisError as e:
        res = e.results
    names = list(res.channels)
    rows = res.data[:, 1:] if len(res) else np.empty((0, len(names)))  # without t
    return names, rows, res.units if units else {}


def _same_branch(model: Model, names: list[str], rows: Array, t0: float, q: Array) -> bool:
    """Whether the run's first row (`rows` of the channels `names`, from
    the placement, as the CLI runs) is where `model` assembles at `t0`
    from the coordinates `q` (within a micrometre per metre of the model,
    angles modulo 2π)."""
    coords = model.coordinates
    if not np.all(np.isfinite(q)):
        return True
    if len(rows) == 0:
        return False
    got, mine, _ = _kinematics(model, np.array([t0]), [], q, units=False)
    if len(mine) == 0:
        return True
    col = {c: i for i, c in enumerate(names)}
    placed = rows[0, [col[c] for c in coords]]
    col = {c: i for i, c in enumerate(got)}
    kept = mine[0, [col[c] for c in coords]]
    bodies = {b["name"] for b in model.bodies}
    length = np.array([c.rsplit(".", 1)[0] in bodies and c.rsplit(".", 1)[1] in ("x", "y")
                       for c in coords])
    d = placed - kept
    d[~length] = (d[~length] + math.pi) % (2 * math.pi) - math.pi
    size = max(1.0, float(np.max(np.abs(kept[length]), initial=0.0)))
    return bool(np.max(np.abs(d)) <= 1e-6 * size)


def solve(model: Model, previous: Solution | None = None
          ) -> tuple[Array, list[str], Array, npt.NDArray[np.bool_], bool, dict[str, str]]:
    """The cycle of `model`: times, channel names, rows (NaN where the
    mechanism does not assemble), the mask of solved rows, each channel's
    unit, and whether the
    branch of the `previous` cycle (over the same times) was kept against
    the placement's: then the run starts from its first row, and each
    restart from its row at that time."""
    t = _times(model)
    points = _points(model)
    n = len(t)
    q = None
    if previous is not None and len(previous.t) == n and np.array_equal(previous.t, t):
        q = previous.coordinates(model.coordinates)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        # From the placement, as the CLI runs the saved file; from the last
        # cycle's first row when the placement is on another branch.
        names, rows, units = _kinematics(model, t, points)
        kept = q is not None and not _same_branch(model, names, rows, t[0], q[0])
        if kept and q is not None:
            names, rows, units = _kinematics(model, t, points, q[0])
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
                part_names, part, _ = _kinematics(model, t[j:], points, None if q is None else q[j],
                                                  units=False)
                if len(part) and part_names == names:
                    values[j : j + len(part)] = part
                    ok[j : j + len(part)] = True
                    start = j + len(part)
                    found = True
                    break
            if not found:
                break
    return t, names, values, ok, kept, units


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
            s = next(m["s_i"] for m in geo["marks"] if m["shape"] == "pin")
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


def _unwrapped(item: Any) -> Any:
    return item.unwrap() if hasattr(item, "unwrap") else item


def _sync(container: Any, plain: dict[str, Any]) -> None:
    """Makes the tomlkit table `container` hold `plain`: keys it lacks are
    added, keys `plain` lacks are removed, and each value that differs is
    set, keeping the old value's comment; equal values keep their text."""
    for key in [k for k in container if k not in plain]:
        del container[key]
    for key, new in plain.items():
        if key not in container:
            container[key] = new
            continue
        old = container[key]
        if isinstance(new, dict) and isinstance(old, dict):
            _sync(old, new)
        elif (isinstance(new, list) and isinstance(old, list) and len(new) == len(old)
              and all(isinstance(n, dict) and isinstance(o, dict) for n, o in zip(new, old, strict=True))):
            for o, n in zip(old, new, strict=True):
                _sync(o, n)
        elif _unwrapped(old) != new:
            item = tomlkit.item(new)
            if isinstance(old, tomlkit.items.Item):
                _keep_comment(old, item)
            container[key] = item


class Editable(ABC):
    """A file open for editing, held as plain data (`_data`): its edits
    with undo and redo, its text and saving. A subclass solves the data
    (`_solve`, giving `solution`) after each edit."""

    solution: Any

    def _open(self, path: Path, text: str) -> None:
        """Holds `text`, the text of the file `path` as opened."""
        self.path = path
        self.format = "json" if path.suffix.lower() == ".json" else "toml"
        #: The file's text as opened: a TOML text is rendered from it.
        self._opened = text
        self._data: Any = json.loads(text) if self.format == "json" else tomllib.loads(text)
        self._json = self._dump()
        self._saved = self._json
        self._undo: list[str] = []
        self._redo: list[str] = []
        self._gesture: object = None

    @abstractmethod
    def _solve(self) -> Any:
        """The solution of the current data (set `_json` to its dump)."""

    # -- text -------------------------------------------------------------

    def _dump(self) -> str:
        """The data as compact JSON: the undo steps, the test for unsaved
        edits and what the model is read from."""
        return json.dumps(self._data, separators=(",", ":"), ensure_ascii=False)

    def text(self) -> str:
        """The document's current text, as `save` writes it."""
        if self.format == "json":
            return json.dumps(self._data, indent=2, ensure_ascii=False) + "\n"
        doc = tomlkit.parse(self._opened)
        _sync(doc, self._data)
        return tomlkit.dumps(doc)

    @property
    def dirty(self) -> bool:
        """Whether the data differs from the file's."""
        return self._json != self._saved

    @property
    def can_undo(self) -> bool:
        return bool(self._undo)

    @property
    def can_redo(self) -> bool:
        return bool(self._redo)

    # -- edits ------------------------------------------------------------

    def _apply(self, gesture: object, change: Any) -> Any:
        """Applies `change` to the data and re-solves; on an error the
        data, undo and redo are as before and the error is raised. A drag
        is many edits and one undo step: the data before the first edit of
        a gesture is kept for undo."""
        before = self._json
        undo, redo, last = list(self._undo), list(self._redo), self._gesture
        if gesture is None or gesture != self._gesture:
            self._undo.append(before)
            self._redo.clear()
        self._gesture = gesture
        try:
            change()
            self.solution = self._solve()
        except (ModelError, ValueError, KeyError, TypeError):
            self._data = json.loads(before)
            self._json = before
            self._undo, self._redo, self._gesture = undo, redo, last
            raise
        return self.solution

    def _restore(self, state: str) -> Any:
        self._data = json.loads(state)
        self._gesture = None
        self.solution = self._solve()
        return self.solution

    def undo(self) -> Any:
        """Goes back one edit (a whole drag); None when there is none."""
        if not self._undo:
            return None
        self._redo.append(self._json)
        return self._restore(self._undo.pop())

    def redo(self) -> Any:
        """Does again the edit last undone; None when there is none."""
        if not self._redo:
            return None
        self._undo.append(self._json)
        return self._restore(self._redo.pop())

    def end_gesture(self) -> None:
        """Ends a drag or a slider move: the next edit is a new undo step."""
        self._gesture = None

    # -- saving -----------------------------------------------------------

    def save(self) -> Path:
        """Writes the text over the model file: into a temporary file in
        its folder, the old file kept as ``NAME.bak`` beside it, then the
        temporary file renamed over the file. Nothing is written outside
        the file's folder."""
        text = self.text()
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
        self._saved = self._json
        return self.path


class Document(Editable):
    """A model file open for editing. `solution` is the cycle of the
    current data; `move` and `set_parameter` change the data and re-solve;
    `undo`, `redo` and `save` as their names say."""

    def __init__(self, path: str | os.PathLike[str]) -> None:
        full = Path(path).resolve()
        if not full.is_file():
            raise FileNotFoundError(f"no such model file: {path}")
        if full.suffix.lower() not in (".toml", ".json"):
            raise ModelError(f"{path}: the studio edits .toml and .json model files")
        text = full.read_text(encoding="utf-8")
        fmt = "json" if full.suffix.lower() == ".json" else "toml"
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            model = camlink.loads(text, fmt, str(full), base_dir=full.parent)
        self._open(full, text)
        self._plots: list[str] | None = None
        self.solution = self._solve(model)

    def default_plots(self, points: list[str]) -> list[str]:
        """The page's first plots (`camlink.viz.front.default_plots`), chosen
        from the cycle as opened (the page keeps its plots through edits)."""
        if self._plots is None:
            sol = self.solution
            self._plots = default_plots(sol.scene.bodies, points, sol.t, sol.names, sol.values)
        return [c for c in self._plots if c in self.solution.names] or self.solution.names[:2]

    # -- solving ----------------------------------------------------------

    def model(self) -> Model:
        """The model of the current data, read as the CLI reads the saved
        file. A data that is not a valid model raises the message of its
        text (naming the file's line and field)."""
        # The data's compact JSON, as dumped for undo (`_json`, made with
        # each change), when it is JSON proper; JSON has no infinity or NaN:
        # such data is read from its text.
        text, fmt = self._json, "json"
        if "NaN" in text or "Infinity" in text:
            try:
                text = json.dumps(self._data, separators=(",", ":"), allow_nan=False)
            except ValueError:
                text, fmt = self.text(), self.format
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                return camlink.loads(text, fmt, str(self.path), base_dir=self.path.parent)
            except ModelError:
                if fmt == self.format and self.format == "toml":
                    raise
                camlink.loads(self.text(), self.format, str(self.path), base_dir=self.path.parent)
                raise

    def _solve(self, model: Model | None = None) -> Solution:
        """Solves the cycle of the current data (of `model` when given),
        from the last cycle's coordinates when there is one."""
        self._json = self._dump()
        if model is None:
            model = self.model()
        scene = Scene.of(model, tol=1e-4)
        previous = getattr(self, "solution", None)
        t, names, values, ok, kept, units = solve(model, previous)
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
        return Solution(model, scene, t, names, values, ok, _handles(model, scene, self._data),
                        error, kept, units)

    def move(self, handle_id: str, row: int, x: float, y: float, gesture: object = None) -> Solution:
        """Moves the handle `handle_id` to the global point (x, y) (m) at
        output row `row`, and re-solves."""
        sol = self.solution
        handle = next((h for h in sol.handles if h.id == handle_id), None)
        if handle is None:
            raise KeyError(f"no handle {handle_id!r}")

        def pair(container: dict[str, Any], key: str, xy: tuple[float, float]) -> None:
            container[key] = [_number(xy[0]), _number(xy[1])]

        def change() -> None:
            data = self._data
            for tgt in handle.targets:
                if tgt.kind == "ground":
                    pair(data["ground"]["points"], tgt.key, (x, y))
                    continue
                px, py, phi = sol.pose(tgt.body, row)
                c, s = math.cos(phi), math.sin(phi)
                local = (c * (x - px) + s * (y - py), -s * (x - px) + c * (y - py))
                if tgt.body != GROUND and "global_points" in self._body(tgt.body):
                    x0, y0, phi0 = sol.scene.placement[tgt.body]
                    c0, s0 = math.cos(phi0), math.sin(phi0)
                    local = (x0 + c0 * local[0] - s0 * local[1], y0 + s0 * local[0] + c0 * local[1])
                if tgt.kind == "joint":
                    pair(data["joints"][tgt.index], tgt.key, local)
                else:
                    pair(data["bodies"][tgt.index][tgt.kind], tgt.key, local)

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
        for name, v in (self._data.get("parameters") or {}).items():
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
            raise ModelError(f"parameter {name!r}: {value} is not a finite number")
        return self._apply(gesture, lambda: params.__setitem__(name, float(value)))

    def motion_segments(self) -> list[dict[str, Any]]:
        """The segments of the file's ``source = "motion"`` curves: curve
        name, index in its program, law, span (rad) and lift (m, or rad of
        swing) as the file gives them (numbers or expressions)."""
        out = []
        for c in self._data.get("curves") or []:
            if c.get("source") != "motion":
                continue
            for k, seg in enumerate(c.get("segments") or []):
                out.append({"curve": str(c.get("name")), "index": k, "law": seg.get("law"),
                            "span": seg.get("span"), "lift": seg.get("lift", 0.0)})
        return out

    def set_segments(self, changes: list[tuple[str, int, str, str | float]],
                     gesture: object = None) -> Solution:
        """Sets, for each (curve, index, key, value) of `changes`, `key`
        (``law``, ``span`` in rad or ``lift`` in m, or rad of swing; a
        number or an expression of the parameters) of segment `index` of
        the motion curve `curve`, all at once (a rise and its return
        together: a program that does not close is not a model), and
        re-solves. Changes that make the model invalid are refused with
        its message."""
        curves = {str(c.get("name")): c for c in self._data.get("curves") or []
                  if c.get("source") == "motion"}
        edits: list[tuple[dict[str, Any], str, str | float]] = []
        for curve, index, key, value in changes:
            if curve not in curves:
                raise KeyError(f"no motion curve {curve!r}")
            segs = curves[curve].get("segments") or []
            if not 0 <= index < len(segs):
                raise KeyError(f"curve {curve!r} has no segment {index} (its program has {len(segs)})")
            if key not in ("law", "span", "lift"):
                raise KeyError(f"segment key {key!r} is not one of law, span, lift")
            if isinstance(value, bool) or not isinstance(value, str | int | float):
                raise TypeError(f"curve {curve!r} segments[{index}].{key}: {value!r} is not a "
                                "number or an expression")
            if not isinstance(value, str):
                value = float(value)
                if not math.isfinite(value):
                    raise ModelError(f"curve {curve!r} segments[{index}].{key}: {value} is not finite")
            edits.append((segs[index], key, value))

        def change() -> None:
            for seg, key, value in edits:
                seg[key] = value

        solution: Solution = self._apply(gesture, change)
        return solution
