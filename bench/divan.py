"""Run a `cargo bench` target and read divan's table of timings."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

_UNITS = {"ns": 1e-9, "µs": 1e-6, "us": 1e-6, "ms": 1e-3, "s": 1.0}
_TIME = re.compile(r"^\s*([0-9.]+)\s*(ns|µs|us|ms|s)\s*$")


def _seconds(cell: str) -> float | None:
    m = _TIME.match(cell)
    return float(m.group(1)) * _UNITS[m.group(2)] if m else None


def parse(text: str) -> dict[str, dict[str, float]]:
    """{"bench/arg": {"fastest": s, "median": s, "mean": s}} from divan's
    tree table (columns fastest │ slowest │ median │ mean │ …)."""
    out: dict[str, dict[str, float]] = {}
    stack: list[tuple[int, str]] = []
    for line in text.splitlines():
        if "│" not in line and "─" not in line:
            continue
        m = re.match(r"^([│├╰─\s]*)(\S+)\s+(.*)$", line)
        if not m or not re.search(r"[├╰]─", m.group(1)):
            continue
        depth = len(m.group(1))
        name = m.group(2)
        while stack and stack[-1][0] >= depth:
            stack.pop()
        stack.append((depth, name))
        cells = [c.strip() for c in m.group(3).split("│")]
        if len(cells) < 4 or _seconds(cells[0]) is None:
            continue
        key = "/".join(n for _, n in stack)
        out[key] = {
            "fastest": _seconds(cells[0]) or 0.0,
            "median": _seconds(cells[2]) or 0.0,
            "mean": _seconds(cells[3]) or 0.0,
        }
    return out


def run(package: str, bench: str, filters: list[str] | None = None) -> dict[str, dict[str, float]]:
    """`cargo bench -p PACKAGE --bench BENCH [-- FILTERS]`, parsed."""
    cmd = ["cargo", "bench", "-q", "-p", package, "--bench", bench]
    if filters:
        cmd += ["--", *filters]
    proc = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, check=False)
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed:\n{proc.stderr[-2000:]}")
    return parse(proc.stdout)
