"""Issue 27, `camlink cam`: its files are written like `run`'s (never over
the design file, an existing default output kept unless --force, each file
through a temporary name), export names are plain file names, the costly
settings are bounded, bad designs end in a clear error or a report, extremes
lie inside their segments, DXF arcs stay within the tolerance, and the face
width's contact travel is a JSON field."""

from __future__ import annotations

import json
import math
import os
from pathlib import Path
from typing import Any

import ezdxf
import numpy as np
import pytest
from scipy.spatial import cKDTree

from camlink import cli
from camlink.cam import design as cam_design
from camlink.cam import export as cam_export
from camlink.cam import plots as cam_plots
from camlink.cli import cam as cam_cli
from conftest import ROOT

VALVE = (ROOT / "examples" / "cam_design_valve.toml").read_text()

#: A centred roller: cycloidal rise and return of 10 mm over 90° each.
ROLLER = """\
name = "roller"
[cam]
base_radius = 0.03
[follower]
type = "translating-roller"
roller_radius = 0.01
[[segments]]
law = "cycloidal"
span_deg = 90
lift = 0.01
[[segments]]
law = "dwell"
span_deg = 90
[[segments]]
law = "cycloidal"
span_deg = 90
lift = -0.01
[[segments]]
law = "dwell"
span_deg = 90
"""


def _write(folder: Path, text: str, name: str = "design.toml") -> Path:
    path = folder / name
    path.write_text(text)
    return path


def _cam(args: list[str], capsys: pytest.CaptureFixture[str]) -> tuple[int, str, str]:
    code = cli.main(["cam", *args])
    out, err = capsys.readouterr()
    return code, out, err


# Finding 1: the files `camlink cam` writes.


