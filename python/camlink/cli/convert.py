"""`camlink convert`: a simEngine2D ``.adm`` model written as a camlink model
file, or a camlink model file written in global or frame form."""

from __future__ import annotations

import argparse
from pathlib import Path

from camlink._core import ModelError
from camlink.io import model_form, simengine2d


def add_parser(sub: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """Registers the ``convert`` subcommand."""
    p = sub.add_parser(
        "convert",
        help="write a simEngine2D .adm model as a camlink file, or a camlink model "
        "in global (--global) or frame (--frame) form",
        description="Convert a simEngine2D course model to camlink's format (the analysis "
        "comes from the .acf file beside the .adm, same name, or from --acf); or, with "
        "--global or --frame, write a camlink model file with its bodies given by the "
        "global positions of their points at the initial instant (global_points), or by "
        "points in their frames (points). The frames, and so the results, stay the same.",
    )
    p.add_argument("model", metavar="MODEL", help="simEngine2D model file (.adm), or a camlink "
                   "model file (.toml, .json) with --global or --frame")
    form = p.add_mutually_exclusive_group()
    form.add_argument(
        "--global",
        dest="form",
        action="store_const",
        const="global",
        help="write MODEL's bodies by the global positions of their points (global_points)",
    )
    form.add_argument(
        "--frame",
        dest="form",
        action="store_const",
        const="frame",
        help="write MODEL's bodies by their points in their frames (points)",
    )
    p.add_argument(
        "-o",
        "--output",
        metavar="FILE",
        help="camlink model file to write, .toml or .json (default: MODEL's name with .toml "
        "in the current directory; with --global or --frame, MODEL's name with .global or "
        ".frame before its suffix)",
    )
    p.add_argument("--acf", metavar="FILE", help="analysis file (default: MODEL with .acf, if present)")
    p.add_argument(
        "--force",
        action="store_true",
        help="replace the output when it exists (for a .adm, a file named with -o is replaced "
        "anyway); an input never is",
    )
    p.add_argument("-q", "--quiet", action="store_true", help="print nothing on success")


def run(args: argparse.Namespace) -> int:
    """Converts; errors propagate to the CLI's handler (exit 2 for bad input)."""
    if args.form is not None:
        return _run_form(args)
    output = Path(args.output) if args.output else Path(Path(args.model).stem + ".toml")
    if not args.output and not args.force and output.exists():
        raise ModelError(
            f"{output} exists; pass --force to replace it, or -o to name another output"
        )
    written = simengine2d.convert(args.model, output, acf=args.acf)
    if not args.quiet:
        print(f"{args.model} → {written}")
    return 0


def _run_form(args: argparse.Namespace) -> int:
    """``--global`` / ``--frame``: the model file rewritten in that form."""
    model = Path(args.model)
    if args.acf:
        raise ModelError("--acf belongs to a .adm model; --global and --frame take a camlink model file")
    if model.suffix.lower() not in (".toml", ".json"):
        raise ModelError(f"{model}: --{args.form} takes a camlink model file (.toml or .json)")
    output = Path(args.output) if args.output else Path(f"{model.stem}.{args.form}{model.suffix}")
    bodies = model_form.convert_form(model, output, args.form, force=args.force)
    if not args.quiet:
        what = ", ".join(bodies) if bodies else "no body needed it"
        print(f"{model} → {output} ({args.form} form: {what})")
    return 0
