"""Kinds of analysis errors and warnings, and warnings as records.

Every `camlink.AnalysisError` carries ``kind`` (one of `ERROR_KINDS`),
``time`` (s), ``joints`` (the joints involved) and ``residual``; every
warning of a run's ``summary["warnings"]`` is a `RunWarning`. Programs
match the kind, never the message (``docs/errors.md`` describes each).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Final

from camlink import _core

__all__ = ["ERROR_KINDS", "WARNING_KINDS", "RunWarning", "warnings_from"]

#: The kinds an `AnalysisError` may have (the core's, in its order).
ERROR_KINDS: Final[tuple[str, ...]] = _core.ERROR_KINDS

#: The kinds a `RunWarning` may have.
WARNING_KINDS: Final[tuple[str, ...]] = _core.WARNING_KINDS


@dataclass(frozen=True)
class RunWarning:
    """A warning of a run: it went on, but a result may need care."""

    #: One of `WARNING_KINDS`.
    kind: str
    #: Time (s) where it arose.
    time: float
    #: Joints involved (may be empty).
    joints: tuple[str, ...]
    #: A sentence for people.
    message: str

    def __str__(self) -> str:
        return f"at t = {self.time:g} s: {self.message}"


def warnings_from(raw: Iterable[Mapping[str, object]]) -> list[RunWarning]:
    """The binding's warning dicts as `RunWarning`s."""
    return [
        RunWarning(
            kind=str(w["kind"]),
            time=float(w["time"]),  # type: ignore[arg-type]
            joints=tuple(str(j) for j in w["joints"]),  # type: ignore[attr-defined]
            message=str(w["message"]),
        )
        for w in raw
    ]
