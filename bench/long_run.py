"""Memory and time of a long kinematic run written to Parquet and to CSV:
the four-bar example for ``--steps`` steps of 10 µs and for 1,000 steps,
each in a fresh process; prints the peak resident memory (MB) and µs per
step of each, and of the long run without output, with the long runs' time
as a ratio to the run without output.

    uv run python bench/long_run.py [--steps 1000000]

The issue's target: the long run's memory within 50 MB of the short one's
(same format), its time within 1.5× of the in-memory run.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

# Runs in a child process so that each figure is that process's own peak:
# its high-water mark VmHWM (Linux), not getrusage's ru_maxrss, which starts
# from the parent's size at fork.
CHILD = """
import json, sys, time
import camlink
steps, output = int(sys.argv[1]), sys.argv[2] or None
model = camlink.load(sys.argv[3])
start = time.perf_counter()
model.kinematics(t_end=steps * 1e-5, step=1e-5, output=output)
seconds = time.perf_counter() - start
with open("/proc/self/status") as status:
    peak = next(int(line.split()[1]) for line in status if line.startswith("VmHWM:")) / 1024
print(json.dumps({"us_per_step": seconds / (steps + 1) * 1e6, "peak_mb": peak}))
"""


def measure(steps: int, output: str) -> dict[str, float]:
    model = ROOT / "examples" / "four_bar.toml"
    out = subprocess.run(
        [sys.executable, "-c", CHILD, str(steps), output, str(model)],
        check=True,
        capture_output=True,
        text=True,
    )
    result: dict[str, float] = json.loads(out.stdout)
    return result


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--steps", type=int, default=1_000_000)
    args = p.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        parquet = str(Path(tmp) / "out.parquet")
        csv = str(Path(tmp) / "out.csv")
        memory = measure(args.steps, "")
        rows = [
            ("1,000 steps to Parquet", measure(1_000, parquet)),
            (f"{args.steps:,} steps to Parquet", measure(args.steps, parquet)),
            ("1,000 steps to CSV", measure(1_000, csv)),
            (f"{args.steps:,} steps to CSV", measure(args.steps, csv)),
            (f"{args.steps:,} steps in memory", memory),
        ]
    print(f"{'run':<30} {'peak MB':>9} {'µs/step':>9} {'ratio':>7}")
    for label, r in rows:
        ratio = r["us_per_step"] / memory["us_per_step"]
        print(f"{label:<30} {r['peak_mb']:>9.0f} {r['us_per_step']:>9.2f} {ratio:>6.2f}×")


if __name__ == "__main__":
    main()
