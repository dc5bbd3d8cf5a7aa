"""SIGTERM and SIGHUP stop a run of the Python API as Ctrl-C does (the rows
computed are kept under the output's partial name) when the program left
them at their default handlers; a program's own handler is kept."""

from __future__ import annotations

import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

import camlink
from camlink import Results
from camlink.signals import Terminated, stop_on_termination
from conftest import four_bar_toml

# The child leaves SIGTERM and SIGHUP at their defaults whatever it
# inherits (a suite started under nohup passes SIGHUP on ignored).
RUN = """
import signal, sys, camlink
from camlink.signals import Terminated
signal.signal(signal.SIGTERM, signal.SIG_DFL)
signal.signal(signal.SIGHUP, signal.SIG_DFL)
camlink.model.CHUNK_ROWS = 64
try:
    camlink.load(sys.argv[1]).simulate(t_end=1000, step=0.001, h=0.001, output=sys.argv[2])
except Terminated as e:
    print("terminated", e.signum, e.output)
    sys.exit(3)
"""


def _wait_for(folder: Path, pattern: str) -> None:
    # A guard for the suite on a busy machine, not a measure of speed.
    deadline = time.monotonic() + 90
    while time.monotonic() < deadline:
        if any(p.stat().st_size > 4096 for p in folder.glob(pattern)):
            return
        time.sleep(0.05)
    raise AssertionError(f"no {pattern} grew in {folder}")


@pytest.mark.parametrize("signame", ["SIGTERM", "SIGHUP"])
def test_python_run_keeps_its_rows_on_sigterm_and_sighup(tmp_path: Path, signame: str) -> None:
    model = tmp_path / "fb.toml"
    model.write_text(four_bar_toml())
    out = tmp_path / "out.csv"
    proc = subprocess.Popen(
        [sys.executable, "-c", RUN, str(model), str(out)], stdout=subprocess.PIPE, text=True
    )
    _wait_for(tmp_path, "out.partial-*")
    sig = getattr(signal, signame)
    proc.send_signal(sig)
    stdout, _ = proc.communicate(timeout=120)
    partial = tmp_path / "out.partial.csv"
    assert proc.returncode == 3, stdout
    assert stdout.split() == ["terminated", str(int(sig)), str(partial)]
    rows = Results.load(partial)
    assert 64 <= len(rows) < 1_000_001
    assert not out.exists() and not list(tmp_path.glob("out.partial-*"))


def test_handlers_are_restored_and_a_programs_own_handler_is_kept() -> None:
    seen: list[int] = []

    def mine(signum: int, _frame: object) -> None:
        seen.append(signum)

    old = signal.signal(signal.SIGHUP, mine)
    try:
        before_term = signal.getsignal(signal.SIGTERM)
        with stop_on_termination(only_default=True):
            assert signal.getsignal(signal.SIGHUP) is mine
            expect_term = before_term is signal.SIG_DFL
            assert (signal.getsignal(signal.SIGTERM) is not before_term) == expect_term
        assert signal.getsignal(signal.SIGTERM) is before_term
        with pytest.raises(Terminated), stop_on_termination():
            signal.raise_signal(signal.SIGHUP)
        assert signal.getsignal(signal.SIGHUP) is mine and seen == []
    finally:
        signal.signal(signal.SIGHUP, old)


def test_a_run_leaves_the_handlers_as_it_found_them() -> None:
    before = {s: signal.getsignal(s) for s in (signal.SIGTERM, signal.SIGHUP)}
    camlink.loads(four_bar_toml()).run(t_end=0.01)
    assert {s: signal.getsignal(s) for s in before} == before
