//! Dead-centre synthesis: a crank-rocker whose rocker swings through a
//! given angle ψ with a given time ratio Q (slow stroke / fast stroke).
//!
//! The classical construction (global frame, m, rad): the rocker O₄B of
//! length c has its extreme positions B₁ = O₄ + c·u(ψ₁) and
//! B₂ = O₄ + c·u(ψ₁ + ψ). At each extreme the crank and the coupler are in
//! line (a toggle): folded, |O₂B| = b − a, or extended, |O₂B| = b + a. The
//! crank turns π + α between them one way and π − α the other, with
//! α = π (Q − 1)/(Q + 1), so the lines O₂B₁ and O₂B₂ meet at α: O₂ lies on
//! the circle through B₁ and B₂ on which the chord B₁B₂ subtends α (for
//! Q = 1, on the line B₁B₂ outside the segment). With L₁ = |O₂B₁| and
//! L₂ = |O₂B₂|: a = |L₂ − L₁|/2, b = (L₁ + L₂)/2, d = |O₄ − O₂|.
//!
//! The free choice is where O₂ sits on that locus (two arcs, mirror images
//! in the chord B₁B₂): given the ground link d (the locus meets the circle
//! of radius d about O₄ at up to four points),
//! or else the point of the locus whose linkage has the largest least
//! transmission angle over a crank turn.

use std::f64::consts::{PI, TAU};

use crate::error::{ErrorKind, SynthError};
use crate::fourbar::{
    add, angle, cross, mod_tau, norm, sub, unit, Checks, FourBar, Grashof, Requirements, Turning,
    P2,
};

/// The problem.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DeadCentreSpec {
    /// O₄ (m).
    pub rocker_pivot: P2,
    /// c (m).
    pub rocker: f64,
    /// ψ (rad), in (0, π).
    pub swing: f64,
    /// ψ₁: the rocker's angle at its first extreme (rad).
    pub rocker_start: f64,
    /// Q ≥ 1.
    pub time_ratio: f64,
    /// d (m), if chosen.
    pub ground: Option<f64>,
    pub requirements: Requirements,
}

/// A crank-rocker from the construction.
#[derive(Clone, Debug)]
pub struct DeadCentre {
    pub linkage: FourBar,
    /// The assembly branch σ.
    pub sigma: f64,
    /// The crank angles at the rocker's extremes B₁ and B₂, unwrapped in
    /// `turning` so that B₁ → B₂ is the slow stroke (rad).
    pub crank_angles: [f64; 2],
    pub turning: Turning,
    /// Crank rotation of the slow (B₁ → B₂) and the fast (B₂ → B₁) stroke (rad).
    pub strokes: [f64; 2],
    pub checks: Checks,
}

/// O₂ at locus parameter τ: on the circle (centre, radius) at angle τ, or
/// on the line B₁B₂ (Q = 1) at signed distance τ·|B₁B₂| beyond the nearer end.
struct Locus {
    b1: P2,
    b2: P2,
    alpha: f64,
    centre: P2,
    radius: f64,
}

impl Locus {
    /// The circle with its centre on the `side` (±1) of the chord B₁B₂.
    fn new(b1: P2, b2: P2, alpha: f64, side: f64) -> Locus {
        let chord = sub(b2, b1);
        let l = norm(chord);
        let mid = [(b1[0] + b2[0]) / 2.0, (b1[1] + b2[1]) / 2.0];
        if alpha <= 0.0 {
            return Locus {
                b1,
                b2,
                alpha,
                centre: mid,
                radius: f64::INFINITY,
            };
        }
        let radius = l / (2.0 * alpha.sin());
        // The centre on the perpendicular bisector, at distance R cos α
        // from the chord (either side: both arcs are searched).
        let n = [-chord[1] / l, chord[0] / l];
        let h = side * radius * alpha.cos();
        Locus {
            b1,
            b2,
            alpha,
            centre: add(mid, [n[0] * h, n[1] * h]),
            radius,
        }
    }

    /// Whether the lines O₂B₁ and O₂B₂ meet at α (to 1e-9 rad) at `o2`.
    fn fits(&self, o2: P2) -> bool {
        let (u, v) = (sub(self.b1, o2), sub(self.b2, o2));
        let ang = cross(u, v).abs().atan2(u[0] * v[0] + u[1] * v[1]);
        (ang - self.alpha).abs() < 1e-9
    }
}

fn invalid(field: &str, m: impl Into<String>) -> SynthError {
    SynthError::new(ErrorKind::Invalid, field, m)
}

