//! The planar four-bar linkage that every synthesis method here returns,
//! its position analysis in closed form, and the checks made on every
//! candidate: Grashof class, transmission angle over the motion, assembly
//! branch and order.
//!
//! Symbols and frames (global frame, m and rad, angles counter-clockwise
//! from +x):
//! - O₂, O₄: the ground pivots of the crank and of the rocker.
//! - a: the crank, signed: the crank's moving pivot is A = O₂ + a·u(φ),
//!   u(φ) = (cos φ, sin φ), with φ the crank body's angle. A negative a
//!   points the crank the other way along its body axis (|a| is the link's
//!   length); Freudenstein's solutions use it to keep φ the input angle.
//! - c: the rocker, signed in the same way: B = O₄ + c·u(ψ).
//! - b > 0: the coupler, |B − A| = b.
//! - d = |O₄ − O₂|: the ground link.
//! - E = |O₄ − A|: the diagonal from the crank pin to the rocker pivot.
//! - μ: the transmission angle, the angle at B between the coupler B→A and
//!   the rocker B→O₄, in [0, π]: cos μ = (b² + c² − E²) / (2 b |c|).
//! - σ: the assembly branch, the sign of the cross product (B − A) × (B − O₄)
//!   of the coupler and the rocker; it changes only where they fall in line
//!   (a toggle), so a motion on one branch keeps σ.

use std::f64::consts::{PI, TAU};

/// A point or a vector of the plane (m).
pub type P2 = [f64; 2];

pub(crate) fn sub(p: P2, q: P2) -> P2 {
    [p[0] - q[0], p[1] - q[1]]
}

pub(crate) fn add(p: P2, q: P2) -> P2 {
    [p[0] + q[0], p[1] + q[1]]
}

pub(crate) fn norm(p: P2) -> f64 {
    p[0].hypot(p[1])
}

pub(crate) fn cross(p: P2, q: P2) -> f64 {
    p[0] * q[1] - p[1] * q[0]
}

pub(crate) fn angle(p: P2) -> f64 {
    p[1].atan2(p[0])
}

/// The unit vector u(θ) = (cos θ, sin θ).
pub(crate) fn unit(theta: f64) -> P2 {
    [theta.cos(), theta.sin()]
}

/// A(θ) p: `p` rotated by θ (rad).
pub(crate) fn rotate(theta: f64, p: P2) -> P2 {
    let (s, c) = theta.sin_cos();
    [c * p[0] - s * p[1], s * p[0] + c * p[1]]
}

/// `x` mod 2π, in [0, 2π).
pub fn mod_tau(x: f64) -> f64 {
    let r = x.rem_euclid(TAU);
    if r >= TAU {
        0.0
    } else {
        r
    }
}

/// `x` wrapped to (−π, π].
pub fn wrap_pi(x: f64) -> f64 {
    let r = mod_tau(x);
    if r > PI {
        r - TAU
    } else {
        r
    }
}

/// The Grashof class of a four-bar, from its shortest link s, longest l
/// and the other two p, q.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Grashof {
    /// s + l < p + q, the crank shortest: the crank turns fully, the rocker rocks.
    CrankRocker,
    /// s + l < p + q, the rocker shortest: the rocker turns fully, the crank rocks.
    RockerCrank,
    /// s + l < p + q, the ground shortest: crank and rocker both turn fully.
    DoubleCrank,
    /// s + l < p + q, the coupler shortest: the coupler turns fully, crank and rocker rock.
    DoubleRocker,
    /// s + l = p + q (to 1e-12 relative): the links can fall in line, where
    /// the motion may change branch.
    ChangePoint,
    /// s + l > p + q: no link turns fully against another.
    TripleRocker,
}

