"""`camlink machine MODEL`: shaking force and moment, counterweights,
flywheel and motor of a linkage at its design speed (the model file's
``[machine]`` table; `docs/machine.md`).

Exit status: 0 every check holds; 1 a check fails; 2 bad input.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from camlink import machine
from camlink._core import AnalysisError, ModelError
from camlink.io.output import check_not_input, replacing

EXIT_OK, EXIT_FAIL, EXIT_INPUT = 0, 1, 2


def add_parser(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """Registers the `machine` subcommand."""
    p = sub.add_parser(
        "machine",
        help="shaking force, balancing, flywheel and motor sizing of a linkage",
        description="Run one cycle of MODEL at the design speed of its [machine] table and report "
        "the shaking force and moment on the frame, the counterweights of a full force balance, the "
        "flywheel for the speed band and the motor checks. Exit 0 when every check holds, 1 when one "
        "fails, 2 for bad input.",
    )
    p.add_argument("model", metavar="MODEL", help="model file (.toml or .json) with a [machine] table")
    p.add_argument("--json", action="store_true", help="print the report as JSON")
    p.add_argument("--plot", metavar="PNG", help="write the polar plot of the shaking force")
    p.add_argument(
        "--balanced",
        metavar="TOML",
        help="write a copy of the (TOML) model with the counterweights on its bodies",
    )


def run(args: argparse.Namespace) -> int:
    """Runs `camlink machine`."""
    src = Path(args.model)
    try:
        r = machine.report(src)
        if args.plot:
            target = Path(args.plot)
            check_not_input(target, [src])
            with replacing(target) as temp:
                machine.save(machine.polar(r, title=f"{src.stem}: shaking force"), temp)
        if args.balanced:
            target = Path(args.balanced)
            check_not_input(target, [src])
            if src.suffix.lower() != ".toml":
                raise ModelError(f"--balanced: {src} is not a TOML model file")
            text = machine.balanced_text(src.read_text(encoding="utf-8"), r)
            with replacing(target) as temp:
                Path(temp).write_text(text, encoding="utf-8")
    except (ModelError, AnalysisError) as e:
        print(f"camlink: error: {e}", file=sys.stderr)
        return EXIT_INPUT
    except OSError as e:
        print(f"camlink: error: {e.filename or ''}: {e.strerror}", file=sys.stderr)
        return EXIT_INPUT
    if args.json:
        print(json.dumps(machine.to_json(r), indent=2))
    else:
        print(machine.format_report(r, src.stem))
    return EXIT_OK if r["ok"] else EXIT_FAIL