/// The crank-rocker with O₂ at `o2`, or `None` if it is not one.
fn build(spec: &DeadCentreSpec, b: [P2; 2], o2: P2) -> Option<DeadCentre> {
    let (l1, l2) = (norm(sub(b[0], o2)), norm(sub(b[1], o2)));
    let a = (l2 - l1).abs() / 2.0;
    let cpl = (l1 + l2) / 2.0;
    let scale = spec.rocker;
    if a <= 1e-9 * scale {
        return None;
    }
    let linkage = FourBar {
        o2,
        o4: spec.rocker_pivot,
        crank: a,
        coupler: cpl,
        rocker: spec.rocker,
    };
    if linkage.grashof() != Grashof::CrankRocker {
        return None;
    }
    // Crank angle at each extreme: towards B if extended, away if folded.
    let phi_at = |k: usize| {
        let dir = angle(sub(b[k], o2));
        let extended = [l1, l2][k] > [l1, l2][1 - k];
        if extended {
            dir
        } else {
            dir + PI
        }
    };
    let (p1, p2) = (phi_at(0), phi_at(1));
    let ccw = mod_tau(p2 - p1);
    let (turning, s) = if ccw >= PI - 1e-12 {
        (Turning::Ccw, 1.0)
    } else {
        (Turning::Cw, -1.0)
    };
    let slow = mod_tau(s * (p2 - p1));
    let a1 = linkage.crank_pin(p1);
    let sigma = linkage.branch(a1, b[0]);
    if sigma == 0.0 {
        return None;
    }
    let mut req = spec.requirements;
    req.full_turn = true;
    req.turning = Some(turning);
    let a2 = linkage.crank_pin(p2);
    let checks = Checks::of(
        &linkage,
        &[a1, a2],
        &[b[0], b[1]],
        &req,
        Some((p1, p1 + s * TAU)),
    );
    Some(DeadCentre {
        linkage,
        sigma,
        crank_angles: [p1, p1 + s * slow],
        turning,
        strokes: [slow, TAU - slow],
        checks,
    })
}

/// The least transmission angle's distance from the in-line positions
/// over a crank turn (rad): min(μ_min, π − μ_max).
fn quality(d: &DeadCentre) -> f64 {
    let r = d.linkage.sweep(0.0, TAU);
    if r.assembled {
        r.mu_min.min(PI - r.mu_max)
    } else {
        f64::NEG_INFINITY
    }
}