impl Grashof {
    /// The class of links (d, |a|, b, |c|) (m).
    pub fn classify(ground: f64, crank: f64, coupler: f64, rocker: f64) -> Grashof {
        let links = [ground, crank, coupler, rocker];
        let mut shortest = 0;
        for k in 1..4 {
            if links[k] < links[shortest] {
                shortest = k;
            }
        }
        let s = links[shortest];
        let l = links.iter().copied().fold(0.0, f64::max);
        let sum: f64 = links.iter().sum();
        let excess = (s + l) - (sum - s - l);
        if excess.abs() <= 1e-12 * sum {
            return Grashof::ChangePoint;
        }
        if excess > 0.0 {
            return Grashof::TripleRocker;
        }
        match shortest {
            0 => Grashof::DoubleCrank,
            1 => Grashof::CrankRocker,
            2 => Grashof::DoubleRocker,
            _ => Grashof::RockerCrank,
        }
    }

    /// The name used in reports: `crank-rocker`, `rocker-crank`,
    /// `double-crank`, `double-rocker`, `change-point`, `triple-rocker`.
    pub fn name(self) -> &'static str {
        match self {
            Grashof::CrankRocker => "crank-rocker",
            Grashof::RockerCrank => "rocker-crank",
            Grashof::DoubleCrank => "double-crank",
            Grashof::DoubleRocker => "double-rocker",
            Grashof::ChangePoint => "change-point",
            Grashof::TripleRocker => "triple-rocker",
        }
    }

    /// Whether the crank turns fully relative to the ground.
    pub fn crank_turns_fully(self) -> bool {
        matches!(self, Grashof::CrankRocker | Grashof::DoubleCrank)
    }
}

/// One assembled position of a four-bar.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Position {
    /// Crank angle φ (rad).
    pub phi: f64,
    /// Rocker angle ψ (rad), in (−π, π].
    pub psi: f64,
    /// The crank's moving pivot A (m).
    pub a: P2,
    /// The rocker's moving pivot B (m).
    pub b: P2,
}

/// A four-bar: ground pivots, signed crank and rocker, coupler (see the
/// module's symbols).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FourBar {
    /// O₂ (m).
    pub o2: P2,
    /// O₄ (m).
    pub o4: P2,
    /// a, signed (m).
    pub crank: f64,
    /// b > 0 (m).
    pub coupler: f64,
    /// c, signed (m).
    pub rocker: f64,
}

/// The diagonal E and the transmission angle μ over a crank sweep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepRange {
    /// Smallest and largest E over the sweep (m).
    pub e_min: f64,
    pub e_max: f64,
    /// Smallest and largest μ over the sweep (rad); NaN where the linkage
    /// does not assemble somewhere in the sweep.
    pub mu_min: f64,
    pub mu_max: f64,
    /// Whether the linkage assembles at every crank angle of the sweep
    /// without reaching a toggle: |b − |c|| < E < b + |c| throughout.
    pub assembled: bool,
}

impl FourBar {
    /// d = |O₄ − O₂| (m).
    pub fn ground(&self) -> f64 {
        norm(sub(self.o4, self.o2))
    }

    /// The link lengths (d, |a|, b, |c|) (m).
    pub fn lengths(&self) -> [f64; 4] {
        [
            self.ground(),
            self.crank.abs(),
            self.coupler,
            self.rocker.abs(),
        ]
    }

    pub fn grashof(&self) -> Grashof {
        let [d, a, b, c] = self.lengths();
        Grashof::classify(d, a, b, c)
    }

    /// A = O₂ + a·u(φ) (m).
    pub fn crank_pin(&self, phi: f64) -> P2 {
        let u = unit(phi);
        [
            self.o2[0] + self.crank * u[0],
            self.o2[1] + self.crank * u[1],
        ]
    }

    /// The position at crank angle `phi` (rad) on branch `sigma` (the sign
    /// of the coupler × rocker cross product, ±1); `None` where the
    /// linkage does not assemble.
    ///
    /// With e = O₄ − A, |e + c·u(ψ)| = b gives E cos(ψ − ε) = κE,
    /// κ = (b² − c² − E²)/(2cE), ε the angle of e; the cross product is
    /// c·E·sin(ψ − ε), so ψ = ε + σ·sign(c)·acos κ.
    pub fn position(&self, phi: f64, sigma: f64) -> Option<Position> {
        let a = self.crank_pin(phi);
        let e = sub(self.o4, a);
        let big_e = norm(e);
        let (b, c) = (self.coupler, self.rocker);
        if big_e == 0.0 || c == 0.0 {
            return None;
        }
        let kappa = (b * b - c * c - big_e * big_e) / (2.0 * c * big_e);
        if !(-1.0..=1.0).contains(&kappa) {
            return None;
        }
        let s = sigma.signum() * c.signum();
        let psi = wrap_pi(angle(e) + s * kappa.acos());
        let u = unit(psi);
        Some(Position {
            phi,
            psi,
            a,
            b: [self.o4[0] + c * u[0], self.o4[1] + c * u[1]],
        })
    }

