"""Timing diagrams and servo cam tables: the cams of one machine on one
master angle.

A timing file (TOML, see docs/cam-design.md, *Timing diagram and servo cam
tables*) names the machine's cams — each a cam design file with its phase
on the master angle — the positions of their followers in the machine, and
the least distances between followers. ``camlink cam TIMING.toml`` checks
the clearances over a master turn, draws the timing diagram and writes a
cam table for each axis for a servo drive: master angle against position,
velocity and acceleration at the machine's speed, plus a table of each
segment's extreme points and continuity class.

Axis k at master angle Θ runs its own program at θ = Θ − φ_k (φ_k its
phase); its follower's tip is at O_k + s_k(θ) (cos α_k, sin α_k) in the
machine's plane (O_k its ``origin``, α_k its ``direction_deg``).
"""

from __future__ import annotations

import csv
import math
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from camlink import _core
from camlink._core import ModelError
from camlink.cam import design as cam_design
from camlink.cam.design import CamDesignError
from camlink.cam.export import MAX_CSV_ROWS
from camlink.units import LENGTH_UNITS as METRES

RPM = cam_design.RPM

#: Length units of tables and the diagram: name -> metres per unit (of
#: camlink's length units, `camlink.units.LENGTH_UNITS`).
UNITS = {u: METRES[u] for u in ("m", "mm")}


class _Table:
    """Typed reads from one TOML table of a timing file with messages
    naming the field."""

    def __init__(self, path: Path, where: str, data: object) -> None:
        if not isinstance(data, dict):
            raise CamDesignError(f"{path}: {where} must be a table")
        self.path, self.where, self.data = path, where, data
        self.used: set[str] = set()

    def fail(self, key: str, message: str) -> CamDesignError:
        return CamDesignError(f"{self.path}: {self.where}.{key}: {message}")

    def number(
        self,
        key: str,
        default: float | None = None,
        *,
        positive: bool = False,
        most: float | None = None,
        unit: str = "",
    ) -> float:
        """The number at `key`; with `most`, |value| ≤ `most` (`unit`)."""
        self.used.add(key)
        v = self.data.get(key, default)
        if v is None:
            raise self.fail(key, "is required")
        if (
            isinstance(v, bool)
            or not isinstance(v, (int, float))
            or not math.isfinite(v)
        ):
            raise self.fail(key, f"must be a number, got {v!r}")
        if positive and v <= 0:
            raise self.fail(key, f"must be positive, got {v}")
        if most is not None and abs(v) > most:
            raise self.fail(key, f"must be at most {most:g}{unit} in size, got {v}")
        return float(v)

    def length(self, key: str, default: float | None = None, *, positive: bool = False) -> float:
        """A length (m) at `key`: at most `cam_design.MAX_LENGTH` in size."""
        return self.number(
            key, default, positive=positive, most=cam_design.MAX_LENGTH, unit=" m"
        )

    def text(
        self, key: str, default: str | None = None, choices: tuple[str, ...] = ()
    ) -> str:
        self.used.add(key)
        v = self.data.get(key, default)
        if not isinstance(v, str):
            raise self.fail(
                key, "is required" if v is None else f"must be a string, got {v!r}"
            )
        if choices and v not in choices:
            raise self.fail(
                key,
                f"'{v}' is not one of {', '.join(choices)}"
                f"{_core.did_you_mean(v, list(choices))}",
            )
        return v

    def finish(self) -> None:
        """Refuses a key no read asked for, suggesting the nearest known one."""
        extra = sorted(set(self.data) - self.used)
        if extra:
            known = sorted(k for k in self.used if not k.startswith("_"))
            raise self.fail(
                extra[0],
                f"unknown key{_core.did_you_mean(extra[0], known)}; "
                f"the keys here are {', '.join(known)}",
            )


@dataclass(frozen=True)
class Axis:
    name: str
    design: cam_design.Design
    phase: float
    """Phase φ (rad) on the master angle."""
    origin: tuple[float, float]
    """The follower's tip at s = 0 (m)."""
    direction: float
    """Direction α (rad) in which s moves the tip."""


