"""Pin centres of examples/four_bar.toml, from the results' body coordinates
and the file's lengths: what the picture tests expect to see."""

from __future__ import annotations

import numpy as np

from camlink.results import Results

#: Crank O2–A and ground O2–O4 (m), as in examples/four_bar.toml.
CRANK, GROUND = 0.12, 0.4


def four_bar_pins(res: Results, k: int) -> dict[str, tuple[float, float]]:
    """Global centres (m) of the pins O2, A, B, O4 at output row k."""
    cx, cy, cphi = res["crank.x"][k], res["crank.y"][k], res["crank.phi"][k]
    return {
        "O2": (0.0, 0.0),
        "A": (cx + CRANK * np.cos(cphi), cy + CRANK * np.sin(cphi)),
        "B": (res["rocker.B.x"][k], res["rocker.B.y"][k]),
        "O4": (GROUND, 0.0),
    }
