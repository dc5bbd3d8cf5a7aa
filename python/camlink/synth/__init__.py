"""Linkage synthesis: from the motion a mechanism must make to a four-bar
that makes it, as a camlink model.

The mathematics, the problem files and the checks are in Rust
(``crates/camlink-synth``); this module presents them::

    from camlink import synth
    result = synth.solve("examples/synthesis_three_positions.toml")
    best = result.solutions[0]
    best.defects            # () when the linkage passes every check
    model = best.model()    # a camlink.Model, ready to run
    synth.write(result, "out")

Problem files and reports are documented in docs/synthesis.md. Lengths
in m, angles in rad.
"""

from __future__ import annotations

import json
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType
from typing import TYPE_CHECKING, Any

from camlink import _core
from camlink._core import ModelError
from camlink.io.output import check_not_input
from camlink.model import Model, loads

if TYPE_CHECKING:
    from distributed import Client

__all__ = ["Defect", "Links", "Solution", "Synthesis", "report_text", "solve", "solve_text", "write"]


@dataclass(frozen=True)
class Defect:
    """A check a solution fails: `kind` (``branch``, ``order``,
    ``dead_position``, ``transmission``, ``grashof``) and what it means here."""

    kind: str
    message: str


@dataclass(frozen=True)
class Links:
    """Link lengths (m) and ground pivots (m, global frame). A slider-crank
    has no ground link, rocker or O4 (None); its slide is in the report's
    ``links.slide`` and its offset (m) in `offset`."""

    ground: float | None
    crank: float
    coupler: float
    rocker: float | None
    o2: tuple[float, float]
    o4: tuple[float, float] | None
    offset: float | None = None


@dataclass(frozen=True)
class Solution:
    """One synthesised four-bar.

    `model_text` is its model file (TOML, runs with ``camlink run``);
    `report` the full report (read-only; fields in docs/synthesis.md)."""

    name: str
    method: str
    links: Links
    grashof: str
    turning: str
    #: Least and largest transmission angle over the motion (rad); None
    #: where the linkage does not assemble through it.
    transmission: tuple[float | None, float | None]
    defects: tuple[Defect, ...]
    model_text: str
    report: Mapping[str, Any]

    def model(self) -> Model:
        """The solution as a camlink model."""
        return loads(self.model_text, source=f"{self.name}.toml")


@dataclass(frozen=True)
class Synthesis:
    """What a problem gave: its kind (``motion``, ``function``,
    ``two_positions``, ``burmester``, ``slider_motion``,
    ``slider_function``) and solutions."""

    kind: str
    solutions: tuple[Solution, ...]


def _freeze(value: Any) -> Any:
    if isinstance(value, dict):
        return MappingProxyType({k: _freeze(v) for k, v in value.items()})
    if isinstance(value, list):
        return tuple(_freeze(v) for v in value)
    return value


def _solution(name: str, model_text: str, report_json: str) -> Solution:
    r = json.loads(report_json)
    links, checks = r["links"], r["checks"]
    return Solution(
        name=name,
        method=r["method"],
        links=Links(
            ground=links.get("ground"),
            crank=links["crank"],
            coupler=links["coupler"],
            rocker=links.get("rocker"),
            o2=(links["O2"][0], links["O2"][1]),
            o4=(links["O4"][0], links["O4"][1]) if "O4" in links else None,
            offset=links.get("offset"),
        ),
        grashof=checks["grashof"],
        turning=checks["turning"],
        transmission=(checks["transmission"]["min"], checks["transmission"]["max"]),
        defects=tuple(Defect(d["kind"], d["message"]) for d in checks["defects"]),
        model_text=model_text,
        report=_freeze(r),
    )


def _synthesis(kind: str, rows: Sequence[tuple[str, str, str]]) -> Synthesis:
    return Synthesis(kind, tuple(_solution(*row) for row in rows))


def solve(problem: str | os.PathLike[str], *, client: Client | None = None) -> Synthesis:
    """Solves the synthesis problem file `problem` (TOML). A bad file raises
    `ModelError` naming the file, the line and the field.

    A path problem's search runs its starts on the local cores; with
    `client` (a ``dask.distributed.Client``) they are spread over its
    workers in batches, and the result is the same as the local run's
    (each start depends on its index and the problem alone)."""
    path = Path(problem)
    if not path.is_file():
        raise FileNotFoundError(2, "no such file", str(path))
    if client is None:
        return _synthesis(*_core.synth_file(path))
    return _solve_dask(path, client)


#: Starts of a path search sent to a Dask worker as one task.
DASK_BATCH = 8


def run_starts_task(text: str, source: str, stem: str, lo: int, hi: int) -> list[tuple[int, list[float]]]:
    """Starts `lo` to `hi` of a path problem's search, on a Dask worker."""
    return _core.synth_path_starts(text, source, stem, lo, hi)[0]


def _solve_dask(path: Path, client: Client) -> Synthesis:
    """The path search of `path` with its starts spread over `client`'s
    workers; other problems are solved here."""
    from distributed import as_completed

    text = _core.synth_read(path)
    source, stem = str(path), path.stem
    # Validates the problem here, and gives its number of starts (none:
    # not a search).
    _, total = _core.synth_path_starts(text, source, stem, 0, 0)
    if total == 0:
        return _synthesis(*_core.synth_str(text, source, stem))
    # Workers may run in other folders: a target file resolves against an
    # absolute path.
    where = os.path.abspath(source)
    futures = [
        client.submit(run_starts_task, text, where, stem, lo, min(lo + DASK_BATCH, total), pure=False)
        for lo in range(0, total, DASK_BATCH)
    ]
    starts: list[tuple[int, list[float]]] = []
    try:
        for f in as_completed(futures):
            starts.extend(f.result())
    except BaseException:
        client.cancel(futures)
        raise
    return _synthesis(*_core.synth_str_from_starts(text, source, stem, starts))


