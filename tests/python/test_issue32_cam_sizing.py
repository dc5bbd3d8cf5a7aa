"""Issue 32, the cam half: Hertz contact stress, bearing life and camshaft
torque, the helical valve spring, follower-train vibration, timing
diagrams and servo cam tables, designer's units and the bore, keyway and
timing mark on the exported profile."""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import ezdxf
import matplotlib

matplotlib.use("Agg")
import numpy as np
import pytest

from camlink import cli
from camlink.cam import design as cam_design
from camlink.cam import plots as cam_plots
from camlink.cam import timing as cam_timing
from conftest import ROOT

VALVE = ROOT / "examples" / "cam_design_valve.toml"
TIMING = ROOT / "examples" / "cam_design_timing.toml"

# Shigley, Mechanical Engineering Design, 10th ed., Table A-5.
STEEL = (207e9, 0.292, 79.3e9, 76.5e3 / 9.80665)
CAST_IRON = (100e9, 0.211, 41.4e9, 70.6e3 / 9.80665)


def _json(capsys: pytest.CaptureFixture[str], args: list[str]) -> tuple[int, dict]:
    code = cli.main(args)
    return code, json.loads(capsys.readouterr().out)


def test_issue32_valve_reports_contact_stress_spring_surge_and_vibration(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    code, out = _json(capsys, ["cam", str(VALVE), "--json", "--out", str(tmp_path)])
    assert code == 0 and out["ok"]
    names = [c["name"] for c in out["checks"]]
    for want in (
        "Hertz contact stress at 3000 rpm",
        "camshaft torque at 3000 rpm",
        "spring coil-clash margin at the largest lift",
        "spring surge / forcing frequency at 3500 rpm",
        "least dynamic contact force at 3000 rpm (1-mass train)",
        "residual vibration after segment 1",
        "residual vibration after segment 3",
    ):
        assert want in names, names
    for c in out["checks"]:
        if c["limit"] is not None and c["margin"] is not None:
            assert c["ok"] == (c["margin"] >= 0), c
    assert (tmp_path / "cam_design_valve_svaj_time.png").stat().st_size > 0


def test_issue32_hertz_stress_against_the_two_cylinder_closed_form() -> None:
    """Along the valve's profile, at the worst sample: a flat tappet on the
    cam's radius ρ, b = √(4FR/(πLE*)), p = 2F/(πbL) (Shigley eqs. 3-73,
    3-74), E* from Table A-5 for cast iron on steel."""
    design = cam_design.load(VALVE)
    d, c = design.dynamics, design.contact
    assert d is not None and c is not None
    s = design.core().stress((d.mass, d.spring_rate, d.preload, d.damping), d.speed, c.width, c.modulus)
    e_star = 1.0 / ((1 - CAST_IRON[1] ** 2) / CAST_IRON[0] + (1 - STEEL[1] ** 2) / STEEL[0])
    assert c.modulus == pytest.approx(e_star, rel=1e-12)
    k = int(np.argmax(s["pressure"]))
    f, rho = s["force"][k], s["rho"][k]
    b = math.sqrt(4 * f * rho / (math.pi * c.width * e_star))
    assert s["half_width"][k] == pytest.approx(b, rel=1e-12)
    assert s["pressure"][k] == pytest.approx(2 * f / (math.pi * b * c.width), rel=1e-12)
    assert s["max_pressure"][0] >= s["pressure"][k]
    # The refined peak is within a sample of the sampled one.
    assert abs(s["max_pressure"][1] - s["theta"][k]) <= 2 * math.pi / 3600


def test_issue32_spring_figures_are_the_formulas() -> None:
    """k = G d⁴/(8 D³ N_a), L_s = d N_t, m_s = ϱ π² d² D N_a / 4,
    f = ½ √(k/m_s) (Shigley eqs. 10-9, 10-27, 10-28), preload k (L₀ − L_i);
    the jump check uses that rate and preload."""
    design = cam_design.load(VALVE)
    sp, d = design.spring, design.dynamics
    assert sp is not None and d is not None
    G, rho = STEEL[2], STEEL[3]
    k = G * 0.0036**4 / (8 * 0.020**3 * 5)
    ms = rho * math.pi**2 * 0.0036**2 * 0.020 * 5 / 4
    f = sp.figures
    assert f["rate"] == pytest.approx(k, rel=1e-12)
    assert f["mass"] == pytest.approx(ms, rel=1e-12)
    assert f["surge"] == pytest.approx(0.5 * math.sqrt(k / ms), rel=1e-12)
    assert f["solid"] == pytest.approx(0.0036 * 7, rel=1e-12)
    assert f["preload"] == pytest.approx(k * (0.044 - 0.038), rel=1e-12)
    assert f["clash_margin"] == pytest.approx(0.038 - 0.009 - 0.0036 * 7, rel=1e-9)
    assert (d.spring_rate, d.preload) == (f["rate"], f["preload"])
    report = cam_design.analyse(design)
    surge = next(c for c in report.checks if c.name.startswith("spring surge"))
    assert surge.value == pytest.approx(f["surge"] / (3500 / 60), rel=1e-12)


def test_issue32_roller_bearing_life_of_the_packaging_cam(
    capsys: pytest.CaptureFixture[str],
) -> None:
    """The roller of a translating follower turns, per cam turn, the cam
    surface's perimeter over its circumference (it rolls along the
    surface; the follower does not turn); L₁₀ = (C/P)^(10/3) million
    revolutions with P the mean of F^(10/3) weighted by the revolutions."""
    path = ROOT / "examples" / "cam_design_packaging.toml"
    design = cam_design.load(path)
    d, c = design.dynamics, design.contact
    assert d is not None and c is not None and c.rating == 8000.0
    core = design.core()
    s = core.stress(
        (d.mass, d.spring_rate, d.preload, d.damping), d.speed, c.width, c.modulus, c.rating, 10 / 3
    )
    b = s["bearing"]
    th = np.linspace(0.0, 2 * math.pi, 400_001)
    pts = np.asarray(core.surface(th))
    perimeter = float(np.sum(np.hypot(*np.diff(pts, axis=0).T)))
    rr = design.dims[-1]
    assert b["roller_turns"] == pytest.approx(perimeter / (2 * math.pi * rr), rel=1e-6)
    assert b["l10_revolutions"] == pytest.approx(
        (8000.0 / b["equivalent_load"]) ** (10 / 3) * 1e6, rel=1e-12
    )
    f = np.asarray(s["force"])
    assert f.min() < b["equivalent_load"] < f.max()
    code, out = _json(capsys, ["cam", str(path), "--json", "--no-files"])
    life = next(x for x in out["checks"] if x["name"].startswith("roller bearing L10 life"))
    assert code == 0 and life["value"] == pytest.approx(b["l10_turns"] / 60 / 60, rel=1e-12)


@pytest.mark.parametrize(
    ("edit", "message"),
    [
        (
            ("installed_length = 0.038", "installed_length = 0.033"),
            "spring.installed_length: the spring goes solid",
        ),
        (
            ('cam_material = "cast-iron"', 'cam_material = "unobtanium"'),
            "contact.cam_material: 'unobtanium' is not in the materials table",
        ),
        (
            ("damping = 0.0\n", "damping = 0.0\nspring_rate = 1000\n"),
            "dynamics.spring_rate: [spring] gives the rate and preload",
        ),
        (("stiffness = [2.5e6]", "stiffness = [2.5e6, 1e6]"), "vibration.stiffness: gives 2 values"),
        (("free_length = 0.044", "free_length = 0.02"), "spring.free_length"),
    ],
)
def test_issue32_bad_sizing_input_exits_2_naming_the_field(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], edit: tuple[str, str], message: str
) -> None:
    text = VALVE.read_text()
    assert edit[0] in text
    p = tmp_path / "design.toml"
    p.write_text(text.replace(edit[0], edit[1], 1))
    code = cli.main(["cam", str(p), "--no-files"])
    err = capsys.readouterr().err
    assert code == 2 and message in err, err
    assert "Traceback" not in err


