//! Path generation: a four-bar whose coupler point P follows target points
//! T₁ … Tₙ (global frame, m).
//!
//! [`fit`] is the approximate synthesis: a least-squares fit of the
//! coupler curve to the target's shape,
//!
//!   min Σⱼ |P(φⱼ) − Tⱼ|²
//!
//! over the linkage (O₂, the ground link's angle θ_d and length d, the
//! crank a, coupler b, rocker c, and P = (p, q) in the coupler frame: origin
//! at the crank pin A, x towards the rocker pin B) and the crank angles φⱼ
//! at the points, which the timing option ties together:
//! - `Free`: each φⱼ is its own unknown (the shape alone is fitted);
//! - `Uniform`: φⱼ = φ₁ ± j·Δ, equal crank steps between the points (for a
//!   closed curve Δ = 2π/n: the points are equally spaced in time over a
//!   crank turn);
//! - `Prescribed(β)`: φⱼ = φ₁ + βⱼ, the crank's rotations from point 1 given.
//!
//! The search is global then local: each start is a linkage shape drawn
//! from a Halton sequence, placed on the target by the similarity
//! transformation (Procrustes) that best maps its coupler points onto the
//! target, then refined by Levenberg–Marquardt ([`crate::lm`]); starts run
//! in parallel (rayon) and the results are independent of the number of
//! threads. Where the linkage does not assemble at a point the residual
//! holds the excess of |κ| over 1 (see [`FourBar::position`]), so a fit
//! that ends assembled has that residual zero; with `ordered` a crank that
//! runs back between consecutive points is penalised in the same way.
//!
//! Every fitted candidate is then checked ([`Checks::of`]: branch, order,
//! dead positions, transmission angle, Grashof class) and ranked: those
//! without defects first, each group by its RMS distance to the targets.

use std::f64::consts::{PI, TAU};

use rayon::prelude::*;

use crate::fourbar::{
    add, angle, mod_tau, norm, rotate, sub, Checks, FourBar, Requirements, Turning, P2,
};
use crate::lm::{self, Residual};

/// A four-bar with a coupler point: P = A + A(θ_AB) `point`, θ_AB the
/// angle of B − A; assembled on branch `sigma`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CouplerLinkage {
    pub linkage: FourBar,
    /// P in the coupler frame (origin A, x towards B) (m).
    pub point: P2,
    /// The assembly branch σ (±1) of [`FourBar::position`].
    pub sigma: f64,
}

impl CouplerLinkage {
    /// (A, B, P) at crank angle `phi` (rad); `None` where it does not assemble.
    pub fn trace(&self, phi: f64) -> Option<(P2, P2, P2)> {
        let pos = self.linkage.position(phi, self.sigma)?;
        Some((pos.a, pos.b, coupler_point(pos.a, pos.b, self.point)))
    }
}

/// P = A + A(θ_AB) p.
pub fn coupler_point(a: P2, b: P2, p: P2) -> P2 {
    add(a, rotate(angle(sub(b, a)), p))
}

/// How the crank angles at the target points are tied together.
#[derive(Clone, Debug, PartialEq)]
pub enum Timing {
    Free,
    Uniform,
    /// β₁ … βₙ (rad): the crank's rotation from point 1 to each point (β₁ = 0).
    Prescribed(Vec<f64>),
}

impl Timing {
    pub fn name(&self) -> &'static str {
        match self {
            Timing::Free => "free",
            Timing::Uniform => "uniform",
            Timing::Prescribed(_) => "prescribed",
        }
    }
}

/// A path-fitting problem.
#[derive(Clone, Debug)]
pub struct FitSpec {
    /// T₁ … Tₙ (m).
    pub targets: Vec<P2>,
    pub timing: Timing,
    /// The targets are a closed curve traced in one crank turn; the crank
    /// must turn fully.
    pub closed: bool,
    /// The crank reaches the targets in the order given.
    pub ordered: bool,
    /// Number of starts of the global search.
    pub starts: usize,
    /// Most candidates returned.
    pub keep: usize,
    pub requirements: Requirements,
}

