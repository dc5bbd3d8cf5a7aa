"""`camlink convert --global / --frame`: a model file rewritten with its
bodies by global positions or by points in their frames, the same results,
written safely (issue 30)."""

from __future__ import annotations

import json
import shutil
import tomllib
from pathlib import Path

import numpy as np
import pytest

import camlink
from camlink import cli
from camlink.io import model_form
from conftest import ROOT

FOUR_BAR = ROOT / "examples" / "four_bar.toml"
WHITWORTH = ROOT / "examples" / "whitworth_global.toml"


@pytest.fixture
def model(tmp_path: Path) -> Path:
    """The four-bar example, copied into `tmp_path`."""
    path = tmp_path / "m.toml"
    shutil.copy(FOUR_BAR, path)
    return path


def _same_results(a: Path, b: Path) -> None:
    ra, rb = camlink.load(a).run(), camlink.load(b).run()
    assert ra.channels == rb.channels
    scale = np.maximum(np.abs(ra.data).max(axis=0), 1.0)
    assert np.all(np.abs(ra.data - rb.data).max(axis=0) <= 1e-9 * scale)


def test_global_and_back_give_the_same_results(model: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = model.with_name("g.toml")
    assert cli.main(["convert", "--global", str(model), "-o", str(out)]) == 0
    assert "global form: crank, coupler, rocker" in capsys.readouterr().out
    bodies = tomllib.loads(out.read_text())["bodies"]
    assert all("global_points" in b and "points" not in b for b in bodies)
    _same_results(model, out)
    back = model.with_name("f.toml")
    assert cli.main(["convert", "--frame", str(out), "-o", str(back), "-q"]) == 0
    assert capsys.readouterr().out == ""
    assert all("global_points" not in b for b in tomllib.loads(back.read_text())["bodies"])
    _same_results(model, back)


def test_default_output_and_json(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    src = tmp_path / "w.json"
    src.write_text(_as_json(WHITWORTH))
    assert cli.main(["convert", "--frame", str(src), "-q"]) == 0
    out = tmp_path / "w.frame.json"
    assert '"points"' in out.read_text()
    _same_results(src, out)


def _as_json(path: Path) -> str:
    """A TOML model file as JSON text."""
    return json.dumps(tomllib.loads(path.read_text()), indent=1)


def test_never_over_the_input_nor_an_existing_file(model: Path, capsys: pytest.CaptureFixture[str]) -> None:
    before = model.read_bytes()
    assert cli.main(["convert", "--global", str(model), "-o", str(model)]) == 2
    assert model.read_bytes() == before
    assert "exists" in capsys.readouterr().err
    # With --force, the input is still refused.
    assert cli.main(["convert", "--global", str(model), "-o", str(model), "--force"]) == 2
    assert "input" in capsys.readouterr().err
    assert model.read_bytes() == before
    other = model.with_name("other.toml")
    other.write_text("# mine\n")
    assert cli.main(["convert", "--global", str(model), "-o", str(other)]) == 2
    assert other.read_text() == "# mine\n"
    assert cli.main(["convert", "--global", str(model), "-o", str(other), "--force"]) == 0
    assert "global_points" in other.read_text()
    # No temporary file is left beside it.
    assert sorted(p.name for p in model.parent.iterdir()) == ["m.toml", "other.toml"]


def test_bad_input_is_named(model: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert cli.main(["convert", "--global", str(model), "-o", str(model.with_suffix(".json"))]) == 2
    assert "keeps the format" in capsys.readouterr().err
    model.write_text(model.read_text().replace('type = "revolute"', 'type = "revolut"', 1))
    assert cli.main(["convert", "--global", str(model), "-o", str(model.with_name("g.toml"))]) == 2
    err = capsys.readouterr().err
    assert "did you mean 'revolute'" in err and "Traceback" not in err
    assert not model.with_name("g.toml").exists()


def test_python_function_returns_the_bodies(model: Path) -> None:
    out = model.with_name("g.toml")
    assert model_form.convert_form(model, out, "global") == ["crank", "coupler", "rocker"]
