"""Animations of a run: GIF (Pillow), MP4 (the ffmpeg inside the
imageio-ffmpeg wheel, no system install), or inline HTML for a notebook.

Every frame is the drawing of `camlink.draw` at one output time, with the
time (and the cam angle where there is a cam) written on it and the traces
drawn as far as they have grown.

The options are bounded (`check_options`): a frame rate up to `MOST_FPS`,
at most `MOST_FRAMES` frames, a width of `WIDTHS` inches at `DPIS` pixels
per inch and at most `MOST_PIXELS` pixels across. A file is written to a
temporary name beside the output and renamed over it when complete.
"""

from __future__ import annotations

import base64
import html
import io
import math
import os
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt
from matplotlib.backends.backend_agg import FigureCanvasAgg
from PIL import Image

from camlink import _core
from camlink._core import ModelError
from camlink.io.output import _Target, check_not_input
from camlink.progress import Progress
from camlink.viz.drawing import Drawing, resolve
from camlink.viz.scene import Scene

if TYPE_CHECKING:
    from camlink.model import Model
    from camlink.results import Results

__all__ = [
    "DPIS", "FORMATS", "MOST_FPS", "MOST_FRAMES", "MOST_PIXELS", "WIDTHS", "Interrupted",
    "animate", "check_options", "check_traces", "frame_count", "frame_rows",
]

#: File suffixes `animate` writes.
FORMATS = {".gif": "gif", ".mp4": "mp4"}
#: Highest frame rate (1/s); a GIF shows at most 50 frames a second.
MOST_FPS = 60.0
#: Most frames of one animation (8 min 20 s at 20 frames a second).
MOST_FRAMES = 10_000
#: Least and greatest figure width (in).
WIDTHS = (1.5, 40.0)
#: Least and greatest resolution (pixels per inch).
DPIS = (10, 600)
#: Most pixels across a frame (width × dpi).
MOST_PIXELS = 4096


def _option(name: str, flag: bool) -> str:
    return f"--{name}" if flag else name


def check_options(
    fps: float, speed: float, width: float, dpi: int, *, flag: bool = False
) -> None:
    """Raises `ModelError` naming the first option out of its bounds: `fps`
    in (0, `MOST_FPS`], `speed` finite and positive, `width` (in) within
    `WIDTHS`, `dpi` an integer within `DPIS`, and width × dpi at most
    `MOST_PIXELS`. With `flag` the options are named as command-line
    flags (``--fps``)."""
    def number(value: object) -> float | None:
        if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
            return None
        v = float(value)
        return v if math.isfinite(v) else None

    def name(option: str) -> str:
        return _option(option, flag)

    f = number(fps)
    if f is None or not 0 < f <= MOST_FPS:
        raise ModelError(f"{name('fps')} must be a number of frames per second in (0, {MOST_FPS:g}], "
                         f"not {fps}")
    v = number(speed)
    if v is None or not v > 0:
        raise ModelError(f"{name('speed')} must be a positive number of seconds of motion per "
                         f"second, not {speed}")
    w = number(width)
    if w is None or not WIDTHS[0] <= w <= WIDTHS[1]:
        raise ModelError(f"{name('width')} must be a width in inches from {WIDTHS[0]:g} to "
                         f"{WIDTHS[1]:g}, not {width}")
    d = number(dpi)
    if d is None or d != int(d) or not DPIS[0] <= d <= DPIS[1]:
        raise ModelError(f"{name('dpi')} must be a whole number of pixels per inch from {DPIS[0]} "
                         f"to {DPIS[1]}, not {dpi}")
    if w * d > MOST_PIXELS:
        raise ModelError(f"{name('width')} × {name('dpi')} is {w * d:g} pixels across; at most "
                         f"{MOST_PIXELS}: lower one of them")


def check_traces(model: Model, traces: Sequence[str], *, flag: bool = False) -> None:
    """Raises `ModelError` naming the first of `traces` that is not a body
    point (``"body.point"``) of `model`, with the points it has."""
    if not traces:
        return
    scene = Scene.of(model, tol=1e-2)
    for name in traces:
        body, _, point = name.partition(".")
        if point not in scene.points.get(body, {}):
            known = [f"{b}.{p}" for b in scene.points for p in scene.points[b]]
            raise ModelError(f"{_option('trace', flag)}: model '{model.name}' has no body point "
                             f"{name!r} (points: {', '.join(known) or 'none'})")


def frame_count(span: float, fps: float, speed: float) -> int:
    """The frames of an animation of `span` seconds of motion at `fps`
    frames per second playing `speed` seconds of motion per second;
    `ModelError` when more than `MOST_FRAMES`."""
    exact = span * fps / speed
    if not (math.isfinite(exact) and exact < MOST_FRAMES):
        shown = f"{exact + 1:.4g}" if math.isfinite(exact) else "too many"
        raise ModelError(
            f"{span:g} s of motion at {fps:g} frames per second and speed {speed:g} is {shown} "
            f"frames; at most {MOST_FRAMES}: raise the speed, lower the frame rate or shorten the run"
        )
    # A frame every speed/fps seconds of motion: the core's grid rule.
    return int(_core.time_grid_rows(span, speed / fps))


@dataclass
class Interrupted(Exception):
    """Ctrl-C stopped an animation; `frames` were written to `path` (the
    output's partial name)."""

    path: Path
    frames: int

    def __str__(self) -> str:
        return f"interrupted: {self.frames} frames written to {self.path}"