def test_issue32_vibration_residual_against_closed_form() -> None:
    """A one-mass undamped train (no return spring) behind a cycloidal rise
    of lift h over time T: the residual amplitude over the following dwell
    is h |sin πr|/(π r |r² − 1|), r = ω_n T/(2π) (derived in the Rust
    test); the sampled peak lies between A cos(ω_n h_t/2) and A."""
    from camlink._core import CamCore

    lift, beta = 0.01, math.pi / 3
    segs = [
        ("cycloidal", beta, lift, [None] * 3, [None] * 3),
        ("dwell", math.pi - beta, 0.0, [None] * 3, [None] * 3),
        ("cycloidal", beta, -lift, [None] * 3, [None] * 3),
        ("dwell", math.pi - beta, 0.0, [None] * 3, [None] * 3),
    ]
    core = CamCore(segs, "translating-flat", [], 0.05, True)
    m, k, omega, steps = 0.2, 4.0e5, 150.0, 36000
    r = core.vibration([m], [k], [0.0], 0.0, 0.0, omega, steps, 1)
    wn = math.sqrt(k / m)
    ratio = wn * (beta / omega) / (2 * math.pi)
    amp = lift * abs(math.sin(math.pi * ratio)) / (math.pi * ratio * abs(ratio**2 - 1))
    _, got, _ = next(x for x in r["residual"] if x[0] == 0)
    dwell = math.pi - beta
    h = dwell / (math.ceil(dwell / (2 * math.pi) * steps) * omega)
    assert amp * math.cos(wn * h / 2) - 1e-9 * lift <= got <= amp * (1 + 1e-9)


