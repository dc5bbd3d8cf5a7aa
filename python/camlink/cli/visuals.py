"""The `camlink animate` and `camlink view` commands: a model's run as a
GIF or MP4, or as one self-contained HTML page with the browser viewer.

Both run the model with no more output rows than they can show: a page
`camlink.viz.viewer.MOST_ROWS`, an animation ten rows a frame (its traces grow
smoothly) up to the same bound; a finer step is coarsened, with a note.
Neither writes over an input of the model, nor over an existing default
output without ``--force``; both write a temporary file beside the output
and rename it over the output when complete.
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

import camlink
from camlink import _core
from camlink._core import AnalysisError, ModelError
from camlink.io.output import check_not_input
from camlink.progress import Progress
from camlink.settings import check_settings

Command = Callable[[argparse.Namespace], int]

#: Output rows an animation runs per frame at most.
ROWS_PER_FRAME = 10


def add_parsers(sub: argparse._SubParsersAction) -> dict[str, Command]:  # type: ignore[type-arg]
    """Adds the subcommands to `sub`; returns their handlers by name."""
    anim = sub.add_parser(
        "animate",
        help="animate the model's run as a GIF or MP4",
        description="Run the model's kinematics (or its file's analysis) and write an "
        "animation: .gif through Pillow, .mp4 through the ffmpeg of imageio-ffmpeg. "
        "At most 10000 frames; the run is output at most ten rows a frame (20000 in all), "
        "a finer --step being coarsened with a note.",
    )
    anim.add_argument("model", metavar="MODEL", help="model file (.toml or .json)")
    anim.add_argument("-o", "--output", metavar="FILE",
                      help="out.gif or out.mp4 (default: MODEL's name .gif)")
    anim.add_argument("--force", action="store_true",
                      help="replace the default output if it exists")
    anim.add_argument("--fps", type=float, default=20.0,
                      help="frames per second, more than 0 and at most 60 (default 20)")
    anim.add_argument(
        "--speed", type=float, default=1.0,
        help="seconds of motion played per second, more than 0 (default 1; 0.25 is slow "
        "motion); the run's length × fps / speed is at most 10000 frames",
    )
    anim.add_argument("--t-end", type=float, metavar="T", help="end time (s)")
    anim.add_argument("--step", type=float, metavar="H", help="output time step (s)")
    anim.add_argument(
        "--trace", action="append", default=[], metavar="BODY.POINT",
        help="draw the path of this body point as it grows (repeatable)",
    )
    anim.add_argument("--width", type=float, default=6.4,
                      help="width in inches, 1.5 to 40 (default 6.4)")
    anim.add_argument("--dpi", type=int, default=80,
                      help="pixels per inch, 10 to 600, at most 4096 pixels across (default 80)")
    anim.add_argument("-q", "--quiet", action="store_true",
                      help="no progress bar, no note, no summary")

    view = sub.add_parser(
        "view",
        help="write the run as one self-contained HTML page to explore in a browser",
        description="Run the model's analysis and write ONE HTML file with the animated "
        "mechanism, play/pause, a time slider, playback speed, a hover read-out and "
        "linked plots; it needs no network. The page holds at most 20000 rows: a finer "
        "--step is coarsened, with a note.",
    )
    view.add_argument("model", metavar="MODEL", help="model file (.toml or .json)")
    view.add_argument("-o", "--output", metavar="FILE", help="HTML file (default: MODEL's name .html)")
    view.add_argument("--force", action="store_true",
                      help="replace the default output if it exists")
    view.add_argument("--t-end", type=float, metavar="T", help="end time (s)")
    view.add_argument("--step", type=float, metavar="H", help="output time step (s)")
    view.add_argument(
        "--plot", action="append", default=None, metavar="CHANNEL",
        help="channel to plot (repeatable; default: two chosen from the model)",
    )
    view.add_argument("-q", "--quiet", action="store_true", help="print nothing on success")
    return {"animate": _cmd_animate, "view": _cmd_view}


def _output(args: argparse.Namespace, model: camlink.Model, suffix: str) -> Path:
    """The output file: `-o`, else MODEL's name with `suffix` in the working
    folder. `ModelError` when it is an input of the model, or when the
    default output exists and `--force` is not given."""
    out = Path(args.output) if args.output else Path(Path(args.model).stem + suffix)
    check_not_input(out, model.inputs)
    if not args.output and not args.force and out.exists():
        raise ModelError(f"{out} exists; pass --force to replace it, or -o to name another output")
    return out


class _Grid:
    """The output times a command asks for, not built until bounded: the
    file's list of `times`, or 0, `step`, … `t_end`, as `Model.times`."""

    def __init__(self, model: camlink.Model, args: argparse.Namespace) -> None:
        for key in ("t_end", "step"):
            try:
                check_settings({key: getattr(args, key)})
            except ModelError as e:
                raise ModelError(f"--{key.replace('_', '-')}: {e}") from None
        a = model.analysis
        self.model = model
        self.times: np.ndarray[Any, np.dtype[np.float64]] | None = None
        self.given_step = args.step is not None
        if args.t_end is None and args.step is None and a.get("times") is not None:
            self.times = model.times()
            self.t_end = float(self.times[-1]) if len(self.times) else 0.0
            self.step = math.nan
            self.rows = float(len(self.times))
            self.span = float(self.times[-1] - self.times[0]) if len(self.times) else 0.0
            return
        t_end = a.get("t_end") if args.t_end is None else args.t_end
        if t_end is None:
            raise ModelError(f"model '{model.name}' gives no end time: pass --t-end "
                             "(or set [analysis] t_end in the file)")
        self.t_end = float(t_end)
        step = a.get("step") if args.step is None else args.step
        if step is None:
            step = _core.default_step(self.t_end)
        self.step = float(step)
        self.rows = _core.time_grid_rows(self.t_end, self.step)
        self.span = self.t_end

    def bounded(self, most: int) -> tuple[dict[str, Any], str | None]:
        """Settings for `Model.run` with at most `most` output rows, and a
        note when the times were thinned or the step coarsened."""
        if self.times is not None:
            n = len(self.times)
            if n <= most:
                return {}, None
            rows = np.unique(np.linspace(0, n - 1, most).round().astype(np.intp))
            return ({"times": self.times[rows]},
                    f"the file's {n} output times thinned to {len(rows)} (at most {most} shown)")
        settings: dict[str, Any] = {"t_end": self.t_end}
        if self.given_step:
            settings["step"] = self.step
        if self.rows <= most:
            return settings, None
        coarse = self.t_end / (most - 1)
        if self.model.analysis_type == "dynamics":
            h = self.model.analysis.get("h")
            if h is None:
                # The integration step the finer output step would have given.
                h = settings["h"] = _core.integration_step(step=self.step)
            # Output times on the integration steps.
            coarse = h * math.ceil(coarse / h * (1 - 1e-12))
        settings["step"] = coarse
        where = "--step" if self.given_step else "the file's step"
        return settings, (f"{where} {self.step:g} s would give {self.rows:.4g} rows, more than the "
                          f"{most} shown: output step {coarse:.6g} s")