@dataclass(frozen=True)
class Clearance:
    a: str
    b: str
    min_distance: float
    """m"""


@dataclass(frozen=True)
class Timing:
    path: Path
    name: str
    speed: float
    """Machine speed (rad/s of the master)."""
    resolution: float
    """Master angle step of the cam tables (rad)."""
    units: str
    axes: tuple[Axis, ...]
    clearances: tuple[Clearance, ...]
    diagram: str | None
    tables: bool


def is_timing(path: str | Path) -> bool:
    """True for a timing file (it has ``[[axes]]``)."""
    try:
        with Path(path).open("rb") as f:
            return "axes" in tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError):
        return False


def load(path: str | Path) -> Timing:
    """Reads a timing file and its cam design files; CamDesignError names
    the file and field."""
    p = Path(path)
    try:
        with p.open("rb") as f:
            doc = tomllib.load(f)
    except tomllib.TOMLDecodeError as e:
        raise CamDesignError(f"{p}: {e}") from None
    top = _Table(p, "timing", doc)
    name = top.text("name", p.stem)
    speed = top.number("speed_rpm", positive=True, most=cam_design.MAX_RPM, unit=" rpm") * RPM
    raw = doc.get("axes")
    top.used.add("axes")
    if not isinstance(raw, list) or not raw:
        raise CamDesignError(f"{p}: [[axes]]: a timing diagram needs at least one axis")
    axes: list[Axis] = []
    for i, r in enumerate(raw):
        t = _Table(p, f"axes[{i}]", r)
        an = t.text("name")
        if any(a.name == an for a in axes):
            raise t.fail("name", f"'{an}' names two axes")
        file = t.text("design")
        problem = _core.plain_file_name_problem(file)
        if problem:
            raise t.fail("design", f"'{file}' {problem}; name a design file beside {p.name}")
        dp = p.parent / file
        if not dp.is_file():
            raise t.fail("design", f"'{file}': no such file beside {p.name}")
        if dp.resolve() == p.resolve():
            raise t.fail("design", "names the timing file itself")
        design = cam_design.load(dp)
        o = t.data.get("origin", [0.0, 0.0])
        t.used.add("origin")
        if not (
            isinstance(o, list)
            and len(o) == 2
            and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in o)
            and all(math.isfinite(x) and abs(x) <= cam_design.MAX_LENGTH for x in o)
        ):
            raise t.fail("origin", f"must be [x, y] (m), got {o!r}")
        axes.append(
            Axis(
                an,
                design,
                math.radians(t.number("phase_deg", 0.0, most=360.0, unit="°")),
                (float(o[0]), float(o[1])),
                math.radians(t.number("direction_deg", 90.0, most=360.0, unit="°")),
            )
        )
        t.finish()
    clearances: list[Clearance] = []
    raw_c = doc.get("clearances", [])
    top.used.add("clearances")
    if not isinstance(raw_c, list):
        raise CamDesignError(f"{p}: [[clearances]] must be an array of tables")
    names = {a.name: a for a in axes}
    for i, r in enumerate(raw_c):
        t = _Table(p, f"clearances[{i}]", r)
        t.used.add("between")
        pair = t.data.get("between")
        if not (isinstance(pair, list) and len(pair) == 2 and all(isinstance(x, str) for x in pair)):
            raise t.fail("between", f"must name two axes, got {pair!r}")
        for x in pair:
            if x not in names:
                raise t.fail("between", f"'{x}' is not an axis ({', '.join(names)})")
            if names[x].design.oscillating:
                raise t.fail(
                    "between",
                    f"'{x}' has an oscillating follower; a clearance needs translating followers",
                )
        if pair[0] == pair[1]:
            raise t.fail("between", "names one axis twice")
        clearances.append(
            Clearance(
                pair[0],
                pair[1],
                t.length("min_distance", positive=True),
            )
        )
        t.finish()
    ex = _Table(p, "export", doc.get("export", {}))
    top.used.add("export")
    step = ex.number("resolution_deg", 1.0, positive=True, most=90.0, unit="°")
    if 360.0 / step > MAX_CSV_ROWS:
        raise ex.fail("resolution_deg", f"{step:g}° makes more than {MAX_CSV_ROWS} rows")
    units = ex.text("units", "m", tuple(UNITS))
    ex.used.add("diagram")
    diagram = ex.data.get("diagram", f"{p.stem}_timing.png")
    plain = isinstance(diagram, str) and diagram and not _core.plain_file_name_problem(diagram)
    if diagram is not False and not plain:
        raise ex.fail("diagram", f"must be a plain file name or false, got {diagram!r}")
    ex.used.add("tables")
    tables = ex.data.get("tables", True)
    if not isinstance(tables, bool):
        raise ex.fail("tables", f"must be true or false, got {tables!r}")
    ex.finish()
    top.finish()
    return Timing(
        p,
        name,
        speed,
        math.radians(step),
        units,
        tuple(axes),
        tuple(clearances),
        None if diagram is False else str(diagram),
        tables,
    )


