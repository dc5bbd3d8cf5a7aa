"""Four-bar crank-rocker kinematics as a textbook NumPy program.

Haug's Cartesian formulation (Computer-Aided Kinematics and Dynamics of
Mechanical Systems, ch. 3 and 6), written the way a course assignment
writes it: dense Φ, Φ_q, ν and γ rebuilt from scratch every Newton
iteration and every step, solved with ``np.linalg.solve``.

Bodies 1 crank, 2 coupler, 3 rocker; q = [x1, y1, φ1, x2, y2, φ2, x3, y3, φ3].
The geometry and the driver are those of ``examples/four_bar.toml``; Newton
stops when max |Φ| ≤ tol, as camlink's kinematic solver does.
"""

from __future__ import annotations

import numpy as np

# examples/four_bar.toml
D, A_LEN, B_LEN, C_LEN = 0.4, 0.12, 0.38, 0.3
W = 2 * np.pi
THETA0 = 0.3

# Revolute joints: (body i, s'_i, body j, s'_j); body 0 is ground.
JOINTS = [
    (0, (0.0, 0.0), 1, (0.0, 0.0)),
    (1, (A_LEN, 0.0), 2, (0.0, 0.0)),
    (2, (B_LEN, 0.0), 3, (C_LEN, 0.0)),
    (0, (D, 0.0), 3, (0.0, 0.0)),
]


def rot(phi: float) -> np.ndarray:
    """A(φ)."""
    c, s = np.cos(phi), np.sin(phi)
    return np.array([[c, -s], [s, c]])


def drot(phi: float) -> np.ndarray:
    """B(φ) = dA/dφ."""
    c, s = np.cos(phi), np.sin(phi)
    return np.array([[-s, -c], [c, -s]])


def body(q: np.ndarray, k: int) -> tuple[np.ndarray, float]:
    if k == 0:
        return np.zeros(2), 0.0
    return q[3 * k - 3 : 3 * k - 1], q[3 * k - 1]


def phi(q: np.ndarray, t: float) -> np.ndarray:
    """Φ(q, t): four revolutes (2 rows each), then the crank-angle driver."""
    out = np.zeros(9)
    for r, (i, si, j, sj) in enumerate(JOINTS):
        ri, pi_ = body(q, i)
        rj, pj = body(q, j)
        out[2 * r : 2 * r + 2] = ri + rot(pi_) @ si - rj - rot(pj) @ sj
    out[8] = q[2] - (THETA0 + W * t)
    return out


def phi_q(q: np.ndarray) -> np.ndarray:
    """Φ_q: [I, B_i s'_i] for body i, [−I, −B_j s'_j] for body j."""
    jac = np.zeros((9, 9))
    for r, (i, si, j, sj) in enumerate(JOINTS):
        for k, s, sign in ((i, si, 1.0), (j, sj, -1.0)):
            if k == 0:
                continue
            c = 3 * k - 3
            jac[2 * r : 2 * r + 2, c : c + 2] = sign * np.eye(2)
            jac[2 * r : 2 * r + 2, c + 2] = sign * drot(q[c + 2]) @ s
    jac[8, 2] = 1.0
    return jac


def nu(t: float) -> np.ndarray:
    """ν = −Φ_t: only the driver depends on time."""
    out = np.zeros(9)
    out[8] = W
    return out


def gamma(q: np.ndarray, qd: np.ndarray) -> np.ndarray:
    """γ = A_i s'_i φ̇_i² − A_j s'_j φ̇_j² per revolute; the driver's f'' = 0."""
    out = np.zeros(9)
    for r, (i, si, j, sj) in enumerate(JOINTS):
        g = np.zeros(2)
        if i:
            g += rot(q[3 * i - 1]) @ si * qd[3 * i - 1] ** 2
        if j:
            g -= rot(q[3 * j - 1]) @ sj * qd[3 * j - 1] ** 2
        out[2 * r : 2 * r + 2] = g
    return out


def initial_guess() -> np.ndarray:
    """The placement in examples/four_bar.toml (a few degrees off)."""
    return np.array([0.0, 0.0, THETA0, 0.11, 0.04, np.deg2rad(30.0), D, 0.0, np.deg2rad(80.0)])


def run(times: np.ndarray, tol: float = 1e-10, max_iter: int = 25) -> np.ndarray:
    """Rows (q, q̇, q̈) for each time: Newton–Raphson from a Taylor
    predictor, then Φ_q q̇ = ν and Φ_q q̈ = γ."""
    out = np.empty((len(times), 27))
    q = initial_guess()
    qd = np.zeros(9)
    qdd = np.zeros(9)
    t_prev = times[0]
    for k, t in enumerate(times):
        h = t - t_prev
        q = q + h * qd + 0.5 * h * h * qdd
        for _ in range(max_iter):
            res = phi(q, t)
            if np.max(np.abs(res)) <= tol:
                break
            q = q - np.linalg.solve(phi_q(q), res)
        else:
            raise RuntimeError(f"Newton did not converge at t = {t}")
        jac = phi_q(q)
        qd = np.linalg.solve(jac, nu(t))
        qdd = np.linalg.solve(jac, gamma(q, qd))
        out[k, :9], out[k, 9:18], out[k, 18:] = q, qd, qdd
        t_prev = t
    return out