def test_issue32_units_mm_in_report_and_exports(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    _, si = _json(capsys, ["cam", str(VALVE), "--json", "--no-files"])
    code, mm = _json(
        capsys, ["cam", str(VALVE), "--json", "--units", "mm,deg", "--out", str(tmp_path)]
    )
    assert code == 0
    by = {c["name"]: c for c in si["checks"]}
    for c in mm["checks"]:
        if by[c["name"]]["unit"] == "m":
            assert c["unit"] == "mm"
            assert c["value"] == pytest.approx(by[c["name"]]["value"] * 1000, rel=1e-12)
        else:
            assert c == by[c["name"]]
    with (tmp_path / "cam_design_valve.csv").open() as f:
        rows = list(csv.reader(f))
    assert rows[0][:3] == ["theta_deg", "x_mm", "y_mm"]
    # θ = 0 on the base circle: the flat face touches at (0, R_b) = 18 mm.
    assert float(rows[1][2]) == pytest.approx(18.0, rel=1e-12)
    doc = ezdxf.readfile(tmp_path / "cam_design_valve.dxf")
    assert doc.header["$INSUNITS"] == 4
    assert cli.main(["cam", str(VALVE), "--units", "inch", "--no-files"]) == 2
    assert "--units inch" in capsys.readouterr().err


def test_issue32_svaj_in_time_units() -> None:
    """The SVAJ at the running speed: t = θ/ω over one turn, v = ω s′,
    a = ω² s″, j = ω³ s‴, in mm with units "mm"."""
    design = cam_design.load(VALVE)
    core = design.core()
    w = 3000 * 2 * math.pi / 60
    fig = cam_plots.svaj_time(core, w, units="mm")
    axes = fig.axes
    th = np.linspace(0.0, 2 * math.pi, 1441)
    m = np.asarray(core.motion(th))
    for k, ax in enumerate(axes):
        x, y = (np.asarray(a) for a in ax.lines[0].get_data())
        assert np.allclose(x, th / w, rtol=1e-15, atol=0)
        assert np.allclose(y, m[:, k] * w**k * 1000, rtol=1e-12, atol=0)
    assert axes[-1].get_xlim()[1] == pytest.approx(60 / 3000)
    assert axes[1].get_ylabel() == "v (mm/s)"


def test_issue32_bore_keyway_and_mark_on_dxf_and_svg(tmp_path: Path) -> None:
    text = VALVE.read_text().replace(
        "[export]\n",
        "[export]\nbore_diameter = 0.012\nkeyway_width = 0.004\nkeyway_depth = 0.0018\n"
        'units = "mm"\n',
    )
    p = tmp_path / "valve.toml"
    p.write_text(text)
    assert cli.main(["cam", str(p), "--out", str(tmp_path)]) == 0
    doc = ezdxf.readfile(tmp_path / "valve.dxf")
    msp = doc.modelspace()
    (bore,) = msp.query("CIRCLE[layer=='BORE']")
    assert bore.dxf.radius == pytest.approx(6.0, rel=1e-12)
    assert tuple(bore.dxf.center)[:2] == (0.0, 0.0)
    (key,) = msp.query("LWPOLYLINE[layer=='KEYWAY']")
    pts = np.array([pt[:2] for pt in key.get_points()])  # type: ignore[attr-defined]
    assert len(pts) == 4
    # Width between the sides, depth from the bore along the centreline,
    # the sides starting on the bore circle; under the timing mark (+y).
    assert np.hypot(*(pts[2] - pts[1])) == pytest.approx(4.0, rel=1e-12)
    mid = 0.5 * (pts[1] + pts[2])
    assert np.hypot(*mid) == pytest.approx(6.0 + 1.8, rel=1e-12)
    assert np.hypot(*pts[0]) == pytest.approx(6.0, rel=1e-12)
    assert np.hypot(*pts[3]) == pytest.approx(6.0, rel=1e-12)
    assert mid[0] == pytest.approx(0.0, abs=1e-12) and mid[1] > 0
    (mark,) = msp.query("LINE[layer=='MARK']")
    assert mark.dxf.start[0] == pytest.approx(0.0, abs=1e-12)
    assert mark.dxf.end[1] == pytest.approx(0.9 * 18.0, rel=1e-9)
    svg = (tmp_path / "valve.svg").read_text()
    assert '<circle id="bore" stroke="green" cx="0" cy="0" r="6.000000"/>' in svg
    assert 'id="keyway"' in svg and 'id="mark"' in svg
    # A bore reaching the profile is refused, naming the field.
    p.write_text(text.replace("bore_diameter = 0.012", "bore_diameter = 0.034"))
    assert cli.main(["cam", str(p), "--no-files"]) == 2


def test_issue32_timing_diagram_and_servo_tables(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    code, out = _json(capsys, ["cam", str(TIMING), "--json", "--out", str(tmp_path)])
    assert code == 0 and out["ok"]
    t = cam_timing.load(TIMING)
    by = {a.name: a for a in t.axes}
    # The least distance of the tips against a dense independent scan.
    th = np.linspace(0.0, 2 * math.pi, 720_001)
    sp = np.asarray(by["pusher"].design.core().motion(th))[:, 0]
    sg = np.asarray(by["gate"].design.core().motion((th - by["gate"].phase) % (2 * math.pi)))[:, 0]
    gap = 0.10 - sg - sp
    (c,) = out["clearances"]
    assert c["least"] == pytest.approx(gap.min(), abs=1e-9)
    assert c["at_deg"] == pytest.approx(math.degrees(th[np.argmin(gap)]), abs=0.01)
    # The gate's cam table: position, velocity, acceleration in mm and s
    # at 60 rpm against its program shifted by the phase.
    with (tmp_path / "cam_design_timing_gate.csv").open() as f:
        rows = list(csv.reader(f))
    assert rows[0] == [
        "master_deg",
        "position_mm",
        "velocity_mm_per_s",
        "acceleration_mm_per_s2",
        "jerk_mm_per_s3",
    ]
    data = np.array(rows[1:], dtype=float)
    assert len(data) == 721 and data[-1, 0] == 360.0
    w = 2 * math.pi
    m = np.asarray(by["gate"].design.core().motion(np.radians(data[:, 0] - 200.0) % (2 * math.pi)))
    assert np.allclose(data[:, 1], m[:, 0] * 1000, rtol=0, atol=1e-9)
    assert np.allclose(data[:, 2], m[:, 1] * w * 1000, rtol=0, atol=1e-9)
    assert np.allclose(data[:, 3], m[:, 2] * w * w * 1000, rtol=0, atol=1e-7)
    with (tmp_path / "cam_design_timing_gate_segments.csv").open() as f:
        segs = list(csv.DictReader(f))
    assert [s["law"] for s in segs] == ["dwell", "cycloidal", "dwell", "cycloidal"]
    # Cycloidal against dwells: s‴ jumps, C2 at every boundary.
    assert {s["continuity_start"] for s in segs} == {"C2"}
    # Cycloidal rise of 60 mm over 70° at 60 rpm: peak velocity 2h/β · ω.
    rise = segs[1]
    assert float(rise["peak_velocity"]) == pytest.approx(
        2 * 60 / math.radians(70) * w, rel=1e-6
    )
    assert float(rise["start_deg"]) == pytest.approx(350.0)


def test_issue32_timing_diagram_draws_each_axis_at_its_pixels() -> None:
    """The pusher's curve passes through its computed pixel: a point of
    s(Θ) in the first row, drawn in C0."""
    t = cam_timing.load(TIMING)
    fig = cam_timing.diagram(t)
    fig.canvas.draw()
    img = np.asarray(fig.canvas.buffer_rgba())
    ax = fig.axes[0]
    pusher = t.axes[0]
    for deg in (100.0, 180.0, 300.0):
        s = cam_timing.motion(pusher, np.array([math.radians(deg)]))[0, 0] * 1000
        x, y = ax.transData.transform((deg, s))
        row, col = round(img.shape[0] - y), round(x)
        patch = img[row - 2 : row + 3, col - 2 : col + 3, :3].reshape(-1, 3).astype(float)
        c0 = np.array(matplotlib.colors.to_rgb("C0")) * 255
        assert np.min(np.linalg.norm(patch - c0, axis=1)) < 40, (deg, patch)
    import matplotlib.pyplot as plt

    plt.close(fig)


def test_issue32_timing_clearance_fails_with_exit_1_and_bad_axis_exits_2(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    for name in ("cam_design_packaging.toml", "cam_design_timing_gate.toml"):
        (tmp_path / name).write_text((ROOT / "examples" / name).read_text())
    text = TIMING.read_text()
    p = tmp_path / "timing.toml"
    p.write_text(text.replace("min_distance = 0.015", "min_distance = 0.03"))
    assert cli.main(["cam", str(p), "--no-files"]) == 1
    assert "FAIL pusher–gate" in capsys.readouterr().out
    p.write_text(text.replace('between = ["pusher", "gate"]', 'between = ["pusher", "door"]'))
    assert cli.main(["cam", str(p), "--no-files"]) == 2
    assert "clearances[0].between: 'door' is not an axis" in capsys.readouterr().err


def test_issue32_vibration_picture_draws_the_train(tmp_path: Path) -> None:
    """The valve's vibration picture: the deviation and the dynamic contact
    force are the core's arrays over the last turn, the rigid train's
    force is Q = m ω² s″ + c ω s′ + F₀ + k s; the file is written."""
    design = cam_design.load(VALVE)
    core = design.core()
    d, v = design.dynamics, design.vibration
    assert d is not None and v is not None
    fig = cam_plots.vibration(core, design)
    r = core.vibration(
        list(v.masses), list(v.stiffness), list(v.damping), d.spring_rate, d.preload, d.speed,
        v.steps, v.turns, False,
    )
    x, y = (np.asarray(a) for a in fig.axes[0].lines[0].get_data())
    assert np.array_equal(x, np.degrees(r["theta"])) and np.array_equal(y, r["deviation"])
    y = np.asarray(fig.axes[1].lines[0].get_ydata())
    assert np.array_equal(y, r["contact"])
    x, y = (np.asarray(a) for a in fig.axes[1].lines[1].get_data())
    m = np.asarray(core.motion(np.radians(x)))
    w = d.speed
    q = d.mass * w * w * m[:, 2] + d.damping * w * m[:, 1] + d.preload + d.spring_rate * m[:, 0]
    assert np.allclose(y, q, rtol=1e-12, atol=1e-9)
    assert cli.main(["cam", str(VALVE), "--out", str(tmp_path)]) == 0
    assert (tmp_path / "cam_design_valve_vibration.png").stat().st_size > 0


def test_issue32_crowned_roller_reports_the_point_contact(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """`crown_radius` on the packaging cam's roller: the report's stress
    is the point contact's, above the straight roller's line contact; a
    crown on a flat face is bad input naming the field."""
    path = ROOT / "examples" / "cam_design_packaging.toml"
    text = path.read_text()
    p = tmp_path / "crowned.toml"
    p.write_text(text.replace('bearing_type = "roller"', 'bearing_type = "roller"\ncrown_radius = 0.2'))
    _, straight = _json(capsys, ["cam", str(path), "--json", "--no-files"])
    code, crowned = _json(capsys, ["cam", str(p), "--json", "--no-files"])
    assert code == 0
    name = "Hertz contact stress at 60 rpm"
    a = next(c for c in straight["checks"] if c["name"] == name)
    b = next(c for c in crowned["checks"] if c["name"] == name)
    assert b["value"] > a["value"] and "crowned roller" in b["note"]
    design = cam_design.load(p)
    d, c = design.dynamics, design.contact
    assert d is not None and c is not None and c.crown == 0.2
    s = design.core().stress(
        (d.mass, d.spring_rate, d.preload, d.damping), d.speed, c.width, c.modulus, None, 3.0, 0.2
    )
    assert b["value"] == pytest.approx(s["max_pressure"][0] / 1e6, rel=1e-12)
    v = VALVE.read_text()
    p.write_text(v.replace('follower_material = "steel"', 'follower_material = "steel"\ncrown_radius = 0.2'))
    assert cli.main(["cam", str(p), "--no-files"]) == 2
    assert "contact.crown_radius: a flat-faced follower has no roller" in capsys.readouterr().err


def test_issue32_timing_outputs_never_replace_inputs_or_existing_files(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # A timing file's outputs get `camlink cam`'s protection: never over the
    # timing file or a design file it reads, never over an existing file
    # without --force.
    for name in ("cam_design_timing.toml", "cam_design_packaging.toml", "cam_design_timing_gate.toml"):
        (tmp_path / name).write_text((ROOT / "examples" / name).read_text(encoding="utf-8"), encoding="utf-8")
    timing = tmp_path / "cam_design_timing.toml"
    text = timing.read_text(encoding="utf-8")
    bad = tmp_path / "bad_timing.toml"
    packaging_as_diagram = text.replace("[export]", '[export]\ndiagram = "cam_design_packaging.toml"')
    bad.write_text(packaging_as_diagram, encoding="utf-8")
    design = (tmp_path / "cam_design_packaging.toml").read_text(encoding="utf-8")
    assert cli.main(["cam", str(bad), "--out", str(tmp_path)]) == 2
    assert "is an input of the model" in capsys.readouterr().err
    assert (tmp_path / "cam_design_packaging.toml").read_text(encoding="utf-8") == design

    out = tmp_path / "out"
    assert cli.main(["cam", str(timing), "--out", str(out)]) == 0
    first = {p.name: p.read_bytes() for p in out.iterdir()}
    assert "cam_design_timing_timing.png" in first and len(first) == 5
    capsys.readouterr()
    assert cli.main(["cam", str(timing), "--out", str(out)]) == 2
    assert "pass --force" in capsys.readouterr().err
    assert {p.name: p.read_bytes() for p in out.iterdir()} == first
    assert cli.main(["cam", str(timing), "--out", str(out), "--force"]) == 0
    assert sorted(p.name for p in out.iterdir()) == sorted(first)
