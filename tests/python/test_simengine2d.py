"""simEngine2D course models from Python and the command line: load with
their .acf, run, check, convert, and the errors users see."""

from __future__ import annotations

import json
import math
import shutil
import subprocess
import tomllib
from pathlib import Path

import numpy as np
import pytest

import camlink
from camlink.io import simengine2d
from camlink.results import Results
from conftest import ROOT
from conftest import run_cli as _run_cli

EXAMPLE = ROOT / "examples" / "simengine2d" / "slider_crank.adm"
FIXTURES = ROOT / "crates" / "camlink-adm" / "tests" / "adm"


def run_cli(*args: object, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    """`python -m camlink ARGS` with paths given as they are."""
    return _run_cli(*map(str, args), cwd=cwd)


def slider_x(t: np.ndarray, r: float = 0.2, rod: float = 0.5) -> np.ndarray:
    """The closed form of the example: θ = t², x = r cos θ + √(l² − r² sin² θ)."""
    th = t * t
    return np.asarray(r * np.cos(th) + np.sqrt(rod * rod - (r * np.sin(th)) ** 2))


def test_example_runs_with_the_acf_beside_it() -> None:
    model = camlink.load(EXAMPLE)
    assert model.analysis_type == "kinematics"
    assert model.check()["dof"] == 0
    res = model.run()
    assert len(res) == 201 and res.t[-1] == pytest.approx(2.0)
    np.testing.assert_allclose(res["slider.x"], slider_x(res.t), rtol=0, atol=1e-9)


def test_acf_given_explicitly_replaces_the_one_beside(tmp_path: Path) -> None:
    acf = tmp_path / "short.acf"
    acf.write_text(json.dumps({"simulation": "Kinematics", "tend": 0.5, "outputSteps": 5}))
    res = camlink.load(EXAMPLE, acf=acf).run()
    assert len(res) == 6
    np.testing.assert_allclose(res["slider.x"], slider_x(res.t), rtol=0, atol=1e-9)


def test_acf_with_a_toml_model_is_refused(tmp_path: Path) -> None:
    acf = tmp_path / "a.acf"
    acf.write_text("{}")
    with pytest.raises(camlink.ModelError, match=r"\.adm model only"):
        camlink.load(ROOT / "examples" / "four_bar.toml", acf=acf)


def test_convert_to_toml_and_json_gives_the_same_results(tmp_path: Path) -> None:
    ref = camlink.load(EXAMPLE).run()
    for suffix in (".toml", ".json"):
        out = simengine2d.convert(EXAMPLE, tmp_path / f"converted{suffix}")
        res = camlink.load(out).run()
        assert res.channels == ref.channels
        for c in ref.channels:
            np.testing.assert_allclose(res[c], ref[c], rtol=0, atol=1e-12)
    doc = tomllib.loads((tmp_path / "converted.toml").read_text())
    assert doc["ground"]["points"]["crank_pin"] == [0.0, 0.0]
    assert [d["name"] for d in doc["drivers"]] == ["motor"]
    assert doc["analysis"] == {"type": "kinematics", "t_end": 2.0, "step": 0.01}


def test_cli_run_check_convert(tmp_path: Path) -> None:
    out = tmp_path / "out.csv"
    proc = run_cli("run", EXAMPLE, "-o", out)
    assert proc.returncode == 0, proc.stderr
    res = Results.load(out)
    np.testing.assert_allclose(res["slider.x"], slider_x(res.t), rtol=0, atol=1e-9)

    proc = run_cli("check", EXAMPLE)
    assert proc.returncode == 0, proc.stderr
    assert "degrees of freedom  0" in proc.stdout and "motor" in proc.stdout

    toml_out = tmp_path / "sc.toml"
    proc = run_cli("convert", EXAMPLE, "-o", toml_out)
    assert proc.returncode == 0, proc.stderr
    proc = run_cli("run", toml_out, "-o", tmp_path / "again.csv")
    assert proc.returncode == 0, proc.stderr
    again = Results.load(tmp_path / "again.csv")
    for c in res.channels:
        np.testing.assert_allclose(again[c], res[c], rtol=0, atol=1e-12)


def test_cli_run_with_acf_option(tmp_path: Path) -> None:
    adm = tmp_path / "m.adm"
    shutil.copy(EXAMPLE, adm)  # no .acf beside it
    acf = tmp_path / "other.acf"
    acf.write_text(json.dumps({"simulation": "Kinematics", "tend": 1, "outputSteps": 4}))
    proc = run_cli("run", adm, "--acf", acf, "-o", tmp_path / "o.csv")
    assert proc.returncode == 0, proc.stderr
    assert len(Results.load(tmp_path / "o.csv")) == 5


def write_model(tmp_path: Path, forces: list[dict[str, object]]) -> Path:
    adm = tmp_path / "bad.adm"
    body = {"name": "b", "id": 1, "mass": 1, "jbar": 1, "q0": [0, 0, 0]}
    adm.write_text(json.dumps({"bodies": [body], "forces": forces}, indent=1))
    return adm


def test_point_force_file_exits_2_naming_force_and_file(tmp_path: Path) -> None:
    # `tire.m` is not a function name, and no tire.m is there to translate.
    force = {"name": "tire", "id": 8, "type": "PointForceFile", "body1": 1}
    adm = write_model(tmp_path, [{**force, "sP1": [0, 0], "frame": "GRF", "mfile": "tire.m"}])
    for command in ("run", "check", "convert"):
        proc = run_cli(command, adm, cwd=tmp_path)
        assert proc.returncode == 2, (command, proc.stderr)
        assert "Traceback" not in proc.stderr
        assert "bad.adm" in proc.stderr and "force 'tire' (id 8)" in proc.stderr
        assert "tire.m" in proc.stderr and "[[forces]]" in proc.stderr


def test_unknown_type_error_lists_supported_types(tmp_path: Path) -> None:
    adm = write_model(tmp_path, [{"name": "f", "id": 2, "type": "Magnet", "body1": 1}])
    with pytest.raises(camlink.ModelError) as e:
        camlink.load(adm)
    text = str(e.value)
    assert "forces[0].type" in text and "force 'f' (id 2)" in text
    assert all(t in text for t in ("PointForce", "Torque", "RSDA1", "RSDA2"))


def test_missing_acf_is_a_clear_error(tmp_path: Path) -> None:
    proc = run_cli("run", EXAMPLE, "--acf", tmp_path / "none.acf", cwd=tmp_path)
    assert proc.returncode == 2 and "none.acf" in proc.stderr
    assert "Traceback" not in proc.stderr


def test_dynamics_acf_runs_forward_dynamics() -> None:
    model = camlink.load(FIXTURES / "forces.adm")
    assert model.analysis_type == "dynamics"
    res = model.run()
    assert len(res) == 11
    # The disc under the torque 2.5 + t (N·m), J = 0.25 kg·m², from rest:
    # φ = (2.5 t²/2 + t³/6) / J.
    t = res.t
    np.testing.assert_allclose(
        res["disc.phi"], (2.5 * t**2 / 2 + t**3 / 6) / 0.25, rtol=0, atol=1e-6
    )
    assert math.isclose(res["disc.alpha"][0], 10.0, abs_tol=1e-9)


def test_equilibrium_acf_balances_an_rsda1_against_gravity(tmp_path: Path) -> None:
    """A rod (m = 2 kg, L = 1 m) pinned at one end to the ground, held by an
    RSDA1 (k = 50 N·m/rad, θ0 = 0.3): at equilibrium the spring torque
    −k(φ − θ0) balances gravity's −m g (L/2) cos φ about the pin."""
    adm = tmp_path / "rod.adm"
    adm.write_text(
        json.dumps(
            {
                "gravity": [0, -9.81],
                "bodies": [{"name": "rod", "id": 1, "mass": 2, "jbar": 2 / 12, "q0": [0.5, 0, 0]}],
                "constraints": [
                    {"name": "pin", "id": 1, "type": "RevoluteJoint", "sP1": [0, 0],
                     "body2": 1, "sP2": [-0.5, 0], "fun": "NONE"}
                ],
                "forces": [
                    {"name": "spring", "id": 1, "type": "RSDA1", "body1": 1,
                     "theta0": 0.3, "k": 50, "c": 0, "fun": "NONE"}
                ],
            }
        )
    )
    (tmp_path / "rod.acf").write_text(json.dumps({"simulation": "Equilibrium"}))
    model = camlink.load(adm)
    assert model.analysis_type == "equilibrium"
    phi = float(model.run()["rod.phi"][0])
    assert abs(-50 * (phi - 0.3) - 2 * 9.81 * 0.5 * math.cos(phi)) < 1e-8
    assert 0.0 < phi < 0.3


def test_cli_convert_default_output_and_a_bad_suffix(tmp_path: Path) -> None:
    proc = run_cli("convert", EXAMPLE, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    converted = tmp_path / "slider_crank.toml"
    assert converted.read_text().startswith("# camlink model converted from the simEngine2D files")
    assert camlink.load(converted).check()["dof"] == 0
    proc = run_cli("convert", EXAMPLE, "-o", tmp_path / "m.yaml")
    assert proc.returncode == 2
    assert "m.yaml" in proc.stderr and ".toml or .json" in proc.stderr
    assert "Traceback" not in proc.stderr


def test_issue27_course_file_parts_ignored_with_warnings(tmp_path: Path) -> None:
    """A course file with a rack and pinion's ``"fun": "0"``, a ``forces``
    list holding ``{}`` and a ``contacts`` list loads and runs, with one
    `CourseFileWarning` per part read past (file, line and field named);
    the command line prints them as warnings and exits 0."""
    course = FIXTURES / "course"
    with pytest.warns(camlink.CourseFileWarning) as caught:
        model = camlink.load(course / "slotted_lever.adm")
    texts = [str(w.message) for w in caught]
    assert len(texts) == 2, texts
    assert "slotted_lever.adm:20:3: forces[0]: an empty entry {} is ignored" in texts[0]
    assert "contacts: 2 contact entries are ignored" in texts[1]
    assert model.load_warnings == texts
    assert len(model.run()) == 151
    with pytest.warns(camlink.CourseFileWarning, match=r"RackPinion's fun"):
        camlink.load(course / "rack_pinion_fun.adm")
    out = run_cli("run", course / "rack_pinion_fun.adm", "-o", tmp_path / "rp.csv")
    assert out.returncode == 0, out.stderr
    assert "camlink: warning: " in out.stderr
    assert "constraints[3].fun: constraint 'mesh' (id 4): fun \"0\" is ignored" in out.stderr
    out = run_cli("check", course / "slotted_lever.adm")
    assert out.returncode == 0, out.stderr
    assert out.stderr.count("camlink: warning: ") == 2, out.stderr
    out = run_cli("convert", course / "slotted_lever.adm", "-o", tmp_path / "lever.toml")
    assert out.returncode == 0, out.stderr
    assert out.stderr.count("camlink: warning: ") == 2, out.stderr
    assert "Traceback" not in out.stderr and "CourseFileWarning" not in out.stderr
    bad = tmp_path / "bad.adm"
    bad.write_text(
        (course / "rack_pinion_fun.adm")
        .read_text()
        .replace('"R2": 0.15, "fun": "0"', '"R2": 0.15, "fun": "sin(t)"')
    )
    out = run_cli("run", bad)
    assert out.returncode == 2
    assert "a RackPinion takes no function of time" in out.stderr
    assert "Traceback" not in out.stderr
