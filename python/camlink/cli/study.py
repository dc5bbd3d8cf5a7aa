"""`camlink study`: run a study file (docs/studies.md) and write its table."""

from __future__ import annotations

import argparse
from collections.abc import Callable
from pathlib import Path

import camlink


def add_parser(
    sub: argparse._SubParsersAction[argparse.ArgumentParser],
) -> Callable[[argparse.Namespace], int]:
    """Registers the ``study`` subcommand; returns its handler."""
    p = sub.add_parser(
        "study",
        help="run a parameter sweep or Monte Carlo study file on local cores or on Dask",
        description="Run the [study] of FILE: every variant of its model, each reduced to the "
        "outputs named, written as batches arrive to a folder of Parquet files. Run the same "
        "command again to resume an interrupted study: variants already written are not run again.",
    )
    p.add_argument("file", metavar="FILE", help="study file (.toml with a [study] table)")
    p.add_argument(
        "-o", "--output", metavar="DIR",
        help="results folder, read with pandas.read_parquet (default: FILE's name with .parquet)",
    )
    p.add_argument(
        "--scheduler", metavar="ADDRESS",
        help="Dask scheduler (tcp://host:8786) to send the batches to; default: local cores",
    )
    p.add_argument("--threads", type=int, metavar="N", help="local threads (default: all cores)")
    p.add_argument("--batch-size", type=int, metavar="N", help="variants per batch (one file each)")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar, no summary")
    return run


def run(args: argparse.Namespace) -> int:
    """Runs the study; bad input raises ModelError or OSError (exit 2)."""
    import pandas as pd

    from camlink.study.runner import ERROR, STATUS, VARIANT
    from camlink.study.sampling import monte_carlo
    from camlink.study.study_file import read_study
    from camlink.study.sweeps import sweep

    sf = read_study(args.file)
    model = camlink.load(sf.model)
    output = Path(args.output) if args.output else Path(Path(args.file).stem + ".parquet")
    scheduler = args.scheduler or sf.scheduler
    execution = {
        "output": output,
        "scheduler": scheduler,
        "threads": args.threads or sf.threads,
        "batch_size": args.batch_size or sf.batch_size,
        "time_limit": sf.time_limit,
        "quiet": args.quiet,
    }
    stats = None
    try:
        if sf.kind == "sweep":
            table = sweep(model, sf.values, sf.outputs, mode="zip" if sf.mode == "zip" else "grid",
                          **execution)
        else:
            mc = monte_carlo(model, sf.distributions, sf.outputs, n=sf.n, seed=sf.seed,
                             sampling="sobol" if sf.sampling == "sobol" else
                             "lhs" if sf.sampling == "lhs" else "random", **execution)
            table, stats = mc.table, mc.statistics
    except KeyboardInterrupt as e:
        e.output = f"{output} (run the same command again to resume)"  # type: ignore[attr-defined]
        raise
    if not args.quiet:
        failed = table[table[STATUS] != "ok"]
        where = f"on {scheduler}" if scheduler else "on local cores"
        print(f"{len(table)} variants of {model.name} {where}: {len(table) - len(failed)} ok, "
              f"{len(failed)} failed → {output}")
        if len(failed):
            first = failed.iloc[0]
            print(f"  first failure, variant {first[VARIANT]}: {first[STATUS]}: {first[ERROR]}")
        if stats is not None:
            with pd.option_context("display.width", 120, "display.max_columns", 20):
                print(stats.to_string(float_format=lambda v: f"{v:.6g}"))
    return 0
