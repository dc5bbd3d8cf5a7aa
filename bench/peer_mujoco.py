"""The benchmark mechanisms in MuJoCo (MJCF strings, default integrator).

MuJoCo works in joint coordinates and closes loops with soft equality
constraints; its default step is semi-implicit Euler. The plane of motion
is x–y with gravity along −y; contacts are off. ``mj_step(m, d, nstep)``
runs the steps in C, so no Python runs between steps.
"""

from __future__ import annotations

import math
import time

import mujoco
import slider_crank as sc

VERSION = mujoco.__version__

_OPTION = """
  <option timestep="0.001" gravity="0 {g} 0">
    <flag contact="disable"/>
  </option>
"""


def _inertial(pos: tuple[float, float], mass: float, izz: float) -> str:
    # Out-of-plane inertias only need to be positive: the motion is planar.
    return f'<inertial pos="{pos[0]} {pos[1]} 0" mass="{mass}" diaginertia="{izz} {izz} {izz}"/>'


def slider_crank_xml() -> str:
    a, b = sc.CRANK, sc.ROD
    rod_c = b / 2 + sc.ROD_CENTROID[0]
    px, py = sc.SPRING_POINT
    return f"""
<mujoco model="slider-crank">
  {_OPTION.format(g=-sc.G)}
  <worldbody>
    <site name="spring_ground" pos="{px} {py} 0"/>
    <body name="crank">
      <joint name="theta" type="hinge" axis="0 0 1"/>
      {_inertial(sc.CRANK_CENTROID, sc.MASS[0], sc.INERTIA[0])}
      <body name="rod" pos="{a} 0 0">
        <joint name="rod" type="hinge" axis="0 0 1"/>
        {_inertial((rod_c, 0.0), sc.MASS[1], sc.INERTIA[1])}
      </body>
    </body>
    <body name="slider" pos="{a + b} 0 0">
      <joint name="x" type="slide" axis="1 0 0"/>
      {_inertial((0.0, 0.0), sc.MASS[2], sc.INERTIA[2])}
      <site name="spring_slider"/>
    </body>
  </worldbody>
  <equality>
    <connect body1="rod" body2="slider" anchor="{b} 0 0"/>
  </equality>
  <tendon>
    <spatial stiffness="{sc.SPRING_K}" springlength="{sc.SPRING_L0}">
      <site site="spring_ground"/>
      <site site="spring_slider"/>
    </spatial>
  </tendon>
</mujoco>
"""


def slider_crank(steps: int = 1000) -> tuple[float, float]:
    """(seconds in mj_step, slider x after `steps` steps of 1 ms).

    At qpos = 0 the crank and rod lie along +x and the slider's frame sits
    at the pin C = (a + b, 0), where the loop closes; the state then starts
    at θ₀ with consistent velocities."""
    m = mujoco.MjModel.from_xml_string(slider_crank_xml())
    d = mujoco.MjData(m)
    init = sc.initial_state()
    psi, psid = init["rod"][2], init["rod"][5]
    x, xd = init["slider"][0], init["slider"][3]
    d.qpos[:] = [sc.TH0, psi - sc.TH0, x - (sc.CRANK + sc.ROD)]
    d.qvel[:] = [sc.W0, psid - sc.W0, xd]
    mujoco.mj_forward(m, d)
    start = time.perf_counter()
    mujoco.mj_step(m, d, nstep=steps)
    elapsed = time.perf_counter() - start
    return elapsed, float(d.qpos[2] + sc.CRANK + sc.ROD)


def chain_xml(n: int, length: float = 0.1) -> str:
    """An n-link chain along +x from the origin, 1 kg links, in maximal
    coordinates as camlink and Exudyn model it: each link a free planar
    body (slide x, slide y, hinge z), `connect` constraints at the pins."""
    inert = _inertial((0.0, 0.0), 1.0, length**2 / 12)
    bodies = "\n".join(
        f'<body name="l{k}" pos="{(k + 0.5) * length} 0 0">'
        f'<joint type="slide" axis="1 0 0"/><joint type="slide" axis="0 1 0"/>'
        f'<joint type="hinge" axis="0 0 1"/>{inert}</body>'
        for k in range(n)
    )
    eqs = [f'<connect body1="l0" anchor="{-length / 2} 0 0"/>'] + [
        f'<connect body1="l{k - 1}" body2="l{k}" anchor="{length / 2} 0 0"/>' for k in range(1, n)
    ]
    return f"""
<mujoco model="chain">
  {_OPTION.format(g=-9.81)}
  <size memory="{max(64, 4 * n)}M"/>
  <worldbody>{bodies}</worldbody>
  <equality>{"".join(eqs)}</equality>
</mujoco>
"""


def chain_tree(n: int, length: float = 0.1) -> mujoco.MjModel:
    """The same chain as a tree of hinges (MuJoCo's own joint coordinates,
    no loop constraints), built with MjSpec: MJCF caps element nesting."""
    spec = mujoco.MjSpec()
    spec.option.timestep = 1e-3
    spec.option.gravity = [0.0, -9.81, 0.0]
    body = spec.worldbody
    izz = length**2 / 12
    for k in range(n):
        body = body.add_body(
            pos=[length if k else 0.0, 0.0, 0.0],
            mass=1.0,
            ipos=[length / 2, 0.0, 0.0],
            inertia=[izz, izz, izz],
        )
        body.add_joint(type=mujoco.mjtJoint.mjJNT_HINGE, axis=[0.0, 0.0, 1.0])
    return spec.compile()


def chain(n: int, steps: int, maximal: bool = True) -> float:
    """Seconds in mj_step for `steps` steps of 1 ms."""
    if maximal:
        m = mujoco.MjModel.from_xml_string(chain_xml(n))
    else:
        m = chain_tree(n)
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    start = time.perf_counter()
    mujoco.mj_step(m, d, nstep=steps)
    elapsed = time.perf_counter() - start
    if not math.isfinite(float(d.qpos.sum())):
        raise RuntimeError(f"MuJoCo chain of {n} diverged")
    return elapsed
