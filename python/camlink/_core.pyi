"""Type stubs for the compiled binding `camlink._core`."""

from collections.abc import Callable, Mapping, Sequence
from os import PathLike
from pathlib import Path
from typing import Any, TypeAlias, final

import numpy as np
import numpy.typing as npt

from camlink.records import (
    AnalysisSettings,
    BodyRecord,
    CheckReport,
    DesignFinding,
    ForceRecord,
    JointRecord,
    LoadWarningRecord,
)
from camlink.results import Results

__version__: str
#: Steps of the cam design report's round trip through the kinematics.
CAM_ROUND_TRIP_STEPS: int
#: The kinds an analysis error may have (`camlink_core::run::Kind`).
ERROR_KINDS: tuple[str, ...]
#: The kinds a run's warning may have.
WARNING_KINDS: tuple[str, ...]
#: The analyses a model file may ask for.
ANALYSES: tuple[str, ...]
#: The statuses a variant's row of study results can hold.
STUDY_STATUSES: tuple[str, ...]

__all__ = [
    "ANALYSES",
    "CAM_ROUND_TRIP_STEPS",
    "ERROR_KINDS",
    "STUDY_STATUSES",
    "WARNING_KINDS",
    "AnalysisError",
    "CamCore",
    "MachineCycle",
    "Model",
    "ModelError",
    "TimingCore",
    "__version__",
    "analysis_settings",
    "cam_angles_by_chord",
    "cam_angles_by_step",
    "cam_check_tolerance",
    "cam_design_limits",
    "cam_design_load",
    "cam_design_read",
    "cam_design_report",
    "cam_export_limits",
    "cam_fit_arcs",
    "cam_followers",
    "cam_is_design",
    "cam_is_timing",
    "cam_laws",
    "cam_materials",
    "cam_report_in_units",
    "cam_timing_read",
    "cam_tool_undercut",
    "check_output",
    "check_setting",
    "check_times",
    "contact_modulus",
    "convert_adm",
    "convert_model",
    "csv_rows",
    "default_step",
    "did_you_mean",
    "fourbar_class",
    "fourbar_marks",
    "fourbar_transmission",
    "helical_spring",
    "integration_step",
    "json_schema",
    "length_units",
    "line_contact",
    "machine_report",
    "model_error_of",
    "not_applicable",
    "output_kinds",
    "parse_units",
    "plain_file_name_problem",
    "quantity_unit",
    "run_batch",
    "setting_is_flag",
    "synth_file",
    "synth_path_starts",
    "synth_read",
    "synth_str",
    "synth_str_from_starts",
    "time_grid",
    "time_grid_rows",
    "toml_position",
]

_OnChunk: TypeAlias = Callable[[list[str], npt.NDArray[np.float64], list[str]], object]
_RunOutput: TypeAlias = tuple[list[str], npt.NDArray[np.float64], dict[str, Any], list[str]]

class ModelError(ValueError):
    """A model file, a builder call or an argument is not valid."""

class AnalysisError(RuntimeError):
    """An analysis could not proceed; carries the results computed so far."""

    kind: str
    time: float
    joints: list[str]
    residual: float
    names: list[str]
    quantities: list[str]
    data: npt.NDArray[np.float64] | None
    # Set by camlink.Model.run: the partial results and the file written.
    results: Results
    output: PathLike[str] | None

