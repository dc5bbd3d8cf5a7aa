"""The benchmark mechanisms in Exudyn (planar rigid bodies, 2D joints).

Each function builds its system, then times the solver call alone. Exudyn's node of a 2D rigid body sits at the centroid, so
joint points are given relative to it.
"""

from __future__ import annotations

import time
import warnings
from typing import Any

import numpy as np
import slider_crank as sc
import textbook_four_bar as tb

warnings.filterwarnings("ignore", category=DeprecationWarning)

import exudyn as exu
from exudyn.itemInterface import (
    CoordinateConstraint,
    LoadMassProportional,
    MarkerBodyMass,
    MarkerBodyPosition,
    MarkerNodeCoordinate,
    NodePointGround,
    NodeRigidBody2D,
    ObjectConnectorSpringDamper,
    ObjectGround,
    ObjectRigidBody2D,
    RevoluteJoint2D,
)

VERSION = exu.__version__


class _System:
    """An Exudyn system with a ground, rigid bodies and revolute joints."""

    def __init__(self) -> None:
        self.sc = exu.SystemContainer()
        self.mbs = self.sc.AddSystem()
        self.ground_node = self.mbs.AddNode(NodePointGround(referenceCoordinates=[0, 0, 0]))
        self.ground = self.mbs.AddObject(ObjectGround())
        self.nodes: list[int] = []
        self.objects: list[int] = []

    def body(
        self, q: Any, qd: Any = (0.0, 0.0, 0.0), mass: float = 1.0, inertia: float = 1.0
    ) -> int:
        """A body with its centroid at (x, y), angle φ; returns its index (1-based)."""
        n = self.mbs.AddNode(
            NodeRigidBody2D(
                referenceCoordinates=[float(v) for v in q],
                initialVelocities=[float(v) for v in qd],
            )
        )
        o = self.mbs.AddObject(
            ObjectRigidBody2D(nodeNumber=n, physicsMass=mass, physicsInertia=inertia)
        )
        self.nodes.append(n)
        self.objects.append(o)
        return len(self.objects)

    def point(self, k: int, s: Any) -> int:
        obj = self.ground if k == 0 else self.objects[k - 1]
        return self.mbs.AddMarker(
            MarkerBodyPosition(bodyNumber=obj, localPosition=[s[0], s[1], 0.0])
        )

    def revolute(self, i: int, si: Any, j: int, sj: Any) -> None:
        self.mbs.AddObject(RevoluteJoint2D(markerNumbers=[self.point(i, si), self.point(j, sj)]))

    def coordinate(self, k: int, c: int) -> int:
        node = self.ground_node if k == 0 else self.nodes[k - 1]
        return self.mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=node, coordinate=c))

    def fix_coordinate(self, k: int, c: int) -> None:
        """Body k's coordinate c stays at its reference value."""
        self.mbs.AddObject(
            CoordinateConstraint(markerNumbers=[self.coordinate(0, 0), self.coordinate(k, c)])
        )

    def gravity(self, k: int) -> None:
        m = self.mbs.AddMarker(MarkerBodyMass(bodyNumber=self.objects[k - 1]))
        self.mbs.AddLoad(LoadMassProportional(markerNumber=m, loadVector=[0.0, -sc.G, 0.0]))


def _quiet(ss: Any) -> None:
    ss.solutionSettings.writeSolutionToFile = False
    ss.solutionSettings.sensorsWritePeriod = 1e9
    ss.displayComputationTime = False
    ss.displayStatistics = False
    ss.parallel.numberOfThreads = 1


# ---------------------------------------------------------------------------
# Four-bar kinematics: the static solver steps through the crank angle.


