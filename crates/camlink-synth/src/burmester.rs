//! Four- and five-pose motion generation by Burmester theory.
//!
//! The coupler carries a line with prescribed poses (x_j, y_j, θ_j),
//! j = 1…n (m, rad; see [`crate::motion`]). A dyad is a ground pivot O (the
//! *centre point*) and a moving pivot A fixed in the coupler (the *circle
//! point*, here given by its position A₁ at pose 1 and by a′ in the
//! coupler frame) that stays at one distance from O at every pose.
//!
//! Standard (complex-number) dyad form (Sandor & Erdman, *Advanced
//! Mechanism Design* vol. 2, ch. 2): with P_j = x_j + i y_j, δ_j = P_j − P₁,
//! α_j = θ_j − θ₁, the link vector W = A₁ − O and the coupler vector
//! Z = P₁ − A₁,
//!
//!   W (e^{iβ_j} − 1) + Z (e^{iα_j} − 1) = δ_j,   j = 2…n,
//!
//! β_j the link's rotation from pose 1 to pose j (rad).
//!
//! Four poses: three complex equations linear in (W, Z) have a solution
//! when the determinant of [e^{iβ_j} − 1, e^{iα_j} − 1, δ_j] vanishes:
//!
//!   Δ₂ e^{iβ₂} + Δ₃ e^{iβ₃} + Δ₄ e^{iβ₄} = Δ₂ + Δ₃ + Δ₄,
//!   Δ₂ = a₃δ₄ − a₄δ₃,  Δ₃ = a₄δ₂ − a₂δ₄,  Δ₄ = a₂δ₃ − a₃δ₂,  a_j = e^{iα_j} − 1,
//!
//! the compatibility linkage: for each β₂ (the free parameter) the vectors
//! Δ₃ e^{iβ₃}, Δ₄ e^{iβ₄} of fixed lengths close the loop on
//! R = Δ₂ + Δ₃ + Δ₄ − Δ₂ e^{iβ₂} in two ways (branch s = ±1) or none.
//! (W, Z) then follow from two of the equations; O = P₁ − Z − W and
//! A₁ = P₁ − Z trace the centre-point and the circle-point curves as β₂
//! goes round.
//!
//! Five poses: the dyads of poses 1–4 that also satisfy the equation of
//! pose 5, |δ₅ − Z a₅ + W| = |W| (then e^{iβ₅} = (δ₅ − Z a₅ + W)/W). The
//! Burmester points are the real roots of
//!
//!   g(β₂) = (|δ₅ − Z a₅ + W|² − |W|²) / (|W|² + |Z|² + L²)
//!
//! (L a length of the problem) on both branches, found by a dense scan of
//! β₂ for sign changes (the branch ends, where the compatibility loop
//! stretches straight, are located by bisection and included), each
//! refined by bisection to the last bit and kept only when its dyad
//! satisfies all five circle conditions to 1e-9 relative. A root where
//! (W, Z) go to infinity (a sign change through a pole of g) fails that
//! test and is dropped. Two roots within one step are bracketed by a
//! golden-section search for the extreme of g between the neighbours of a
//! local minimum of |g|; a sample where (W, Z) are not determined is
//! replaced by two a hair to either side.

use std::f64::consts::{PI, TAU};

use crate::complex::C;
use crate::error::{ErrorKind, SynthError};
use crate::fourbar::{norm, sub, wrap_pi, Checks, FourBar, Requirements, P2};
use crate::motion::Pose;

/// A dyad of the poses: its centre point, circle point and the link's
/// rotations.
#[derive(Clone, Debug, PartialEq)]
pub struct Dyad {
    /// The ground pivot O (global, m).
    pub centre: P2,
    /// The moving pivot at pose 1, A₁ (global, m).
    pub circle: P2,
    /// The moving pivot in the coupler frame, a′ (m).
    pub moving: P2,
    /// The link's rotation β_j from pose 1 to pose j, j = 2…n (rad, in (−π, π]).
    pub beta: Vec<f64>,
    /// The free parameter β₂ (rad) and the branch s = ±1 of the
    /// compatibility loop the dyad lies on.
    pub beta2: f64,
    pub branch: f64,
}