/// One fitted candidate.
#[derive(Clone, Debug)]
pub struct PathFit {
    pub mechanism: CouplerLinkage,
    /// The crank angle at each target, in the targets' order (rad).
    pub crank_angles: Vec<f64>,
    /// The target indices in the order the crank reaches them (0-based).
    pub visit: Vec<usize>,
    /// RMS and largest distance |P(φⱼ) − Tⱼ| (m).
    pub rms: f64,
    pub max: f64,
    /// The checks through the targets in `visit` order.
    pub checks: Checks,
}

/// Linkage parameters: O₂x, O₂y, θ_d, d, a, b, c, p, q.
const NL: usize = 9;
/// Weight of the assembly and order residuals (the targets are scaled to
/// an RMS radius of 1).
const PENALTY: f64 = 10.0;

/// The fitting problem in scaled coordinates for one start's branch and
/// sense.
struct Problem<'a> {
    targets: &'a [P2],
    timing: &'a Timing,
    closed: bool,
    ordered: bool,
    sigma: f64,
    /// +1: the crank turns counter-clockwise through the points.
    sense: f64,
}

/// P at crank angle φ for parameters `x` (soft: |κ| is clamped to 1) and
/// the excess |κ| − 1 where the linkage does not assemble.
fn soft_point(x: &[f64], phi: f64, sigma: f64) -> (P2, f64) {
    let o2 = [x[0], x[1]];
    let o4 = add(o2, [x[3] * x[2].cos(), x[3] * x[2].sin()]);
    let (a, b, c) = (x[4], x[5], x[6]);
    let pa = add(o2, [a * phi.cos(), a * phi.sin()]);
    let e = sub(o4, pa);
    let big_e = norm(e).max(1e-300);
    let kappa = (b * b - c * c - big_e * big_e) / (2.0 * c * big_e);
    let excess = (kappa.abs() - 1.0).max(0.0);
    let kappa = kappa.clamp(-1.0, 1.0);
    let psi = angle(e) + sigma * c.signum() * kappa.acos();
    let pb = add(o4, [c * psi.cos(), c * psi.sin()]);
    (coupler_point(pa, pb, [x[7], x[8]]), excess)
}

impl Problem<'_> {
    fn n(&self) -> usize {
        self.targets.len()
    }

    fn phis(&self, x: &[f64], out: &mut [f64]) {
        let t = &x[NL..];
        let n = self.n();
        match self.timing {
            Timing::Free => out.copy_from_slice(&t[..n]),
            Timing::Uniform => {
                let step = if self.closed {
                    self.sense * TAU / n as f64
                } else {
                    t[1]
                };
                for (j, o) in out.iter_mut().enumerate() {
                    *o = t[0] + step * j as f64;
                }
            }
            Timing::Prescribed(beta) => {
                for (o, b) in out.iter_mut().zip(beta) {
                    *o = t[0] + b;
                }
            }
        }
    }

    /// The number of parameters: the linkage's and the timing's.
    fn size(&self) -> usize {
        NL + match self.timing {
            Timing::Free => self.n(),
            Timing::Uniform if !self.closed => 2,
            _ => 1,
        }
    }

    /// Residual rows: 3 per point (P − T, assembly), then for free ordered
    /// timing n − 1 order rows and one closure row.
    fn order_rows(&self) -> bool {
        self.ordered && *self.timing == Timing::Free
    }
}

