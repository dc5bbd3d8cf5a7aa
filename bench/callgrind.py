"""Instruction counts per step of the core benchmarks, under callgrind.

Each benchmark runs twice under ``valgrind --tool=callgrind`` (the example
``crates/camlink-model/examples/steps.rs``, release build), at ``--steps`` and
at twice as many steps; the difference of the two totals divided by the
difference of the step counts is the cost of one step, with loading and
set-up cancelled out. Counts do not depend on the machine's load, so they
show a regression that timings would hide in noise.

    uv run python bench/callgrind.py                      # all benchmarks
    uv run python bench/callgrind.py --only four_bar --steps 500

valgrind comes from Debian's packages (``apt-get install valgrind``).
"""

from __future__ import annotations

import argparse
import re
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BINARY = ROOT / "target" / "release" / "examples" / "steps"

# (benchmark, bodies): the chain's count is also given per body.
BENCHMARKS: list[tuple[str, int]] = [
    ("four_bar", 3),
    ("cam_roller", 2),
    ("slider_crank", 3),
    ("chain10", 10),
    ("chain100", 100),
    ("driven_chain100", 100),
    ("driven_chain1000", 1000),
]


@dataclass(frozen=True)
class Count:
    """Instructions of one benchmark per step and per body per step."""

    name: str
    per_step: float
    per_body_step: float


def total_instructions(name: str, steps: int) -> int:
    """The callgrind total (Ir) of one run of ``steps`` steps."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "callgrind.out"
        subprocess.run(
            [
                "valgrind",
                "--tool=callgrind",
                f"--callgrind-out-file={out}",
                str(BINARY),
                name,
                str(steps),
            ],
            check=True,
            capture_output=True,
        )
        text = out.read_text()
    match = re.search(r"^(?:summary|totals):\s*(\d+)", text, re.MULTILINE)
    if match is None:
        raise RuntimeError(f"no instruction total in callgrind's output for {name}")
    return int(match.group(1))


def count(name: str, bodies: int, steps: int) -> Count:
    """Instructions per step: the difference between 2·steps and steps."""
    one = total_instructions(name, steps)
    two = total_instructions(name, 2 * steps)
    per_step = (two - one) / steps
    return Count(name, per_step, per_step / bodies)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=1000, help="steps of the shorter run")
    parser.add_argument("--only", action="append", help="a benchmark name (repeatable)")
    parser.add_argument("--no-build", action="store_true", help="use the existing binary")
    args = parser.parse_args()
    if shutil.which("valgrind") is None:
        print("valgrind is not installed (apt-get install valgrind)", file=sys.stderr)
        return 1
    if not args.no_build:
        subprocess.run(
            ["cargo", "build", "--release", "-p", "camlink-model", "--example", "steps"],
            cwd=ROOT,
            check=True,
        )
    chosen = [(n, b) for n, b in BENCHMARKS if not args.only or n in args.only]
    print(f"{'benchmark':<18} {'instructions/step':>18} {'per body':>12}")
    for name, bodies in chosen:
        c = count(name, bodies, args.steps)
        print(f"{c.name:<18} {c.per_step:>18,.0f} {c.per_body_step:>12,.0f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
