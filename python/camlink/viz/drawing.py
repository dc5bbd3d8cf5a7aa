"""Drawing a mechanism from its own model, at any instant of a run.

`draw(model_or_results, t=...)` returns a matplotlib `Figure`: links through
each body's joint and named points, pins, ground anchors (turned away from
their links), guides and sliders, cam and roller curves (sampled so that the
drawn outline is within a quarter pixel of the exact curve), flat faces,
slots as double lines, gear pitch circles, springs and dampers, with
optional traces of body points (each marked where it is), force vectors and
body and joint names; labels are moved apart so that none overlaps another.
The frame holds the whole motion; both axes share one scale, in metres.

`Drawing` keeps the artists of one figure and moves them to any output row
(`Drawing.show`): the animations reuse it frame by frame.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt
from matplotlib.artist import Artist
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import FancyArrowPatch, Polygon
from matplotlib.text import Text
from matplotlib.transforms import Bbox

from camlink._core import AnalysisError, ModelError
from camlink.viz.scene import GROUND, Guide, Pin, Rod, Scene, place

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.backend_bases import RendererBase

    from camlink.model import Model
    from camlink.results import Results

__all__ = ["Drawing", "Frame", "Shape", "angle_text", "draw", "number_text", "resolve"]

Array = npt.NDArray[np.float64]

#: Fill colours of the moving bodies' links, in body order.
LINK_COLORS = ("#d6e4f0", "#f3e0c4", "#d8ecd4", "#efd5d5", "#e3d9ef", "#e9e9e9")
CAM_COLOR = "#c9d3de"
EDGE = "#1a1a1a"
TRACE_COLOR = "#b03a2e"
FORCE_COLOR = "#1f5f99"
SPRING_COLOR = "#2e6b30"
LABEL_COLOR = "#333333"
#: Half-coils of a drawn spring.
SPRING_ZIGS = 12
#: Font size (pt) of the title.
TITLE_SIZE = 10.0
#: Rows over which the frame is fitted to the motion (evenly spaced).
FRAMING_ROWS = 240


@dataclass(frozen=True)
class Shape:
    """One drawn polygon or polyline: `points` (k × 2, m) in `body`'s
    frame; colours as CSS strings (None: not filled / not stroked); line
    width in points; `dash` a dash pattern in points (empty: solid); `dot`
    the radius (points) of a marker at each point (0: none); `gid` names
    what it shows (``"pin:A"``, ``"link:crank"`` …)."""

    body: str
    points: Array
    closed: bool
    fill: str | None
    stroke: str | None
    width: float
    dash: tuple[float, ...]
    dot: float
    z: float
    gid: str


def _css(rgba: Sequence[float]) -> str | None:
    r, g, b, a = (float(v) for v in rgba)
    if a == 0:
        return None
    return f"rgba({round(r * 255)},{round(g * 255)},{round(b * 255)},{a:.3g})"


def _shape(artist: Artist, body: str, local: Array) -> Shape:
    gid = artist.get_gid() or ""
    z = float(artist.get_zorder())
    if isinstance(artist, Polygon):
        _, dashes = artist._dash_pattern  # type: ignore[attr-defined]
        from matplotlib.colors import to_rgba

        return Shape(body, local, True, _css(to_rgba(artist.get_facecolor())),
                     _css(to_rgba(artist.get_edgecolor())),
                     float(artist.get_linewidth()), tuple(dashes or ()), 0.0, z, gid)
    assert isinstance(artist, Line2D)
    from matplotlib.colors import to_rgba

    color = _css(to_rgba(artist.get_color()))
    marker = artist.get_marker() not in (None, "None", "none", "")
    solid = artist.get_linestyle() in ("-", "solid")
    dashes = () if solid or artist.get_linestyle() in ("None", "none", "") else tuple(
        float(d) for d in (artist._dash_pattern[1] or ())  # type: ignore[attr-defined]
    )
    stroke = None if artist.get_linestyle() in ("None", "none", "") else color
    return Shape(body, local, False, color if marker else None, stroke,
                 float(artist.get_linewidth()), dashes,
                 float(artist.get_markersize()) / 2 if marker else 0.0, z, gid)


@dataclass(frozen=True)
class Frame:
    """Where the drawing's axes are: data limits (m) and the axes box in
    pixels; `px_per_m` is the common scale of both axes."""

    xlim: tuple[float, float]
    ylim: tuple[float, float]
    px_per_m: float
    size_px: tuple[int, int]


def resolve(source: Model | Results) -> tuple[Model, Results | None]:
    """The model and (if any) results behind `source`. Results carry the
    model that produced them; results read from a file do not, and raise
    `ModelError`."""
    from camlink.model import Model
    from camlink.results import Results

    if isinstance(source, Model):
        return source, None
    if isinstance(source, Results):
        if source.mechanism is None:
            raise ModelError(
                "these results carry no model (read from a file?): draw them with "
                "camlink.draw(model, results=...)"
            )
        return source.mechanism, source
    raise TypeError(f"expected a camlink Model or Results, not {type(source).__name__}")


def motion_of(model: Model) -> Results | None:
    """Positions to draw a model alone: its kinematic run over the file's
    times, or None when it is not fully driven (then the file's placement
    is drawn)."""
    try:
        return model.kinematics()
    except (AnalysisError, ModelError):
        return None


class Drawing:
    """A figure of a mechanism whose artists move to any output row.

    `results` gives the motion (None: the file's placement); `traces` names
    body points (``"coupler.P"``) whose paths are drawn, each marked where
    the point is; `forces` names joints whose force on body j
    (``<joint>.fx_j``, ``.fy_j``, N) is drawn as an arrow at the joint;
    `labels` writes each body's name on it and each joint's beside it;
    `width` is the figure width (in) at `dpi`; `title` is written above the
    frame, wrapped to its width.
    """

    def __init__(
        self,
        model: Model,
        results: Results | None = None,
        *,
        traces: Sequence[str] = (),
        forces: Sequence[str] = (),
        width: float = 6.4,
        dpi: int = 100,
        title: str | None = None,
        labels: bool = False,
    ) -> None:
        self.model = model
        self.results = results
        coarse = Scene.of(model, tol=1e-4)
        poses = coarse.poses(results)
        self.rows = len(next(iter(poses.values())))
        self.times = results.t if results is not None else np.zeros(1)
        lo, hi = _extent(coarse, poses)
        size = float(np.hypot(*(hi - lo))) or 1.0
        self.size = size
        pad = 0.08 * size
        lo, hi = lo - pad, hi + pad
        self.figure = Figure(dpi=dpi)
        FigureCanvasAgg(self.figure)
        self.ax = self.figure.add_axes((0.1, 0.1, 0.8, 0.8))
        _style(self.ax)
        self.title = _wrap(title, width) if title else None
        # Room above the frame for the title's lines and its pad.
        self._top = 0.15 + (
            (self.title.count("\n") + 1) * 1.25 * TITLE_SIZE + 8.0) / 72 if self.title else 0.0
        self.frame = _layout(self.figure, self.ax, lo, hi, width, dpi, self._top)
        tol = 0.25 / self.frame.px_per_m
        self.scene = Scene.of(model, tol=tol)
        self.poses = self.scene.poses(results)
        self._movers: list[tuple[str, Array, Callable[[Array], None]]] = []
        #: The artists that move, by id, with their body and local points.
        self._moving: dict[int, tuple[str, Array, Artist]] = {}
        self._growing: list[tuple[Line2D, Array]] = []
        self._arrows: list[tuple[FancyArrowPatch, Array, Array, Text, str]] = []
        self._static: list[Array] = []
        self._rods: list[tuple[Rod, Line2D]] = []
        #: Springs and dampers: the line, its kind, and the global paths
        #: (rows × 2, m) of its two ends.
        self._springs: list[tuple[Line2D, str, Array, Array]] = []
        #: Body and joint names: the text and the global path (rows × 2,
        #: m) of the point it names.
        self._names: list[tuple[Text, Array]] = []
        self._width, self._dpi = width, dpi
        self.pin_radius = 0.012 * size
        self.half_width = 0.022 * size
        self._draw_static(traces, forces)
        self.cams = self.scene.cam_bodies()
        self.label = self.ax.text(
            0.015, 0.985, "", transform=self.ax.transAxes, va="top", ha="left",
            fontsize=9, family="monospace", color="#333333", zorder=10,
            bbox={"facecolor": "white", "edgecolor": "none", "pad": 1.5, "alpha": 0.85},
        )
        if labels:
            self._draw_names()
        if self.title:
            self.ax.set_title(self.title, fontsize=TITLE_SIZE)
        self._fit()

    def _fit(self) -> None:
        """Frames everything drawn, at every output row: the mechanism never
        leaves the picture. The frame only grows from the first estimate,
        so the curves' sampling stays finer than a quarter pixel."""
        rows = np.unique(np.linspace(0, self.rows - 1, min(self.rows, FRAMING_ROWS)).astype(int))
        found = list(self._static)
        for body, local, _ in self._movers:
            q = self.poses[body][rows]
            c, s = np.cos(q[:, 2])[:, None], np.sin(q[:, 2])[:, None]
            found.append(np.column_stack([
                (q[:, 0:1] + c * local[:, 0] - s * local[:, 1]).ravel(),
                (q[:, 1:2] + s * local[:, 0] + c * local[:, 1]).ravel(),
            ]))
        for _, path in self._growing:
            found.append(path)
        for _, at, vec, _, _ in self._arrows:
            found.append(at)
            found.append(at + vec)
        for _, _, a, b in self._springs:
            found.extend((a, b))
        pts = np.vstack(found)
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        pad = 0.05 * self.size
        lo, hi = lo - pad, hi + pad
        # Room above for the time read-out.
        hi = hi + np.array([0.0, 0.06 * float(hi[1] - lo[1])])
        self.frame = _layout(self.figure, self.ax, lo, hi, self._width, self._dpi, self._top)

    # -- building -------------------------------------------------------------

    def _mover(self, body: str, local: npt.ArrayLike, set_xy: Callable[[Array], None]) -> None:
        self._movers.append((body, np.asarray(local, dtype=np.float64).reshape(-1, 2), set_xy))

    def _polygon(self, body: str, local: Array, z: float, **kw: object) -> Polygon:
        patch = Polygon(local, closed=True, zorder=z, **kw)
        self.ax.add_patch(patch)
        self._mover(body, local, patch.set_xy)
        self._moving[id(patch)] = (body, np.asarray(local, dtype=np.float64), patch)
        return patch

    def _line(self, body: str, local: Array, z: float, **kw: object) -> Line2D:
        (line,) = self.ax.plot(local[:, 0], local[:, 1], zorder=z, **kw)  # type: ignore[arg-type]
        self._mover(body, local, lambda xy: line.set_data(xy[:, 0], xy[:, 1]))
        self._moving[id(line)] = (body, np.asarray(local, dtype=np.float64), line)
        return line

    def shapes(self) -> list[Shape]:
        """Every drawn polygon and line as a `Shape` in its body's frame
        (static ones on the ground), by drawing order: what the browser
        viewer draws."""
        out: list[Shape] = []
        for artist in [*self.ax.patches, *self.ax.lines]:
            # Arrows, springs and dampers change shape from row to row.
            if isinstance(artist, FancyArrowPatch) or (artist.get_gid() or "").startswith(
                    ("spring", "damper")):
                continue
            moving = self._moving.get(id(artist))
            if moving is not None:
                body, local, _ = moving
            elif isinstance(artist, Polygon):
                body, local = GROUND, np.asarray(artist.get_xy(), dtype=np.float64)
            elif isinstance(artist, Line2D):
                body = GROUND
                local = np.column_stack([artist.get_xdata(), artist.get_ydata()]).astype(np.float64)
            else:
                continue
            out.append(_shape(artist, body, local))
        out.sort(key=lambda sh: sh.z)
        return out

    def _draw_static(self, traces: Sequence[str], forces: Sequence[str]) -> None:
        scene, ax = self.scene, self.ax
        r_pin, hw = self.pin_radius, self.half_width
        colors = {b: LINK_COLORS[k % len(LINK_COLORS)] for k, b in enumerate(scene.bodies)}
        # Curves: cams filled, rollers white, slots as double lines.
        for c in scene.curves:
            if c.role == "cam":
                self._polygon(c.body, c.points, 2, facecolor=CAM_COLOR, edgecolor=EDGE,
                              linewidth=1.2, gid=f"curve:{c.joint}:{c.body}")
            elif c.role == "roller":
                self._polygon(c.body, c.points, 5, facecolor="white", edgecolor=EDGE,
                              linewidth=1.2, gid=f"curve:{c.joint}:{c.body}")
                centre = c.points[:-1].mean(axis=0) if c.closed else c.points.mean(axis=0)
                self._line(c.body, centre[None, :], 5.5, marker="o", markersize=2.5,
                           color=EDGE, linestyle="none")
            elif c.role == "slot":
                for side in (-1.0, 1.0):
                    self._line(c.body, _offset(c.points, side * 1.4 * r_pin), 3.5,
                               color=EDGE, linewidth=1.1)
                self._line(c.body, c.points, 3.4, color="#888888", linewidth=0.6,
                           linestyle=(0, (6, 3)), gid=f"curve:{c.joint}:{c.body}")
            else:
                self._line(c.body, c.points, 3, color=EDGE, linewidth=1.2,
                           gid=f"curve:{c.joint}:{c.body}")
        # Links: a rounded hull round each body's attachment points.
        for link in scene.links:
            self._polygon(link.body, _rounded_hull(link.points, hw), 3,
                          facecolor=colors[link.body], edgecolor=EDGE, linewidth=1.0,
                          gid=f"link:{link.body}")
        for body, outline in scene.outlines.items():
            self._polygon(body, outline, 3, facecolor=colors[body], edgecolor=EDGE, linewidth=1.0,
                          gid=f"outline:{body}")
        for rod in scene.rods:
            line = Line2D([], [], color="#555555", linewidth=3, zorder=3, solid_capstyle="round")
            ax.add_line(line)
            self._rods.append((rod, line))
        # Gears: dash-dot pitch circles with a radius line showing the turn.
        for g in scene.gears:
            n = _circle_count(g.radius, 0.25 / self.frame.px_per_m)
            a = np.linspace(0.0, 2 * np.pi, n + 1)
            circle = np.column_stack([g.centre[0] + g.radius * np.cos(a),
                                      g.centre[1] + g.radius * np.sin(a)])
            self._polygon(g.body, circle, 2, facecolor="none" if g.internal else colors.get(g.body, "none"),
                          edgecolor=EDGE, linewidth=1.0, linestyle="-.", gid=f"gear:{g.joint}:{g.body}")
            spoke = np.array([g.centre, (g.centre[0] + g.radius, g.centre[1])])
            self._line(g.body, spoke, 2.5, color=EDGE, linewidth=0.8)
        # Faces: flat follower faces and rack pitch lines.
        for f in scene.faces:
            half = self._face_half_length(f.body, f.joint)
            u = np.asarray(f.u) / np.hypot(*f.u)
            seg = np.array([np.asarray(f.s) - half * u, np.asarray(f.s) + half * u])
            self._line(f.body, seg, 4, color=EDGE, linewidth=2.4, solid_capstyle="butt",
                       gid=f"face:{f.joint}")
        for guide in scene.guides:
            self._draw_guide(guide, colors)
        for p in scene.pins:
            self._draw_pin(p.body_i, p.s_i, f"pin:{p.joint}")
            if p.grounded:
                body, s = (p.body_i, p.s_i) if p.body_i == GROUND else (p.body_j, p.s_j)
                if body == GROUND:
                    away = self._away_from_links(p)
                    self._static.append(_ground_anchor(ax, np.asarray(s), r_pin, self.size, away,
                                                       f"ground:{p.joint}"))
        for rod in scene.rods:
            self._draw_pin(rod.body_i, rod.s_i, f"pin:{rod.joint}:i")
            self._draw_pin(rod.body_j, rod.s_j, f"pin:{rod.joint}:j")
        # Springs and dampers between their attachment points.
        self._draw_springs()
        # Traces of body points over the whole run, grown as time goes,
        # each with a mark where the point is.
        for name in traces:
            path = self.scene.point_path(name, self.poses)
            (line,) = ax.plot(path[:, 0], path[:, 1], color=TRACE_COLOR, linewidth=1.1,
                              zorder=5.8, gid=f"trace:{name}")
            self._growing.append((line, path))
            body, _, point = name.partition(".")
            self._line(body, np.array([self.scene.points[body][point]]), 6.8, marker="o",
                       markersize=5.0, markerfacecolor=TRACE_COLOR, markeredgecolor="white",
                       markeredgewidth=0.8, linestyle="none", color=TRACE_COLOR,
                       gid=f"mark:{name}")
        # Forces on body j at each joint, scaled to the largest over the run.
        self._draw_forces(forces)

    def _away_from_links(self, pin: Pin) -> Array:
        """The unit direction in which a ground pin's anchor stands: the
        first of down, up, left, right and the diagonals that stays 60° or
        more from every direction in which the pinned body reaches over
        the run, else the one farthest from them (down when the body
        reaches every way, as a full-turning crank does)."""
        body, s = (pin.body_j, pin.s_j) if pin.body_i == GROUND else (pin.body_i, pin.s_i)
        local = [np.array(list(self.scene.points.get(body, {}).values())).reshape(-1, 2)]
        local += [link.points for link in self.scene.links if link.body == body]
        local += [c.points for c in self.scene.curves if c.body == body]
        if body in self.scene.outlines:
            local.append(self.scene.outlines[body])
        pts = np.vstack(local)
        pts = pts[np.hypot(*(pts - np.asarray(s)).T) > 2.0 * self.pin_radius]
        down = np.array([0.0, -1.0])
        if not len(pts):
            return down
        n = len(self.poses[body])
        rows = np.unique(np.linspace(0, n - 1, min(n, FRAMING_ROWS)).astype(int))
        origin = np.asarray(pin.s_i if pin.body_i == GROUND else pin.s_j)
        reach = np.vstack([place(pts, self.poses[body][k]) for k in rows]) - origin
        angles = np.arctan2(reach[:, 1], reach[:, 0])
        best, best_gap = down, -1.0
        for deg in (-90.0, 90.0, 180.0, 0.0, -135.0, -45.0, 135.0, 45.0):
            a = np.radians(deg)
            gap = float(np.min(np.abs(np.angle(np.exp(1j * (angles - a))))))
            if gap >= np.radians(60.0):
                return np.array([np.cos(a), np.sin(a)])
            if gap > best_gap + 1e-9:
                best, best_gap = np.array([np.cos(a), np.sin(a)]), gap
        return best if best_gap >= np.radians(20.0) else down

    def _draw_springs(self) -> None:
        """Springs (zigzags) and dampers (dashpots) of the model's
        spring–damper–actuators, and torsion springs (spirals round the pin
        joining their bodies)."""
        for f in self.model._core.forces:
            bi, bj = f["bodies"]
            k, c = float(f["stiffness"] or 0.0), float(f["damping"] or 0.0)
            if f["kind"] == "tsda":
                assert f["s_i"] is not None and f["s_j"] is not None
                a = self._path(bi, np.asarray(f["s_i"], dtype=np.float64))
                b = self._path(bj, np.asarray(f["s_j"], dtype=np.float64))
                # Spring and damper side by side when it has both; an
                # actuator alone is drawn as a spring.
                kinds = ["spring"] * (k != 0.0 or c == 0.0) + ["damper"] * (c != 0.0)
                for kind in kinds:
                    (line,) = self.ax.plot([], [], color=SPRING_COLOR, linewidth=1.2, zorder=4.2,
                                           solid_joinstyle="miter", gid=f"{kind}:{f['name']}")
                    self._springs.append((line, kind if len(kinds) == 1 else f"{kind}+", a, b))
                for end, path in (("i", a), ("j", b)):
                    (dot,) = self.ax.plot([], [], marker="o", markersize=3.0, color=SPRING_COLOR,
                                          linestyle="none", zorder=4.3,
                                          gid=f"spring-end:{f['name']}:{end}")
                    self._springs.append((dot, "end", path, path))
            elif f["kind"] == "rsda":
                pin = next((p for p in self.scene.pins if {p.body_i, p.body_j} == {bi, bj}), None)
                if pin is None:
                    continue
                turns = np.linspace(0.0, 2.5 * 2 * np.pi, 160)
                r = self.pin_radius * (1.4 + 1.6 * turns / turns[-1])
                spiral = np.column_stack([pin.s_i[0] + r * np.cos(turns),
                                          pin.s_i[1] + r * np.sin(turns)])
                self._line(pin.body_i, spiral, 5.5, color=SPRING_COLOR, linewidth=1.1,
                           gid=f"torsion:{f['name']}")

    def _draw_names(self) -> None:
        """Each body's name at the middle of its shape, each joint's beside
        its point (a pin's centre, a slider's block, a gear pair's pitch
        point, a curve contact's contact point when the run has it)."""
        scene = self.scene
        middles: dict[str, Array] = {}
        for link in scene.links:
            middles[link.body] = link.points.mean(axis=0)
        for body, outline in scene.outlines.items():
            middles[body] = outline.mean(axis=0)
        for c in scene.curves:
            if c.role in ("cam", "roller"):
                middles.setdefault(c.body, c.points.mean(axis=0))
        for g in scene.gears:
            middles.setdefault(g.body, np.asarray(g.centre))
        for body in scene.bodies:
            middle = middles.get(body, np.zeros(2))
            self._name("body", body, self._path(body, middle))
        named: set[str] = set()
        ends: list[Pin | Rod] = [*scene.pins, *scene.rods]
        for end in ends:
            if end.joint not in named:
                named.add(end.joint)
                self._name("joint", end.joint, self._path(end.body_i, np.asarray(end.s_i)))
        for guide in scene.guides:
            named.add(guide.joint)
            block = next(a for a in self.ax.patches if a.get_gid() == f"slider:{guide.joint}")
            local = self._moving[id(block)][1]
            self._name("joint", guide.joint, self._path(guide.body_j, local.mean(axis=0)))
        res = self.results
        for joint in dict.fromkeys(c.joint for c in scene.curves):
            if joint not in named and res is not None and f"{joint}.cx" in res:
                named.add(joint)
                self._name("joint", joint, np.column_stack([res[f"{joint}.cx"], res[f"{joint}.cy"]]))
        gears = scene.gears
        for g in gears:
            if g.joint in named:
                continue
            other = next((h for h in gears if h.joint == g.joint and h is not g), None)
            ci = self._path(g.body, np.asarray(g.centre))
            if other is None:
                rack = next((f for f in scene.faces if f.joint == g.joint), None)
                if rack is None:
                    continue
                named.add(g.joint)
                # The pitch point: the pinion's centre dropped onto the
                # rack's pitch line.
                on = self._path(rack.body, np.asarray(rack.s))
                u = self._path(rack.body, np.asarray(rack.s) + np.asarray(rack.u)) - on
                u /= np.hypot(u[:, 0], u[:, 1])[:, None]
                along = np.sum((ci - on) * u, axis=1)
                self._name("joint", g.joint, on + along[:, None] * u)
                continue
            named.add(g.joint)
            cj = self._path(other.body, np.asarray(other.centre))
            d = cj - ci
            dist = np.hypot(d[:, 0], d[:, 1])
            dist[dist == 0] = 1.0
            # The pitch point: on the line of centres, a pitch radius from
            # the first gear's centre (outside it for a ring gear's mate).
            sign = -1.0 if other.internal else 1.0
            self._name("joint", g.joint, ci + sign * g.radius * d / dist[:, None])

    def _path(self, body: str, local: Array) -> Array:
        """Global path (rows × 2, m) of the point `local` of `body`."""
        q = self.poses[body]
        c, s = np.cos(q[:, 2]), np.sin(q[:, 2])
        return np.column_stack([q[:, 0] + c * local[0] - s * local[1],
                                q[:, 1] + s * local[0] + c * local[1]])

    def _name(self, kind: str, text: str, path: Array) -> None:
        """A body's name (bold, centred on its point) or a joint's (beside
        its point) at the global `path` (rows × 2, m)."""
        label = self.ax.text(0, 0, text, fontsize=9.0 if kind == "body" else 8.0,
                             fontweight="bold" if kind == "body" else "normal",
                             color=LABEL_COLOR, ha="left", va="bottom", zorder=9.5,
                             gid=f"{kind}:{text}",
                             bbox={"facecolor": "white", "edgecolor": "none", "pad": 0.8,
                                   "alpha": 0.75})
        self._names.append((label, path))

    def _draw_pin(self, body: str, s: tuple[float, float], gid: str) -> None:
        a = np.linspace(0.0, 2 * np.pi, 33)
        r = self.pin_radius
        ring = np.column_stack([s[0] + r * np.cos(a), s[1] + r * np.sin(a)])
        self._polygon(body, ring, 6, facecolor="white", edgecolor=EDGE, linewidth=1.1, gid=gid)
        self._line(body, np.array([s]), 6.5, marker="o", markersize=1.8, color=EDGE,
                   linestyle="none")

    def _draw_guide(self, g: Guide, colors: dict[str, str]) -> None:
        scene, size = self.scene, self.size
        v = np.asarray(g.v_i) / np.hypot(*g.v_i)
        n = np.array([-v[1], v[0]])
        blen, bwid = 0.10 * size, 0.055 * size
        # The block sits at s_j unless the body's curve or face is there:
        # then it moves along the axis, away from the contact, on a stem.
        occupied = [c for c in scene.curves if c.body == g.body_j] + [
            f for f in scene.faces if f.body == g.body_j]
        sj = np.asarray(g.s_j)
        q_i, q_j = self.poses[g.body_i], self.poses[g.body_j]
        v_j = _to_local(v, q_i[0], q_j[0])
        shift = 0.0
        if occupied:
            reach = max(
                [float(np.max(np.hypot(*(c.points - sj).T))) for c in occupied
                 if hasattr(c, "points")] + [0.0]
            )
            other = self._contact_other(g.body_j)
            gj = place(sj[None, :], q_j[0])[0]
            away = np.sign(np.dot(place(_v(v_j), q_j[0])[0] - place(np.zeros((1, 2)), q_j[0])[0],
                                  gj - other)) or 1.0
            shift = away * (reach + 0.6 * blen)
        centre = sj + shift * v_j
        n_j = np.array([-v_j[1], v_j[0]])
        block = np.array([centre - 0.5 * blen * v_j - 0.5 * bwid * n_j,
                          centre + 0.5 * blen * v_j - 0.5 * bwid * n_j,
                          centre + 0.5 * blen * v_j + 0.5 * bwid * n_j,
                          centre - 0.5 * blen * v_j + 0.5 * bwid * n_j])
        if shift:
            self._line(g.body_j, np.array([sj, centre]), 3.5, color=EDGE, linewidth=2.2)
        self._polygon(g.body_j, block, 4.5, facecolor=colors.get(g.body_j, "#e9e9e9"),
                      edgecolor=EDGE, linewidth=1.0, gid=f"slider:{g.joint}")
        # Guide rails on body i over the block's travel.
        travel = np.array([_to_local_point(place(centre[None, :], q)[0], qi)
                           for q, qi in zip(q_j, q_i, strict=True)])
        along = (travel - np.asarray(g.s_i)) @ v
        a0, a1 = float(along.min()) - 0.8 * blen, float(along.max()) + 0.8 * blen
        base = np.asarray(g.s_i) + float(np.mean((travel - np.asarray(g.s_i)) @ n)) * n
        # A block slides on one rail; a stem runs between two.
        for side in (-1.0, 1.0) if shift else (-1.0,):
            off = base + side * (0.5 * bwid + 0.004 * size) * n
            rail = np.array([off + a0 * v, off + a1 * v])
            self._line(g.body_i, rail, 4, color=EDGE, linewidth=1.1, gid=f"guide:{g.joint}")
            if g.body_i == GROUND:
                self._static.append(_hatch(self.ax, rail[0], rail[1], side * n, self.size,
                                           f"ground:{g.joint}:hatch"))

    def _contact_other(self, body: str) -> Array:
        """Global position (row 0) of the body on the other side of `body`'s
        cam contact: the cam's frame origin."""
        for c in self.scene.curves:
            if c.body != body:
                others = [d for d in self.scene.curves if d.joint == c.joint and d.body == body]
                faces = [f for f in self.scene.faces if f.joint == c.joint and f.body == body]
                if others or faces:
                    return place(np.zeros((1, 2)), self.poses[c.body][0])[0]
        return np.zeros(2)

    def _face_half_length(self, body: str, joint: str) -> float:
        """Half the drawn length of a face: past every contact point of the
        run, or a fixed share of the frame without contact channels."""
        res = self.results
        if res is not None and f"{joint}.cx" in res:
            pts = np.column_stack([res[f"{joint}.cx"], res[f"{joint}.cy"]])
            q = self.poses[body]
            face = next(f for f in self.scene.faces if f.joint == joint)
            local = np.array([_to_local_point(p, qq) for p, qq in zip(pts, q, strict=True)])
            u = np.asarray(face.u) / np.hypot(*face.u)
            reach = np.abs((local - np.asarray(face.s)) @ u)
            return float(reach.max()) + 0.05 * self.size
        curves = [c for c in self.scene.curves if c.joint == joint]
        if curves:
            pts = curves[0].points
            return 0.6 * float(np.max(np.ptp(pts, axis=0)))
        return 0.15 * self.size

    def _draw_forces(self, joints: Sequence[str]) -> None:
        res = self.results
        if not joints:
            return
        if res is None:
            raise ModelError("forces need results of inverse dynamics or dynamics")
        vectors = []
        for j in joints:
            if f"{j}.fx_j" not in res:
                raise ModelError(
                    f"no force channels for joint {j!r} ({j}.fx_j, {j}.fy_j): run inverse "
                    "dynamics or dynamics"
                )
            vectors.append(np.column_stack([res[f"{j}.fx_j"], res[f"{j}.fy_j"]]))
        biggest = max(float(np.max(np.hypot(*v.T))) for v in vectors) or 1.0
        scale = 0.25 * self.size / biggest
        for j, vec in zip(joints, vectors, strict=True):
            at = self._joint_path(j)
            arrow = FancyArrowPatch((0, 0), (0, 0), arrowstyle="-|>", mutation_scale=12,
                                    color=FORCE_COLOR, linewidth=1.6, zorder=8, gid=f"force:{j}")
            self.ax.add_patch(arrow)
            text = self.ax.text(0, 0, "", fontsize=8, color=FORCE_COLOR, zorder=9, gid=f"force-label:{j}",
                                bbox={"facecolor": "white", "edgecolor": "none", "pad": 0.8,
                                      "alpha": 0.75})
            self._arrows.append((arrow, at, vec * scale, text, j))

    def _joint_path(self, joint: str) -> Array:
        """Global path (rows × 2, m) of a joint's point: a pin's centre or a
        cam contact point."""
        res = self.results
        assert res is not None
        if f"{joint}.cx" in res:
            return np.column_stack([res[f"{joint}.cx"], res[f"{joint}.cy"]])
        for p in self.scene.pins:
            if p.joint == joint:
                return np.array([place(np.asarray(p.s_i)[None, :], q)[0]
                                 for q in self.poses[p.body_i]])
        raise ModelError(f"joint {joint!r} has no point to draw its force at")

    # -- moving ---------------------------------------------------------------

    def row(self, t: float | None) -> int:
        """The output row nearest the time `t` (s); row 0 for None."""
        if t is None:
            return 0
        return int(np.argmin(np.abs(self.times - t)))

    def show(self, k: int, grow: bool = False) -> None:
        """Moves every artist to output row `k`; with `grow`, traces end
        there."""
        for body, local, set_xy in self._movers:
            set_xy(place(local, self.poses[body][k]))
        for rod, line in self._rods:
            a = place(np.asarray(rod.s_i)[None, :], self.poses[rod.body_i][k])[0]
            b = place(np.asarray(rod.s_j)[None, :], self.poses[rod.body_j][k])[0]
            line.set_data([a[0], b[0]], [a[1], b[1]])
        for line, path in self._growing:
            shown = path[: k + 1] if grow else path
            line.set_data(shown[:, 0], shown[:, 1])
        for line, kind, a, b in self._springs:
            if kind == "end":
                line.set_data([a[k, 0]], [a[k, 1]])
                continue
            amp = 0.6 * self.half_width
            # A spring and a damper side by side sit apart on bars.
            shift = 0.0 if not kind.endswith("+") else (1.3 if kind.startswith("spring") else -1.3)
            xy = _zigzag(a[k], b[k], amp, shift * amp) if kind.startswith("spring") else _dashpot(
                a[k], b[k], amp, shift * amp)
            line.set_data(xy[:, 0], xy[:, 1])
        parts = [f"t = {number_text(float(self.times[k]), '.3f')} s"] if self.results is not None else []
        for cam in self.cams[:1]:
            parts.append(f"θ = {angle_text(float(self.poses[cam][k, 2]))}")
        self.label.set_text("   ".join(parts))
        # Labels, placed one after another clear of those before them.
        placed = [self._extent(self.label)] if parts else []
        # A joint's name clears its pin.
        pin_px = 1.15 * self.pin_radius * self.frame.px_per_m
        for name_text, path in self._names:
            on_body = (name_text.get_gid() or "").startswith("body:")
            self._place(name_text, path[k], placed, centred=on_body, clear=0.0 if on_body else pin_px)
        for arrow, at, vec, text, name in self._arrows:
            p, f = at[k], vec[k]
            arrow.set_positions(tuple(p), tuple(p + f))
            assert self.results is not None
            mag = float(np.hypot(self.results[f"{name}.fx_j"][k], self.results[f"{name}.fy_j"][k]))
            text.set_text(f"{name}: {number_text(mag, '.3g')} N")
            self._place(text, p + f, placed, centred=False, clear=0.0)

    def _renderer(self) -> RendererBase:
        get = getattr(self.figure.canvas, "get_renderer", None)
        return get() if get is not None else FigureCanvasAgg(self.figure).get_renderer()

    def _extent(self, text: Text) -> Bbox:
        """A text's box (display pixels) with its background patch."""
        renderer = self._renderer()
        box = text.get_window_extent(renderer)
        patch = text.get_bbox_patch()
        if patch is not None:
            text.update_bbox_position_size(renderer)
            box = Bbox.union([box, patch.get_window_extent(renderer)])
        return box

    def _place(self, text: Text, at: Array, placed: list[Bbox], centred: bool, clear: float) -> None:
        """Puts `text` near the global point `at` (m) where its box overlaps
        none of `placed` (display pixels) and stays in the frame: centred
        on the point (for `centred`) or beside it, `clear` pixels and a
        small gap away, then ever farther round it. The box is added to
        `placed`."""
        anchor = self.ax.transData.transform(np.asarray(at, dtype=np.float64).reshape(1, 2))[0]
        inverse = self.ax.transData.inverted()
        text.set_horizontalalignment("left")
        text.set_verticalalignment("bottom")
        text.set_position(tuple(inverse.transform(anchor)))
        box = self._extent(text)
        w, h = box.width, box.height
        # Where the box's lower left goes, relative to its text's lower left.
        lift = np.array([box.x0, box.y0]) - anchor
        gap = clear + 2.0 * self.figure.dpi / 72.0
        spots = [(-w / 2, -h / 2)] if centred else []
        for ring in range(6):
            d = gap + ring * h
            # Diagonal spots clear a round pin at d / √2 across and up.
            for sx, sy in ((1, 1), (1, -1), (-1, 1), (-1, -1), (1, 0), (-1, 0), (0, 1), (0, -1)):
                e = d / np.sqrt(2.0) if sx and sy else d
                x = e if sx > 0 else (-e - w if sx < 0 else -w / 2)
                y = e if sy > 0 else (-e - h if sy < 0 else -h / 2)
                spots.append((x, y))
        frame = self.ax.bbox
        fits = None
        for dx, dy in spots:
            cand = Bbox.from_bounds(anchor[0] + dx, anchor[1] + dy, w, h)
            if any(cand.overlaps(other) for other in placed):
                continue
            inside = (cand.x0 >= frame.x0 and cand.x1 <= frame.x1
                      and cand.y0 >= frame.y0 and cand.y1 <= frame.y1)
            if inside:
                fits = (dx, dy)
                break
            if fits is None:
                fits = (dx, dy)
        dx, dy = fits if fits is not None else spots[0]
        text.set_position(tuple(inverse.transform(anchor + np.array([dx, dy]) - lift)))
        placed.append(self._extent(text))

    def pixel(self, xy: npt.ArrayLike) -> Array:
        """Pixel positions (k × 2, from the image's top left) of global
        points (m) in the saved figure."""
        disp = self.ax.transData.transform(np.asarray(xy, dtype=np.float64).reshape(-1, 2))
        height = self.figure.bbox.height
        return np.column_stack([disp[:, 0], height - disp[:, 1]])


def draw(
    source: Model | Results,
    t: float | None = None,
    *,
    results: Results | None = None,
    traces: Sequence[str] = (),
    forces: Sequence[str] = (),
    width: float = 6.4,
    dpi: int = 100,
    title: str | None = None,
    labels: bool = False,
) -> Figure:
    """A figure of the mechanism at time `t` (s; the output row nearest it,
    default the first).

    `source` is a `Model` (its kinematic run over the file's times gives
    the motion; a model that is not fully driven is drawn at its file
    placement) or `Results` (drawn with the model that produced them).
    `traces` names body points (``"coupler.P"``) whose whole path is drawn;
    `forces` names joints whose force on body j (N) is drawn as an arrow,
    scaled to the largest over the run and labelled; `labels` writes the
    bodies' and joints' names. The frame holds the whole motion; axes in
    metres on one scale.
    """
    model, res = resolve(source)
    if results is not None:
        res = results
    if res is None:
        res = motion_of(model)
    drawing = Drawing(model, res, traces=traces, forces=forces, width=width, dpi=dpi, title=title,
                      labels=labels)
    drawing.show(drawing.row(t))
    return drawing.figure


def number_text(value: float, spec: str) -> str:
    """`value` formatted by `spec`, never as a negative zero (``-0.000``
    is written ``0.000``)."""
    text = format(value, spec)
    if text.startswith("-") and float(text) == 0.0:
        return text[1:]
    return text


def angle_text(phi: float) -> str:
    """An angle φ (rad) in degrees on [0, 360) to one decimal: an angle
    that rounds to 360.0° or to −0.0° is written 0.0°."""
    deg = round(float(np.degrees(phi)), 1) % 360.0
    return f"{0.0 if deg >= 359.95 else deg + 0.0:.1f}°"


def _wrap(title: str, width: float) -> str:
    """`title` broken at spaces into lines that fit a figure `width` (in)
    wide at `TITLE_SIZE`; a word longer than a line stays whole."""
    import textwrap

    # Sans-serif glyphs average under 0.62 em; the title is centred over
    # the axes, whose centre is 0.3 in right of the figure's.
    chars = max(8, int((width - 0.6) * 72 / (0.62 * TITLE_SIZE)))
    return "\n".join(textwrap.wrap(title, chars, break_long_words=False)) or title


# -- geometry helpers ----------------------------------------------------------


def _zigzag(a: Array, b: Array, amp: float, shift: float) -> Array:
    """A spring from `a` to `b` (m): straight ends of a sixth of its length,
    `SPRING_ZIGS` half-coils between of half-width `amp` (m); `shift` (m)
    moves the coils sideways, joined to the ends by bars."""
    d = b - a
    length = float(np.hypot(*d)) or 1e-12
    u = d / length
    n = np.array([-u[1], u[0]])
    lead = length / 6
    t = lead + (np.arange(SPRING_ZIGS) + 0.5) / SPRING_ZIGS * (length - 2 * lead)
    side = np.where(np.arange(SPRING_ZIGS) % 2 == 0, 1.0, -1.0)
    coils = a + t[:, None] * u + (shift + side[:, None] * amp) * n
    ends = [a, a + lead * u + shift * n], [b - lead * u + shift * n, b]
    if shift:
        ends = ([a, a + 0.5 * lead * u, a + 0.5 * lead * u + shift * n, a + lead * u + shift * n],
                [b - lead * u + shift * n, b - 0.5 * lead * u + shift * n, b - 0.5 * lead * u, b])
    return np.vstack([*ends[0], coils, *ends[1]])


def _dashpot(a: Array, b: Array, amp: float, shift: float) -> Array:
    """A damper from `a` to `b` (m): a cylinder (open towards `b`,
    half-width `amp`) on a rod from `a`, a piston on a rod from `b`;
    `shift` (m) moves it sideways, joined to the ends by bars. Pieces are
    separated by NaN rows."""
    d = b - a
    length = float(np.hypot(*d)) or 1e-12
    u = d / length
    n = np.array([-u[1], u[0]])
    c = a + shift * n
    e = b + shift * n

    def at(f: float, side: float = 0.0) -> Array:
        return c + f * length * u + side * amp * n

    gap = np.full(2, np.nan)
    rod_a = [a, a + 0.15 * length * u, c + 0.15 * length * u] if shift else [a]
    rod_b = [b, b - 0.15 * length * u, e - 0.15 * length * u] if shift else [b]
    return np.vstack([
        *rod_a, at(0.3), gap,
        at(0.7, 1.0), at(0.3, 1.0), at(0.3, -1.0), at(0.7, -1.0), gap,
        at(0.55, 0.8), at(0.55, -0.8), gap,
        at(0.55), *rod_b[::-1],
    ])



def _v(v: Array) -> Array:
    return np.asarray(v, dtype=np.float64).reshape(1, 2)


def _to_local(v: Array, q_from: Array, q_to: Array) -> Array:
    """A direction fixed in the frame of pose `q_from`, in that of `q_to`."""
    a = q_from[2] - q_to[2]
    c, s = np.cos(a), np.sin(a)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def _to_local_point(p: Array, q: Array) -> Array:
    """A global point (m) in the frame of pose q = (x, y, φ)."""
    c, s = np.cos(q[2]), np.sin(q[2])
    d = np.asarray(p) - q[:2]
    return np.array([c * d[0] + s * d[1], -s * d[0] + c * d[1]])


def _extent(scene: Scene, poses: dict[str, Array]) -> tuple[Array, Array]:
    """Lower-left and upper-right corners (m) of everything over the run."""
    n = len(next(iter(poses.values())))
    rows = np.unique(np.linspace(0, n - 1, min(n, FRAMING_ROWS)).astype(int))
    local: dict[str, list[Array]] = {}
    for body, named in scene.points.items():
        if named:
            local.setdefault(body, []).append(np.array(list(named.values())))
    for link in scene.links:
        local.setdefault(link.body, []).append(link.points)
    for body, outline in scene.outlines.items():
        local.setdefault(body, []).append(outline)
    for c in scene.curves:
        local.setdefault(c.body, []).append(c.points)
    for g in scene.gears:
        ring = np.array([[g.centre[0] + dx * g.radius, g.centre[1] + dy * g.radius]
                         for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1))])
        local.setdefault(g.body, []).append(ring)
    for f in scene.faces:
        local.setdefault(f.body, []).append(np.array([f.s]))
    for p in scene.pins:
        local.setdefault(p.body_i, []).append(np.array([p.s_i]))
    # A slider's block travels with body j's point along the guide of body i.
    for guide in scene.guides:
        local.setdefault(guide.body_i, []).append(np.array([guide.s_i]))
        local.setdefault(guide.body_j, []).append(np.array([guide.s_j]))
    found = [np.zeros((1, 2))] if not local else []
    for body, parts in local.items():
        pts = np.vstack(parts)
        for k in rows:
            found.append(place(pts, poses[body][k]))
    allp = np.vstack(found)
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    span = max(float(np.max(hi - lo)), 1e-3)
    # A degenerate (straight) extent still gets some height.
    lo = np.minimum(lo, (lo + hi) / 2 - 0.15 * span)
    hi = np.maximum(hi, (lo + hi) / 2 + 0.15 * span)
    return lo, hi


