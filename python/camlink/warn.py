"""camlink's warnings through Python's `warnings` module, so that a
notebook or a script shows them as they happen; each kind has its own
category, so a user can filter one (``warnings.simplefilter("ignore",
camlink.LiftOffWarning)``) or turn them into errors."""

from __future__ import annotations

import warnings
from collections.abc import Iterable, Mapping
from typing import Any

__all__ = [
    "CamlinkWarning",
    "CourseFileWarning",
    "DesignWarning",
    "LiftOffWarning",
    "LimitWarning",
    "LoadWarning",
    "NearSingularWarning",
    "issue_design_warnings",
    "issue_load_warnings",
    "issue_run_warnings",
]


class CamlinkWarning(UserWarning):
    """Base of every camlink warning."""


class NearSingularWarning(CamlinkWarning):
    """The mechanism passed a near-singular position (a toggle or dead
    centre): velocities and accelerations there are less accurate."""


class LiftOffWarning(CamlinkWarning):
    """A cam contact's normal force went negative: the follower would leave
    its cam (see `Results.lift_off`)."""


class LimitWarning(CamlinkWarning):
    """A driven motion took a joint's angle or stroke out of its `limits`
    (kinematics and inverse dynamics follow their drivers; forward
    dynamics stops the joint there)."""


class CourseFileWarning(CamlinkWarning):
    """A simEngine2D course file holds something that is read past, as the
    course engine reads past it (a joint's constant ``fun``, an empty force
    entry, a ``contacts`` list); the message names the file, line and field."""


class DesignWarning(CamlinkWarning):
    """A design finding of a curve contact (see `Model.design_check`)."""


class LoadWarning(CamlinkWarning):
    """A model file left a value to be measured in a placement that the
    assembly moved, or a similar finding made while loading (see
    `Model.warnings`)."""


#: The category of each warning kind of `camlink.WARNING_KINDS`.
CATEGORIES: dict[str, type[CamlinkWarning]] = {
    "near_singular": NearSingularWarning,
    "lift_off": LiftOffWarning,
    "limit_exceeded": LimitWarning,
}


def issue_run_warnings(summary: Mapping[str, Any], stacklevel: int = 4) -> None:
    """Issues each of a run summary's ``warnings`` (`camlink.RunWarning`
    records) as a Python warning of its kind's category."""
    for w in summary.get("warnings", []):
        warnings.warn(str(w), CATEGORIES.get(w.kind, CamlinkWarning), stacklevel=stacklevel)


def issue_load_warnings(
    records: Iterable[Mapping[str, Any]], source: object, stacklevel: int = 3
) -> None:
    """Issues each warning found while loading a model as a `LoadWarning`,
    prefixed with the model's `source`."""
    for w in records:
        warnings.warn(f"{source}: {w['text']}", LoadWarning, stacklevel=stacklevel)


def issue_design_warnings(findings: Iterable[Mapping[str, Any]], stacklevel: int = 3) -> None:
    """Issues each design finding as a `DesignWarning`."""
    for f in findings:
        warnings.warn(str(f["text"]), DesignWarning, stacklevel=stacklevel)