def solve_text(text: str, name: str = "synthesis") -> Synthesis:
    """Solves the synthesis problem in `text` (TOML); `name` names the
    solutions (unless the problem gives ``name``) and the text in errors."""
    return _synthesis(*_core.synth_str(text, f"{name}.toml", name))


def _paths(result: Synthesis, folder: Path) -> list[Path]:
    return [folder / f"{s.name}.toml" for s in result.solutions]


def write(
    result: Synthesis,
    folder: str | os.PathLike[str],
    *,
    inputs: Sequence[str | os.PathLike[str]] = (),
    force: bool = False,
) -> list[Path]:
    """Writes each solution's model to ``folder/<name>.toml`` (the folder
    is made if missing) and returns the paths. A file that exists is
    replaced only with `force`, and never one of `inputs` (the problem
    file); each is written to a temporary file renamed over the output."""
    from camlink.io.output import _Target

    out = Path(folder)
    if out.exists() and not out.is_dir():
        raise ModelError(f"output '{out}' is a file; give a folder")
    paths = _paths(result, out)
    for p in paths:
        check_not_input(p, inputs)
        if p.exists() and not force:
            raise ModelError(f"'{p}' exists; use --force (force=True) to replace it")
    out.mkdir(parents=True, exist_ok=True)
    for s, p in zip(result.solutions, paths, strict=True):
        target = _Target(p, ".toml")
        try:
            target.temp.write_text(s.model_text, encoding="utf-8")
            target.finish(target.temp, complete=True)
        finally:
            target.temp.unlink(missing_ok=True)
    return paths


def _deg(x: float | None) -> str:
    return "—" if x is None else f"{x * 180 / 3.141592653589793:.2f}°"


def report_text(result: Synthesis) -> str:
    """The report of `result` as text: per solution its links, class,
    transmission angle, structural error (function generation) and
    defects."""
    lines: list[str] = []
    for s in result.solutions:
        r, links = s.report, s.links
        if links.rocker is None or links.ground is None or links.o4 is None:
            slide = r["links"]["slide"]
            lines.append(f"{s.name}: {s.method.replace('_', ' ')}, {s.grashof}")
            lines.append(
                f"  links (m)     crank {links.crank:.6g}  coupler {links.coupler:.6g}  "
                f"offset {links.offset:.6g}"
            )
            lines.append(
                f"  pivot (m)     O2 ({links.o2[0]:.6g}, {links.o2[1]:.6g})  slide through "
                f"({slide['point'][0]:.6g}, {slide['point'][1]:.6g}) at {_deg(slide['angle'])}"
            )
        else:
            four_bar = "" if s.method.startswith("burmester") else " four-bar"
            lines.append(f"{s.name}: {s.method.replace('_', ' ')}{four_bar}, {s.grashof}")
            lines.append(
                f"  links (m)     ground {links.ground:.6g}  crank {links.crank:.6g}  "
                f"coupler {links.coupler:.6g}  rocker {links.rocker:.6g}"
            )
            lines.append(
                f"  pivots (m)    O2 ({links.o2[0]:.6g}, {links.o2[1]:.6g})  "
                f"O4 ({links.o4[0]:.6g}, {links.o4[1]:.6g})"
            )
        if "quality" in r:
            q = r["quality"]
            cand = r["candidates"]
            lines.append(
                f"  rank {r['rank']}        least transmission angle {_deg(q['value'])}, link ratio "
                f"{q['link_ratio']:.3g}; {cand['kept']} of {cand['pairs']} pairs kept"
            )
        if "moving_pivots" in r:
            a, b = r["moving_pivots"]["A"], r["moving_pivots"]["B"]
            lines.append(
                f"  coupler frame A ({a[0]:.6g}, {a[1]:.6g})  B ({b[0]:.6g}, {b[1]:.6g})"
            )
        lines.append(
            f"  transmission  {_deg(s.transmission[0])} … {_deg(s.transmission[1])} over the motion; "
            f"crank turns {s.turning}"
        )
        if "structural_error" in r and r["structural_error"].get("units") == "m":
            se = r["structural_error"]
            lines.append(
                f"  structural error  max {se['max']:.4g} m at x = {se['at_x']:.6g}, "
                f"rms {se['rms']:.4g} m ({se['samples']} samples)"
            )
        elif "structural_error" in r:
            se = r["structural_error"]
            lines.append(
                f"  structural error  max {_deg(se['max'])} at x = {se['at_x']:.6g}, "
                f"rms {_deg(se['rms'])} ({se['samples']} samples)"
            )
        if "error" in r:
            e = r["error"]
            lines.append(
                f"  path error    RMS {e['rms'] * 1000:.4g} mm, largest {e['max'] * 1000:.4g} mm "
                f"over {len(r['targets'])} targets"
            )
        if "time_ratio" in r:
            lines.append(f"  rocker swing  {_deg(r['swing'])}, time ratio {r['time_ratio']:.6g}")
        if s.defects:
            for d in s.defects:
                lines.append(f"  DEFECT {d.kind}: {d.message}")
        else:
            lines.append("  no defects")
    return "\n".join(lines)
