"""What running a study costs: N variants of the four-bar example (crank
length a spread over ±20 %), each a kinematic run of 1,000 steps reduced to
the rocker's swing, on all local cores (rayon) and, with --scheduler, on a
Dask cluster; against a plain Python loop of `model.with_parameters(...).run()`
on one core and against the ideal, one run's time × N ÷ cores.

    uv run python bench/study_four_bar.py                    # 10,000 variants
    uv run python bench/study_four_bar.py --n 1000 --loop-n 200
    uv run python bench/study_four_bar.py --scheduler tcp://host:8786

The Python loop runs `--loop-n` variants and is scaled to N (it is linear
in N); one run's time is the best of five single-variant batches on one
thread, the run alone without Python in between. The CPU time per variant
(process time ÷ variants) is also printed: on a machine shared with other
work the wall times say more about the load than about camlink.
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

import numpy as np

import camlink
from camlink import _core
from camlink.study import range_of

ROOT = Path(__file__).resolve().parents[1]


def four_bar() -> camlink.Model:
    """The example four-bar over one crank turn in 1,000 steps of 1 ms."""
    path = ROOT / "examples" / "four_bar.toml"
    text = path.read_text().replace("t_end = 2.0", "t_end = 0.999").replace("step = 0.005", "step = 0.001")
    return camlink.loads(text, "toml", str(path))


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--n", type=int, default=10_000, help="variants (default 10,000)")
    p.add_argument("--loop-n", type=int, default=500, help="variants of the Python loop (default 500)")
    p.add_argument("--scheduler", help="also run on this Dask scheduler")
    p.add_argument("--threads", type=int, help="local threads (default: all cores)")
    args = p.parse_args()

    model = four_bar()
    steps = len(model.times())
    a = np.linspace(0.096, 0.144, args.n)
    variants = [{"a": float(x)} for x in a]
    outputs = {"swing": range_of("rocker.phi")}
    spec = [("swing", outputs["swing"].to_json())]
    cores = args.threads or os.cpu_count() or 1

    one = min(_timed(lambda: _core.run_batch(model._core, [{"a": 0.12}], spec, threads=1)) for _ in range(5))
    cpu = time.process_time()
    _core.run_batch(model._core, variants[:200], spec, threads=1)
    one_cpu = (time.process_time() - cpu) / min(200, args.n)
    ideal = one * args.n / cores

    def loop() -> None:
        for v in variants[: args.loop_n]:
            np.ptp(model.with_parameters(**v).run()["rocker.phi"])

    cpu = time.process_time()
    py_loop = _timed(loop) * args.n / args.loop_n
    loop_cpu = (time.process_time() - cpu) / args.loop_n
    cpu = time.process_time()
    local = _timed(lambda: camlink.sweep(model, {"a": a}, outputs, threads=args.threads))
    sweep_cpu = (time.process_time() - cpu) / args.n

    print(f"{args.n} four-bar variants of {steps} steps, {cores} cores")
    print(f"  one run (Rust, one thread)       {one * 1e3:9.3f} ms")
    print(f"  ideal  (one run × N ÷ cores)     {ideal:9.2f} s")
    print(f"  Python loop of model.run, 1 core {py_loop:9.2f} s  (measured on {args.loop_n}, scaled)")
    print(f"  camlink.sweep on local cores     {local:9.2f} s  ({local / ideal:.2f}× ideal, "
          f"{py_loop / local:.1f}× faster than the loop)")
    # CPU time per variant does not depend on what else the machine runs.
    print(f"  CPU per variant: one run {one_cpu * 1e3:.3f} ms, sweep {sweep_cpu * 1e3:.3f} ms, "
          f"Python loop {loop_cpu * 1e3:.3f} ms")
    if args.scheduler:
        from distributed import Client

        with Client(args.scheduler) as client:
            workers = sum(client.nthreads().values())
            dask = _timed(lambda: camlink.sweep(model, {"a": a}, outputs, client=client))
        print(f"  camlink.sweep on Dask ({workers} threads) {dask:9.2f} s  "
              f"({dask / (one * args.n / workers):.2f}× its ideal)")


def _timed(f: object) -> float:
    start = time.perf_counter()
    f()  # type: ignore[operator]
    return time.perf_counter() - start


if __name__ == "__main__":
    main()