def frame_rows(t: npt.NDArray[np.float64], fps: float, speed: float) -> npt.NDArray[np.intp]:
    """The output rows shown by an animation at `fps` frames per second
    playing `speed` seconds of motion per second: the rows nearest
    t₀, t₀ + speed/fps, … up to the last time."""
    if not (fps > 0 and np.isfinite(fps)):
        raise ModelError(f"fps must be a positive number, not {fps}")
    if not (speed > 0 and np.isfinite(speed)):
        raise ModelError(f"speed must be a positive number, not {speed}")
    if len(t) == 0:
        raise ModelError("no output rows to animate")
    span = float(t[-1] - t[0])
    count = frame_count(span, fps, speed)
    wanted = t[0] + np.arange(count) * speed / fps
    idx = np.searchsorted(t, wanted).clip(1, len(t) - 1) if len(t) > 1 else np.zeros(count, int)
    if len(t) > 1:
        left = idx - 1
        idx = np.where(np.abs(t[left] - wanted) <= np.abs(t[idx] - wanted), left, idx)
    return np.asarray(idx, dtype=np.intp)


def _frames(
    drawing: Drawing, rows: npt.NDArray[np.intp], progress: Progress
) -> Iterator[npt.NDArray[np.uint8]]:
    """RGB frames (h × w × 3, uint8) of the drawing at `rows`."""
    canvas = FigureCanvasAgg(drawing.figure)
    for k in rows:
        drawing.show(int(k), grow=True)
        canvas.draw()
        rgb = np.asarray(canvas.buffer_rgba())[:, :, :3]
        progress.update()
        yield rgb.copy()


def animate(
    source: Model | Results,
    path: str | os.PathLike[str] | None = None,
    *,
    fps: float = 20.0,
    speed: float = 1.0,
    traces: Sequence[str] = (),
    width: float = 6.4,
    dpi: int = 80,
    quiet: bool = False,
) -> Path | str:
    """Animates a run (or a model's kinematic run over its file's times).

    Writes a GIF or MP4 to `path` (by suffix) and returns the path; with no
    path returns HTML (an ``<img>`` of the GIF, inline) for a notebook.
    `fps` is the frame rate (1/s) and `speed` the seconds of motion played
    per second; `traces` names body points whose paths grow as the
    mechanism moves. A progress bar shows on a terminal unless `quiet`.
    Ctrl-C stops cleanly: the frames so far are written to the output's
    partial name (``<stem>.partial<suffix>``, `camlink.io.output.partial_path`)
    and `Interrupted` is raised. The options are bounded as
    `check_options` says; `ModelError` for one out of bounds, a trace that
    is not a body point, or a `path` that is one of the model's inputs.
    """
    from camlink.viz.drawing import motion_of

    check_options(fps, speed, width, dpi)
    model, res = resolve(source)
    check_traces(model, traces)
    if path is not None:
        check_not_input(Path(path), model.inputs)
    if res is None:
        res = motion_of(model)
    if res is None or len(res) == 0:
        raise ModelError(f"model '{model.name}' has no motion to animate (not fully driven)")
    kind = "gif"
    if path is not None:
        path = Path(path)
        try:
            kind = FORMATS[path.suffix.lower()]
        except KeyError:
            raise ModelError(
                f"cannot animate to '{path}': unknown file type '{path.suffix or '(none)'}' "
                "(use .gif or .mp4)"
            ) from None
    rows = frame_rows(res.t, fps, speed)
    drawing = Drawing(model, res, traces=traces, width=width, dpi=dpi)
    with Progress(len(rows), f"animating {model.name}", unit="frame", quiet=quiet) as bar:
        frames = _frames(drawing, rows, bar)
        if path is None:
            buf = io.BytesIO()
            _write_gif(buf, frames, fps)
            data = base64.b64encode(buf.getvalue()).decode("ascii")
            return (f'<img alt="animation of {html.escape(model.name, quote=True)}" '
                    f'src="data:image/gif;base64,{data}"/>')
        target = _Target(path, path.suffix)
        try:
            if kind == "gif":
                written = _write_gif(target.temp, frames, fps)
            else:
                written = _write_mp4(target.temp, frames, fps)
        except BaseException:
            target.temp.unlink(missing_ok=True)
            raise
    if written < len(rows):
        raise Interrupted(target.finish(target.temp, False), written)
    return target.finish(target.temp, True)


def _write_gif(target: Path | io.BytesIO, frames: Iterable[npt.NDArray[np.uint8]], fps: float) -> int:
    """Writes the frames as a looping GIF; stops early (keeping what is
    drawn) on Ctrl-C. Returns the frame count."""
    images: list[Image.Image] = []
    try:
        for rgb in frames:
            images.append(Image.fromarray(rgb).quantize(colors=255, method=Image.Quantize.MEDIANCUT))
    except KeyboardInterrupt:
        pass
    if not images:
        raise ModelError("no frame was drawn")
    duration = max(20, round(1000.0 / fps))
    images[0].save(target, format="GIF", save_all=True, append_images=images[1:],
                   duration=duration, loop=0, disposal=1)
    return len(images)


def _write_mp4(path: Path, frames: Iterable[npt.NDArray[np.uint8]], fps: float) -> int:
    """Writes the frames as H.264 MP4 (even width and height); stops early
    on Ctrl-C and closes the file so that it plays. Returns the count."""
    import imageio_ffmpeg

    writer = None
    count = 0
    try:
        for rgb in frames:
            h, w = (rgb.shape[0] // 2) * 2, (rgb.shape[1] // 2) * 2
            if writer is None:
                writer = imageio_ffmpeg.write_frames(
                    str(path), (w, h), fps=fps, codec="libx264", pix_fmt_out="yuv420p",
                    macro_block_size=1, quality=7, ffmpeg_log_level="error",
                )
                writer.send(None)
            writer.send(np.ascontiguousarray(rgb[:h, :w]))
            count += 1
    except KeyboardInterrupt:
        pass
    finally:
        if writer is not None:
            writer.close()
    return count
