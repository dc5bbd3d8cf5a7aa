"""Animations: GIF and MP4 frame counts and content, inline HTML, the
`camlink animate` and `camlink view` commands, Ctrl-C and progress bars."""

from __future__ import annotations

import base64
import io
import itertools
import re
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import camlink
from camlink.cli import main
from camlink.progress import Progress, wanted
from camlink.viz import animate as animate_module
from camlink.viz.animate import Interrupted, animate, frame_rows
from camlink.viz.drawing import Drawing

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


@pytest.fixture(scope="module")
def four_bar() -> camlink.Results:
    return camlink.load(EXAMPLES / "four_bar.toml").run(t_end=0.5, step=0.01)


def _gif_frames(source: Path | str | io.BytesIO) -> list[np.ndarray]:
    im = Image.open(source)
    frames = []
    for k in range(getattr(im, "n_frames", 1)):
        im.seek(k)
        frames.append(np.asarray(im.convert("RGB")))
    return frames


def test_frame_rows_follow_fps_and_speed() -> None:
    t = np.linspace(0.0, 1.0, 101)
    assert list(frame_rows(t, 10, 1.0)) == list(range(0, 101, 10))
    assert len(frame_rows(t, 10, 0.5)) == 21
    assert len(frame_rows(t, 10, 2.0)) == 6
    with pytest.raises(camlink.ModelError, match="fps must be a positive number"):
        frame_rows(t, 0, 1.0)


def test_gif_has_the_frames_and_they_move(four_bar: camlink.Results, tmp_path: Path) -> None:
    path = animate(four_bar, tmp_path / "four_bar.gif", fps=10, traces=["coupler.P"], width=3.2, dpi=50)
    frames = _gif_frames(path)
    assert len(frames) == 6
    assert all(f.shape == frames[0].shape for f in frames)
    for a, b in itertools.pairwise(frames):
        assert np.any(a != b)
    assert Image.open(path).info["duration"] == 100


def test_mp4_reads_back_with_its_frame_count_and_size(four_bar: camlink.Results, tmp_path: Path) -> None:
    import imageio_ffmpeg

    path = animate(four_bar, tmp_path / "four_bar.mp4", fps=20, speed=0.5, width=3.2, dpi=50)
    reader = imageio_ffmpeg.read_frames(str(path))
    meta = next(reader)
    frames = [np.frombuffer(f, np.uint8) for f in reader]
    drawing = Drawing(four_bar.mechanism, four_bar, width=3.2, dpi=50)  # type: ignore[arg-type]
    w, h = drawing.frame.size_px
    assert tuple(meta["size"]) == ((w // 2) * 2, (h // 2) * 2)
    assert len(frames) == 21
    assert np.any(frames[0] != frames[10])


def test_inline_html_is_a_gif(four_bar: camlink.Results) -> None:
    html = four_bar.animate(fps=4, width=2.5, dpi=40)
    assert isinstance(html, str)
    m = re.fullmatch(r'<img alt="[^"]*" src="data:image/gif;base64,([A-Za-z0-9+/=]+)"/>', html)
    assert m
    assert len(_gif_frames(io.BytesIO(base64.b64decode(m.group(1))))) == 3


def test_ctrl_c_keeps_the_frames_drawn(four_bar: camlink.Results, tmp_path: Path,
                                       monkeypatch: pytest.MonkeyPatch) -> None:
    show = Drawing.show
    calls = {"n": 0}

    def interrupted(self: Drawing, k: int, grow: bool = False) -> None:
        calls["n"] += 1
        if calls["n"] == 4:
            raise KeyboardInterrupt
        show(self, k, grow)

    monkeypatch.setattr(animate_module.Drawing, "show", interrupted)
    with pytest.raises(Interrupted) as e:
        animate(four_bar, tmp_path / "cut.gif", fps=10, width=2.5, dpi=40)
    assert e.value.frames == 3
    # Kept under the partial name, beside the output (never over it).
    assert e.value.path == tmp_path / "cut.partial.gif"
    assert len(_gif_frames(tmp_path / "cut.partial.gif")) == 3
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cut.partial.gif"]


def test_cli_animate_and_view(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    gif = tmp_path / "cam.gif"
    code = main(["animate", str(EXAMPLES / "cam_seed_example_3_4_3.toml"), "-o", str(gif),
                 "--fps", "5", "--t-end", "0.4", "--dpi", "40", "-q"])
    assert code == 0
    assert len(_gif_frames(gif)) == 3
    html = tmp_path / "four_bar.html"
    assert main(["view", str(EXAMPLES / "four_bar.toml"), "-o", str(html)]) == 0
    text = html.read_text()
    assert "viewer of four_bar" in capsys.readouterr().out
    assert not re.search(r"""(src|href)\s*=\s*["']?(https?:)?//""", text)
    assert "camlink-data" in text
    assert main(["animate", str(EXAMPLES / "four_bar.toml"), "-o", str(tmp_path / "x.avi")]) == 2
    assert "unknown file type '.avi' (use .gif or .mp4)" in capsys.readouterr().err


class _Tty(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_progress_only_on_a_terminal(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("CI", raising=False)
    assert not wanted(stream=io.StringIO())
    assert wanted(stream=_Tty())
    assert not wanted(quiet=True, stream=_Tty())
    monkeypatch.setenv("CI", "true")
    assert not wanted(stream=_Tty())
    monkeypatch.delenv("CI")
    out = _Tty()
    with Progress(50, "run", stream=out) as bar:
        for _ in range(50):
            bar.update()
    assert "run:" in out.getvalue() and "step/s" in out.getvalue() and "left" in out.getvalue()
    piped = io.StringIO()
    with Progress(5, "run", stream=piped) as bar:
        bar.update(5)
    assert piped.getvalue() == "" and bar.done == 5
