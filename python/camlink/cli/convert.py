"""`camlink convert`: a simEngine2D ``.adm`` model written as a camlink model file."""

from __future__ import annotations

import argparse
from pathlib import Path

from camlink._core import ModelError
from camlink.io import simengine2d


def add_parser(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """Registers the ``convert`` subcommand."""
    p = sub.add_parser(
        "convert",
        help="write a simEngine2D .adm model (and its .acf) as a camlink .toml or .json file",
        description="Convert a simEngine2D course model to camlink's format. The analysis "
        "comes from the .acf file beside the .adm (same name), or from --acf.",
    )
    p.add_argument("model", metavar="MODEL", help="simEngine2D model file (.adm)")
    p.add_argument(
        "-o",
        "--output",
        metavar="FILE",
        help="camlink model file to write, .toml or .json (default: MODEL's name with .toml, "
        "in the current directory)",
    )
    p.add_argument("--acf", metavar="FILE", help="analysis file (default: MODEL with .acf, if present)")
    p.add_argument(
        "--force",
        action="store_true",
        help="replace the default output when it exists (a file named with -o is replaced anyway; "
        "an input never is)",
    )
    p.add_argument("-q", "--quiet", action="store_true", help="print nothing on success")


def run(args: argparse.Namespace) -> int:
    """Converts; errors propagate to the CLI's handler (exit 2 for bad input)."""
    output = Path(args.output) if args.output else Path(Path(args.model).stem + ".toml")
    if not args.output and not args.force and output.exists():
        raise ModelError(
            f"{output} exists; pass --force to replace it, or -o to name another output"
        )
    written = simengine2d.convert(args.model, output, acf=args.acf)
    if not args.quiet:
        print(f"{args.model} → {written}")
    return 0