def motion(axis: Axis, master: NDArray[np.float64]) -> NDArray[np.float64]:
    """[s, s′, s″, s‴] of `axis` at master angles Θ (rad): its program at
    Θ − φ, derivatives per radian of the master."""
    th = np.mod(master - axis.phase, 2.0 * math.pi)
    return np.asarray(axis.design.core().motion(th))


def tip(axis: Axis, s: NDArray[np.float64]) -> NDArray[np.float64]:
    """The follower's tip (m) for displacements s: (n, 2)."""
    d = np.array([math.cos(axis.direction), math.sin(axis.direction)])
    return np.asarray(axis.origin) + np.outer(s, d)


@dataclass(frozen=True)
class ClearanceReport:
    a: str
    b: str
    least: float
    """Least tip distance over a master turn (m)."""
    at_deg: float
    limit: float
    ok: bool


#: Master angles sampled for the clearance check per turn.
SAMPLES = 36000


def clearances(t: Timing) -> list[ClearanceReport]:
    """The least distance between each pair of followers' tips over a
    master turn (sampled at `SAMPLES` angles, the least refined by a
    parabola through it and its neighbours)."""
    master = np.linspace(0.0, 2.0 * math.pi, SAMPLES, endpoint=False)
    by = {a.name: a for a in t.axes}
    out = []
    for c in t.clearances:
        pa = tip(by[c.a], motion(by[c.a], master)[:, 0])
        pb = tip(by[c.b], motion(by[c.b], master)[:, 0])
        d = np.hypot(*(pa - pb).T)
        k = int(np.argmin(d))
        least, at = float(d[k]), float(master[k])
        y0, y1, y2 = d[k - 1], d[k], d[(k + 1) % SAMPLES]
        curv = y0 - 2 * y1 + y2
        if curv > 0:
            h = master[1] - master[0]
            x = 0.5 * (y0 - y2) / curv
            least = float(y1 - 0.25 * (y0 - y2) * x)
            at = float(master[k] + x * h)
        out.append(
            ClearanceReport(
                c.a, c.b, least, math.degrees(at) % 360.0, c.min_distance, least >= c.min_distance
            )
        )
    return out


def table_rows(t: Timing, axis: Axis) -> NDArray[np.float64]:
    """The cam table of `axis`: rows [master deg, position, velocity,
    acceleration, jerk] in the timing file's length unit and seconds at
    the machine speed, every `resolution` over a turn, both ends included."""
    n = max(2, round(2.0 * math.pi / t.resolution))
    master = np.linspace(0.0, 2.0 * math.pi, n + 1)
    m = motion(axis, master)
    scale = 1.0 if axis.design.oscillating else 1.0 / UNITS[t.units]
    w = t.speed
    return np.column_stack(
        [
            np.degrees(master),
            m[:, 0] * scale,
            m[:, 1] * w * scale,
            m[:, 2] * w * w * scale,
            m[:, 3] * w**3 * scale,
        ]
    )


