"""Progress bars for long work: runs, animations, galleries.

A bar shows on a terminal only: it stays quiet when stderr is piped or
redirected, under ``--quiet`` and in CI (the ``CI`` environment variable
set). It shows the steps done, steps per second and the time left
(through tqdm).
"""

from __future__ import annotations

import os
import sys
from types import TracebackType
from typing import Self, TextIO

from tqdm import tqdm

__all__ = ["Progress", "wanted"]


def wanted(quiet: bool = False, stream: TextIO | None = None) -> bool:
    """True when a bar should show: not `quiet`, not in CI, and `stream`
    (default stderr) is a terminal."""
    stream = sys.stderr if stream is None else stream
    if quiet or os.environ.get("CI", "").lower() not in ("", "0", "false"):
        return False
    isatty = getattr(stream, "isatty", None)
    return bool(isatty and isatty())


class Progress:
    """A bar of `total` steps labelled `label`; `update(n)` adds n steps.
    Shown only when `wanted(quiet, stream)`; otherwise every call is a
    no-op."""

    def __init__(
        self, total: int, label: str, *, unit: str = "step", quiet: bool = False,
        stream: TextIO | None = None,
    ) -> None:
        stream = sys.stderr if stream is None else stream
        self.shown = wanted(quiet, stream)
        self.done = 0
        self._bar = (
            tqdm(total=total, desc=label, unit=unit, file=stream, mininterval=0.2,
                 dynamic_ncols=True, leave=False,
                 bar_format="{desc}: {percentage:3.0f}%|{bar}| {n_fmt}/{total_fmt} "
                 "[{rate_fmt}, {remaining} left]")
            if self.shown
            else None
        )

    def update(self, n: int = 1) -> None:
        self.done += n
        if self._bar is not None:
            self._bar.update(n)

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
            self._bar = None

    def __enter__(self) -> Self:
        return self

    def __exit__(
        self, kind: type[BaseException] | None, value: BaseException | None, tb: TracebackType | None
    ) -> None:
        self.close()