impl Residual for Problem<'_> {
    fn count(&self) -> usize {
        3 * self.n() + if self.order_rows() { self.n() } else { 0 }
    }

    fn eval(&self, x: &[f64], r: &mut [f64]) {
        let n = self.n();
        let mut phi = vec![0.0; n];
        self.phis(x, &mut phi);
        for j in 0..n {
            let (p, excess) = soft_point(x, phi[j], self.sigma);
            r[3 * j] = p[0] - self.targets[j][0];
            r[3 * j + 1] = p[1] - self.targets[j][1];
            r[3 * j + 2] = PENALTY * excess;
        }
        if self.order_rows() {
            let s = self.sense;
            for j in 1..n {
                r[3 * n + j - 1] = PENALTY * (-s * (phi[j] - phi[j - 1])).max(0.0);
            }
            let limit = if self.closed { TAU } else { 2.0 * TAU };
            r[4 * n - 1] = PENALTY * (s * (phi[n - 1] - phi[0]) - limit).max(0.0);
        }
    }

    fn jacobian(&self, x: &[f64], r: &[f64], jac: &mut [f64]) {
        let nx = x.len();
        if *self.timing != Timing::Free {
            lm::forward_columns(self, x, r, 0..nx, jac);
            return;
        }
        lm::forward_columns(self, x, r, 0..NL, jac);
        let n = self.n();
        let m = r.len();
        for i in 0..m {
            for k in NL..nx {
                jac[i * nx + k] = 0.0;
            }
        }
        // Row j's point rows depend on φⱼ alone: one evaluation with every
        // φⱼ stepped gives them all.
        let mut xp = x.to_vec();
        let h: Vec<f64> = (0..n).map(|j| 1e-7 * x[NL + j].abs().max(1.0)).collect();
        for j in 0..n {
            xp[NL + j] += h[j];
        }
        let mut phi = vec![0.0; n];
        self.phis(&xp, &mut phi);
        for j in 0..n {
            let (p, excess) = soft_point(x, phi[j], self.sigma);
            let rp = [
                p[0] - self.targets[j][0],
                p[1] - self.targets[j][1],
                PENALTY * excess,
            ];
            for k in 0..3 {
                jac[(3 * j + k) * nx + NL + j] = (rp[k] - r[3 * j + k]) / h[j];
            }
        }
        if self.order_rows() {
            let s = self.sense;
            self.phis(x, &mut phi);
            for j in 1..n {
                if -s * (phi[j] - phi[j - 1]) > 0.0 {
                    let row = (3 * n + j - 1) * nx;
                    jac[row + NL + j] = -PENALTY * s;
                    jac[row + NL + j - 1] = PENALTY * s;
                }
            }
            let limit = if self.closed { TAU } else { 2.0 * TAU };
            if s * (phi[n - 1] - phi[0]) - limit > 0.0 {
                let row = (4 * n - 1) * nx;
                jac[row + NL + n - 1] = PENALTY * s;
                jac[row + NL] = -PENALTY * s;
            }
        }
    }
}

/// The radical inverse of `i` in base `b`: the Halton sequence's coordinate.
fn halton(mut i: usize, b: usize) -> f64 {
    let (mut f, mut r) = (1.0, 0.0);
    while i > 0 {
        f /= b as f64;
        r += f * (i % b) as f64;
        i /= b;
    }
    r
}

const PRIMES: [usize; 8] = [2, 3, 5, 7, 11, 13, 17, 19];