impl Dyad {
    /// |A_j − O| at every pose, less |A₁ − O|, largest in absolute value
    /// (m): 0 for a dyad that guides the coupler through the poses.
    pub fn circle_residual(&self, poses: &[Pose]) -> f64 {
        let r = norm(sub(self.circle, self.centre));
        poses
            .iter()
            .map(|p| (norm(sub(p.place(self.moving), self.centre)) - r).abs())
            .fold(0.0, f64::max)
    }

    /// The link length |A₁ − O| (m).
    pub fn length(&self) -> f64 {
        norm(sub(self.circle, self.centre))
    }
}

/// The data of the dyad equations of four or five poses.
#[derive(Clone, Debug)]
pub struct Equations {
    poses: Vec<Pose>,
    /// δ_j and a_j = e^{iα_j} − 1 for j = 2…n (index j − 2).
    delta: Vec<C>,
    a: Vec<C>,
    /// Δ₂, Δ₃, Δ₄ and their sum.
    big: [C; 3],
    sum: C,
    /// A length of the problem (m): the largest distance of a pose's
    /// origin from the first, at least 1e-300.
    pub scale: f64,
}

/// Relative size under which two poses count as one.
const COINCIDENT: f64 = 1e-9;

/// Checks the poses are distinct and finite; the scale of the problem.
pub fn check_poses(poses: &[Pose], field: &str) -> Result<f64, SynthError> {
    let mut scale: f64 = 0.0;
    for p in poses {
        if !(p.x.is_finite() && p.y.is_finite() && p.theta.is_finite()) {
            return Err(SynthError::new(
                ErrorKind::Invalid,
                field,
                "a pose is not finite",
            ));
        }
        scale = scale.max(norm(sub([p.x, p.y], [poses[0].x, poses[0].y])));
    }
    let scale = scale.max(1e-300);
    for i in 0..poses.len() {
        for j in i + 1..poses.len() {
            let (p, q) = (poses[i], poses[j]);
            if norm(sub([q.x, q.y], [p.x, p.y])) <= COINCIDENT * scale
                && wrap_pi(q.theta - p.theta).abs() <= COINCIDENT
            {
                return Err(SynthError::new(
                    ErrorKind::Coincident,
                    field,
                    format!(
                        "poses {} and {} coincide; {} distinct poses are needed",
                        i + 1,
                        j + 1,
                        poses.len()
                    ),
                ));
            }
        }
    }
    Ok(scale)
}

impl Equations {
    /// The equations of four or five `poses` (checked distinct).
    pub fn new(poses: &[Pose], field: &str) -> Result<Equations, SynthError> {
        if !(4..=5).contains(&poses.len()) {
            return Err(SynthError::new(
                ErrorKind::Invalid,
                field,
                format!(
                    "{} poses given; Burmester synthesis takes four or five",
                    poses.len()
                ),
            ));
        }
        let scale = check_poses(poses, field)?;
        let p1 = C(poses[0].x, poses[0].y);
        let delta: Vec<C> = poses[1..].iter().map(|p| C(p.x, p.y) - p1).collect();
        let a: Vec<C> = poses[1..]
            .iter()
            .map(|p| C::cis(p.theta - poses[0].theta) - C(1.0, 0.0))
            .collect();
        let (a2, a3, a4) = (a[0], a[1], a[2]);
        let (d2, d3, d4) = (delta[0], delta[1], delta[2]);
        let big = [a3 * d4 - a4 * d3, a4 * d2 - a2 * d4, a2 * d3 - a3 * d2];
        let sum = big[0] + big[1] + big[2];
        Ok(Equations {
            poses: poses.to_vec(),
            delta,
            a,
            big,
            sum,
            scale,
        })
    }

    pub fn poses(&self) -> &[Pose] {
        &self.poses
    }

    /// The loop's discriminant at β₂: h² (scaled, m⁸); the loop closes
    /// where it is ≥ 0. Returns (h², x, R) of the two-circle intersection
    /// |u| = |Δ₃|, |R − u| = |Δ₄|, u = (R/|R|)(x ± i h).
    fn loop_at(&self, beta2: f64) -> (f64, f64, C) {
        let r = self.sum - self.big[0] * C::cis(beta2);
        let rho = r.abs();
        let (r3, r4) = (self.big[1].abs(), self.big[2].abs());
        if rho == 0.0 {
            return (-1.0, 0.0, r);
        }
        let x = (rho * rho + r3 * r3 - r4 * r4) / (2.0 * rho);
        (r3 * r3 - x * x, x, r)
    }

