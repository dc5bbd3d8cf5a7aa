"""Animations of a run: GIF (Pillow), MP4 (the ffmpeg inside the
imageio-ffmpeg wheel, no system install), or inline HTML for a notebook.

Every frame is the drawing of `camlink.draw` at one output time, with the
time (and the cam angle where there is a cam) written on it and the traces
drawn as far as they have grown.
"""

from __future__ import annotations

import base64
import io
import os
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt
from matplotlib.backends.backend_agg import FigureCanvasAgg
from PIL import Image

from camlink._core import ModelError
from camlink.drawing import Drawing, resolve
from camlink.progress import Progress

if TYPE_CHECKING:
    from camlink.model import Model
    from camlink.results import Results

__all__ = ["FORMATS", "Interrupted", "animate", "frame_rows"]

#: File suffixes `animate` writes.
FORMATS = {".gif": "gif", ".mp4": "mp4"}


@dataclass
class Interrupted(Exception):
    """Ctrl-C stopped an animation; `frames` were written to `path`."""

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
    count = int(np.floor(span * fps / speed + 1e-9)) + 1
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
    Ctrl-C stops cleanly: the frames so far are written and `Interrupted`
    is raised.
    """
    from camlink.drawing import motion_of

    model, res = resolve(source)
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
            return (f'<img alt="animation of {model.name}" '
                    f'src="data:image/gif;base64,{data}"/>')
        if kind == "gif":
            written = _write_gif(path, frames, fps)
        else:
            written = _write_mp4(path, frames, fps)
    if written < len(rows):
        raise Interrupted(path, written)
    return path


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