def _style(ax: Axes) -> None:
    """Metres on both axes, light ticks and frame."""
    ax.set_xlabel("x (m)", fontsize=9)
    ax.set_ylabel("y (m)", fontsize=9)
    ax.tick_params(labelsize=8, direction="in", top=True, right=True)
    for spine in ax.spines.values():
        spine.set_linewidth(0.6)
        spine.set_color("#777777")


def _layout(fig: Figure, ax: Axes, lo: Array, hi: Array, width: float, dpi: int,
            title: float = 0.0) -> Frame:
    """Sizes the figure and its axes box to the aspect of the data limits
    `lo`–`hi` (m), so that one metre is as many pixels across as up, with
    `title` (in) more above the axes for a title. The pixel size truncates
    as the Agg canvas does."""
    left, right, bottom, top = 0.75, 0.15, 0.5, 0.15 + title
    aw = width - left - right
    w, h = float(hi[0] - lo[0]), float(hi[1] - lo[1])
    ah = aw * h / w
    ah = min(max(ah, 0.35 * aw), 1.1 * aw)
    # Widen the shorter side so that the scale is the same on both axes.
    if h / w < ah / aw:
        extra = (ah / aw * w - h) / 2
        lo, hi = lo - np.array([0.0, extra]), hi + np.array([0.0, extra])
    else:
        extra = (h * aw / ah - w) / 2
        lo, hi = lo - np.array([extra, 0.0]), hi + np.array([extra, 0.0])
    height = ah + bottom + top
    fig.set_size_inches(width, height)
    ax.set_position((left / width, bottom / height, aw / width, ah / height))
    ax.set_xlim(float(lo[0]), float(hi[0]))
    ax.set_ylim(float(lo[1]), float(hi[1]))
    ax.set_aspect("equal", adjustable="box")
    return Frame(
        (float(lo[0]), float(hi[0])),
        (float(lo[1]), float(hi[1])),
        aw * dpi / float(hi[0] - lo[0]),
        (int(width * dpi), int(height * dpi)),
    )