    /// The dyad at β₂ on branch `s` (±1), from the equations of poses 2–4;
    /// `None` where the loop does not close or (W, Z) are not determined.
    pub fn dyad(&self, beta2: f64, s: f64) -> Option<Dyad> {
        let (h2, x, r) = self.loop_at(beta2);
        if h2 < 0.0 {
            return None;
        }
        let rho = r.abs();
        let u = (r.scale(1.0 / rho)) * C(x, s * h2.sqrt());
        let beta3 = u.arg() - self.big[1].arg();
        let beta4 = (r - u).arg() - self.big[2].arg();
        let c = [
            C::cis(beta2) - C(1.0, 0.0),
            C::cis(beta3) - C(1.0, 0.0),
            C::cis(beta4) - C(1.0, 0.0),
        ];
        // The best-conditioned pair of the three equations.
        let mut best: Option<(f64, usize, usize)> = None;
        for (i, j) in [(0, 1), (0, 2), (1, 2)] {
            let det = (c[i] * self.a[j] - c[j] * self.a[i]).abs();
            let size = (c[i].abs() + self.a[i].abs()) * (c[j].abs() + self.a[j].abs());
            let rel = det / size.max(1e-300);
            if best.is_none_or(|b| rel > b.0) {
                best = Some((rel, i, j));
            }
        }
        let (rel, i, j) = best?;
        if rel.is_nan() || rel <= 1e-12 {
            return None;
        }
        let det = c[i] * self.a[j] - c[j] * self.a[i];
        let w = (self.delta[i] * self.a[j] - self.delta[j] * self.a[i]).div(det);
        let z = (c[i] * self.delta[j] - c[j] * self.delta[i]).div(det);
        let p1 = C(self.poses[0].x, self.poses[0].y);
        let circle = p1 - z;
        let centre = circle - w;
        if !(centre.0.is_finite() && centre.1.is_finite()) {
            return None;
        }
        let mut beta = vec![wrap_pi(beta2), wrap_pi(beta3), wrap_pi(beta4)];
        if self.poses.len() == 5 {
            let v = self.delta[3] - z * self.a[3] + w;
            beta.push(wrap_pi(v.arg() - w.arg()));
        }
        Some(Dyad {
            centre: centre.p(),
            circle: circle.p(),
            moving: self.poses[0].local(circle.p()),
            beta,
            beta2: mod_tau_open(beta2),
            branch: s,
        })
    }

    /// g(β₂) on branch `s` for five poses (see the module); `None` where
    /// the dyad is not defined.
    fn fifth(&self, beta2: f64, s: f64) -> Option<f64> {
        let d = self.dyad(beta2, s)?;
        let w = C(d.circle[0] - d.centre[0], d.circle[1] - d.centre[1]);
        let p1 = C(self.poses[0].x, self.poses[0].y);
        let z = p1 - C(d.circle[0], d.circle[1]);
        let v = self.delta[3] - z * self.a[3] + w;
        let l2 = self.scale * self.scale;
        Some((v.abs2() - w.abs2()) / (w.abs2() + z.abs2() + l2))
    }