    /// σ of a position: the sign of (B − A) × (B − O₄); 0 at a toggle.
    pub fn branch(&self, a: P2, b: P2) -> f64 {
        let x = cross(sub(b, a), sub(b, self.o4));
        let scale = self.coupler * self.rocker.abs();
        if x.abs() <= 1e-12 * scale {
            0.0
        } else {
            x.signum()
        }
    }

    /// The transmission angle μ (rad) for a diagonal E (m); NaN where the
    /// linkage does not assemble.
    pub fn transmission(&self, big_e: f64) -> f64 {
        let (b, c) = (self.coupler, self.rocker.abs());
        let cos_mu = (b * b + c * c - big_e * big_e) / (2.0 * b * c);
        if (-1.0..=1.0).contains(&cos_mu) {
            cos_mu.acos()
        } else {
            f64::NAN
        }
    }

    /// E and μ over the crank sweep from `phi_start` to `phi_end` (rad, in
    /// either direction, not wrapped), in closed form:
    /// E² = d² + a² − 2 a d cos(φ − θ_d), θ_d the angle of O₄ − O₂, has its
    /// extremes at the ends of the sweep and where φ − θ_d is a multiple
    /// of π; μ grows with E.
    pub fn sweep(&self, phi_start: f64, phi_end: f64) -> SweepRange {
        let (lo, hi) = if phi_start <= phi_end {
            (phi_start, phi_end)
        } else {
            (phi_end, phi_start)
        };
        let theta_d = angle(sub(self.o4, self.o2));
        let e_at = |phi: f64| norm(sub(self.o4, self.crank_pin(phi)));
        let (mut e_min, mut e_max) = (e_at(lo).min(e_at(hi)), e_at(lo).max(e_at(hi)));
        // Interior extremes: φ = θ_d + kπ inside (lo, hi).
        let mut k = ((lo - theta_d) / PI).ceil();
        while theta_d + k * PI < hi {
            let e = e_at(theta_d + k * PI);
            e_min = e_min.min(e);
            e_max = e_max.max(e);
            k += 1.0;
        }
        let (b, c) = (self.coupler, self.rocker.abs());
        let assembled = e_min > (b - c).abs() && e_max < b + c;
        let (mu_min, mu_max) = if assembled {
            (self.transmission(e_min), self.transmission(e_max))
        } else {
            (f64::NAN, f64::NAN)
        };
        SweepRange {
            e_min,
            e_max,
            mu_min,
            mu_max,
            assembled,
        }
    }
}

/// The sense in which the crank turns through the poses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Turning {
    /// Counter-clockwise: φ increases.
    Ccw,
    /// Clockwise: φ decreases.
    Cw,
}

impl Turning {
    pub fn name(self) -> &'static str {
        match self {
            Turning::Ccw => "ccw",
            Turning::Cw => "cw",
        }
    }
}

/// What is wrong with a candidate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DefectKind {
    /// The poses are not all on one assembly branch σ (or one is at a toggle).
    Branch,
    /// The crank reaches the poses in another order than asked, or two
    /// poses need the same crank angle.
    Order,
    /// Between the first and the last pose the crank reaches a limit
    /// (coupler and rocker in line): a motor cannot drive it through the
    /// poses in one sense.
    DeadPosition,
    /// The transmission angle leaves [μ_min, π − μ_min] of the problem.
    Transmission,
    /// The crank does not turn fully though the problem asks it to.
    Grashof,
}