/// Start `k`: a linkage shape from the Halton sequence, the crank angles
/// laid out along the target, then placed by Procrustes; `None` if the
/// shape's coupler points all coincide.
fn start(p: &Problem<'_>, k: usize) -> Option<Vec<f64>> {
    let h = |dim: usize| halton(k / 4 + 1, PRIMES[dim]);
    let n = p.n();
    // Shape in units of the crank: a = 1.
    let (d, b, c) = (1.2 + 3.0 * h(0), 1.2 + 3.0 * h(1), 1.2 + 3.0 * h(2));
    let (pp, pq) = (-1.0 + 5.0 * h(3), -3.0 + 6.0 * h(4));
    let phi0 = TAU * h(5);
    let span = if p.closed {
        TAU * (n as f64 - 1.0) / n as f64
    } else {
        PI / 3.0 + PI * h(6)
    };
    let mut x = vec![0.0, 0.0, 0.0, d, 1.0, b, c, pp, pq];
    let s = p.sense;
    let phis: Vec<f64> = match p.timing {
        Timing::Prescribed(beta) => beta.iter().map(|b| phi0 + b).collect(),
        _ => (0..n)
            .map(|j| phi0 + s * span * j as f64 / (n - 1).max(1) as f64)
            .collect(),
    };
    let z: Vec<P2> = phis.iter().map(|&f| soft_point(&x, f, p.sigma).0).collect();
    // Procrustes: T ≈ k z + t with k complex.
    let mean = |v: &[P2]| {
        let s = v.iter().fold([0.0, 0.0], |acc, q| add(acc, *q));
        [s[0] / v.len() as f64, s[1] / v.len() as f64]
    };
    let (zm, tm) = (mean(&z), mean(p.targets));
    let (mut num, mut den) = ([0.0, 0.0], 0.0);
    for (zj, tj) in z.iter().zip(p.targets) {
        let (u, v) = (sub(*zj, zm), sub(*tj, tm));
        // v · conj(u)
        num[0] += v[0] * u[0] + v[1] * u[1];
        num[1] += v[1] * u[0] - v[0] * u[1];
        den += u[0] * u[0] + u[1] * u[1];
    }
    if den <= 1e-12 {
        return None;
    }
    let kk = [num[0] / den, num[1] / den];
    let (scale, rot) = (norm(kk), angle(kk));
    if scale <= 1e-9 {
        return None;
    }
    let t = sub(tm, rotate(rot, [zm[0] * scale, zm[1] * scale]));
    x[0] = t[0];
    x[1] = t[1];
    x[2] = rot;
    for v in &mut x[3..NL] {
        *v *= scale;
    }
    match p.timing {
        Timing::Free => x.extend(phis.iter().map(|f| f + rot)),
        Timing::Uniform if !p.closed => {
            x.push(phis[0] + rot);
            x.push(s * span / (n - 1).max(1) as f64);
        }
        _ => x.push(phis[0] + rot),
    }
    Some(x)
}

/// The targets' centroid and RMS radius (m), and the targets scaled to them.
fn scaling(spec: &FitSpec) -> (P2, f64, Vec<P2>) {
    let n = spec.targets.len();
    let centre = spec.targets.iter().fold([0.0, 0.0], |a, t| add(a, *t));
    let centre = [centre[0] / n as f64, centre[1] / n as f64];
    let radius = (spec
        .targets
        .iter()
        .map(|t| {
            let d = sub(*t, centre);
            d[0] * d[0] + d[1] * d[1]
        })
        .sum::<f64>()
        / n as f64)
        .sqrt();
    let scaled: Vec<P2> = spec
        .targets
        .iter()
        .map(|t| {
            let d = sub(*t, centre);
            [d[0] / radius, d[1] / radius]
        })
        .collect();
    (centre, radius, scaled)
}

/// The problem of start `k`: its branch and crank sense.
fn problem_of<'a>(spec: &'a FitSpec, scaled: &'a [P2], k: usize) -> Problem<'a> {
    Problem {
        targets: scaled,
        timing: &spec.timing,
        closed: spec.closed,
        ordered: spec.ordered,
        sigma: if k.is_multiple_of(2) { 1.0 } else { -1.0 },
        sense: if (k / 2).is_multiple_of(2) { 1.0 } else { -1.0 },
    }
}

/// One start of the global search refined: its index and the refined
/// parameters (scaled; see [`fit_starts`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Start {
    pub k: usize,
    pub x: Vec<f64>,
}

