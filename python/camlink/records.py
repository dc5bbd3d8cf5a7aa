"""What a model says about itself, as typed records: its bodies, joints,
forces and analysis settings, the check of its constraints and the design
findings of its curve contacts (``Model.bodies``, ``joints``, ``forces``,
``analysis``, ``check()``, ``design_check()``).

Records are TypedDicts: plain dicts at run time, typed for mypy and the
editor. Lengths in m, angles in rad, masses in kg, inertias in kg·m².
"""

from __future__ import annotations

from typing import TypedDict

__all__ = [
    "AnalysisSettings",
    "BodyRecord",
    "CheckReport",
    "ConstraintCount",
    "DesignFinding",
    "ForceRecord",
    "JointRecord",
    "LoadWarningRecord",
    "RedundantEquation",
]


class BodyRecord(TypedDict):
    """A moving body as placed in the model file."""

    name: str
    #: Body-frame origin (x, y) in the global frame (m).
    position: list[float]
    #: Body-frame angle φ (rad).
    angle: float
    mass: float
    #: Centroidal moment of inertia (kg·m²).
    inertia: float
    #: Centroid in the body frame (m).
    centroid: list[float]
    #: Named points in the body frame (m).
    points: dict[str, list[float]]


class JointRecord(TypedDict):
    """A joint or driver."""

    name: str
    #: The constraint kind, e.g. ``"revolute"``.
    kind: str
    #: Names of body i and body j (``"ground"`` for the ground).
    bodies: list[str]
    #: Number of scalar equations.
    equations: int
    #: The equations' names in order, e.g. ``["x", "y"]``; a driver's say
    #: what it drives (``"phi"`` an angle; ``"x"``, ``"y"``, ``"along"``,
    #: ``"distance"`` a length).
    equation_names: list[str]
    #: True for a driver (a function of time).
    driver: bool


class ForceRecord(TypedDict):
    """An applied force."""

    name: str
    #: The force kind, e.g. ``"tsda"`` or ``"callback"``.
    kind: str
    #: Names of body i and body j (``"ground"`` for a one-body force).
    bodies: list[str]
    #: A ``tsda``'s attachment points P_i on body i and P_j on body j
    #: (body frames, m); None for other kinds.
    s_i: list[float] | None
    s_j: list[float] | None
    #: A ``tsda``'s k (N/m) or an ``rsda``'s (N·m/rad); None for others.
    stiffness: float | None
    #: A ``tsda``'s c (N·s/m) or an ``rsda``'s (N·m·s/rad); None for others.
    damping: float | None


class ConstraintCount(TypedDict):
    """A constraint in `CheckReport`."""

    name: str
    kind: str
    equations: int
    driver: bool


class RedundantEquation(TypedDict):
    """An equation of Φ that depends on others at the placement."""

    #: ``"joint.equation"``, e.g. ``"O4.x"``.
    equation: str
    #: The equations it is a combination of, as (equation, coefficient).
    depends_on: list[tuple[str, float]]


class CheckReport(TypedDict):
    """Counts of the model and the diagnosis of Φ_q at t = 0."""

    bodies: int
    coordinates: int
    equations: int
    joints: list[ConstraintCount]
    #: Rank of Φ_q.
    rank: int
    #: Degrees of freedom: coordinates − rank.
    dof: int
    redundant: list[RedundantEquation]
    #: The drivers among the redundant equations and those they depend on
    #: (the model is over-driven when there is one).
    redundant_drivers: list[str]
    #: Each free motion as (coordinate name, component) pairs.
    free_motions: list[list[tuple[str, float]]]
    #: Largest |Φ| at the placement (m or rad).
    residual: float
    #: Condition number of Φ_q.
    condition: float
    #: Joints that stay open after assembly, with their |Φ| (m or rad).
    open_joints: list[tuple[str, float]]
    #: Unilateral contacts that remove no freedom at the start (open at the
    #: placement, or compliant), left out of rank and degrees of freedom.
    released: list[ReleasedContact]


class ReleasedContact(TypedDict):
    """A unilateral contact left out of the count of `CheckReport`."""

    joint: str
    #: Its gap at the placement (m); None for a compliant contact.
    gap: float | None
    #: One line, e.g. ``contact 'floor': open at t = 0 s (gap 0.1 m): its 2
    #: equations and 1 own coordinate are not counted``.
    text: str


class DesignFinding(TypedDict):
    """A design finding of a curve contact."""

    #: ``"warning"`` or ``"error"``.
    severity: str
    joint: str
    message: str
    #: One printable line.
    text: str


class LoadWarningRecord(TypedDict):
    """A warning about a model found while it was loaded (see
    `Model.warnings`)."""

    #: A stable name, e.g. ``"default_moved"`` (docs/model-files.md).
    kind: str
    #: The field of the model file, e.g. ``"joints[3].offset"``.
    field: str
    message: str
    #: One printable line: the field, then the message.
    text: str


class AnalysisSettings(TypedDict):
    """The model file's ``[analysis]`` settings (None where not given;
    `h` None when it follows the output step)."""

    #: One of `camlink.ANALYSES`.
    type: str
    t_end: float | None
    step: float | None
    times: list[float] | None
    time: float
    tol: float | None
    max_iter: int | None
    points: list[str]
    jerk: bool
    h: float | None
    rho_inf: float
    projection_tol: float
    adaptive: bool
    atol: float
    rtol: float
    h_min: float