impl DefectKind {
    /// The report's name of the defect (a stable slug).
    pub fn name(self) -> &'static str {
        match self {
            DefectKind::Branch => "branch",
            DefectKind::Order => "order",
            DefectKind::DeadPosition => "dead_position",
            DefectKind::Transmission => "transmission",
            DefectKind::Grashof => "grashof",
        }
    }
}

/// A defect of a candidate: its kind and what it means here.
#[derive(Clone, Debug, PartialEq)]
pub struct Defect {
    pub kind: DefectKind,
    pub message: String,
}

/// What a problem asks of every candidate.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Requirements {
    /// The sense the crank must turn in; `None`: either.
    pub turning: Option<Turning>,
    /// Least transmission angle μ_min (rad): μ must stay in [μ_min, π − μ_min].
    pub min_transmission: Option<f64>,
    /// Whether the crank must turn fully (a motor drives it round).
    pub full_turn: bool,
}

/// The checks of one candidate through its poses (or precision points).
#[derive(Clone, Debug, PartialEq)]
pub struct Checks {
    pub grashof: Grashof,
    /// The crank angle at each pose, unwrapped along the motion (rad):
    /// the first in (−π, π], the others reached from it by turning in
    /// `turning`.
    pub crank_angles: Vec<f64>,
    /// σ at each pose.
    pub branches: Vec<f64>,
    pub turning: Turning,
    /// μ over the motion from the first to the last pose (rad).
    pub transmission_min: f64,
    pub transmission_max: f64,
    pub defects: Vec<Defect>,
}