def _hull(pts: Array) -> Array:
    """Convex hull (counter-clockwise) of 2-D points: Andrew's monotone chain."""
    p = sorted(set(map(tuple, np.round(pts, 15))))
    if len(p) <= 2:
        return np.asarray(p)

    def half(seq: list[tuple[float, float]]) -> list[tuple[float, float]]:
        out: list[tuple[float, float]] = []
        for q in seq:
            while len(out) >= 2 and (
                (out[-1][0] - out[-2][0]) * (q[1] - out[-2][1])
                - (out[-1][1] - out[-2][1]) * (q[0] - out[-2][0])
            ) <= 0:
                out.pop()
            out.append(q)
        return out

    lower, upper = half(p), half(p[::-1])
    return np.asarray(lower[:-1] + upper[:-1])


def _rounded_hull(points: Array, r: float) -> Array:
    """The outline of the points' hull grown by `r`: a bar with round ends
    for two points, a rounded polygon for more."""
    a = np.linspace(0.0, 2 * np.pi, 48, endpoint=False)
    disc = np.column_stack([r * np.cos(a), r * np.sin(a)])
    return _hull(np.vstack([p + disc for p in points]))


def _offset(points: Array, d: float) -> Array:
    """A polyline moved sideways by `d` (m) along its normals."""
    tangent = np.gradient(points, axis=0)
    norm = np.hypot(tangent[:, 0], tangent[:, 1])
    norm[norm == 0] = 1.0
    normal = np.column_stack([-tangent[:, 1], tangent[:, 0]]) / norm[:, None]
    return points + d * normal


