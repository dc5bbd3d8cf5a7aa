"""Issue 27, `camlink convert`: it never writes over its inputs, keeps an
existing default output unless --force, and writes through a temporary
file renamed over the output."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

import camlink
from camlink import cli
from camlink._core import ModelError
from camlink.io import output, simengine2d
from conftest import ROOT

EXAMPLE = ROOT / "examples" / "simengine2d" / "slider_crank.adm"


@pytest.fixture
def course(tmp_path: Path) -> Path:
    """The example .adm with its .acf, copied into `tmp_path`."""
    for suffix in (".adm", ".acf"):
        shutil.copy(EXAMPLE.with_suffix(suffix), tmp_path / f"m{suffix}")
    return tmp_path / "m.adm"


def test_issue27_convert_never_writes_over_its_acf(course: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """`convert --acf a.json -o a.json` used to replace its own input."""
    acf = course.with_name("a.json")
    shutil.copy(course.with_suffix(".acf"), acf)
    before = acf.read_bytes()
    code = cli.main(["convert", str(course), "--acf", str(acf), "-o", str(acf)])
    assert code == 2
    err = capsys.readouterr().err
    assert "input" in err and str(acf) in err
    assert acf.read_bytes() == before
    # The .acf read by default (beside the .adm), reached through a link.
    link = course.with_name("link.json")
    link.symlink_to(course.with_suffix(".acf"))
    before = course.with_suffix(".acf").read_bytes()
    assert cli.main(["convert", str(course), "-o", str(link)]) == 2
    assert course.with_suffix(".acf").read_bytes() == before
    # From Python too.
    with pytest.raises(ModelError, match="input"):
        simengine2d.convert(course, acf, acf=acf)
    assert not list(course.parent.glob("*partial*"))


def test_issue27_convert_keeps_an_existing_default_output(
    course: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """Without -o the output is MODEL's name with .toml in the current
    folder: an existing (edited) one stays unless --force."""
    monkeypatch.chdir(course.parent)
    edited = course.with_suffix(".toml")
    edited.write_text("# my edits\n")
    assert cli.main(["convert", str(course)]) == 2
    assert "--force" in capsys.readouterr().err
    assert edited.read_text() == "# my edits\n"
    assert cli.main(["convert", str(course), "--force", "-q"]) == 0
    assert camlink.load(edited).check()["dof"] == 0
    # A file named with -o is the user's choice: replaced.
    named = course.with_name("named.toml")
    named.write_text("# old\n")
    assert cli.main(["convert", str(course), "-o", str(named), "-q"]) == 0
    assert camlink.load(named).check()["dof"] == 0
    assert not list(course.parent.glob("*partial*"))


def test_issue27_convert_writes_through_a_temporary_file(
    course: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The converted text goes to a temporary file beside the output, which
    is renamed over it: a write that fails leaves the old file whole."""
    out = course.with_name("out.toml")
    out.write_text("# old\n")
    seen: list[Path] = []
    real = Path.write_text

    def failing(self: Path, *args: object, **kwargs: object) -> int:
        seen.append(self)
        real(self, "half")
        raise OSError(28, "No space left on device", str(self))

    monkeypatch.setattr(Path, "write_text", failing)
    with pytest.raises(OSError):
        simengine2d.convert(course, out)
    monkeypatch.undo()
    assert seen and seen[0] != out and seen[0].parent == out.parent
    assert out.read_text() == "# old\n"
    assert not seen[0].exists()
    simengine2d.convert(course, out)
    assert camlink.load(out).check()["dof"] == 0


def test_issue27_replacing_renames_whole_or_not_at_all(tmp_path: Path) -> None:
    """`output.replacing`, shared by every command that writes a file."""
    path = tmp_path / "x.txt"
    path.write_text("old")
    with pytest.raises(RuntimeError), output.replacing(path) as temp:
        temp.write_text("new, half")
        assert path.read_text() == "old"
        raise RuntimeError
    assert path.read_text() == "old"
    assert os.listdir(tmp_path) == ["x.txt"]
    with output.replacing(path) as temp:
        assert temp.suffix == ".txt" and temp.parent == tmp_path
        temp.write_text("new")
    assert path.read_text() == "new"
    assert os.listdir(tmp_path) == ["x.txt"]
    with pytest.raises(IsADirectoryError), output.replacing(tmp_path):
        pass
