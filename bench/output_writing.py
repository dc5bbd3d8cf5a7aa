"""What writing results costs: the four-bar example's kinematics, 200,000
steps, with no output, to CSV and to Parquet, in one run; µs per step and
the ratio to the run without output (targets: CSV within 2×, Parquet within
1.3×).

    uv run python bench/output_writing.py [--steps N] [--repeat R]
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import camlink

ROOT = Path(__file__).resolve().parents[1]


def best_of(repeat: int, run: object) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        run()  # type: ignore[operator]
        times.append(time.perf_counter() - start)
    return min(times)


def measure(steps: int, repeat: int) -> dict[str, float]:
    """µs per step of the four-bar kinematics with no output, to CSV and to
    Parquet (best of `repeat`)."""
    model = camlink.load(ROOT / "examples" / "four_bar.toml")
    step = 1e-5
    t_end = steps * step
    rows = {}
    with tempfile.TemporaryDirectory() as tmp:
        # The first Parquet output loads pyarrow's writers (seconds): a
        # cost per process, not per step.
        model.kinematics(t_end=10 * step, step=step, output=Path(tmp) / "warm.parquet")
        for label, output in [
            ("no output", None),
            ("CSV", Path(tmp) / "out.csv"),
            ("Parquet", Path(tmp) / "out.parquet"),
        ]:
            seconds = best_of(
                repeat,
                lambda output=output: model.kinematics(t_end=t_end, step=step, output=output),
            )
            rows[label] = seconds / (steps + 1) * 1e6
    return rows


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--steps", type=int, default=200_000)
    p.add_argument("--repeat", type=int, default=3)
    args = p.parse_args()
    rows = measure(args.steps, args.repeat)
    base = rows["no output"]
    print(f"four-bar kinematics, {args.steps} steps, best of {args.repeat}")
    for label, us in rows.items():
        print(f"  {label:<10} {us:7.2f} µs/step  {us / base:5.2f}×")


if __name__ == "__main__":
    main()
