"""The `camlink animate` and `camlink view` commands: a model's run as a
GIF or MP4, or as one self-contained HTML page with the browser viewer."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from pathlib import Path

import camlink
from camlink._core import AnalysisError
from camlink.progress import Progress

Command = Callable[[argparse.Namespace], int]


def add_parsers(sub: argparse._SubParsersAction) -> dict[str, Command]:  # type: ignore[type-arg]
    """Adds the subcommands to `sub`; returns their handlers by name."""
    anim = sub.add_parser(
        "animate",
        help="animate the model's run as a GIF or MP4",
        description="Run the model's kinematics (or its file's analysis) and write an "
        "animation: .gif through Pillow, .mp4 through the ffmpeg of imageio-ffmpeg.",
    )
    anim.add_argument("model", metavar="MODEL", help="model file (.toml or .json)")
    anim.add_argument("-o", "--output", metavar="FILE", required=True, help="out.gif or out.mp4")
    anim.add_argument("--fps", type=float, default=20.0, help="frames per second (default 20)")
    anim.add_argument(
        "--speed", type=float, default=1.0,
        help="seconds of motion played per second (default 1; 0.25 is slow motion)",
    )
    anim.add_argument("--t-end", type=float, metavar="T", help="end time (s)")
    anim.add_argument("--step", type=float, metavar="H", help="output time step (s)")
    anim.add_argument(
        "--trace", action="append", default=[], metavar="BODY.POINT",
        help="draw the path of this body point as it grows (repeatable)",
    )
    anim.add_argument("--width", type=float, default=6.4, help="width in inches (default 6.4)")
    anim.add_argument("--dpi", type=int, default=80, help="pixels per inch (default 80)")
    anim.add_argument("-q", "--quiet", action="store_true", help="no progress bar, no summary")

    view = sub.add_parser(
        "view",
        help="write the run as one self-contained HTML page to explore in a browser",
        description="Run the model's analysis and write ONE HTML file with the animated "
        "mechanism, play/pause, a time slider, playback speed, a hover read-out and "
        "linked plots; it needs no network.",
    )
    view.add_argument("model", metavar="MODEL", help="model file (.toml or .json)")
    view.add_argument("-o", "--output", metavar="FILE", help="HTML file (default: MODEL's name .html)")
    view.add_argument("--t-end", type=float, metavar="T", help="end time (s)")
    view.add_argument("--step", type=float, metavar="H", help="output time step (s)")
    view.add_argument(
        "--plot", action="append", default=None, metavar="CHANNEL",
        help="channel to plot (repeatable; default: two chosen from the model)",
    )
    view.add_argument("-q", "--quiet", action="store_true", help="print nothing on success")
    return {"animate": _cmd_animate, "view": _cmd_view}


def _results(args: argparse.Namespace) -> camlink.Results:
    model = camlink.load(args.model)
    settings = {k: v for k, v in (("t_end", args.t_end), ("step", args.step)) if v is not None}
    kind = model.analysis_type
    if kind == "equilibrium":
        kind = "kinematics"
    total = len(model.times(args.t_end, args.step))
    try:
        with Progress(total, f"{kind} of {model.name}", quiet=args.quiet) as bar:
            return model.run(analysis=kind, on_rows=bar.update, **settings)
    except AnalysisError as e:
        partial = e.results
        if len(partial) < 2:
            raise
        print(f"camlink: warning: {e}; showing the {len(partial)} steps before it",
              file=sys.stderr)
        return partial


def _cmd_animate(args: argparse.Namespace) -> int:
    from camlink.animate import Interrupted, animate

    res = _results(args)
    try:
        path = animate(res, args.output, fps=args.fps, speed=args.speed, traces=args.trace,
                       width=args.width, dpi=args.dpi, quiet=args.quiet)
    except Interrupted as e:
        print(f"camlink: {e}", file=sys.stderr)
        return 130
    if not args.quiet:
        print(f"animation of {res.model}: {len(res)} steps → {path}")
    return 0


def _cmd_view(args: argparse.Namespace) -> int:
    from camlink.viewer import to_html

    res = _results(args)
    out = Path(args.output) if args.output else Path(Path(args.model).stem + ".html")
    to_html(res, out, plots=args.plot)
    if not args.quiet:
        print(f"viewer of {res.model}: {len(res)} steps → {out}")
    return 0
