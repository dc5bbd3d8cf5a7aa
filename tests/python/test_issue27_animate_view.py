"""Issue 27 (Trust), `camlink animate` and `camlink view`: they never write
over an input of the model nor over an existing default output without
`--force`, and write whole files; they run no more rows than they can show;
their options are bounded, a bad one being a usage error (exit 2)."""

from __future__ import annotations

import base64
import io
import json
import re
import shutil
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import camlink
from camlink.cli import main
from camlink.cli.visuals import ROWS_PER_FRAME
from camlink.viz import animate as animate_module
from camlink.viz.animate import DPIS, MOST_FPS, MOST_FRAMES, MOST_PIXELS, WIDTHS, animate
from camlink.viz.viewer import MOST_ROWS

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


@pytest.fixture
def folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A working folder with the four-bar (m.toml) and the cam whose
    profile is a data file (cam.toml, data/cam_profile.csv)."""
    shutil.copy(EXAMPLES / "four_bar.toml", tmp_path / "m.toml")
    shutil.copy(EXAMPLES / "cam_csv_profile.toml", tmp_path / "cam.toml")
    (tmp_path / "data").mkdir()
    shutil.copy(EXAMPLES / "data" / "cam_profile.csv", tmp_path / "data" / "cam_profile.csv")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def _page_rows(path: Path) -> int:
    m = re.search(r'<script id="camlink-data" type="application/json">(.*?)</script>',
                  path.read_text(encoding="utf-8"), re.DOTALL)
    assert m
    return len(np.frombuffer(base64.b64decode(json.loads(m.group(1))["t"]), "<f8"))


def _gif_frames(path: Path) -> int:
    return int(getattr(Image.open(path), "n_frames", 1))


# -- finding: view and animate overwrite their inputs ---------------------------


@pytest.mark.parametrize("command", ["view", "animate"])
@pytest.mark.parametrize(("model", "output"), [
    ("m.toml", "m.toml"),
    ("cam.toml", "data/cam_profile.csv"),
    ("cam.toml", "./data/../cam.toml"),
])
def test_issue27_view_animate_refuse_their_inputs(
    folder: Path, command: str, model: str, output: str, capsys: pytest.CaptureFixture[str]
) -> None:
    before = {p: p.read_bytes() for p in folder.rglob("*") if p.is_file()}
    assert main([command, model, "-o", output, "--t-end", "0.1", "-q"]) == 2
    assert "is an input of the model" in capsys.readouterr().err
    assert {p: p.read_bytes() for p in folder.rglob("*") if p.is_file()} == before


def test_issue27_view_animate_refuse_a_symlink_to_an_input(
    folder: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    (folder / "link.html").symlink_to(folder / "m.toml")
    before = (folder / "m.toml").read_bytes()
    assert main(["view", "m.toml", "-o", "link.html", "-q"]) == 2
    assert (folder / "m.toml").read_bytes() == before


@pytest.mark.parametrize(("command", "suffix"), [("view", ".html"), ("animate", ".gif")])
def test_issue27_view_animate_default_output_needs_force(
    folder: Path, command: str, suffix: str, capsys: pytest.CaptureFixture[str]
) -> None:
    out = folder / f"m{suffix}"
    out.write_bytes(b"earlier work")
    args = [command, "m.toml", "--t-end", "0.2", "-q"]
    assert main(args) == 2
    assert f"m{suffix} exists; pass --force" in capsys.readouterr().err
    assert out.read_bytes() == b"earlier work"
    assert main([*args, "--force"]) == 0
    assert out.read_bytes() != b"earlier work"
    if command == "view":
        assert _page_rows(out) == 41  # the file's step, 5 ms
    else:
        assert _gif_frames(out) == 5
    # -o names the output: replaced without --force.
    assert main([command, "m.toml", "--t-end", "0.2", "-q", "-o", str(out)]) == 0
    # No temporary file is left.
    assert sorted(p.name for p in folder.iterdir()) == sorted(["cam.toml", "data", "m.toml", out.name])


def test_issue27_view_failure_keeps_the_earlier_page(
    folder: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = folder / "page.html"
    assert main(["view", "m.toml", "-o", "page.html", "--t-end", "0.2", "-q"]) == 0
    good = out.read_bytes()
    # A channel that does not exist: a usage error, and the page stays.
    assert main(["view", "m.toml", "-o", "page.html", "--plot", "coupler.ph", "-q"]) == 2
    assert "cannot plot 'coupler.ph': no channel named 'coupler.ph' (did you mean 'coupler.phi'" \
        in capsys.readouterr().err
    assert out.read_bytes() == good
    assert sorted(p.name for p in folder.iterdir()) == ["cam.toml", "data", "m.toml", "page.html"]


def test_issue27_animate_interrupted_keeps_the_earlier_file(
    folder: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    out = folder / "a.gif"
    assert main(["animate", "m.toml", "-o", "a.gif", "--t-end", "0.3", "--dpi", "30", "-q"]) == 0
    good = out.read_bytes()
    show = animate_module.Drawing.show
    calls = {"n": 0}

    def interrupted(self: animate_module.Drawing, k: int, grow: bool = False) -> None:
        calls["n"] += 1
        if calls["n"] == 3:
            raise KeyboardInterrupt
        show(self, k, grow)

    monkeypatch.setattr(animate_module.Drawing, "show", interrupted)
    assert main(["animate", "m.toml", "-o", "a.gif", "--t-end", "0.3", "--dpi", "30", "-q"]) == 130
    assert "interrupted: 2 frames written to a.partial.gif" in capsys.readouterr().err
    assert out.read_bytes() == good
    assert _gif_frames(folder / "a.partial.gif") == 2


# -- finding: every row held in memory ------------------------------------------


def test_issue27_view_step_is_coarsened_to_the_page(
    folder: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # 2 s at 1e-7 s would be 2e7 rows (the core ran out of memory).
    assert main(["view", "m.toml", "-o", "fine.html", "--step", "1e-7"]) == 0
    out, err = capsys.readouterr()
    assert _page_rows(folder / "fine.html") == MOST_ROWS
    notes = err.strip().splitlines()
    assert notes == [f"camlink: note: --step 1e-07 s would give 2e+07 rows, more than the "
                     f"{MOST_ROWS} shown: output step 0.000100005 s"]
    assert f"{MOST_ROWS} steps" in out
    # A step the page can hold is kept, with no note.
    assert main(["view", "m.toml", "-o", "fine.html", "--step", "0.001"]) == 0
    assert "note" not in capsys.readouterr().err
    assert _page_rows(folder / "fine.html") == 2001


def test_issue27_view_dynamics_step_stays_on_the_integration_steps(
    folder: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # The pendulum's h defaults to its output step (at most 1 ms): the
    # coarser output step is a whole number of those steps.
    shutil.copy(EXAMPLES / "dyn_pendulum.toml", folder / "p.toml")
    assert main(["view", "p.toml", "-o", "p.html", "--step", "1e-5"]) == 0
    err = capsys.readouterr().err
    assert "output step 0.00016 s" in err and "warning" not in err
    assert _page_rows(folder / "p.html") == int(3.0 / 0.00016) + 1


def test_issue27_animate_runs_ten_rows_a_frame(
    folder: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["animate", "m.toml", "-o", "a.gif", "--step", "1e-7", "--fps", "10",
                 "--dpi", "30"]) == 0
    out, err = capsys.readouterr()
    frames = 21
    assert _gif_frames(folder / "a.gif") == frames
    assert f"more than the {ROWS_PER_FRAME * frames} shown" in err
    assert f"{ROWS_PER_FRAME * frames} steps" in out


def test_issue27_view_thins_the_files_times(folder: Path, capsys: pytest.CaptureFixture[str]) -> None:
    text = (folder / "m.toml").read_text(encoding="utf-8")
    times = ", ".join(f"{t:.6f}" for t in np.linspace(0.0, 1.0, 500))
    text = text.replace("t_end = 2.0", f"times = [{times}]", 1).replace("step = 0.005", "", 1)
    (folder / "t.toml").write_text(text, encoding="utf-8")
    assert main(["animate", "t.toml", "-o", "t.gif", "--fps", "5", "--dpi", "30"]) == 0
    err = capsys.readouterr().err
    assert "the file's 500 output times thinned to 60" in err
    assert _gif_frames(folder / "t.gif") == 6


# -- finding: animate options not validated -------------------------------------


@pytest.mark.parametrize(("option", "message"), [
    (["--dpi", "0"], "--dpi must be a whole number of pixels per inch from 10 to 600, not 0"),
    (["--dpi", "100000"], "--dpi must be a whole number of pixels per inch from 10 to 600"),
    (["--width", "1e5"], "--width must be a width in inches from 1.5 to 40, not 100000.0"),
    (["--width", "-1"], "--width must be a width in inches from 1.5 to 40, not -1.0"),
    (["--width", "nan"], "--width must be a width in inches from 1.5 to 40, not nan"),
    (["--width", "40", "--dpi", "600"], "--width × --dpi is 24000 pixels across; at most 4096"),
    (["--fps", "1e9"], "--fps must be a number of frames per second in (0, 60]"),
    (["--fps", "0"], "--fps must be a number of frames per second in (0, 60]"),
    (["--fps", "inf"], "--fps must be a number of frames per second in (0, 60]"),
    (["--speed", "0"], "--speed must be a positive number"),
    (["--speed", "nan"], "--speed must be a positive number"),
    (["--speed", "1e-9"], "2 s of motion at 20 frames per second and speed 1e-09 is 4e+10 frames; "
                          f"at most {MOST_FRAMES}"),
    (["--trace", "nope.P"], "--trace: model 'four_bar' has no body point 'nope.P' (points: "
                            "ground.O2, ground.O4, crank.A"),
    (["--trace", "coupler"], "has no body point 'coupler'"),
    (["--step", "-1"], "--step:"),
    (["--t-end", "nan"], "--t-end:"),
])
def test_issue27_animate_option_bounds(
    folder: Path, option: list[str], message: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main(["animate", "m.toml", "-o", "a.gif", "-q", *option]) == 2
    err = capsys.readouterr().err
    assert message in err, err
    assert "internal error" not in err and "Traceback" not in err
    assert not (folder / "a.gif").exists()


def test_issue27_animate_bounds_in_help(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit):
        main(["animate", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    assert f"at most {MOST_FPS:g}" in text
    assert f"{WIDTHS[0]:g} to {WIDTHS[1]:g}" in text
    assert f"{DPIS[0]} to {DPIS[1]}" in text and f"at most {MOST_PIXELS} pixels across" in text
    assert f"at most {MOST_FRAMES} frames" in text
    with pytest.raises(SystemExit):
        main(["view", "--help"])
    assert f"at most {MOST_ROWS} rows" in " ".join(capsys.readouterr().out.split())


def test_issue27_animate_library_bounds_and_alt_text(tmp_path: Path) -> None:
    text = (EXAMPLES / "four_bar.toml").read_text(encoding="utf-8")
    model = camlink.loads(text.replace('name = "four_bar"', 'name = "a\\" onload=\\"x <b>"', 1))
    res = model.run(t_end=0.2, step=0.01)
    for kw in ({"dpi": 0}, {"width": float("nan")}, {"fps": 1e9}, {"speed": -1.0},
               {"traces": ["coupler.Q"]}):
        with pytest.raises(camlink.ModelError):
            animate(res, tmp_path / "x.gif", **kw)
    assert not list(tmp_path.iterdir())
    page = animate(res, fps=5, width=2.0, dpi=20)
    assert isinstance(page, str)
    m = re.fullmatch(r'<img alt="([^"]*)" src="data:image/gif;base64,([A-Za-z0-9+/=]+)"/>', page)
    assert m and m.group(1) == "animation of a&quot; onload=&quot;x &lt;b&gt;"
    assert getattr(Image.open(io.BytesIO(base64.b64decode(m.group(2)))), "n_frames", 1) == 2