@final
class Model:
    @staticmethod
    def load(path: str | PathLike[str], allow_outside: bool = False) -> Model: ...
    @staticmethod
    def load_adm(path: str | PathLike[str], acf: str | PathLike[str] | None = None) -> Model: ...
    @staticmethod
    def from_str(
        text: str,
        format: str,
        source: str = "<string>",
        base_dir: str | PathLike[str] | None = None,
        allow_outside: bool = False,
    ) -> Model: ...
    @property
    def name(self) -> str: ...
    @property
    def data_files(self) -> list[Path]: ...
    @property
    def load_warnings(self) -> list[str]: ...
    @property
    def bodies(self) -> list[BodyRecord]: ...
    @property
    def ground_points(self) -> dict[str, list[float]]: ...
    def geometry(self, tol: float = 1e-4) -> list[dict[str, Any]]: ...
    def outlines(self, tol: float = 1e-4) -> dict[str, npt.NDArray[np.float64]]: ...
    @property
    def joints(self) -> list[JointRecord]: ...
    @property
    def analysis(self) -> AnalysisSettings: ...
    def check(self) -> CheckReport: ...
    @property
    def gravity(self) -> tuple[float, float]: ...
    @property
    def forces(self) -> list[ForceRecord]: ...
    def design_check(self) -> list[DesignFinding]: ...
    @property
    def warnings(self) -> list[LoadWarningRecord]: ...
    def with_callback_force(
        self,
        name: str,
        body: str,
        f: Callable[[float, tuple[float, float, float], tuple[float, float, float]], Sequence[float]],
    ) -> Model: ...
    def with_parameters(self, values: dict[str, float | str]) -> Model: ...
    @property
    def parameter_names(self) -> list[str]: ...
    def run_kinematics(
        self,
        times: npt.NDArray[np.float64],
        *,
        tol: float | None = None,
        max_iter: int | None = None,
        points: Sequence[str] = ...,
        on_chunk: _OnChunk | None = None,
        chunk_rows: int = ...,
        keep_rows: bool = True,
        jerk: bool = False,
        start: npt.NDArray[np.float64] | None = None,
    ) -> _RunOutput: ...
    @property
    def coordinates(self) -> list[str]: ...
    def run_inverse_dynamics(
        self,
        times: npt.NDArray[np.float64],
        *,
        tol: float | None = None,
        max_iter: int | None = None,
        points: Sequence[str] = ...,
        on_chunk: _OnChunk | None = None,
        chunk_rows: int = ...,
        keep_rows: bool = True,
    ) -> _RunOutput: ...
    def run_equilibrium(
        self,
        time: float = 0.0,
        *,
        tol: float | None = None,
        max_iter: int | None = None,
        points: Sequence[str] = ...,
        on_chunk: _OnChunk | None = None,
        chunk_rows: int = ...,
        keep_rows: bool = True,
    ) -> _RunOutput: ...
    def run_dynamics(
        self,
        times: npt.NDArray[np.float64],
        *,
        step: float | None = None,
        h: float | None = None,
        rho_inf: float | None = None,
        adaptive: bool | None = None,
        atol: float | None = None,
        rtol: float | None = None,
        h_min: float | None = None,
        projection_tol: float | None = None,
        tol: float | None = None,
        max_iter: int | None = None,
        points: Sequence[str] = ...,
        on_chunk: _OnChunk | None = None,
        chunk_rows: int = ...,
        keep_rows: bool = True,
    ) -> _RunOutput: ...

