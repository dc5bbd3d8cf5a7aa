"""camlink: planar multibody kinematics and dynamics.

Load a model file or build one in code, run an analysis, and get named
time series back::

    import camlink
    model = camlink.load("fourbar.toml")
    res = model.run(t_end=2.0, step=0.01)   # the file's [analysis] type
    res["crank.phi"], res.to_pandas()
    model.inverse_dynamics()["motor.effort"]
    model.simulate(t_end=1.0, h=1e-3)["energy.total"]

The package is in layers, each importing only from those below it
(tests/python/test_layers.py checks it): the base modules (`errors`, `warn`,
`signals`, `progress`, `settings`, `records`, `units`); files (`camlink.io`);
the model API and results (`model`, `results`, `builder`); pictures
(`camlink.viz`); cam design (`camlink.cam`); machine sizing
(`camlink.machine`); linkage synthesis
(`camlink.synth`); studies (`camlink.study`); this namespace, which
re-exports their public names; the studio (`camlink.studio`); the command
line (`camlink.cli`).
"""

import importlib
import importlib.abc
import importlib.machinery
import importlib.util
import sys
import warnings
from types import ModuleType
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
    LimitWarning,
    LoadWarning,
    NearSingularWarning,
)

if TYPE_CHECKING:
    from camlink import cam as cam
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
    "LimitWarning",
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
    "draw": "camlink.viz.drawing",
    "plot": "camlink.viz.plots",
    "svaj": "camlink.viz.plots",
    "jump_plot": "camlink.cam.jump",
    "jump_speed": "camlink.cam.jump",
}
#: Study functions, imported on first use (they load pandas and scipy).
_STUDIES = {"sweep": "camlink.study", "monte_carlo": "camlink.study", "optimize": "camlink.study"}


#: Subpackages, imported on first use.
_SUBPACKAGES = ("cam", "cli", "io", "study", "synth", "viz")


def __getattr__(name: str) -> object:
    if name in _PICTURES or name in _STUDIES:
        return getattr(importlib.import_module({**_PICTURES, **_STUDIES}[name]), name)
    if name in _SUBPACKAGES:
        return importlib.import_module(f"camlink.{name}")
    raise AttributeError(f"module 'camlink' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(__all__) | set(_SUBPACKAGES))


#: Modules that moved into subpackages, by their old names. Importing an old
#: name still works for one release and warns (DeprecationWarning).
MOVED_MODULES = {
    "camlink.animate": "camlink.viz.animate",
    "camlink.cam_cli": "camlink.cli.cam",
    "camlink.cam_design": "camlink.cam.design",
    "camlink.cam_export": "camlink.cam.export",
    "camlink.cam_plots": "camlink.cam.plots",
    "camlink.cli_convert": "camlink.cli.convert",
    "camlink.cli_study": "camlink.cli.study",
    "camlink.cli_synth": "camlink.cli.synth",
    "camlink.cli_visuals": "camlink.cli.visuals",
    "camlink.drawing": "camlink.viz.drawing",
    "camlink.gallery": "camlink.viz.gallery",
    "camlink.jump": "camlink.cam.jump",
    "camlink.notebook": "camlink.viz.notebook",
    "camlink.output": "camlink.io.output",
    "camlink.plots": "camlink.viz.plots",
    "camlink.results_file": "camlink.io.results_file",
    "camlink.scene": "camlink.viz.scene",
    "camlink.simengine2d": "camlink.io.simengine2d",
    "camlink.viewer": "camlink.viz.viewer",
}


class _MovedModule(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finds a moved module by its old name and hands back the module itself."""

    def find_spec(
        self, fullname: str, path: object = None, target: ModuleType | None = None
    ) -> importlib.machinery.ModuleSpec | None:
        if fullname not in MOVED_MODULES:
            return None
        return importlib.util.spec_from_loader(fullname, self)

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> ModuleType:
        new = MOVED_MODULES[spec.name]
        warnings.warn(
            f"{spec.name} is now {new}; the old name goes in the next release",
            DeprecationWarning,
            stacklevel=2,
        )
        return importlib.import_module(new)

    def exec_module(self, module: ModuleType) -> None:
        pass


if not any(isinstance(f, _MovedModule) for f in sys.meta_path):
    sys.meta_path.insert(0, _MovedModule())
