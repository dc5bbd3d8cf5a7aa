"""The outputs of a study: reductions of each run, declared, never code.

Each is computed next to its run, in Rust, as the rows are produced, so
that a study of many variants never holds their full result tables. Angles
are in radians, times in seconds, efforts in N·m (revolute drivers) or N.

| kind | fields | value |
|---|---|---|
| ``max_abs`` | channel | largest \\|value\\| of the channel |
| ``max`` / ``min`` | channel | largest / least value |
| ``range`` | channel | largest minus least value (an angle's swing) |
| ``at`` | channel, time | value at `time`, linear between output times |
| ``least_transmission_angle`` | bodies | least angle between two bodies' x axes, folded into [0, π/2] |
| ``max_pressure_angle`` | joint | largest ``<joint>.pressure_angle`` |
| ``peak_effort`` | driver | largest \\|``<driver>.effort``\\| (inverse or forward dynamics) |
| ``first_lift_off`` | joint (optional) | first time a follower leaves its cam; NaN when it stays on |
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from camlink import _core
from camlink._core import ModelError

__all__ = [
    "KINDS",
    "Output",
    "at",
    "first_lift_off",
    "least_transmission_angle",
    "max_abs",
    "max_of",
    "max_pressure_angle",
    "min_of",
    "parse_outputs",
    "peak_effort",
    "range_of",
]

#: Each kind and the fields it needs (the core's table,
#: ``camlink_study::declaration::KINDS``; ``first_lift_off`` may name a
#: joint).
KINDS: dict[str, tuple[str, ...]] = {k: tuple(v) for k, v in _core.output_kinds().items()}


@dataclass(frozen=True)
class Output:
    """One declared output: its kind and the fields it reads."""

    kind: str
    fields: tuple[tuple[str, Any], ...] = ()

    def to_json(self) -> str:
        """The declaration as the Rust batch runner reads it."""
        return json.dumps({"kind": self.kind, **dict(self.fields)})


def max_abs(channel: str) -> Output:
    """Largest |value| of `channel` over the run."""
    return Output("max_abs", (("channel", channel),))


def max_of(channel: str) -> Output:
    """Largest value of `channel`."""
    return Output("max", (("channel", channel),))


def min_of(channel: str) -> Output:
    """Least value of `channel`."""
    return Output("min", (("channel", channel),))


def range_of(channel: str) -> Output:
    """Largest minus least value of `channel` (the swing of an angle, rad)."""
    return Output("range", (("channel", channel),))


def at(channel: str, time: float) -> Output:
    """The value of `channel` at `time` (s), linear between output times."""
    return Output("at", (("channel", channel), ("time", float(time))))


def least_transmission_angle(body_i: str, body_j: str) -> Output:
    """Least angle (rad) between the x axes of two bodies, folded into
    [0, π/2]: a four-bar's transmission angle when the coupler's and the
    rocker's frames lie along their links."""
    return Output("least_transmission_angle", (("bodies", [body_i, body_j]),))


def max_pressure_angle(joint: str) -> Output:
    """Largest pressure angle (rad) of a curve-contact joint."""
    return Output("max_pressure_angle", (("joint", joint),))


def peak_effort(driver: str) -> Output:
    """Largest |effort| of a driver (N·m or N): the peak driver torque."""
    return Output("peak_effort", (("driver", driver),))


def first_lift_off(joint: str | None = None) -> Output:
    """First time (s) a cam follower (of `joint`, or any) leaves its cam;
    NaN when it stays on."""
    return Output("first_lift_off", () if joint is None else (("joint", joint),))


def parse_outputs(
    outputs: Mapping[str, Output | Mapping[str, Any]], where: str = "outputs"
) -> dict[str, Output]:
    """Named outputs from `Output` values or plain tables such as
    ``{"kind": "range", "channel": "rocker.phi"}``; an error names the
    output and the field at fault (`where` prefixes it)."""
    if not isinstance(outputs, Mapping) or not outputs:
        raise ModelError(f"{where}: give at least one output, as name = {{ kind = ..., ... }}")
    parsed: dict[str, Output] = {}
    for name, spec in outputs.items():
        field = f"{where}.{name}"
        if isinstance(spec, Output):
            parsed[name] = spec
            continue
        if not isinstance(spec, Mapping):
            raise ModelError(f"{field}: expected a table with a kind, got {type(spec).__name__}")
        # The core checks the kind and each field, naming the one at fault.
        _core.check_output(field, dict(spec))
        kind = spec["kind"]
        values = {k: v for k, v in spec.items() if k != "kind"}
        parsed[name] = Output(
            kind, tuple((k, list(v) if k == "bodies" else v) for k, v in sorted(values.items()))
        )
    return parsed
