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
    "NearSingularWarning",
    "LiftOffWarning",
    "DesignWarning",
    "issue_run_warnings",
    "issue_design_warnings",
]


class CamlinkWarning(UserWarning):
    """Base of every camlink warning."""


class NearSingularWarning(CamlinkWarning):
    """The mechanism passed a near-singular position (a toggle or dead
    centre): velocities and accelerations there are less accurate."""


class LiftOffWarning(CamlinkWarning):
    """A cam contact's normal force went negative: the follower would leave
    its cam (see `Results.lift_off`)."""


class DesignWarning(CamlinkWarning):
    """A design finding of a curve contact (see `Model.design_check`)."""


def _category(message: str, lift_off_joints: set[str]) -> type[CamlinkWarning]:
    if message.startswith("near-singular"):
        return NearSingularWarning
    if any(message.startswith(f"{j}: normal force < 0") for j in lift_off_joints):
        return LiftOffWarning
    return CamlinkWarning


def issue_run_warnings(summary: Mapping[str, Any], stacklevel: int = 4) -> None:
    """Issues each of a run summary's ``warnings`` as a Python warning."""
    joints = {str(row["joint"]) for row in summary.get("lift_off", [])}
    for t, message in summary.get("warnings", []):
        warnings.warn(
            f"at t = {t:g} s: {message}", _category(message, joints), stacklevel=stacklevel
        )


def issue_design_warnings(findings: Iterable[Mapping[str, Any]], stacklevel: int = 3) -> None:
    """Issues each design finding as a `DesignWarning`."""
    for f in findings:
        warnings.warn(str(f["text"]), DesignWarning, stacklevel=stacklevel)