/// Synthesises the crank-rockers of `spec`: every point of the locus at
/// distance d from O₄ when d is given, else the best point of the locus.
/// `fields` name the problem's rocker, swing, time ratio and ground fields.
pub fn synthesise(spec: &DeadCentreSpec, fields: [&str; 4]) -> Result<Vec<DeadCentre>, SynthError> {
    let [f_rocker, f_swing, f_q, f_ground] = fields;
    if spec.rocker.is_nan() || spec.rocker <= 0.0 {
        return Err(invalid(
            f_rocker,
            format!("{} m; the rocker must be longer than 0", spec.rocker),
        ));
    }
    if !(spec.swing > 0.0 && spec.swing < PI) {
        return Err(invalid(
            f_swing,
            format!(
                "{} rad; a rocker swings through an angle in (0, π) (rad)",
                spec.swing
            ),
        ));
    }
    if spec.time_ratio.is_nan() || spec.time_ratio < 1.0 || !spec.time_ratio.is_finite() {
        return Err(invalid(
            f_q,
            format!(
                "{}; the time ratio is the slow stroke's time over the fast one's, at least 1",
                spec.time_ratio
            ),
        ));
    }
    let alpha = PI * (spec.time_ratio - 1.0) / (spec.time_ratio + 1.0);
    let b = [
        add(
            spec.rocker_pivot,
            [
                spec.rocker * spec.rocker_start.cos(),
                spec.rocker * spec.rocker_start.sin(),
            ],
        ),
        add(spec.rocker_pivot, {
            let u = unit(spec.rocker_start + spec.swing);
            [spec.rocker * u[0], spec.rocker * u[1]]
        }),
    ];
    let mut found = Vec::new();
    // Both circles (centre either side of the chord) hold a locus arc.
    let loci: Vec<Locus> = if alpha > 0.0 {
        vec![
            Locus::new(b[0], b[1], alpha, 1.0),
            Locus::new(b[0], b[1], alpha, -1.0),
        ]
    } else {
        vec![Locus::new(b[0], b[1], 0.0, 1.0)]
    };
    match spec.ground {
        Some(d) => {
            if d.is_nan() || d <= 0.0 {
                return Err(invalid(
                    f_ground,
                    format!("{d} m; the ground link must be longer than 0"),
                ));
            }
            for locus in &loci {
                for o2 in meet(locus, spec.rocker_pivot, d) {
                    if locus.fits(o2) {
                        if let Some(c) = build(spec, b, o2) {
                            found.push(c);
                        }
                    }
                }
            }
            if found.is_empty() {
                return Err(SynthError::new(
                    ErrorKind::NoSolution,
                    f_ground,
                    format!(
                        "no crank-rocker with a ground link of {d} m gives this swing and time \
                         ratio: the circle of radius d about the rocker pivot misses the crank \
                         pivot's locus where it makes a crank-rocker; try another length, or \
                         leave ground out to let camlink choose"
                    ),
                ));
            }
        }
        None => {
            // Scan the locus, then refine the best by golden section.
            let mut best: Option<(f64, f64, usize)> = None;
            let n = 3600;
            for (li, locus) in loci.iter().enumerate() {
                for k in 0..n {
                    let tau = param(locus, k as f64 / n as f64);
                    let o2 = point(locus, tau);
                    if !locus.fits(o2) {
                        continue;
                    }
                    if let Some(c) = build(spec, b, o2) {
                        let q = quality(&c);
                        if best.is_none_or(|(bq, _, _)| q > bq) {
                            best = Some((q, tau, li));
                        }
                    }
                }
            }
            let Some((_, tau, li)) = best else {
                return Err(SynthError::new(
                    ErrorKind::NoSolution,
                    f_swing,
                    "no crank-rocker gives this swing and time ratio",
                ));
            };
            let locus = &loci[li];
            let step = param(locus, 1.0 / n as f64) - param(locus, 0.0);
            let f = |t: f64| {
                let o2 = point(locus, t);
                if !locus.fits(o2) {
                    return f64::NEG_INFINITY;
                }
                build(spec, b, o2).map_or(f64::NEG_INFINITY, |c| quality(&c))
            };
            let (mut lo, mut hi) = (tau - step, tau + step);
            let g = (5f64.sqrt() - 1.0) / 2.0;
            for _ in 0..60 {
                let (m1, m2) = (hi - g * (hi - lo), lo + g * (hi - lo));
                if f(m1) >= f(m2) {
                    hi = m2;
                } else {
                    lo = m1;
                }
            }
            let t = if f(0.5 * (lo + hi)) >= f(tau) {
                0.5 * (lo + hi)
            } else {
                tau
            };
            if let Some(c) = build(spec, b, point(locus, t)) {
                found.push(c);
            }
        }
    }
    found.sort_by(|p, q| quality(q).total_cmp(&quality(p)));
    Ok(found)
}

/// The locus parameter at fraction `u` ∈ [0, 1) of its range.
fn param(locus: &Locus, u: f64) -> f64 {
    if locus.radius.is_finite() {
        TAU * u
    } else {
        // Along the line, |τ| up to 20 chord lengths from the middle.
        -20.0 + 40.0 * u
    }
}

fn point(locus: &Locus, tau: f64) -> P2 {
    if locus.radius.is_finite() {
        let u = unit(tau);
        add(locus.centre, [locus.radius * u[0], locus.radius * u[1]])
    } else {
        let c = sub(locus.b2, locus.b1);
        add(locus.centre, [c[0] * tau, c[1] * tau])
    }
}

/// Where the locus meets the circle of radius `d` about `o4`.
fn meet(locus: &Locus, o4: P2, d: f64) -> Vec<P2> {
    if locus.radius.is_finite() {
        let v = sub(o4, locus.centre);
        let dist = norm(v);
        let r = locus.radius;
        if dist == 0.0 || dist > r + d || dist < (r - d).abs() {
            return vec![];
        }
        let x = (dist * dist + r * r - d * d) / (2.0 * dist);
        let h = (r * r - x * x).max(0.0).sqrt();
        let e = [v[0] / dist, v[1] / dist];
        let base = add(locus.centre, [e[0] * x, e[1] * x]);
        vec![
            add(base, [-e[1] * h, e[0] * h]),
            add(base, [e[1] * h, -e[0] * h]),
        ]
    } else {
        // Line through the chord's middle m along e: |m + t e − o4| = d.
        let c = sub(locus.b2, locus.b1);
        let l = norm(c);
        let e = [c[0] / l, c[1] / l];
        let w = sub(locus.centre, o4);
        let bq = w[0] * e[0] + w[1] * e[1];
        let cq = w[0] * w[0] + w[1] * w[1] - d * d;
        let disc = bq * bq - cq;
        if disc < 0.0 {
            return vec![];
        }
        [-bq + disc.sqrt(), -bq - disc.sqrt()]
            .iter()
            .map(|t| add(locus.centre, [e[0] * t, e[1] * t]))
            .collect()
    }
}