def segment_rows(t: Timing, axis: Axis) -> list[dict[str, Any]]:
    """Each segment of `axis` on the master angle: start and end (deg),
    law, lift, the continuity class (0…3 for C0…C3) at its start and end,
    and its extreme velocity and acceleration at the machine speed with the
    master angles where they occur (sampled at 2001 points a segment, the
    ends included)."""
    core = axis.design.core()
    starts = [*core.starts(), 2.0 * math.pi]
    cont_start = {b[2]: b[3] for b in core.boundaries()}
    cont_end = {b[1]: b[3] for b in core.boundaries()}
    osc = axis.design.oscillating
    scale = 1.0 if osc else 1.0 / UNITS[t.units]
    w = t.speed
    rows = []
    for k, seg in enumerate(axis.design.segments):
        a, b = starts[k], starts[k + 1]
        th = np.linspace(a, b, 2001)
        th[-1] = np.nextafter(b, a)
        m = np.asarray(core.motion(th))
        v, acc = m[:, 1] * w * scale, m[:, 2] * w * w * scale
        at = np.round(np.degrees(th + axis.phase) % 360.0, 9)
        iv, ia = int(np.argmax(np.abs(v))), int(np.argmax(np.abs(acc)))
        ip, iq = int(np.argmax(acc)), int(np.argmin(acc))
        rows.append(
            {
                "segment": k,
                "law": seg.law,
                "start_deg": round(math.degrees(a + axis.phase) % 360.0, 9),
                "end_deg": round(math.degrees(b + axis.phase) % 360.0, 9) or 360.0,
                "lift": seg.lift if osc else seg.lift * scale,
                "continuity_start": f"C{cont_start.get(k, 3)}",
                "continuity_end": f"C{cont_end.get(k, 3)}",
                "peak_velocity": float(v[iv]),
                "peak_velocity_deg": float(at[iv]),
                "max_acceleration": float(acc[ip]),
                "max_acceleration_deg": float(at[ip]),
                "min_acceleration": float(acc[iq]),
                "min_acceleration_deg": float(at[iq]),
                "peak_acceleration": float(acc[ia]),
            }
        )
    return rows


def diagram(t: Timing, report: list[ClearanceReport] | None = None) -> Any:
    """The timing diagram: one row per axis (displacement over the master
    angle, its segment boundaries as dotted lines) and, with clearances, a
    row of the tip distances against their limits."""
    import matplotlib.pyplot as plt

    rows = len(t.axes) + (1 if t.clearances else 0)
    fig, axs = plt.subplots(rows, 1, sharex=True, figsize=(8.0, 1.6 * rows + 0.8), squeeze=False)
    master = np.linspace(0.0, 2.0 * math.pi, 3601)
    deg = np.degrees(master)
    unit = t.units
    for ax, axis in zip(axs[:, 0], t.axes, strict=False):
        s = motion(axis, master)[:, 0]
        if axis.design.oscillating:
            ax.plot(deg, np.degrees(s), color="C0", lw=1.5)
            ax.set_ylabel(f"{axis.name}\n(deg)")
        else:
            ax.plot(deg, s / UNITS[unit], color="C0", lw=1.5)
            ax.set_ylabel(f"{axis.name}\n({unit})")
        for st in axis.design.core().starts():
            ax.axvline(math.degrees(st + axis.phase) % 360.0, color="0.6", lw=0.8, ls=":")
        ax.grid(True, alpha=0.3)
    if t.clearances:
        ax = axs[-1, 0]
        by = {a.name: a for a in t.axes}
        for i, c in enumerate(t.clearances):
            pa = tip(by[c.a], motion(by[c.a], master)[:, 0])
            pb = tip(by[c.b], motion(by[c.b], master)[:, 0])
            d = np.hypot(*(pa - pb).T) / UNITS[unit]
            ax.plot(deg, d, color=f"C{i + 1}", lw=1.5, label=f"{c.a}–{c.b}")
            ax.axhline(c.min_distance / UNITS[unit], color=f"C{i + 1}", lw=1.0, ls="--")
        ax.set_ylabel(f"clearance\n({unit})")
        ax.legend(loc="best", fontsize=8)
        ax.grid(True, alpha=0.3)
    axs[-1, 0].set_xlabel("master angle (deg)")
    axs[-1, 0].set_xlim(0.0, 360.0)
    axs[-1, 0].set_xticks(np.arange(0, 361, 45))
    fig.suptitle(f"{t.name}: timing at {t.speed / RPM:g} rpm")
    fig.tight_layout()
    return fig