/// Starts `range` (within 0 … `spec.starts`) refined in parallel (rayon):
/// those that end assembled at every target, with their candidates, in
/// the order of their index.
fn run_starts(spec: &FitSpec, range: std::ops::Range<usize>) -> Vec<(Start, PathFit)> {
    let n = spec.targets.len();
    let (centre, radius, scaled) = scaling(spec);
    // A start still at an RMS distance above half the target's RMS radius
    // after 20 iterations is abandoned.
    let settings = lm::Settings {
        max_iter: 150,
        rel_tol: 1e-10,
        abs_tol: 1e-26,
        give_up: Some((20, 0.25 * n as f64)),
    };
    let range = range.start.min(spec.starts)..range.end.min(spec.starts);
    range
        .into_par_iter()
        .map(|k| {
            let problem = problem_of(spec, &scaled, k);
            let x0 = start(&problem, k)?;
            let f = lm::minimise(&problem, &x0, &settings);
            let c = candidate(spec, &problem, &f.x, centre, radius)?;
            Some((Start { k, x: f.x }, c))
        })
        .collect::<Vec<_>>()
        .into_iter()
        .flatten()
        .collect()
}

/// Runs starts `range` (within 0 … `spec.starts`) of the global search in
/// parallel (rayon) and returns those that end assembled at every target,
/// in the order of their index. Start k depends on k and the spec alone,
/// so the starts can be split over processes or machines and their
/// results joined by [`fit_from`].
pub fn fit_starts(spec: &FitSpec, range: std::ops::Range<usize>) -> Vec<Start> {
    run_starts(spec, range)
        .into_iter()
        .map(|(s, _)| s)
        .collect()
}

/// Fits the spec's targets; returns up to `keep` candidates, best first,
/// and the number of starts that converged to an assembled linkage.
pub fn fit(spec: &FitSpec) -> (Vec<PathFit>, usize) {
    let (_, radius, _) = scaling(spec);
    let fits = run_starts(spec, 0..spec.starts)
        .into_iter()
        .map(|(_, c)| c)
        .collect();
    rank(spec, fits, radius)
}

/// The candidates of refined `starts` (of [`fit_starts`], joined in any
/// order; a start given twice counts once), checked and ranked as [`fit`]
/// ranks them: up to `keep`, best first, and the number of starts.
pub fn fit_from(spec: &FitSpec, starts: &[Start]) -> (Vec<PathFit>, usize) {
    let (centre, radius, scaled) = scaling(spec);
    let mut order: Vec<&Start> = starts.iter().filter(|s| s.k < spec.starts).collect();
    order.sort_by_key(|s| s.k);
    order.dedup_by_key(|s| s.k);
    let fits: Vec<PathFit> = order
        .par_iter()
        .map(|s| {
            let problem = problem_of(spec, &scaled, s.k);
            if s.x.len() != problem.size() {
                return None;
            }
            candidate(spec, &problem, &s.x, centre, radius)
        })
        .collect::<Vec<_>>()
        .into_iter()
        .flatten()
        .collect();
    rank(spec, fits, radius)
}

