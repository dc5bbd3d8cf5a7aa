"""Pictures: drawings of a mechanism, plots of channels, SVAJ diagrams,
animations, the browser viewer, notebook displays and the gallery.

Layer: above the model API, whose `Model.draw`, `Results.plot` and friends
hand over to these modules. Each loads matplotlib, so the names below are
imported on first use. (`animate` is the module `camlink.viz.animate`,
whose function of that name `Results.animate` calls.)
"""

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from camlink.viz.drawing import Drawing, draw
    from camlink.viz.plots import plot, pressure_angle, reactions, svaj
    from camlink.viz.viewer import to_html

__all__ = ["Drawing", "draw", "plot", "pressure_angle", "reactions", "svaj", "to_html"]

_WHERE = {
    "Drawing": "camlink.viz.drawing",
    "draw": "camlink.viz.drawing",
    "plot": "camlink.viz.plots",
    "pressure_angle": "camlink.viz.plots",
    "reactions": "camlink.viz.plots",
    "svaj": "camlink.viz.plots",
    "to_html": "camlink.viz.viewer",
}


def __getattr__(name: str) -> object:
    if name in _WHERE:
        import importlib

        return getattr(importlib.import_module(_WHERE[name]), name)
    raise AttributeError(f"module 'camlink.viz' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