def four_bar(times: np.ndarray) -> tuple[float, np.ndarray]:
    """Positions only. The crank-angle driver is a coordinate constraint
    whose offset follows t through a Python user function; the static
    solver takes one load step per output time (its 'time' runs over the
    load steps). Returns (seconds, final q of the three bodies' nodes)."""
    q0 = tb.run(times[:1])[0, :9]
    s = _System()
    for k in range(3):
        s.body(q0[3 * k : 3 * k + 3])
    for i, si, j, sj in tb.JOINTS:
        s.revolute(i, si, j, sj)
    # Node coordinates are displacements from the reference: φ₁ − θ(t₀).
    t0 = float(times[0])
    s.mbs.AddObject(
        CoordinateConstraint(
            markerNumbers=[s.coordinate(0, 0), s.coordinate(1, 2)],
            offsetUserFunction=lambda mbs, t, item, off: tb.W * (t - t0),
        )
    )
    s.mbs.Assemble()
    ss = exu.SimulationSettings()
    _quiet(ss)
    st = ss.staticSolver
    st.numberOfLoadSteps = len(times) - 1
    st.loadStepStart = t0
    st.loadStepDuration = float(times[-1] - times[0])
    st.adaptiveStep = False
    st.newton.relativeTolerance = 1e-10
    st.newton.absoluteTolerance = 1e-10
    st.verboseMode = 0
    start = time.perf_counter()
    exu.SolveStatic(s.mbs, ss, showHints=False)
    elapsed = time.perf_counter() - start
    q = np.concatenate(
        [s.mbs.GetNodeOutput(n, exu.OutputVariableType.Coordinates) for n in s.nodes]
    )
    return elapsed, q + q0


# ---------------------------------------------------------------------------
# Forward dynamics: generalized-α, index 3.


def _dynamic_settings(steps: int, t_end: float, sparse: bool) -> Any:
    ss = exu.SimulationSettings()
    _quiet(ss)
    ti = ss.timeIntegration
    ti.numberOfSteps = steps
    ti.endTime = t_end
    ti.verboseMode = 0
    ga = ti.generalizedAlpha
    ga.spectralRadius = 0.8
    ga.useIndex2Constraints = False
    ga.useNewmark = False
    # Exudyn's advice for speed: keep the Jacobian while Newton contracts.
    ti.newton.useModifiedNewton = True
    if sparse:
        ss.linearSolverType = exu.LinearSolverType.EigenSparse
    return ss


def slider_crank(steps: int = 1000, t_end: float = 1.0) -> tuple[float, float]:
    """(seconds in the solver, slider x at t_end)."""
    s = _System()
    init = sc.initial_state()
    for k, name in enumerate(("crank", "rod", "slider")):
        v = init[name]
        s.body(v[:3], v[3:], sc.MASS[k], sc.INERTIA[k])
        s.gravity(k + 1)
    a, b = sc.CRANK, sc.ROD
    cx, rx = sc.CRANK_CENTROID[0], sc.ROD_CENTROID[0]
    s.revolute(0, (0.0, 0.0), 1, (-cx, 0.0))
    s.revolute(1, (a - cx, 0.0), 2, (-b / 2 - rx, 0.0))
    s.revolute(2, (b / 2 - rx, 0.0), 3, (0.0, 0.0))
    # Translational joint along the x axis: the slider's y and φ stay 0.
    s.fix_coordinate(3, 1)
    s.fix_coordinate(3, 2)
    s.mbs.AddObject(
        ObjectConnectorSpringDamper(
            markerNumbers=[s.point(0, sc.SPRING_POINT), s.point(3, (0.0, 0.0))],
            stiffness=sc.SPRING_K,
            damping=0.0,
            referenceLength=sc.SPRING_L0,
        )
    )
    s.mbs.Assemble()
    ss = _dynamic_settings(steps, t_end, sparse=False)
    start = time.perf_counter()
    exu.SolveDynamic(s.mbs, ss, solverType=exu.DynamicSolverType.GeneralizedAlpha, showHints=False)
    elapsed = time.perf_counter() - start
    x = s.mbs.GetNodeOutput(s.nodes[2], exu.OutputVariableType.Position)[0]
    return elapsed, float(x)


def chain(n: int, steps: int, length: float = 0.1) -> float:
    """Seconds in the solver for `steps` steps of 1 ms of an n-link chain
    falling from the horizontal (1 kg links, sparse linear solver)."""
    s = _System()
    for k in range(n):
        s.body(((k + 0.5) * length, 0.0, 0.0), mass=1.0, inertia=length**2 / 12)
        s.gravity(k + 1)
        s.revolute(k, (0.0, 0.0) if k == 0 else (length / 2, 0.0), k + 1, (-length / 2, 0.0))
    s.mbs.Assemble()
    ss = _dynamic_settings(steps, steps * 1e-3, sparse=n > 20)
    start = time.perf_counter()
    exu.SolveDynamic(s.mbs, ss, solverType=exu.DynamicSolverType.GeneralizedAlpha, showHints=False)
    return time.perf_counter() - start