def outputs(t: Timing, out: Path) -> list[Path]:
    """The files `write` writes into `out`: the diagram, then each axis's
    cam table and segment table."""
    paths = [] if t.diagram is None else [out / t.diagram]
    if t.tables:
        for axis in t.axes:
            paths += [out / f"{t.path.stem}_{axis.name}.csv", out / f"{t.path.stem}_{axis.name}_segments.csv"]
    return paths


def write(t: Timing, out: Path, report: list[ClearanceReport], force: bool = False) -> list[str]:
    """Writes the diagram and the cam tables into `out`; the paths. None is
    the timing file or an axis's design file (nor a link to one), and none
    that exists is replaced unless `force`; each is written to a temporary
    name and renamed."""
    from camlink.cam import plots as cam_plots
    from camlink.io.output import check_not_input, replacing

    targets = outputs(t, out)
    inputs = [t.path, *(a.design.path for a in t.axes)]
    try:
        for path in targets:
            check_not_input(path, inputs)
    except ModelError as e:
        raise CamDesignError(str(e)) from None
    existing = [str(p) for p in targets if p.exists()]
    if existing and not force:
        raise CamDesignError(
            f"{', '.join(existing)} {'exists' if len(existing) == 1 else 'exist'}; pass --force "
            "to replace, or choose another --out"
        )
    out.mkdir(parents=True, exist_ok=True)
    written = []
    if t.diagram is not None:
        path = out / t.diagram
        with replacing(path) as temp:
            cam_plots.save(diagram(t, report), temp)
        written.append(str(path))
    if t.tables:
        u = t.units
        for axis in t.axes:
            lu = "rad" if axis.design.oscillating else u
            path = out / f"{t.path.stem}_{axis.name}.csv"
            rows = table_rows(t, axis)
            with replacing(path) as temp, open(temp, "w", newline="") as f:
                w = csv.writer(f)
                w.writerow(
                    [
                        "master_deg",
                        f"position_{lu}",
                        f"velocity_{lu}_per_s",
                        f"acceleration_{lu}_per_s2",
                        f"jerk_{lu}_per_s3",
                    ]
                )
                for r in rows:
                    w.writerow([repr(float(x)) for x in r])
            written.append(str(path))
            path = out / f"{t.path.stem}_{axis.name}_segments.csv"
            segs = segment_rows(t, axis)
            with replacing(path) as temp, open(temp, "w", newline="") as f:
                dw = csv.DictWriter(f, fieldnames=list(segs[0]))
                dw.writeheader()
                dw.writerows(segs)
            written.append(str(path))
    return written


def format_report(t: Timing, report: list[ClearanceReport], files: list[str]) -> str:
    lines = [f"timing '{t.name}': {len(t.axes)} axes at {t.speed / RPM:g} rpm", ""]
    for a in t.axes:
        lines.append(
            f"  {a.name}: {a.design.path.name}, phase {math.degrees(a.phase):g}°, "
            f"{a.design.follower}"
        )
    if report:
        lines.append("")
        lines.append("clearances:")
    scale = UNITS[t.units]
    for c in report:
        mark = "ok  " if c.ok else "FAIL"
        lines.append(
            f"  {mark} {c.a}–{c.b}: least {c.least / scale:.6g} {t.units} at {c.at_deg:.2f}° "
            f"(limit {c.limit / scale:.6g} {t.units}, margin {(c.least - c.limit) / scale:.6g})"
        )
    for f in files:
        lines.append(f"wrote {f}")
    lines.append("")
    lines.append("all clearances hold" if all(c.ok for c in report) else "some clearances fail")
    return "\n".join(lines)
