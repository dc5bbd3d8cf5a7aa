"""Cam design: a motion program and its limits (`camlink cam DESIGN.toml`),
the profile's exports (CSV, DXF, SVG), its pictures, and the jump-speed
check of a spring-loaded follower.

Layer: above the model API and the pictures (`camlink.viz`).
"""

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from camlink.cam.design import CamDesignError, Design, Report, analyse, load
    from camlink.cam.jump import jump_plot, jump_speed

__all__ = ["CamDesignError", "Design", "Report", "analyse", "jump_plot", "jump_speed", "load"]

_WHERE = {
    "CamDesignError": "camlink.cam.design",
    "Design": "camlink.cam.design",
    "Report": "camlink.cam.design",
    "analyse": "camlink.cam.design",
    "load": "camlink.cam.design",
    "jump_plot": "camlink.cam.jump",
    "jump_speed": "camlink.cam.jump",
}


def __getattr__(name: str) -> object:
    if name in _WHERE:
        import importlib

        return getattr(importlib.import_module(_WHERE[name]), name)
    raise AttributeError(f"module 'camlink.cam' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
