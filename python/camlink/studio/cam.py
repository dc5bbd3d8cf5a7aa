"""The studio's cam design document: a cam design file (docs/cam-design.md)
open for editing, its motion program's segments changed in place and the
design analysed again by the core on each edit.

The file is held as plain data (`Editable`); an edit sets one key of one
``[[segments]]`` entry: ``law``, ``span_deg`` (deg of cam angle), ``lift``
(m, translating followers) or ``swing_deg`` (deg of arm swing, oscillating
followers). Each edit reads the data as `camlink cam` reads the file
(`camlink.cam.design.from_data`) and analyses it (`analyse`, the report
`camlink cam` prints): SVAJ over a turn (`CamCore.motion`), the profile
(`CamCore.surface`, a roller's pitch curve) and every design limit.

The analysis is a function of the data alone (the design file reads no
other file): the analyses of the last `CACHED` data are kept, keyed on
the data's JSON, so going back to data seen before (undo, redo, a law
tried and tried back) reuses its analysis, the base circle search of
``[limits] base_radius_search`` with it, instead of analysing again. Every
segment edit changes the motion program, which the search depends on:
an edit to data not seen before runs it.

An edit that makes the design invalid (spans that do not add up to 360°,
lifts that do not return the follower) is kept, so the next edit can mend
it; the solution then carries the loader's message and no curves, and the
file is not saved until the design loads again.
"""

from __future__ import annotations

import math
import os
import tomllib
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from camlink._core import ModelError
from camlink.cam.design import (
    LAWS,
    CamDesignError,
    Design,
    Report,
    analyse,
    from_data,
    is_design,
    json_safe,
    sample,
)
from camlink.studio.document import Document, Editable
from camlink.viz.front import b64

__all__ = ["CamDocument", "CamSolution", "cam_payload", "open_document"]

Array = npt.NDArray[np.float64]

#: Samples of θ over a turn for SVAJ and the profile: every 0.25°.
SAMPLES = 1441

#: Analyses kept for data seen before (`CamDocument`).
CACHED = 16

#: The keys of a segment the studio edits.
KEYS = ("law", "span_deg", "lift", "swing_deg")


@dataclass
class CamSolution:
    """An analysed design: θ over a turn (rad), [s, s′, s″, s‴] at each
    (m or rad of swing, per rad of cam angle), the cam surface (cam frame,
    m; n × 2), a roller's pitch curve (or None) and `camlink cam`'s
    report; or, for data that is not a valid design, `error` and no curves."""

    design: Design | None
    report: Report | None
    theta: Array
    motion: Array
    surface: Array
    pitch: Array | None
    #: Pressure angle at each θ (rad; None for a translating flat face,
    #: whose pressure angle is 0).
    pressure: Array | None = None
    #: Curvature κ = 1/ρ of the cam surface at each θ (1/m; > 0 convex,
    #: < 0 concave).
    curvature: Array | None = None
    error: str | None = None


def _invalid(message: str) -> CamSolution:
    empty = np.empty((0, 4))
    return CamSolution(None, None, np.empty(0), empty, np.empty((0, 2)), None, None, None, message)