def json_schema() -> str: ...
def convert_adm(
    path: str | PathLike[str], format: str, acf: str | PathLike[str] | None = None
) -> str: ...
def convert_model(
    path: str | PathLike[str], form: str, allow_outside: bool = False
) -> tuple[str, list[str]]: ...
def model_error_of(
    text: str, format: str, base_dir: str | PathLike[str] | None = None
) -> dict[str, Any] | None: ...
def time_grid(t_end: float, step: float) -> npt.NDArray[np.float64]: ...
def time_grid_rows(t_end: float, step: float) -> float: ...
def cam_followers() -> list[tuple[str, list[str]]]: ...
def cam_laws() -> list[str]: ...
def cam_design_load(
    text: str, source: str, json: bool = False
) -> tuple[dict[str, Any], list[str]]: ...
def cam_design_read(path: str | PathLike[str]) -> tuple[dict[str, Any], list[str]]: ...
def cam_design_limits() -> dict[str, Any]: ...
def cam_is_design(json: str) -> bool: ...
def cam_timing_read(
    path: str | PathLike[str],
) -> tuple[TimingCore, dict[str, Any], list[str]]: ...
def cam_is_timing(path: str | PathLike[str]) -> bool: ...
def cam_angles_by_step(step: float) -> npt.NDArray[np.float64]: ...
def cam_check_tolerance(core: CamCore, tolerance: float, offset: float = 0.0) -> None: ...
def cam_angles_by_chord(
    core: CamCore, tolerance: float, offset: float = 0.0, check: bool = True
) -> npt.NDArray[np.float64]: ...
def cam_fit_arcs(
    points: npt.NDArray[np.float64], tolerance: float, slack: float = 0.0
) -> list[
    tuple[
        tuple[float, float], float, float, float, tuple[float, float], tuple[float, float]
    ]
]: ...
def cam_export_limits() -> dict[str, Any]: ...
def did_you_mean(name: str, candidates: Sequence[str]) -> str: ...
def plain_file_name_problem(name: str) -> str | None: ...
def cam_design_report(design: Any) -> dict[str, Any]: ...
def cam_report_in_units(report: Any, units: str) -> dict[str, Any]: ...
def cam_tool_undercut(
    core: CamCore, tool_radius: float, n: int | None = None
) -> list[tuple[float, float]]: ...
def quantity_unit(quantity: str, units: str = "m,rad") -> tuple[str, float]: ...
def parse_units(units: str) -> tuple[str, str]: ...
def length_units() -> list[tuple[str, float]]: ...

def csv_rows(rows: npt.NDArray[np.float64]) -> bytes: ...
def check_setting(key: str, value: float) -> None: ...
def setting_is_flag(key: str) -> bool: ...
def analysis_settings() -> dict[str, list[str]]: ...
def not_applicable(key: str, kind: str) -> str: ...
def integration_step(h: float | None = None, step: float | None = None) -> float: ...
def check_times(times: npt.NDArray[np.float64]) -> None: ...
def default_step(t_end: float) -> float: ...
def run_batch(
    model: Model,
    variants: Sequence[Mapping[str, float]],
    outputs: Sequence[tuple[str, str]],
    *,
    threads: int | None = None,
    time_limit: float | None = None,
) -> tuple[npt.NDArray[np.float64], list[str], list[str]]: ...
def toml_position(text: str, path: str) -> tuple[int, int] | None: ...
def output_kinds() -> dict[str, list[str]]: ...
def check_output(field: str, spec: dict[str, Any]) -> None: ...

# The machine report of a model file's [machine] table: camlink.machine.MachineReport.
def machine_report(path: str | PathLike[str]) -> dict[str, Any]: ...

@final
class MachineCycle:
    """A machine's cycle at its design speed and its full force balance
    (the Rust core's `machine::Cycle`), for a partial balance."""

    def __new__(cls, path: str | PathLike[str]) -> MachineCycle: ...
    @property
    def bodies(self) -> list[str]: ...
    @property
    def linkage(self) -> str: ...
    @property
    def unbalanced(self) -> tuple[float, float, float]: ...
    @property
    def balanced(self) -> tuple[float, float, float]: ...
    def evaluate(
        self, points: Sequence[Sequence[float]], weights: tuple[float, float, float]
    ) -> list[tuple[float, float, float, float]]: ...
    def counterweights(self, k: Sequence[float]) -> list[dict[str, Any]]: ...

# A synthesis solution: name, model file text (TOML), report (JSON text).
_SynthRow: TypeAlias = tuple[str, str, str]

def synth_file(path: str | PathLike[str]) -> tuple[str, list[_SynthRow]]: ...
def synth_str(text: str, source: str, stem: str) -> tuple[str, list[_SynthRow]]: ...
def synth_read(path: str | PathLike[str]) -> str: ...

# One refined start of a path search: its index and its parameters.
_StartRow: TypeAlias = tuple[int, list[float]]

