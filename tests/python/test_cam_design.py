"""Cam design: the `camlink cam` command on the example design files, its
exit codes and messages, the pictures and the manufacturing exports."""

from __future__ import annotations

import csv
import itertools
import json
import math
from pathlib import Path
from typing import Any

import ezdxf
import numpy as np
import pytest

from camlink import cli
from camlink._core import CamCore
from camlink.cam import design as cam_design
from camlink.cam import export as cam_export
from camlink.cam import plots as cam_plots
from camlink.cli import cam as cam_cli
from conftest import ROOT

# Timing files (with [[axes]]) are tested in test_issue32_cam_sizing.py.
DESIGNS = sorted(
    p for p in (ROOT / "examples").glob("cam_design_*.toml") if p.name != "cam_design_timing.toml"
)


def test_every_design_example_is_tested_here() -> None:
    names = {p.name for p in DESIGNS}
    assert names == {
        "cam_design_valve.toml",
        "cam_design_indexing.toml",
        "cam_design_packaging.toml",
        "cam_design_timing_gate.toml",
    }


@pytest.mark.parametrize("path", DESIGNS, ids=lambda p: p.name)
def test_design_example_runs_holds_its_limits_and_round_trips(
    path: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    code = cli.main(["cam", str(path), "--json", "--out", str(tmp_path)])
    out = json.loads(capsys.readouterr().out)
    assert code == 0 and out["ok"], [c for c in out["checks"] if not c["ok"]]
    # The synthesised cam run through camlink's own kinematics reproduces
    # the program.
    d, v, a = out["round_trip"]
    assert d < 1e-9 and v < 1e-7 and a < 1e-7
    stem = path.stem
    for name in (
        f"{stem}_svaj.png",
        f"{stem}_profile.png",
        f"{stem}.csv",
        f"{stem}.dxf",
        f"{stem}.svg",
    ):
        assert (tmp_path / name).stat().st_size > 0, name


def test_valve_example_text_report(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    code = cli.main(
        [
            "cam",
            str(ROOT / "examples" / "cam_design_valve.toml"),
            "--out",
            str(tmp_path),
        ]
    )
    text = capsys.readouterr().out
    assert code == 0
    assert "jump speed vs redline" in text and "all limits hold" in text
    assert "4-5-6-7" in text and "C3 at 150°" in text


def test_valve_jump_speed_is_the_closed_form() -> None:
    """Jump speed of the valve (no damping): ω² = min over s″ < 0 of
    (F₀ + k s)/(m |s″|), on a fine grid of the program."""
    design = cam_design.load(ROOT / "examples" / "cam_design_valve.toml")
    report = cam_design.analyse(design)
    jump = next(c for c in report.checks if c.name == "jump speed vs redline")
    dyn = design.dynamics
    assert dyn is not None
    th = np.linspace(0.0, 2 * math.pi, 400_001)
    m = np.asarray(design.core().motion(th))
    neg = m[:, 2] < 0
    w = np.sqrt(
        (dyn.preload + dyn.spring_rate * m[neg, 0]) / (dyn.mass * -m[neg, 2])
    ).min()
    assert jump.value == pytest.approx(w * 60 / (2 * math.pi), rel=1e-7)


def _write(tmp_path: Path, text: str) -> Path:
    p = tmp_path / "design.toml"
    p.write_text(text)
    return p


VALVE = (ROOT / "examples" / "cam_design_valve.toml").read_text()


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (
            ('law = "4-5-6-7"', 'law = "septic"'),
            "segments[1].law: 'septic' is not one of",
        ),
        (
            ("base_radius = 0.018", "base_radius = -1"),
            "cam.base_radius: must be positive",
        ),
        (("span_deg = 150", "span_deg = 140"), "360"),
        (("lift = -0.009", "lift = -0.008"), "return"),
        (("mass = 0.12", "mass = 'heavy'"), "dynamics.mass: must be a number"),
        (("[limits]", "[limits]\nmin_radiuss = 1"), "limits.min_radiuss: unknown key"),
        (
            ("[limits]", "[limits]\nmax_presure_angle_deg = 30"),
            "unknown key (did you mean 'max_pressure_angle_deg'?)",
        ),
        (
            ("[limits]", "[limits]\nbase_radius_serach = [0.01, 0.05]"),
            "(did you mean 'base_radius_search'?)",
        ),
        (('law = "4-5-6-7"', 'law = "cycloidl"'), "(did you mean 'cycloidal'?)"),
        (('type = "translating-flat"', 'type = "translating-flatt"'), "'translating-flat'?"),
        (('type = "translating-flat"', 'type = "sideways"'), "follower.type"),
        (("name = ", "name = = "), "design.toml"),
    ],
)
def test_bad_design_exits_2_naming_the_field(
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    edit: tuple[str, str],
    message: str,
) -> None:
    path = _write(tmp_path, VALVE.replace(*edit, 1))
    code = cli.main(["cam", str(path), "--no-files"])
    err = capsys.readouterr().err
    assert code == 2
    assert message in err and "design.toml" in err and "Traceback" not in err


