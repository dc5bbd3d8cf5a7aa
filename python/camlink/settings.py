"""Run settings given in Python, checked by the same rules as a model
file's ``[analysis]`` keys (the rules live in Rust: ``camlink_core::setting``)."""

from __future__ import annotations

import numbers
from collections.abc import Mapping

import numpy as np

from camlink import _core
from camlink._core import ModelError

__all__ = ["check_settings"]

#: Arguments that are not numbers checked by a rule.
_OTHER = {"self", "points", "times", "output", "analysis", "on_rows", "start"}


def check_settings(settings: Mapping[str, object]) -> None:
    """Raises `ModelError` naming the first setting whose value breaks its
    rule (`None` means "not given" and passes)."""
    for key, value in settings.items():
        if value is None or key in _OTHER:
            continue
        if _core.setting_is_flag(key):
            if not isinstance(value, (bool, np.bool_)):
                raise ModelError(f"{key} must be True or False, not {value!r}")
            continue
        if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
            raise ModelError(f"{key} must be a number, not {value!r}")
        _core.check_setting(key, float(value))
