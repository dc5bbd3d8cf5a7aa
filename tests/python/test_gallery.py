"""The gallery page is generated from the examples and up to date."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from PIL import Image

from camlink.viz.gallery import build

ROOT = Path(__file__).resolve().parents[2]


def test_gallery_is_generated_and_up_to_date(tmp_path: Path) -> None:
    page = build(tmp_path, dpi=40, quiet=True)
    text = page.read_text()
    assert text == (ROOT / "docs" / "gallery.md").read_text(), (
        "docs/gallery.md is out of date: run `uv run python -m camlink.viz.gallery docs`"
    )
    examples = sorted(
        p.stem
        for p in (ROOT / "examples").glob("*.toml")
        if not p.name.startswith(("cam_design_", "study_", "synthesis_"))
    )
    assert examples
    for stem in examples:
        assert f"## {stem}.toml" in text
        for name in (f"{stem}.png", f"{stem}_plot.png"):
            assert f"gallery/{name}" in text
            assert (ROOT / "docs" / "gallery" / name).is_file()
            # The picture is drawn: dark ink on a light page.
            image = np.asarray(Image.open(tmp_path / "gallery" / name).convert("L"))
            assert (image < 128).mean() > 0.001 and (image > 240).mean() > 0.5, name