def analyse_data(data: dict[str, Any], path: Path) -> CamSolution:
    """The design `data` of the file `path`, read and analysed as `camlink
    cam` does; a design that does not load gives its message as `error`."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            design = from_data(data, path)
            report = analyse(design)
        except (ModelError, ValueError) as e:
            return _invalid(str(e))
        core = design.core()
        theta, motion = sample(core, SAMPLES)
        surface = np.asarray(core.surface(theta), dtype=np.float64)
        pitch = core.pitch(theta)
        contact = core.contact(theta)
        pressure = (None if design.follower == "translating-flat" else
                    np.asarray(contact["pressure_angle"], dtype=np.float64))
        with np.errstate(divide="ignore"):
            curvature = 1.0 / np.asarray(contact["rho"], dtype=np.float64)
    return CamSolution(design, report, theta, motion, surface,
                       None if pitch is None else np.asarray(pitch, dtype=np.float64), pressure,
                       curvature)


class CamDocument(Editable):
    """A cam design file open for editing. `solution` is the analysis of
    the current data; `set_segment` changes one segment's key; `undo`,
    `redo` and `save` as their names say."""

    def __init__(self, path: str | os.PathLike[str], text: str | None = None) -> None:
        full = Path(path).resolve()
        if text is None:
            if not full.is_file():
                raise FileNotFoundError(f"no such design file: {path}")
            text = full.read_text(encoding="utf-8")
        try:
            data = tomllib.loads(text)
        except tomllib.TOMLDecodeError as e:
            raise CamDesignError(f"{full}: {e}") from None
        first = analyse_data(data, full)
        if first.error is not None:
            raise CamDesignError(first.error)
        self._open(full, text)
        # The analyses of the last data, by the data's JSON (oldest first).
        self._analyses: dict[str, CamSolution] = {self._json: first}
        self.solution: CamSolution = first

    @property
    def oscillating(self) -> bool:
        """Whether the follower swings (lifts are ``swing_deg``, deg)."""
        return str((self._data.get("follower") or {}).get("type", "")).startswith("oscillating")

    def segments(self) -> list[dict[str, Any]]:
        """Each segment's law, span (deg) and lift (m, or swing in deg for
        an oscillating follower) as the data gives them, the cam angle it
        starts at (deg: the sum of the spans before it) and whether it has
        end conditions (a polynomial's ``start``/``end``)."""
        key = "swing_deg" if self.oscillating else "lift"
        out = []
        at: float | None = 0.0
        for seg in self._data.get("segments") or []:
            span = seg.get("span_deg")
            out.append({"law": seg.get("law"), "span_deg": span, "lift": seg.get(key, 0.0),
                        "from_deg": at, "ends": "start" in seg or "end" in seg})
            number = isinstance(span, int | float) and not isinstance(span, bool)
            at = at + float(span) if at is not None and number else None
        return out

    def _solve(self) -> CamSolution:
        self._json = self._dump()
        solution = self._analyses.pop(self._json, None)
        if solution is None:
            solution = analyse_data(self._data, self.path)
        self._analyses[self._json] = solution
        while len(self._analyses) > CACHED:
            del self._analyses[next(iter(self._analyses))]
        return solution

    def set_segment(self, index: int, key: str, value: str | float,
                    gesture: object = None) -> CamSolution:
        """Sets `key` (``law``, ``span_deg``, or ``lift``: the lift in m, or
        the swing in deg for an oscillating follower) of segment `index`
        (from 0) to `value`, and analyses the design again."""
        segs = self._data.get("segments") or []
        if not 0 <= index < len(segs):
            raise KeyError(f"no segment {index} (the program has {len(segs)})")
        if key not in KEYS:
            raise KeyError(f"segment key {key!r} is not one of {', '.join(KEYS)}")
        if key in ("lift", "swing_deg"):
            key = "swing_deg" if self.oscillating else "lift"
        if key == "law":
            if not isinstance(value, str):
                raise TypeError(f"segments[{index}].law: {value!r} is not a name")
            new: str | float = value
        else:
            try:
                new = float(value)
            except (TypeError, ValueError):
                raise ModelError(f"segments[{index}].{key}: {value!r} is not a number") from None
            if not math.isfinite(new):
                raise ModelError(f"segments[{index}].{key}: {value} is not a finite number")
        seg = segs[index]
        solution: CamSolution = self._apply(gesture, lambda: seg.__setitem__(key, new))
        return solution

    def save(self) -> Path:
        """Writes the file as `Editable.save` does, once the design loads."""
        if self.solution.error is not None:
            raise CamDesignError(f"{self.path.name} not saved: {self.solution.error}")
        return super().save()


def _peaks(theta: Array, motion: Array) -> dict[str, list[float]]:
    """Each of s, s′, s″, s‴: its largest |value| (signed) and the θ (deg) there."""
    out = {}
    for k, name in enumerate(("s", "v", "a", "j")):
        i = int(np.argmax(np.abs(motion[:, k])))
        out[name] = [float(motion[i, k]), math.degrees(float(theta[i]))]
    return out


def cam_payload(doc: CamDocument, encode: Callable[..., Any] = b64
                ) -> dict[str, Any]:
    """The cam page's data: the segments, and for a valid design SVAJ over
    a turn (θ in rad; s, v = s′, a = s″, j = s‴ in m or rad per rad^k),
    their peaks, the profile (cam frame, m, x and y interleaved), the base
    circle, the pressure angle at each θ (rad; not for a translating flat
    face) with its peak and the limit (rad, or None), the surface's
    curvature κ = 1/ρ at each θ (1/m, > 0 convex) with its largest and the
    limit 1/min_radius (1/m, or None), and `camlink cam`'s report (as
    ``--json`` gives it). Each array is given as `encode(array, dtype)`
    (base64 text by default)."""
    sol = doc.solution
    data: dict[str, Any] = {
        "kind": "cam",
        "title": str(doc._data.get("name") or doc.path.stem),
        "file": doc.path.name,
        "follower": str((doc._data.get("follower") or {}).get("type", "")),
        "oscillating": doc.oscillating,
        "laws": list(LAWS),
        "segments": doc.segments(),
        "error": sol.error,
        "dirty": doc.dirty,
        "undo": doc.can_undo,
        "redo": doc.can_redo,
    }
    if sol.report is None or sol.design is None:
        return data
    data["theta"] = encode(sol.theta)
    for k, name in enumerate(("s", "v", "a", "j")):
        data[name] = encode(sol.motion[:, k])
    data["peaks"] = _peaks(sol.theta, sol.motion)
    if sol.pressure is not None:
        data["pressure"] = encode(sol.pressure)
        i = int(np.argmax(np.abs(sol.pressure)))
        data["peaks"]["p"] = [float(sol.pressure[i]), math.degrees(float(sol.theta[i]))]
        data["pressure_limit"] = sol.design.limits.max_pressure_angle
    if sol.curvature is not None:
        data["curvature"] = encode(sol.curvature)
        i = int(np.argmax(sol.curvature))
        data["peaks"]["k"] = [float(sol.curvature[i]), math.degrees(float(sol.theta[i]))]
        least = sol.design.limits.min_radius
        data["curvature_limit"] = None if least is None else 1.0 / least
    data["surface"] = encode(sol.surface.ravel())
    data["pitch"] = None if sol.pitch is None else encode(sol.pitch.ravel())
    data["base_radius"] = sol.design.base_radius
    data["report"] = json_safe(sol.report.to_dict())
    return data


def open_document(path: str | os.PathLike[str]) -> Document | CamDocument:
    """The document for `path`: a `CamDocument` for a cam design file (a
    TOML file with ``[follower]`` and ``[[segments]]``), else a model
    `Document`."""
    full = Path(path)
    if full.suffix.lower() == ".toml" and full.is_file():
        text = full.read_text(encoding="utf-8")
        try:
            data = tomllib.loads(text)
        except tomllib.TOMLDecodeError:
            data = {}
        if is_design(data):
            return CamDocument(full, text)
    return Document(full)
