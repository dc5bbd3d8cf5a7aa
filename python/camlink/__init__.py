"""camlink: planar multibody kinematics and dynamics.

Load a model file or build one in code, run an analysis, and get named
time series back::

    import camlink
    model = camlink.load("fourbar.toml")
    res = model.run(t_end=2.0, step=0.01)   # the file's [analysis] type
    res["crank.phi"], res.to_pandas()
    model.inverse_dynamics()["motor.effort"]
    model.simulate(t_end=1.0, h=1e-3)["energy.total"]
"""

from typing import TYPE_CHECKING

from camlink._core import AnalysisError, ModelError, __version__
from camlink.builder import Mechanism
from camlink.errors import ERROR_KINDS, WARNING_KINDS, RunWarning
from camlink.model import ANALYSES, Model, json_schema, load, loads
from camlink.results import Results
from camlink.warn import (
    CamlinkWarning,
    CourseFileWarning,
    DesignWarning,
    LiftOffWarning,
    LoadWarning,
    NearSingularWarning,
)

if TYPE_CHECKING:
    from camlink import study
    from camlink.study import monte_carlo, optimize, sweep

__all__ = [
    "ANALYSES",
    "ERROR_KINDS",
    "WARNING_KINDS",
    "AnalysisError",
    "CamlinkWarning",
    "CourseFileWarning",
    "DesignWarning",
    "LiftOffWarning",
    "LoadWarning",
    "Mechanism",
    "Model",
    "ModelError",
    "NearSingularWarning",
    "Results",
    "RunWarning",
    "__version__",
    "draw",
    "json_schema",
    "jump_plot",
    "jump_speed",
    "load",
    "loads",
    "monte_carlo",
    "optimize",
    "plot",
    "study",
    "svaj",
    "sweep",
]

#: Picture functions, imported on first use (they load matplotlib).
_PICTURES = {
    "draw": "camlink.drawing",
    "plot": "camlink.plots",
    "svaj": "camlink.plots",
    "jump_plot": "camlink.jump",
    "jump_speed": "camlink.jump",
}
#: Study functions, imported on first use (they load pandas and scipy).
_STUDIES = {"sweep": "camlink.study", "monte_carlo": "camlink.study", "optimize": "camlink.study"}


def __getattr__(name: str) -> object:
    if name in _PICTURES or name in _STUDIES:
        import importlib

        return getattr(importlib.import_module({**_PICTURES, **_STUDIES}[name]), name)
    if name == "study":
        import importlib

        return importlib.import_module("camlink.study")
    raise AttributeError(f"module 'camlink' has no attribute {name!r}")