    /// The intervals of β₂ in [0, 2π] where the loop closes, with their
    /// ends located by bisection; `n` scan steps.
    fn domain(&self, n: usize) -> Vec<(f64, f64)> {
        let at = |k: usize| k as f64 * TAU / n as f64;
        let ok = |b: f64| self.loop_at(b).0 >= 0.0;
        let edge = |mut lo: f64, mut hi: f64| {
            // ok(lo) != ok(hi); returns the point on the closing side.
            let lo_ok = ok(lo);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                if ok(mid) == lo_ok {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            if lo_ok {
                lo
            } else {
                hi
            }
        };
        let mut out = Vec::new();
        let mut start: Option<f64> = if ok(0.0) { Some(0.0) } else { None };
        for k in 1..=n {
            let (b0, b1) = (at(k - 1), at(k));
            match (ok(b0), ok(b1), start) {
                (false, true, _) => start = Some(edge(b0, b1)),
                (true, false, Some(s)) => {
                    out.push((s, edge(b0, b1)));
                    start = None;
                }
                _ => {}
            }
        }
        if let Some(s) = start {
            out.push((s, TAU));
        }
        out
    }

    /// The centre-point and circle-point curves of poses 1–4, sampled at
    /// `n` steps of β₂ per branch (plus the ends of the intervals where
    /// the loop closes): one polyline per branch and interval, broken
    /// where (W, Z) are not determined.
    pub fn curves(&self, n: usize) -> Vec<Vec<Dyad>> {
        let mut out = Vec::new();
        for (lo, hi) in self.domain(n.max(8)) {
            let steps = (((hi - lo) / TAU) * n as f64).ceil().max(1.0) as usize;
            for s in [1.0, -1.0] {
                let mut line = Vec::new();
                for k in 0..=steps {
                    let b = lo + (hi - lo) * k as f64 / steps as f64;
                    match self.dyad(b, s) {
                        Some(d) => line.push(d),
                        None => {
                            if line.len() > 1 {
                                out.push(std::mem::take(&mut line));
                            }
                            line.clear();
                        }
                    }
                }
                if line.len() > 1 {
                    out.push(line);
                }
            }
        }
        out
    }

    /// The Burmester points of five poses: every dyad found on a scan of
    /// `n` steps of β₂ (see the module), each satisfying the five circle
    /// conditions to 1e-9 relative, ordered by β₂.
    pub fn burmester_points(&self, n: usize) -> Vec<Dyad> {
        assert_eq!(self.poses.len(), 5, "Burmester points need five poses");
        let mut found: Vec<Dyad> = Vec::new();
        for (lo, hi) in self.domain(n.max(8)) {
            let steps = (((hi - lo) / TAU) * n as f64).ceil().max(1.0) as usize;
            for s in [1.0, -1.0] {
                let at = |k: usize| lo + (hi - lo) * k as f64 / steps as f64;
                // A sample where (W, Z) are not determined (the link's
                // rotations all 0 or all α_j) is replaced by two a hair to
                // either side, so that a root next to it keeps its bracket.
                let hair = 1e-7 * (hi - lo) / steps as f64;
                let mut samples: Vec<(f64, Option<f64>)> = Vec::with_capacity(steps + 3);
                for k in 0..=steps {
                    let b = at(k);
                    match self.fifth(b, s) {
                        Some(g) => samples.push((b, Some(g))),
                        None => {
                            for x in [b - hair, b + hair] {
                                if (lo..=hi).contains(&x) {
                                    samples.push((x, self.fifth(x, s)));
                                }
                            }
                        }
                    }
                }
                for w in samples.windows(2) {
                    if let [(b0, Some(g0)), (b1, Some(g1))] = *w {
                        if g1 == 0.0 || g0.signum() != g1.signum() {
                            found.extend(self.refine(b0, g0, b1, s));
                        }
                    }
                }
                // Two roots within one step leave no sign change at the
                // samples: where |g| has a local minimum without one, the
                // extreme of g between the neighbours (golden section) is
                // looked at, and a sign change there brackets both roots.
                for w in samples.windows(3) {
                    if let [(b0, Some(g0)), (_, Some(g1)), (b2, Some(g2))] = *w {
                        let same = g0.signum() == g1.signum() && g1.signum() == g2.signum();
                        if same && g1 != 0.0 && g1.abs() < g0.abs() && g1.abs() <= g2.abs() {
                            if let Some((m, gm)) = self.golden(b0, b2, s, g1.signum()) {
                                if gm.signum() != g1.signum() {
                                    found.extend(self.refine(b0, g0, m, s));
                                    found.extend(self.refine(m, gm, b2, s));
                                }
                            }
                        }
                    }
                }
            }
        }
        // Roots at an interval's end appear on both branches; roots at an
        // even sample in two intervals.
        let mut out: Vec<Dyad> = Vec::new();
        for d in found {
            if out
                .iter()
                .all(|e| norm(sub(e.centre, d.centre)) > 1e-7 * self.scale.max(d.length()))
            {
                out.push(d);
            }
        }
        out.sort_by(|p, q| p.beta2.total_cmp(&q.beta2));
        out
    }

    /// The minimum of `sign`·g on [a, b] by golden-section search (60
    /// steps): (β₂, g) there; `None` where g is not defined.
    fn golden(&self, mut a: f64, mut b: f64, s: f64, sign: f64) -> Option<(f64, f64)> {
        let r = 0.5 * (5f64.sqrt() - 1.0);
        let f = |x: f64| self.fifth(x, s).map(|g| sign * g);
        let (mut c, mut d) = (b - r * (b - a), a + r * (b - a));
        let (mut fc, mut fd) = (f(c)?, f(d)?);
        for _ in 0..60 {
            if fc < fd {
                b = d;
                (d, fd) = (c, fc);
                c = b - r * (b - a);
                fc = f(c)?;
            } else {
                a = c;
                (c, fc) = (d, fd);
                d = a + r * (b - a);
                fd = f(d)?;
            }
        }
        let m = 0.5 * (a + b);
        Some((m, sign * f(m)?))
    }

    /// Bisection of g on [b0, b1] (g(b0) = g0, signs differ) to the last
    /// bit; the dyad there if it passes the five circle conditions.
    fn refine(&self, mut b0: f64, g0: f64, mut b1: f64, s: f64) -> Option<Dyad> {
        let s0 = g0.signum();
        for _ in 0..200 {
            let mid = 0.5 * (b0 + b1);
            if mid <= b0 || mid >= b1 {
                break;
            }
            match self.fifth(mid, s) {
                Some(0.0) => {
                    b0 = mid;
                    b1 = mid;
                    break;
                }
                Some(g) if g.signum() == s0 => b0 = mid,
                Some(_) => b1 = mid,
                None => return None,
            }
        }
        let pick = |b: f64| self.fifth(b, s).map(|g| (g.abs(), b));
        let (_, b) = match (pick(b0), pick(b1)) {
            (Some(x), Some(y)) => {
                if x.0 <= y.0 {
                    x
                } else {
                    y
                }
            }
            (Some(x), None) | (None, Some(x)) => x,
            (None, None) => return None,
        };
        let d = self.dyad(b, s)?;
        let size = d.length().max(self.scale);
        if d.circle_residual(&self.poses) <= 1e-9 * size {
            Some(d)
        } else {
            None
        }
    }
}

/// β in [0, 2π) (2π itself maps to 0).
fn mod_tau_open(b: f64) -> f64 {
    crate::fourbar::mod_tau(b)
}

/// A four-bar of two dyads and its checks.
#[derive(Clone, Debug)]
pub struct Candidate {
    /// Indices of the crank's and the rocker's dyad in the list paired.
    pub dyads: [usize; 2],
    pub linkage: FourBar,
    /// A and B in the coupler frame (m).
    pub moving: [P2; 2],
    pub checks: Checks,
    /// The quality figure: the least transmission angle's distance from
    /// the in-line positions over the motion, min(μ_min, π − μ_max) (rad),
    /// 0 where the linkage does not assemble throughout; larger is better.
    pub quality: f64,
    /// Longest link over shortest.
    pub link_ratio: f64,
}

/// Why pairs of dyads were not kept: how many pairs each check removed,
/// and of how many. The checks run in the order same pivot, region, link
/// ratio, branch, then the rest of [`Checks`]; a pair is counted under the
/// first of those four it fails, or under every other check it fails.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Tally {
    pub pairs: usize,
    /// (check name, pairs failing it), in the order of the checks.
    pub removed: Vec<(String, usize)>,
    pub kept: usize,
}

