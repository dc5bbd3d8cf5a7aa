"""Every number in an error or warning message is readable: at most six
significant digits (the core's `fmt_num`), never a run of digits like
``0.00005840402688042947`` or ``18446744073709551615``. Each case below
printed such a run before its message went through `fmt_num`."""

from __future__ import annotations

import re
from collections.abc import Callable
from pathlib import Path

import pytest

import camlink
from conftest import ROOT, run_cli

EXAMPLES = ROOT / "examples"

#: More than six significant digits in a row (a decimal point may sit
#: inside: "0.3333333", "12345.678").
LONG = re.compile(r"\d(?:\.?\d){7,}")


def long_numbers(text: str) -> list[str]:
    """The digit runs of `text` longer than six significant digits,
    leading zeros of a fraction not counted."""
    found = []
    for m in LONG.finditer(text):
        digits = m.group().replace(".", "").lstrip("0")
        if len(digits) > 6:
            found.append(m.group())
    return found


def test_the_scanner_finds_long_numbers() -> None:
    assert long_numbers("at t = 0.00005840402688042947 s") == ["0.00005840402688042947"]
    assert long_numbers("18446744073709551615 steps") == ["18446744073709551615"]
    assert long_numbers("at t = 5.8404e-5 s, 0.333333 s, 1e+300 steps, 0.000001 m") == []


def _pendulum() -> camlink.Model:
    return camlink.load(EXAMPLES / "pendulum.toml")


def _four_bar() -> camlink.Model:
    return camlink.load(EXAMPLES / "four_bar.toml")


CASES: dict[str, Callable[[], object]] = {
    # The step fell below the rounding of an odd time.
    "adaptive step below rounding": lambda: _pendulum().simulate(
        t_end=0.5, step=0.1, adaptive=True, atol=1e-300, h_min=1e-300
    ),
    # Output times that do not increase, at odd values.
    "times must increase": lambda: _pendulum().simulate(times=[0.0, 1 / 3, 1 / 7]),
    "kinematic times must increase": lambda: _four_bar().kinematics(times=[0.0, 1 / 3, 1 / 7]),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_python_errors_have_readable_numbers(name: str) -> None:
    with pytest.raises((camlink.AnalysisError, camlink.ModelError)) as info:
        CASES[name]()
    text = str(info.value)
    assert long_numbers(text) == [], text


def test_cli_lock_up_at_an_odd_time_has_readable_numbers(stuck_file: Path, tmp_path: Path) -> None:
    # The stuck four-bar locks between two output times of an odd step.
    proc = run_cli("run", stuck_file, "-o", "o.csv", "--t-end", "0.3", "--step", str(1 / 300),
                   cwd=tmp_path)
    assert proc.returncode == 1, proc.stderr
    assert "at t = " in proc.stderr
    assert long_numbers(proc.stderr) == [], proc.stderr


def test_cli_tiny_step_has_readable_numbers(four_bar_file: Path, tmp_path: Path) -> None:
    proc = run_cli("run", four_bar_file, "--step", "1e-300", "-o", "o.csv", cwd=tmp_path)
    assert proc.returncode == 2
    assert long_numbers(proc.stderr) == [], proc.stderr


def test_warnings_have_readable_numbers(stuck_file: Path) -> None:
    # Near the stuck position Φ_q becomes near singular: a warning with its
    # pivot and condition number.
    model = camlink.load(stuck_file)
    with pytest.raises(camlink.AnalysisError) as info:
        model.kinematics(t_end=0.3, step=1 / 300)
    partial = info.value.results
    texts = [str(w) for w in partial.summary.get("warnings", [])]
    texts.append(str(info.value))
    for text in texts:
        assert long_numbers(text) == [], text