/// `fits` in the order of their starts, ranked: those without defects
/// first, each group by RMS distance; near-duplicates (link lengths equal
/// to 1e-6 of the targets' RMS `radius`) dropped; up to `keep`.
fn rank(spec: &FitSpec, fits: Vec<PathFit>, radius: f64) -> (Vec<PathFit>, usize) {
    let mut all = fits;
    let found = all.len();
    all.sort_by(|p, q| {
        (!p.checks.defects.is_empty(), p.rms)
            .partial_cmp(&(!q.checks.defects.is_empty(), q.rms))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    let mut kept: Vec<PathFit> = Vec::new();
    for c in all {
        if kept.len() >= spec.keep {
            break;
        }
        let same = kept.iter().any(|k| {
            let (mut u, mut v) = (k.mechanism.linkage.lengths(), c.mechanism.linkage.lengths());
            u.sort_by(f64::total_cmp);
            v.sort_by(f64::total_cmp);
            u.iter()
                .zip(&v)
                .all(|(a, b)| (a - b).abs() <= 1e-6 * radius)
        });
        if !same {
            kept.push(c);
        }
    }
    (kept, found)
}

/// The candidate of fitted scaled parameters `x`, in metres; `None` if it
/// does not assemble at every target.
fn candidate(
    spec: &FitSpec,
    problem: &Problem<'_>,
    x: &[f64],
    centre: P2,
    radius: f64,
) -> Option<PathFit> {
    let n = spec.targets.len();
    let mut phi = vec![0.0; n];
    problem.phis(x, &mut phi);
    if x.iter().any(|v| !v.is_finite()) || x[5].abs() < 1e-9 || x[6].abs() < 1e-9 {
        return None;
    }
    let o2 = add(centre, [x[0] * radius, x[1] * radius]);
    let linkage = FourBar {
        o2,
        o4: add(o2, [x[3] * radius * x[2].cos(), x[3] * radius * x[2].sin()]),
        crank: x[4] * radius,
        coupler: x[5].abs() * radius,
        rocker: x[6] * radius,
    };
    if linkage.crank.abs() < 1e-9 * radius || linkage.ground() < 1e-9 * radius {
        return None;
    }
    let mechanism = CouplerLinkage {
        linkage,
        point: [x[7] * radius, x[8] * radius],
        sigma: problem.sigma,
    };
    // The sense the crank turns: the start's with free timing (the order
    // rows hold it), else that of the fitted or prescribed steps.
    let s = match problem.timing {
        Timing::Free => problem.sense,
        _ if n > 1 && phi[1] < phi[0] => -1.0,
        _ => 1.0,
    };
    checked(spec, mechanism, &phi, s)
}

/// The candidate `mechanism` with its coupler point at the spec's targets
/// at crank angles `phi` (rad, in the targets' order), the crank turning
/// in sense `s` (+1 counter-clockwise): its distances to the targets and
/// its checks; `None` if it does not assemble at every target.
pub fn checked(spec: &FitSpec, mechanism: CouplerLinkage, phi: &[f64], s: f64) -> Option<PathFit> {
    let n = spec.targets.len();
    let linkage = mechanism.linkage;
    let mut pins = Vec::with_capacity(n);
    let (mut sum, mut max) = (0.0, 0.0f64);
    for (j, &f) in phi.iter().enumerate() {
        let (a, b, p) = mechanism.trace(f)?;
        let e = norm(sub(p, spec.targets[j]));
        sum += e * e;
        max = max.max(e);
        pins.push((a, b));
    }
    // The order the crank reaches the targets: as given, or by crank angle.
    let mut visit: Vec<usize> = (0..n).collect();
    if !spec.ordered {
        visit.sort_by(|&i, &j| {
            mod_tau(s * (phi[i] - phi[0])).total_cmp(&mod_tau(s * (phi[j] - phi[0])))
        });
    }
    let mut req = spec.requirements;
    req.full_turn |= spec.closed;
    if req.turning.is_none() {
        req.turning = Some(if s > 0.0 { Turning::Ccw } else { Turning::Cw });
    }
    let a_pins: Vec<P2> = visit.iter().map(|&j| pins[j].0).collect();
    let b_pins: Vec<P2> = visit.iter().map(|&j| pins[j].1).collect();
    let first = phi[visit[0]];
    let span = if spec.closed {
        Some((first, first + s * TAU))
    } else {
        None
    };
    let checks = Checks::of(&linkage, &a_pins, &b_pins, &req, span);
    // Crank angles in the targets' order, unwrapped as the checks found them.
    let mut crank_angles = vec![0.0; n];
    for (k, &j) in visit.iter().enumerate() {
        crank_angles[j] = checks.crank_angles[k];
    }
    Some(PathFit {
        mechanism,
        crank_angles,
        visit,
        rms: (sum / n as f64).sqrt(),
        max,
        checks,
    })
}
