"""SIGTERM and SIGHUP stop a run as Ctrl-C does: they raise `Terminated`
(a `KeyboardInterrupt`), which the run turns into its partial output.

The CLI installs the handlers for its whole life. The Python API installs
them only for the length of a run, only in the main thread, and only for a
signal whose handler is the default one (which would end the process at
once and leave the output under its temporary name): a program that
handles these signals itself keeps its own handlers.
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

__all__ = ["Terminated", "stop_on_termination"]

#: The signals handled, by name (SIGHUP does not exist on Windows).
SIGNALS = ("SIGTERM", "SIGHUP")


class Terminated(KeyboardInterrupt):
    """SIGTERM or SIGHUP, stopping a run as Ctrl-C does."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum


def _terminate(signum: int, _frame: object) -> None:
    raise Terminated(signum)


@contextmanager
def stop_on_termination(*, only_default: bool = False) -> Iterator[None]:
    """Within the block, SIGTERM and SIGHUP raise `Terminated`; with
    `only_default`, only where their handler is the default one. Outside
    the main thread (where Python cannot set handlers) it does nothing."""
    old: dict[int, Any] = {}
    if threading.current_thread() is threading.main_thread():
        for name in SIGNALS:
            sig = getattr(signal, name, None)
            if sig is None:
                continue
            if only_default and signal.getsignal(sig) is not signal.SIG_DFL:
                continue
            old[sig] = signal.signal(sig, _terminate)
    try:
        yield
    finally:
        for sig, handler in old.items():
            signal.signal(sig, handler)