def test_issue27_cam_keeps_existing_default_outputs_without_force(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    design = _write(tmp_path, ROLLER)
    out = tmp_path / "out"
    code, _, _ = _cam([str(design), "--out", str(out)], capsys)
    assert code == 0
    names = sorted(os.listdir(out))
    assert names == [
        "design.csv",
        "design.dxf",
        "design.svg",
        "design_profile.png",
        "design_svaj.png",
    ]
    (out / "design.csv").write_text("my edits")
    code, _, err = _cam([str(design), "--out", str(out)], capsys)
    assert code == 2
    assert "--force" in err and "exist;" in err
    for name in names:
        assert str(out / name) in err
    assert (out / "design.csv").read_text() == "my edits"
    code, _, _ = _cam([str(design), "--out", str(out), "--force"], capsys)
    assert code == 0
    assert (out / "design.csv").read_text().startswith("theta_deg,x,y")
    assert sorted(os.listdir(out)) == names
    # A name the design file gives is replaced without --force.
    named = _write(
        tmp_path,
        ROLLER + '[export]\ncsv = "mine.csv"\nsvaj_plot = false\n'
        "profile_plot = false\ndxf = false\nsvg = false\n",
        "named.toml",
    )
    (out / "mine.csv").write_text("old")
    code, _, _ = _cam([str(named), "--out", str(out)], capsys)
    assert code == 0
    assert (out / "mine.csv").read_text().startswith("theta_deg,x,y")


def test_issue27_cam_never_writes_over_its_design_file(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """An export that is (a link to) the design file is refused before
    anything is written."""
    design = _write(tmp_path, ROLLER + '[export]\ncsv = "link.csv"\n')
    before = design.read_text()
    (tmp_path / "link.csv").symlink_to(design)
    code, _, err = _cam([str(design), "--out", str(tmp_path)], capsys)
    assert code == 2
    assert "export.csv" in err and "design file" in err
    assert design.read_text() == before
    assert sorted(os.listdir(tmp_path)) == ["design.toml", "link.csv"]
    # A hard link too.
    (tmp_path / "link.csv").unlink()
    os.link(design, tmp_path / "link.csv")
    assert _cam([str(design), "--out", str(tmp_path)], capsys)[0] == 2
    assert design.read_text() == before


def test_issue27_cam_writes_each_file_through_a_temporary_name(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A picture that fails half-way leaves the earlier file whole and no
    temporary file behind; the others are written to a temporary name
    beside their output and renamed."""
    design = cam_design.load(_write(tmp_path, ROLLER + '[export]\nsvaj_plot = "s.png"\n'))
    (tmp_path / "s.png").write_bytes(b"earlier picture")
    seen: list[Path] = []

    def failing(fig: Any, path: Path, dpi: int = 120) -> None:
        seen.append(Path(path))
        Path(path).write_bytes(b"half")
        raise RuntimeError("disk full")

    monkeypatch.setattr(cam_plots, "save", failing)
    with pytest.raises(RuntimeError):
        cam_cli._write_files(design, tmp_path)
    assert (tmp_path / "s.png").read_bytes() == b"earlier picture"
    assert seen[0].parent == tmp_path and seen[0].name != "s.png"
    assert seen[0].suffix == ".png"
    assert sorted(os.listdir(tmp_path)) == ["design.toml", "s.png"]


# Finding 2: export names.


@pytest.mark.parametrize(
    ("key", "name", "message"),
    [
        ("csv", "design.toml", "the design file's name"),
        ("svg", "../x.svg", "path separator"),
        ("svg", "sub/x.svg", "path separator"),
        ("dxf", "..\\\\x.dxf", "path separator"),
        ("svaj_plot", "/tmp/issue27.png", "path separator"),
        ("profile_plot", "..", "is a folder"),
        ("csv", "a\\nb.csv", "control character"),
        ("dxf", "design.csv", "also export.csv"),
    ],
)
def test_issue27_export_names_are_plain_file_names(
    tmp_path: Path,
    capsys: pytest.CaptureFixture[str],
    key: str,
    name: str,
    message: str,
) -> None:
    folder = tmp_path / "d"
    folder.mkdir()
    design = _write(folder, ROLLER + f'[export]\n{key} = "{name}"\n')
    before = design.read_text()
    code, _, err = _cam([str(design), "--out", str(folder)], capsys)
    assert code == 2, err
    assert f"export.{key}" in err and message in err
    assert design.read_text() == before
    assert os.listdir(folder) == ["design.toml"]
    assert os.listdir(tmp_path) == ["d"]
    assert not Path("/tmp/issue27.png").exists()


# Finding 3: bounds.


@pytest.mark.parametrize(
    ("text", "field"),
    [
        ("[export]\ntolerance = 1e-300\n", "export.tolerance"),
        ("[export]\ncsv_chord_tolerance = 1e-300\n", "export.csv_chord_tolerance"),
        ("[export]\ncsv_step_deg = 1e-7\n", "export.csv_step_deg"),
        ("[export]\ntool_radius = 1e300\n", "export.tool_radius"),
    ],
)
def test_issue27_export_settings_are_bounded(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], text: str, field: str
) -> None:
    design = _write(tmp_path, ROLLER + text)
    code, _, err = _cam([str(design), "--out", str(tmp_path)], capsys)
    assert code == 2 and field in err, err
    assert os.listdir(tmp_path) == ["design.toml"]


def test_issue27_export_bounds_hold_from_python_too() -> None:
    core = cam_design.load(ROOT / "examples" / "cam_design_valve.toml").core()
    size = float(core.geometry()["max_radius"])
    with pytest.raises(ValueError, match="finer than"):
        cam_export.angles_by_chord(core, 1e-300)
    with pytest.raises(ValueError, match="finer than"):
        cam_export.write_dxf(core, os.devnull, 0.5 * cam_export.MIN_RELATIVE_TOLERANCE * size)
    with pytest.raises(ValueError, match="rows"):
        cam_export.angles_by_step(math.radians(1e-7))
    assert len(cam_export.angles_by_step(math.radians(360.0 / cam_export.MAX_CSV_ROWS))) == (
        cam_export.MAX_CSV_ROWS
    )
    # At the bound the count stays far below MAX_POINTS.
    th = cam_export.angles_by_chord(core, cam_export.MIN_RELATIVE_TOLERANCE * size)
    assert 10_000 < len(th) < cam_export.MAX_POINTS // 10


def test_issue27_segment_count_is_bounded(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    n = cam_design.MAX_SEGMENTS + 1
    segs = "".join(f'[[segments]]\nlaw = "dwell"\nspan_deg = {360 / n!r}\n' for _ in range(n))
    design = _write(
        tmp_path,
        'name = "many"\n[cam]\nbase_radius = 0.05\n[follower]\ntype = "translating-flat"\n' + segs,
    )
    code, _, err = _cam([str(design), "--no-files"], capsys)
    assert code == 2 and "[[segments]]" in err and str(cam_design.MAX_SEGMENTS) in err


# Finding 4: designs that load end in a clear error or a report.


@pytest.mark.parametrize(
    ("edit", "field"),
    [
        (("base_radius = 0.03", "base_radius = 1e300"), "cam.base_radius"),
        (("span_deg = 90\nlift = 0.01", "span_deg = 1e-12\nlift = 0.01"), "segments[0].span_deg"),
        (("base_radius = 0.03", "base_radius = 1e-300"), "not finite"),
    ],
)
def test_issue27_unusable_designs_exit_2(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], edit: tuple[str, str], field: str
) -> None:
    design = _write(tmp_path, ROLLER.replace(*edit, 1))
    code, _, err = _cam([str(design), "--out", str(tmp_path)], capsys)
    assert code == 2 and field in err and "internal error" not in err, err


def test_issue27_base_radius_search_must_be_finite(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    design = _write(tmp_path, ROLLER + "[limits]\nbase_radius_search = [0.01, inf]\n")
    code, _, err = _cam([str(design), "--no-files"], capsys)
    assert code == 2 and "limits.base_radius_search" in err


def test_issue27_steep_rise_ends_in_a_report(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """A rise too steep for the follower to stay on: the round trip's
    failure is a failing check in the report (exit 1), at a cam angle and
    without the names of camlink's own joints."""
    steep = ROLLER.replace("span_deg = 90\nlift = 0.01", "span_deg = 0.5\nlift = 0.01", 1)
    steep = steep.replace('law = "dwell"\nspan_deg = 90', 'law = "dwell"\nspan_deg = 179.5', 1)
    design = _write(tmp_path, steep)
    code, out, err = _cam([str(design), "--json", "--out", str(tmp_path)], capsys)
    assert code == 1, err
    report = json.loads(out)
    assert report["round_trip"] is None
    check = next(c for c in report["checks"] if c["name"] == "round trip")
    assert not check["ok"] and "θ = " in check["note"]
    for joint in ("'contact'", "'motor'", "follower-guide"):
        assert joint not in check["note"]
    # The undercut, narrower than the samples, is reported too.
    undercut = next(c for c in report["checks"] if c["name"] == "undercut ranges")
    assert not undercut["ok"] and report["undercut_deg"]
    code, out, _ = _cam([str(design), "--out", str(tmp_path), "--force"], capsys)
    assert code == 1 and "FAIL round trip: camlink's kinematics" in out


def test_issue27_name_is_shown_literally_in_pictures(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    name = "$x^{2$ cam"
    design = _write(tmp_path, ROLLER.replace('name = "roller"', f'name = "{name}"'))
    code, _, err = _cam([str(design), "--out", str(tmp_path)], capsys)
    assert code == 0, err
    core = cam_design.load(design).core()
    for fig in (
        cam_plots.svaj(core, title=f"{name}: SVAJ"),
        cam_plots.profile(core, base_radius=0.03, title=f"{name}: profile"),
    ):
        fig.canvas.draw()
        title = fig.axes[0].title
        # Drawn as plain text (no mathtext), the dollar signs shown.
        shown, math_text = title._preprocess_math(title.get_text())  # type: ignore[attr-defined]
        assert not math_text and shown.startswith(f"{name}: ")
        cam_plots.save(fig, os.devnull)


# Finding 5: extremes inside their segments, arcs within the tolerance.


@pytest.mark.parametrize("ccw", [True, False])
@pytest.mark.parametrize("rb", [0.03, 0.05])
def test_issue27_extremes_lie_inside_their_segments(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], ccw: bool, rb: float
) -> None:
    """Oscillating roller, rise 0°–90°, return 180°–270°: the golden-section
    search used to report the rise's extreme at 359.95° and the return's at
    270° (in the dwells)."""
    text = (
        ROLLER.replace("base_radius = 0.03", f"base_radius = {rb}")
        .replace(
            'type = "translating-roller"\nroller_radius = 0.01',
            'type = "oscillating-roller"\npivot_distance = 0.1\narm_length = 0.06\nroller_radius = 0.01',
        )
        .replace("lift = 0.01", "swing_deg = 15")
        .replace("lift = -0.01", "swing_deg = -15")
    )
    if not ccw:
        text = text.replace("[cam]\n", '[cam]\nrotation = "cw"\n')
    code, out, err = _cam([_write(tmp_path, text).as_posix(), "--json", "--no-files"], capsys)
    assert code in (0, 1), err
    checks = {c["name"]: c for c in json.loads(out)["checks"]}
    assert 0.0 <= checks["pressure angle, rise"]["at_deg"] < 90.0
    assert 180.0 <= checks["pressure angle, return"]["at_deg"] < 270.0


def _arc_points(arcs: list[cam_export.Arc], m: int = 400) -> tuple[np.ndarray, np.ndarray]:
    pts, owner = [], []
    for k, a in enumerate(arcs):
        if math.isinf(a.radius):
            t = np.linspace(0.0, 1.0, m)[:, None]
            pts.append(np.array(a.p0) * (1 - t) + np.array(a.p1) * t)
        else:
            a0, a1 = math.radians(a.start), math.radians(a.end)
            a1 += 2 * math.pi if a1 < a0 else 0.0
            t = np.linspace(a0, a1, m)
            pts.append(
                np.column_stack([a.centre[0] + a.radius * np.cos(t), a.centre[1] + a.radius * np.sin(t)])
            )
        owner.append(np.full(m, k))
    return np.vstack(pts), np.concatenate(owner)


def _to_piece(p: np.ndarray, a: cam_export.Arc) -> np.ndarray:
    """Distance of points `p` to the line or arc `a`."""
    p0, p1 = np.array(a.p0), np.array(a.p1)
    if math.isinf(a.radius):
        d = p1 - p0
        t = np.clip((p - p0) @ d / (d @ d), 0.0, 1.0)
        return np.asarray(np.hypot(*(p0 + t[:, None] * d - p).T))
    c = np.array(a.centre)
    v = p - c
    ang = np.degrees(np.arctan2(v[:, 1], v[:, 0]))
    inside = (ang - a.start) % 360.0 <= (a.end - a.start) % 360.0
    ends = [c + a.radius * np.array([math.cos(e), math.sin(e)]) for e in np.radians([a.start, a.end])]
    to_end = np.minimum(*(np.hypot(*(p - e).T) for e in ends))
    return np.where(inside, np.abs(np.hypot(*v.T) - a.radius), to_end)


def _deviation(arcs: list[cam_export.Arc], exact: np.ndarray) -> float:
    """Largest distance between the pieces and the exact profile, both
    ways: from points along every piece to the finely sampled profile, and
    from every profile point to the nearest piece."""
    ap, owner = _arc_points(arcs)
    n = len(exact)
    _, i = cKDTree(exact).query(ap)
    to_curve = np.full(len(ap), np.inf)
    for j in (i - 1, i):
        a, b = exact[j % n], exact[(j + 1) % n]
        d = b - a
        t = np.clip(np.einsum("ij,ij->i", ap - a, d) / np.einsum("ij,ij->i", d, d), 0.0, 1.0)
        to_curve = np.minimum(to_curve, np.hypot(*(a + t[:, None] * d - ap).T))
    _, k = cKDTree(ap).query(exact)
    near = owner[k]
    to_arcs = np.full(n, np.inf)
    for o in np.unique(near):
        sel = np.nonzero(near == o)[0]
        for oo in (o - 1, o, (o + 1) % len(arcs)):
            to_arcs[sel] = np.minimum(to_arcs[sel], _to_piece(exact[sel], arcs[oo]))
    return float(max(to_curve.max(), to_arcs.max()))


@pytest.mark.parametrize(
    ("example", "tol"),
    [
        ("cam_design_valve.toml", 1e-5),
        ("cam_design_valve.toml", 1e-6),
        ("cam_design_indexing.toml", 1e-4),
        ("cam_design_indexing.toml", 1e-7),
        ("cam_design_packaging.toml", 1e-5),
    ],
)
def test_issue27_dxf_arcs_stay_within_the_tolerance(tmp_path: Path, example: str, tol: float) -> None:
    """The DXF's arcs and lines, read back, against the exact profile at
    400,000 angles (sampling error below 1e-3 of the tolerance): within the
    tolerance both ways. The fit used to reach 1.02 of it (1.08 on the
    indexing cam at 1e-7 m)."""
    core = cam_design.load(ROOT / "examples" / example).core()
    path = tmp_path / "cam.dxf"
    count = cam_export.write_dxf(core, path, tol, "arcs")
    pieces = []
    for e in ezdxf.readfile(path).modelspace():
        if e.dxftype() == "ARC":
            c, r = e.dxf.center, e.dxf.radius
            a0, a1 = e.dxf.start_angle, e.dxf.end_angle
            p0, p1 = (
                (c[0] + r * math.cos(math.radians(a)), c[1] + r * math.sin(math.radians(a))) for a in (a0, a1)
            )
            pieces.append(cam_export.Arc((c[0], c[1]), r, a0, a1, p0, p1))
        else:
            s, t = tuple(e.dxf.start), tuple(e.dxf.end)
            pieces.append(cam_export.Arc((math.nan, math.nan), math.inf, 0.0, 0.0, s[:2], t[:2]))
    assert len(pieces) == count
    exact = np.asarray(core.surface(np.linspace(0.0, 2 * math.pi, 400_000, endpoint=False)))
    assert _deviation(pieces, exact) <= tol


# Finding 6: the face width's contact travel as a JSON field.


def test_issue27_face_travel_is_a_json_field(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    design = _write(tmp_path, VALVE)
    code, out, _ = _cam([str(design), "--json", "--no-files"], capsys)
    assert code == 0
    report = json.loads(out)
    travel = report["face_travel"]
    assert set(travel) == {"lo", "hi", "lo_at_deg", "hi_at_deg", "width"}
    width = next(c for c in report["checks"] if c["name"] == "face width needed")
    assert travel["width"] == width["value"] == travel["hi"] - travel["lo"]
    # Translating face, counterclockwise cam: the contact sits at x = s′.
    core = cam_design.load(design).core()
    th = np.linspace(0.0, 2 * math.pi, 400_001)
    s1 = np.asarray(core.motion(th))[:, 1]
    # Refined between the samples: at least as far out, by little.
    assert s1.min() - 1e-10 < travel["lo"] <= s1.min()
    assert s1.max() <= travel["hi"] < s1.max() + 1e-10
    for key in ("lo", "hi"):
        at = np.radians(travel[f"{key}_at_deg"])
        assert float(np.asarray(core.motion(np.array([at])))[0, 1]) == pytest.approx(travel[key], abs=1e-15)
    # A roller has none.
    code, out, _ = _cam([str(_write(tmp_path, ROLLER, "r.toml")), "--json", "--no-files"], capsys)
    assert json.loads(out)["face_travel"] is None
