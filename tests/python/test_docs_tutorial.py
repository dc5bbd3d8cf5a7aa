"""docs/tutorial.md runs as written: its model files are written out, its
shell commands run through the CLI, and its Python block prints the output
the page shows."""

from __future__ import annotations

import re
import shlex
import subprocess
import sys
from pathlib import Path

from camlink.cli import main

ROOT = Path(__file__).resolve().parents[2]
PAGE = (ROOT / "docs" / "tutorial.md").read_text(encoding="utf-8")


def _blocks(info: str) -> list[str]:
    return re.findall(rf"```{re.escape(info)}\n(.*?)```", PAGE, re.S)


def test_tutorial_runs_as_written(tmp_path: Path, monkeypatch, capsys) -> None:
    monkeypatch.chdir(tmp_path)
    files = re.findall(r"```toml file=(\S+)\n(.*?)```", PAGE, re.S)
    assert [name for name, _ in files] == ["first_linkage.toml", "first_cam.toml"]
    for name, text in files:
        (tmp_path / name).write_text(text, encoding="utf-8")

    # Every command of the page, through the CLI's entry point.
    commands = [line for block in _blocks("sh") for line in block.splitlines() if line.strip()]
    assert len(commands) == 4
    for line in commands:
        words = shlex.split(line)
        assert words[:3] == ["uv", "run", "camlink"], line
        assert main(words[3:]) == 0, line
    # What the page says of the cam's report.
    assert "ok   pressure angle, rise: 17.8" in capsys.readouterr().out
    assert (tmp_path / "first_linkage.csv").stat().st_size > 0
    # The viewer page: its app element, its data and the front end inlined.
    page = (tmp_path / "first_linkage.html").read_text(encoding="utf-8")
    assert '<div id="app">' in page and '<script id="camlink-data"' in page and "uPlot" in page
    designed = sorted(p.suffix for p in (tmp_path / "first_cam").iterdir())
    for suffix in (".csv", ".dxf", ".png", ".svg"):
        assert suffix in designed, (suffix, designed)

    # The Python block prints what the page shows after it.
    (python,) = _blocks("python")
    (shown,) = _blocks("text")
    done = subprocess.run(
        [sys.executable, "-c", python], cwd=tmp_path, capture_output=True, text=True, check=True
    )
    assert done.stdout == shown
    assert (tmp_path / "first_linkage.png").stat().st_size > 0