impl Tally {
    fn count(&mut self, name: &str) {
        match self.removed.iter_mut().find(|(n, _)| n == name) {
            Some(r) => r.1 += 1,
            None => self.removed.push((name.to_string(), 1)),
        }
    }
}

/// What the pairing asks of a four-bar besides [`Requirements`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Limits {
    /// Largest longest-over-shortest link ratio.
    pub max_link_ratio: Option<f64>,
    /// Ground pivots inside [x_min, y_min, x_max, y_max] (m).
    pub region: Option<[f64; 4]>,
}

/// Every ordered pair of distinct `dyads` (crank, rocker) as a four-bar
/// through `poses`, checked against `req` and `limits`: the defect-free
/// ones ranked by quality (best first), and the tally of the others.
pub fn pair(
    poses: &[Pose],
    dyads: &[Dyad],
    req: &Requirements,
    limits: &Limits,
) -> (Vec<Candidate>, Tally) {
    let scale = check_poses(poses, "poses").unwrap_or(1.0);
    let mut tally = Tally::default();
    let mut kept = Vec::new();
    let inside = |p: P2| match limits.region {
        None => true,
        Some([x0, y0, x1, y1]) => p[0] >= x0 && p[0] <= x1 && p[1] >= y0 && p[1] <= y1,
    };
    for (i, di) in dyads.iter().enumerate() {
        for (j, dj) in dyads.iter().enumerate() {
            if i == j {
                continue;
            }
            tally.pairs += 1;
            let size = scale.max(di.length()).max(dj.length());
            if norm(sub(di.centre, dj.centre)) <= 1e-9 * size
                || norm(sub(di.moving, dj.moving)) <= 1e-9 * size
            {
                tally.count("same_pivot");
                continue;
            }
            if !inside(di.centre) || !inside(dj.centre) {
                tally.count("region");
                continue;
            }
            let linkage = FourBar {
                o2: di.centre,
                o4: dj.centre,
                crank: di.length(),
                coupler: norm(sub(dj.moving, di.moving)),
                rocker: dj.length(),
            };
            let lengths = linkage.lengths();
            let longest = lengths.iter().copied().fold(0.0, f64::max);
            let shortest = lengths.iter().copied().fold(f64::INFINITY, f64::min);
            let ratio = longest / shortest;
            if let Some(m) = limits.max_link_ratio {
                if ratio.is_nan() || ratio > m {
                    tally.count("link_ratio");
                    continue;
                }
            }
            let pins: Vec<P2> = poses.iter().map(|p| p.place(di.moving)).collect();
            let rockers: Vec<P2> = poses.iter().map(|p| p.place(dj.moving)).collect();
            // The branch first, cheaply: most pairs fail it, and those are
            // counted under it alone.
            let sigma = linkage.branch(pins[0], rockers[0]);
            if sigma == 0.0
                || pins
                    .iter()
                    .zip(&rockers)
                    .any(|(&a, &b)| linkage.branch(a, b) != sigma)
            {
                tally.count("branch");
                continue;
            }
            let checks = Checks::of(&linkage, &pins, &rockers, req, None);
            if !checks.defects.is_empty() {
                for d in &checks.defects {
                    tally.count(d.kind.name());
                }
                continue;
            }
            let worst = checks.transmission_min.min(PI - checks.transmission_max);
            kept.push(Candidate {
                dyads: [i, j],
                linkage,
                moving: [di.moving, dj.moving],
                checks,
                quality: if worst.is_nan() { 0.0 } else { worst },
                link_ratio: ratio,
            });
        }
    }
    kept.sort_by(|p, q| {
        q.quality
            .total_cmp(&p.quality)
            .then(p.link_ratio.total_cmp(&q.link_ratio))
    });
    tally.kept = kept.len();
    (kept, tally)
}

