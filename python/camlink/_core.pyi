"""Type stubs for the compiled binding `camlink._core`."""

from collections.abc import Callable, Sequence
from os import PathLike
from typing import Any

import numpy as np
import numpy.typing as npt

from camlink.results import Results

__version__: str

class ModelError(ValueError):
    """A model file, a builder call or an argument is not valid."""

class AnalysisError(RuntimeError):
    """An analysis could not proceed; carries the results computed so far."""

    time: float
    joints: list[str]
    residual: float
    names: list[str]
    data: npt.NDArray[np.float64] | None
    # Set by camlink.Model.run: the partial results and the file written.
    results: Results
    output: PathLike[str] | None

class Model:
    @staticmethod
    def load(path: str | PathLike[str]) -> Model: ...
    @staticmethod
    def from_str(text: str, format: str, source: str = "<string>") -> Model: ...
    @property
    def name(self) -> str: ...
    @property
    def bodies(self) -> list[dict[str, Any]]: ...
    @property
    def joints(self) -> list[dict[str, Any]]: ...
    @property
    def analysis(self) -> dict[str, Any]: ...
    def check(self) -> dict[str, Any]: ...
    def run_kinematics(
        self,
        times: npt.NDArray[np.float64],
        tol: float = 1e-10,
        max_iter: int = 25,
        points: Sequence[str] = ...,
        on_chunk: Callable[[list[str], npt.NDArray[np.float64]], object] | None = None,
        chunk_rows: int = 1024,
    ) -> tuple[list[str], npt.NDArray[np.float64], dict[str, Any]]: ...

def json_schema() -> str: ...
def time_grid(t_end: float, step: float) -> npt.NDArray[np.float64]: ...