impl Checks {
    /// Checks `linkage` through positions with the crank pins `pins` and
    /// rocker pins `rockers` (m), in the order the motion must reach them.
    /// The transmission angle and the dead positions are checked over the
    /// crank sweep `span` (rad, from, to), by default from the first to the
    /// last position.
    pub fn of(
        linkage: &FourBar,
        pins: &[P2],
        rockers: &[P2],
        req: &Requirements,
        span: Option<(f64, f64)>,
    ) -> Checks {
        let mut defects = Vec::new();
        let grashof = linkage.grashof();
        // Crank angles; a negative crank points against its body axis.
        let flip = if linkage.crank < 0.0 { PI } else { 0.0 };
        let raw: Vec<f64> = pins
            .iter()
            .map(|&p| wrap_pi(angle(sub(p, linkage.o2)) + flip))
            .collect();
        let branches: Vec<f64> = pins
            .iter()
            .zip(rockers)
            .map(|(&a, &b)| linkage.branch(a, b))
            .collect();
        // The sense that visits the poses in order within one turn.
        let ahead = |k: usize, s: f64| mod_tau(s * (raw[k] - raw[0]));
        let in_order = |s: f64| (1..raw.len()).all(|k| ahead(k, s) > ahead(k - 1, s));
        let same: Vec<usize> = (1..raw.len())
            .filter(|&k| wrap_pi(raw[k] - raw[k - 1]).abs() <= 1e-12)
            .collect();
        let turning = match req.turning {
            Some(t) => t,
            None if in_order(1.0) || !in_order(-1.0) => Turning::Ccw,
            None => Turning::Cw,
        };
        let s = if turning == Turning::Ccw { 1.0 } else { -1.0 };
        if let Some(&k) = same.first() {
            defects.push(Defect {
                kind: DefectKind::Order,
                message: format!(
                    "poses {} and {} need the same crank angle, so the crank cannot drive \
                     the coupler from one to the other",
                    k,
                    k + 1
                ),
            });
        } else if !in_order(s) {
            defects.push(Defect {
                kind: DefectKind::Order,
                message: format!(
                    "turning {}, the crank reaches the poses out of order",
                    turning.name()
                ),
            });
        }
        let crank_angles: Vec<f64> = (0..raw.len()).map(|k| raw[0] + s * ahead(k, s)).collect();
        if let Some(k) = branches.iter().position(|&b| b == 0.0) {
            defects.push(Defect {
                kind: DefectKind::Branch,
                message: format!(
                    "at pose {} the coupler and the rocker are in line (a toggle)",
                    k + 1
                ),
            });
        } else if branches.iter().any(|&b| b != branches[0]) {
            let other = branches.iter().position(|&b| b != branches[0]).unwrap_or(0);
            defects.push(Defect {
                kind: DefectKind::Branch,
                message: format!(
                    "poses 1 and {} lie on different assembly branches: the linkage cannot \
                     move between them without being taken apart or passing a toggle",
                    other + 1
                ),
            });
        }
        let last = *crank_angles.last().unwrap_or(&raw[0]);
        let (from, to) = span.unwrap_or((crank_angles[0], last));
        let range = linkage.sweep(from, to);
        if !range.assembled {
            defects.push(Defect {
                kind: DefectKind::DeadPosition,
                message: format!(
                    "turning {} from φ = {:.4} to {:.4} rad, the crank reaches a limit where \
                     the coupler and the rocker fall in line",
                    turning.name(),
                    from,
                    to
                ),
            });
        }
        if let Some(mu) = req.min_transmission {
            let worst = range.mu_min.min(PI - range.mu_max);
            if worst.is_nan() || worst < mu {
                defects.push(Defect {
                    kind: DefectKind::Transmission,
                    message: format!(
                        "the transmission angle reaches {:.2}° from the in-line position; the \
                         problem asks for at least {:.2}°",
                        worst.to_degrees(),
                        mu.to_degrees()
                    ),
                });
            }
        }
        if req.full_turn && !grashof.crank_turns_fully() {
            defects.push(Defect {
                kind: DefectKind::Grashof,
                message: format!(
                    "a {} linkage: the crank does not turn fully",
                    grashof.name()
                ),
            });
        }
        Checks {
            grashof,
            crank_angles,
            branches,
            turning,
            transmission_min: range.mu_min,
            transmission_max: range.mu_max,
            defects,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn example() -> FourBar {
        // examples/four_bar.toml's linkage.
        FourBar {
            o2: [0.0, 0.0],
            o4: [0.4, 0.0],
            crank: 0.12,
            coupler: 0.38,
            rocker: 0.3,
        }
    }

    #[test]
    fn grashof_classes() {
        assert_eq!(example().grashof(), Grashof::CrankRocker);
        assert_eq!(Grashof::classify(0.1, 0.3, 0.35, 0.3), Grashof::DoubleCrank);
        assert_eq!(
            Grashof::classify(0.4, 0.3, 0.1, 0.35),
            Grashof::DoubleRocker
        );
        assert_eq!(Grashof::classify(0.4, 0.3, 0.35, 0.1), Grashof::RockerCrank);
        assert_eq!(Grashof::classify(0.4, 0.2, 0.4, 0.2), Grashof::ChangePoint);
        assert_eq!(
            Grashof::classify(0.4, 0.3, 0.35, 0.32),
            Grashof::TripleRocker
        );
    }

    #[test]
    fn position_closes_the_loop_on_both_branches() {
        let l = example();
        for k in 0..36 {
            let phi = k as f64 * TAU / 36.0;
            for sigma in [1.0, -1.0] {
                let p = l
                    .position(phi, sigma)
                    .expect("a crank-rocker assembles everywhere");
                assert!((norm(sub(p.b, p.a)) - l.coupler).abs() < 1e-14);
                assert!((norm(sub(p.b, l.o4)) - l.rocker).abs() < 1e-14);
                assert_eq!(l.branch(p.a, p.b), sigma);
            }
        }
    }

    #[test]
    fn sweep_extremes_match_a_dense_scan() {
        let l = example();
        let (start, end) = (0.3, 4.0);
        let r = l.sweep(start, end);
        let n = 100_000;
        let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
        for k in 0..=n {
            let phi = start + (end - start) * k as f64 / n as f64;
            let e = norm(sub(l.o4, l.crank_pin(phi)));
            lo = lo.min(e);
            hi = hi.max(e);
        }
        assert!((r.e_min - lo).abs() < 1e-9 && (r.e_max - hi).abs() < 1e-9);
        assert!(r.assembled);
        // The sweep passes φ = π, where E = d + a.
        assert!((r.e_max - 0.52).abs() < 1e-15);
    }
}