def synth_path_starts(
    text: str, source: str, stem: str, lo: int, hi: int
) -> tuple[list[_StartRow], int]: ...
def synth_str_from_starts(
    text: str, source: str, stem: str, starts: list[_StartRow]
) -> tuple[str, list[_SynthRow]]: ...
def fourbar_class(ground: float, crank: float, coupler: float, rocker: float) -> str: ...
def fourbar_transmission(
    coupler: float, rocker: float, diagonal: npt.NDArray[np.float64]
) -> npt.NDArray[np.float64]: ...
def fourbar_marks(
    t: npt.NDArray[np.float64],
    motion: npt.NDArray[np.float64],
    solved: npt.NDArray[np.bool_],
    o2: tuple[float, float],
    o4: tuple[float, float],
    a_on_crank: tuple[float, float],
    b_on_rocker: tuple[float, float],
) -> list[tuple[float, str, float, float, float]]: ...

# One segment: law, span (rad), lift, start and end [s′, s″, s‴] (None where free).
_CamSegment: TypeAlias = tuple[str, float, float, Sequence[float | None], Sequence[float | None]]

# A follower train: mass (kg), spring rate (N/m), preload (N), damping (N·s/m).
_Train: TypeAlias = tuple[float, float, float, float]

@final
class CamCore:
    """A cam synthesised from a motion program (the Rust core's `cam::Cam`)."""

    def __new__(
        cls,
        segments: Sequence[_CamSegment],
        follower: str,
        dims: Sequence[float],
        base_radius: float,
        ccw: bool,
    ) -> CamCore: ...
    def motion(self, theta: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]: ...
    def starts(self) -> list[float]: ...
    def boundaries(self) -> list[tuple[float, int, int, int, tuple[float, float, float], str]]: ...
    def factors(
        self,
    ) -> list[tuple[int, str, tuple[float, float, float], tuple[float, float, float] | None]]: ...
    def surface(self, theta: npt.NDArray[np.float64], offset: float = 0.0) -> npt.NDArray[np.float64]: ...
    def pitch(self, theta: npt.NDArray[np.float64]) -> npt.NDArray[np.float64] | None: ...
    def contact(self, theta: npt.NDArray[np.float64]) -> dict[str, npt.NDArray[np.float64]]: ...
    def geometry(self) -> dict[str, Any]: ...
    def force(self, train: _Train, omega: float) -> dict[str, Any]: ...
    def smallest_base_radius(
        self, max_pressure: float | None, min_radius: float | None, lo: float, hi: float
    ) -> float | None: ...
    def stress(
        self,
        train: _Train,
        omega: float,
        width: float,
        modulus: float,
        rating: float | None = None,
        exponent: float = 3.0,
        crown: float | None = None,
    ) -> dict[str, Any]: ...
    def vibration(
        self,
        masses: Sequence[float],
        stiffness: Sequence[float],
        damping: Sequence[float],
        spring_rate: float,
        preload: float,
        omega: float,
        steps: int = 7200,
        turns: int = 3,
        polydyne: bool = False,
    ) -> dict[str, Any]: ...
    def round_trip(self, omega: float, steps: int) -> tuple[float, float, float]: ...

def cam_materials() -> list[tuple[str, float, float, float, float]]: ...
def contact_modulus(a: tuple[float, float], b: tuple[float, float]) -> float: ...
def line_contact(
    r1: float, r2: float, force: float, length: float, modulus: float
) -> tuple[float, float] | None: ...
def helical_spring(
    wire: float,
    mean_diameter: float,
    active_coils: float,
    total_coils: float,
    free_length: float,
    shear_modulus: float,
    density: float,
    installed: float,
    max_lift: float,
) -> dict[str, float]: ...

@final
class TimingCore:
    """A checked timing file (the Rust core's `camlink_cam::timing::Timing`);
    axes by their index in the file."""

    def motion(self, k: int, master: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]: ...
    def tips(self, k: int, s: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]: ...
    def clearances(self) -> list[tuple[int, int, float, float, float, bool]]: ...
    def table(self, k: int, units: str) -> npt.NDArray[np.float64]: ...
    def segments(self, k: int, units: str) -> list[dict[str, Any]]: ...