/// The dyads a four-pose problem pairs: `per_branch` evenly spaced β₂ on
/// each branch of each interval where the compatibility loop closes.
pub fn sample_dyads(eq: &Equations, per_branch: usize) -> Vec<Dyad> {
    let mut out = Vec::new();
    for (lo, hi) in eq.domain(720) {
        let steps = (((hi - lo) / TAU) * per_branch as f64).ceil().max(1.0) as usize;
        for s in [1.0, -1.0] {
            // Interior samples: the ends, where both branches meet, once.
            for k in 0..steps {
                let b = lo + (hi - lo) * (k as f64 + 0.5) / steps as f64;
                if let Some(d) = eq.dyad(b, s) {
                    out.push(d);
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn poses4() -> Vec<Pose> {
        vec![
            Pose {
                x: 0.0,
                y: 0.0,
                theta: 0.0,
            },
            Pose {
                x: 0.1,
                y: 0.05,
                theta: 0.3,
            },
            Pose {
                x: 0.18,
                y: 0.02,
                theta: 0.7,
            },
            Pose {
                x: 0.25,
                y: -0.05,
                theta: 1.1,
            },
        ]
    }

    #[test]
    fn every_sampled_dyad_keeps_its_length() {
        let eq = Equations::new(&poses4(), "poses").unwrap();
        let curves = eq.curves(360);
        assert!(!curves.is_empty());
        let mut n = 0;
        for line in &curves {
            for d in line {
                let size = d.length().max(eq.scale);
                assert!(d.circle_residual(eq.poses()) < 1e-11 * size);
                n += 1;
            }
        }
        assert!(n > 300);
    }

    #[test]
    fn four_bars_of_four_poses_are_found() {
        let poses = poses4();
        let eq = Equations::new(&poses, "poses").unwrap();
        let dyads = sample_dyads(&eq, 24);
        let (kept, tally) = pair(&poses, &dyads, &Requirements::default(), &Limits::default());
        assert!(tally.pairs > 100);
        assert!(!kept.is_empty(), "{tally:?}");
    }
}