def _circle_count(r: float, tol: float) -> int:
    """Segments of a polygon within `tol` (m) of a circle of radius `r`."""
    if r <= tol:
        return 8
    return max(16, int(np.ceil(np.pi / np.arccos(1.0 - tol / r))))


def _hatch(ax: Axes, a: Array, b: Array, side: Array, size: float, gid: str | None = None) -> Array:
    """Short slanted strokes along the segment a–b on its `side`: the
    textbook sign of the ground."""
    length = 0.014 * size
    d = b - a
    count = max(3, int(np.hypot(*d) / (0.012 * size)) + 1)
    u = d / (np.hypot(*d) or 1.0)
    slant = (side + u) / np.sqrt(2)
    ends = []
    for f in np.linspace(0.0, 1.0, count):
        p = a + f * d
        q = p + length * slant
        ax.plot([p[0], q[0]], [p[1], q[1]], color=EDGE, linewidth=0.7, zorder=1, gid=gid)
        ends.append(q)
    return np.asarray(ends)


def _ground_anchor(ax: Axes, s: Array, r: float, size: float, away: Array, gid: str) -> Array:
    """A fixed pivot: a triangle from the pin to a hatched base, standing
    in the unit direction `away` from it."""
    h = 3.2 * r
    across = np.array([away[1], -away[0]])
    foot = s + h * away
    tri = np.array([s, foot + 1.6 * r * across, foot - 1.6 * r * across])
    ax.add_patch(Polygon(tri, closed=True, facecolor="white", edgecolor=EDGE, linewidth=1.0,
                         zorder=1.2, gid=gid))
    base = np.array([foot + 2.6 * r * across, foot - 2.6 * r * across])
    ax.plot(base[:, 0], base[:, 1], color=EDGE, linewidth=1.2, zorder=1.3, gid=f"{gid}:base")
    return np.vstack([base, _hatch(ax, base[0], base[1], away, size, f"{gid}:hatch")])