def _results(args: argparse.Namespace, model: camlink.Model, settings: dict[str, Any],
             note: str | None) -> camlink.Results:
    kind = model.analysis_type
    if kind == "equilibrium":
        kind = "kinematics"
    if note and not args.quiet:
        print(f"camlink: note: {note}", file=sys.stderr)
    times = settings.get("times")
    total = len(times) if times is not None else len(model.times(settings["t_end"], settings.get("step")))
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
    from camlink.viz.animate import FORMATS, Interrupted, animate, check_options, check_traces, frame_count
    from camlink.viz.viewer import MOST_ROWS

    check_options(args.fps, args.speed, args.width, args.dpi, flag=True)
    model = camlink.load(args.model)
    out = _output(args, model, ".gif")
    if out.suffix.lower() not in FORMATS:
        raise ModelError(f"cannot animate to '{out}': unknown file type '{out.suffix or '(none)'}' "
                         "(use .gif or .mp4)")
    check_traces(model, args.trace, flag=True)
    grid = _Grid(model, args)
    frames = frame_count(grid.span, args.fps, args.speed)
    settings, note = grid.bounded(max(2, min(MOST_ROWS, ROWS_PER_FRAME * frames)))
    res = _results(args, model, settings, note)
    try:
        path = animate(res, out, fps=args.fps, speed=args.speed, traces=args.trace,
                       width=args.width, dpi=args.dpi, quiet=args.quiet)
    except Interrupted as e:
        print(f"camlink: {e}", file=sys.stderr)
        return 130
    if not args.quiet:
        print(f"animation of {res.model}: {len(res)} steps → {path}")
    return 0


def _cmd_view(args: argparse.Namespace) -> int:
    from camlink.viz.viewer import MOST_ROWS, to_html

    model = camlink.load(args.model)
    out = _output(args, model, ".html")
    settings, note = _Grid(model, args).bounded(MOST_ROWS)
    res = _results(args, model, settings, note)
    to_html(res, out, plots=args.plot)
    if not args.quiet:
        print(f"viewer of {res.model}: {len(res)} steps → {out}")
    return 0
