"""Progress of runs and Ctrl-C: the rows computed before it stay written."""

from __future__ import annotations

from pathlib import Path

import pytest

import camlink
from camlink.cli import main

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


def test_on_rows_counts_every_row() -> None:
    seen: list[int] = []
    res = camlink.load(EXAMPLES / "four_bar.toml").run(t_end=12.0, step=0.005, on_rows=seen.append)
    assert sum(seen) == len(res) == 2401
    assert seen[0] == 1024


def test_ctrl_c_keeps_the_rows_written(tmp_path: Path) -> None:
    def stop(n: int) -> None:
        raise KeyboardInterrupt

    out = tmp_path / "cut.csv"
    with pytest.raises(KeyboardInterrupt):
        camlink.load(EXAMPLES / "four_bar.toml").run(t_end=12.0, step=0.005, output=out, on_rows=stop)
    # The rows are kept under the output's partial name, never as the output.
    assert not out.exists()
    back = camlink.Results.load(tmp_path / "cut.partial.csv")
    assert len(back) == 1024 and back.t[-1] == pytest.approx(1023 * 0.005)


def test_cli_run_interrupted_exits_130(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                       capsys: pytest.CaptureFixture[str]) -> None:
    import camlink.progress

    def update(self: camlink.progress.Progress, n: int = 1) -> None:
        raise KeyboardInterrupt

    monkeypatch.setattr(camlink.progress.Progress, "update", update)
    out = tmp_path / "cut.csv"
    code = main(["run", str(EXAMPLES / "four_bar.toml"), "--t-end", "12", "-o", str(out)])
    assert code == 130
    partial = tmp_path / "cut.partial.csv"
    assert f"interrupted; the steps computed are in {partial}" in capsys.readouterr().err
    assert len(camlink.Results.load(partial)) == 1024