def test_failing_limit_exits_1(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # A redline above the jump speed (about 4470 rpm) fails.
    path = _write(tmp_path, VALVE.replace("redline_rpm = 3500", "redline_rpm = 4500"))
    assert cli.main(["cam", str(path), "--no-files"]) == 1
    assert "FAIL jump speed vs redline" in capsys.readouterr().out


def _valve_core() -> CamCore:
    return cam_design.load(ROOT / "examples" / "cam_design_valve.toml").core()


def test_flat_face_report_radius_is_rb_plus_s_plus_s2() -> None:
    design = cam_design.load(ROOT / "examples" / "cam_design_valve.toml")
    rho = next(
        c
        for c in cam_design.analyse(design).checks
        if c.name.startswith("least radius")
    )
    th = np.linspace(0.0, 2 * math.pi, 400_001)
    m = np.asarray(design.core().motion(th))
    assert rho.value == pytest.approx(
        float(np.min(design.base_radius + m[:, 0] + m[:, 2])), abs=1e-9
    )


def test_csv_by_step_and_by_chord(tmp_path: Path) -> None:
    core = _valve_core()
    path = tmp_path / "p.csv"
    cam_export.write_csv(
        core, path, cam_export.angles_by_step(math.radians(1.0)), tool_radius=0.05
    )
    rows = list(csv.reader(path.open()))
    assert rows[0] == ["theta_deg", "x", "y", "tool_x", "tool_y"]
    assert len(rows) == 361
    # θ = 0 is on the dwell: the base circle point straight up (cam frame).
    assert float(rows[1][1]) == pytest.approx(0.0, abs=1e-15)
    assert float(rows[1][2]) == pytest.approx(0.018, abs=1e-15)
    assert float(rows[1][4]) == pytest.approx(0.018 + 0.05, abs=1e-12)
    # Chord tolerance: every curve point between neighbours is within it.
    tol = 1e-5
    th = cam_export.angles_by_chord(core, tol)
    th = np.append(th, 2 * math.pi)
    for a, b in itertools.pairwise(th):
        mid = np.linspace(a, b, 9)
        p = np.asarray(core.surface(mid))
        d = p[-1] - p[0]
        dev = np.abs(
            d[0] * (p[:, 1] - p[0, 1]) - d[1] * (p[:, 0] - p[0, 0])
        ) / np.hypot(*d)
        assert dev.max() <= 1.01 * tol


def _dense(core: CamCore) -> np.ndarray:
    return np.asarray(
        core.surface(np.linspace(0.0, 2 * math.pi, 20_000, endpoint=False))
    )


def _distance_to(points: np.ndarray, curve: np.ndarray) -> np.ndarray:
    """Distance of each point to the closed polyline `curve`."""
    a, b = curve, np.roll(curve, -1, axis=0)
    d = b - a
    dd = np.einsum("ij,ij->i", d, d)
    out = []
    for p in points:
        t = np.clip(np.einsum("ij,ij->i", p - a, d) / dd, 0.0, 1.0)
        q = a + t[:, None] * d
        out.append(np.min(np.hypot(*(q - p).T)))
    return np.array(out)


@pytest.mark.parametrize("mode", ["polyline", "arcs"])
def test_dxf_lies_on_the_profile_within_tolerance(tmp_path: Path, mode: str) -> None:
    core = _valve_core()
    tol = 1e-5
    path = tmp_path / "cam.dxf"
    count = cam_export.write_dxf(core, path, tol, mode, tool_radius=0.05)
    doc = ezdxf.readfile(path)
    msp = doc.modelspace()
    dense = _dense(core)
    cam = [e for e in msp if e.dxf.layer == "CAM"]
    assert len(cam) == count
    if mode == "polyline":
        poly: Any = cam[0]
        pts = np.array([(x, y) for x, y, *_ in poly.get_points()])
        assert poly.closed
        assert _distance_to(pts, dense).max() < 1e-8
    else:
        assert 4 < count < 400
        for e in cam:
            if e.dxftype() == "ARC":
                a0, a1 = math.radians(e.dxf.start_angle), math.radians(e.dxf.end_angle)
                if a1 < a0:
                    a1 += 2 * math.pi
                t = np.linspace(a0, a1, 7)
                c, r = e.dxf.center, e.dxf.radius
                pts = np.column_stack([c[0] + r * np.cos(t), c[1] + r * np.sin(t)])
            else:
                pts = np.array([tuple(e.dxf.start)[:2], tuple(e.dxf.end)[:2]])
            assert _distance_to(pts, dense).max() < 1.5 * tol
    tool = [e for e in msp if e.dxf.layer == "TOOL"]
    assert len(tool) == 1


def test_svg_path_is_the_profile_in_millimetres(tmp_path: Path) -> None:
    core = _valve_core()
    path = tmp_path / "cam.svg"
    cam_export.write_svg(core, path, 1e-5)
    text = path.read_text()
    d = text.split('id="cam"')[1].split('d="')[1].split('"')[0]
    nums = np.array(
        [
            float(v)
            for v in d.replace("M", " ").replace("L", " ").replace("Z", " ").split()
        ]
    )
    pts = nums.reshape(-1, 2) / 1000.0
    assert _distance_to(pts, _dense(core)).max() < 1e-8


def test_tool_undercut_where_concave_tighter_than_the_tool() -> None:
    design = cam_design.load(ROOT / "examples" / "cam_design_indexing.toml")
    core = design.core()
    rho = np.asarray(
        core.contact(np.linspace(0.0, 2 * math.pi, 3600, endpoint=False))["rho"]
    )
    tightest = float(-rho[rho < 0].max())  # least |ρ| of the concave parts
    assert cam_design.tool_undercut(core, 0.9 * tightest) == []
    ranges = cam_design.tool_undercut(core, 1.1 * tightest)
    assert ranges
    for a, b in ranges:
        r = np.asarray(core.contact(np.array([0.5 * (a + b)]))["rho"])[0]
        assert -1.1 * tightest < r < 0


def _pixel(fig: Any, ax: Any, xy: Any) -> tuple[int, int]:
    fig.canvas.draw()
    x, y = ax.transData.transform(xy)
    h = fig.canvas.get_width_height()[1]
    return round(x), round(h - y)


def test_svaj_plots_the_program_with_boundaries() -> None:
    core = _valve_core()
    fig = cam_plots.svaj(core, title="valve")
    axes = fig.axes
    th = np.linspace(0.0, 2 * math.pi, 1441)
    m = np.asarray(core.motion(th))
    for k in range(4):
        line = axes[k].lines[0]
        assert np.allclose(line.get_xdata(), np.degrees(th))
        assert np.allclose(line.get_ydata(), m[:, k])
    marks = sorted(
        {round(float(np.asarray(ln.get_xdata())[0]), 9) for ln in axes[0].lines[2:]}
    )
    assert marks == [0.0, 150.0, 250.0, 260.0]
    cam_plots.save(fig, "/dev/null")


def test_profile_draws_the_surface_at_its_pixels() -> None:
    core = _valve_core()
    fig = cam_plots.profile(core, base_radius=0.018, colour_by="rho")
    ax = fig.axes[0]
    fig.canvas.draw()
    canvas: Any = fig.canvas
    img = np.asarray(canvas.buffer_rgba())
    # Points of the surface are drawn (not white); a point halfway between
    # the nose and the frame's edge is empty.
    th = np.array([0.3, 1.0, 3.5, 4.2, 5.0])
    for p in np.asarray(core.surface(th)):
        x, y = _pixel(fig, ax, p)
        patch = img[y - 1 : y + 2, x - 1 : x + 2, :3]
        assert patch.min() < 200, (p, patch)
    x, y = _pixel(fig, ax, (0.0255, 0.0285))
    assert img[y, x, :3].min() > 240
    cam_plots.save(fig, "/dev/null")


def test_cam_core_rejects_bad_programs() -> None:
    with pytest.raises(ValueError, match="unknown law"):
        CamCore(
            [("sine", 2 * math.pi, 0.0, [None] * 3, [None] * 3)],
            "translating-flat",
            [],
            0.02,
            True,
        )
    with pytest.raises(ValueError, match="takes 2 dimensions"):
        CamCore(
            [("dwell", 2 * math.pi, 0.0, [None] * 3, [None] * 3)],
            "translating-roller",
            [0.0],
            0.02,
            True,
        )
    assert cam_cli.EXIT_INPUT == 2
