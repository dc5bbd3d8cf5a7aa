//! Slider-cranks: the linkage, its checks, function generation (crank
//! angle to slider position) and motion generation (a crank dyad and a
//! slider dyad guiding the coupler through two or three poses), and the
//! model file a solution is written as.
//!
//! Symbols (global frame, m and rad, angles counter-clockwise from +x):
//! - O₂ the crank's ground pivot, a the crank (signed, as in
//!   [`crate::fourbar`]): A = O₂ + a·u(φ);
//! - the slide: the line through C with direction u(γ); the slider's pin
//!   B = C + s·u(γ), s its position (m);
//! - b > 0 the coupler, |B − A| = b;
//! - h(φ) = u(γ) × (A − C), the signed distance of A from the slide
//!   (left positive) = h₀ + a sin(φ − γ), h₀ = u(γ) × (O₂ − C);
//! - s(φ) = u(γ)·(A − C) + σ √(b² − h²): σ = ±1 the branch, the sign of
//!   u(γ)·(B − A) (the slider ahead of or behind the crank pin);
//! - the transmission angle μ = acos(|h|/b) ∈ [0, π/2], the angle between
//!   the coupler and the slide's normal: π/2 with the coupler along the
//!   slide, 0 with the coupler across it (a dead position).
//!
//! The crank turns fully when |h₀| + |a| < b.
//!
//! Function generation (an offset slider-crank, C = (0, e), γ = 0, O₂ at
//! the origin): (s − a cos φ)² + (e − a sin φ)² = b² is, with K₁ = 2a,
//! K₂ = 2ae, K₃ = a² + e² − b²,
//!
//!   K₁ s cos φ + K₂ sin φ − K₃ = s²,
//!
//! linear in K: three (φ_j, s_j) fix it exactly, more in the least-squares
//! sense of the equation's residual (m²). Then a = K₁/2, e = K₂/K₁,
//! b² = a² + e² − K₃.

use std::f64::consts::{FRAC_PI_2, PI};
use std::fmt::Write;

use crate::error::{ErrorKind, SynthError};
use crate::fourbar::{
    add, angle, cross, mod_tau, norm, sub, unit, wrap_pi, Defect, DefectKind, Requirements,
    Turning, P2,
};
use crate::model_file::{crank_and_coupler, num, pair, CrankCoupler};
use crate::motion::{Pivot, Pose};

/// A slider-crank (see the module's symbols).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SliderCrank {
    /// O₂ (m).
    pub o2: P2,
    /// a, signed (m).
    pub crank: f64,
    /// b > 0 (m).
    pub coupler: f64,
    /// C, a point of the slide (m).
    pub line: P2,
    /// γ, the slide's direction (rad).
    pub dir: f64,
}

impl SliderCrank {
    pub fn crank_pin(&self, phi: f64) -> P2 {
        add(self.o2, [self.crank * phi.cos(), self.crank * phi.sin()])
    }

    /// h₀ (m).
    pub fn offset(&self) -> f64 {
        cross(unit(self.dir), sub(self.o2, self.line))
    }

    /// s at crank angle `phi` on branch `sigma` (m); `None` where it does
    /// not assemble.
    pub fn slider(&self, phi: f64, sigma: f64) -> Option<f64> {
        let u = unit(self.dir);
        let ac = sub(self.crank_pin(phi), self.line);
        let h = cross(u, ac);
        let r = self.coupler * self.coupler - h * h;
        if r < 0.0 {
            return None;
        }
        Some(u[0] * ac[0] + u[1] * ac[1] + sigma.signum() * r.sqrt())
    }

    /// The slider's pin at position `s` (m).
    pub fn pin(&self, s: f64) -> P2 {
        add(self.line, [s * self.dir.cos(), s * self.dir.sin()])
    }

    /// σ of a position: the sign of u(γ)·(B − A); 0 with the coupler across the slide.
    pub fn branch(&self, a: P2, b: P2) -> f64 {
        let u = unit(self.dir);
        let d = sub(b, a);
        let x = u[0] * d[0] + u[1] * d[1];
        if x.abs() <= 1e-12 * self.coupler {
            0.0
        } else {
            x.signum()
        }
    }

    /// The largest |h| over the crank sweep between `from` and `to` (rad),
    /// in closed form (extremes at the ends and at φ − γ = π/2 + kπ).
    pub fn max_offset(&self, from: f64, to: f64) -> f64 {
        let (lo, hi) = (from.min(to), from.max(to));
        let h0 = self.offset();
        let h = |phi: f64| (h0 + self.crank * (phi - self.dir).sin()).abs();
        let mut m = h(lo).max(h(hi));
        let first = self.dir + FRAC_PI_2;
        let mut k = ((lo - first) / PI).ceil();
        while first + k * PI < hi {
            m = m.max(h(first + k * PI));
            k += 1.0;
        }
        m
    }

    /// Whether the crank turns fully: |h₀| + |a| < b.
    pub fn crank_turns_fully(&self) -> bool {
        self.offset().abs() + self.crank.abs() < self.coupler
    }
}

/// The checks of a slider-crank through its positions.
#[derive(Clone, Debug, PartialEq)]
pub struct SliderChecks {
    pub crank_angles: Vec<f64>,
    pub branches: Vec<f64>,
    pub turning: Turning,
    /// Least μ over the motion (rad); 0 where it reaches a dead position.
    pub transmission_min: f64,
    pub full_turn: bool,
    pub defects: Vec<Defect>,
}

impl SliderChecks {
    /// Checks `l` through the crank pins `pins` and slider pins `sliders`
    /// (m) in the order given; the transmission and dead positions over
    /// the crank sweep `span` (rad), by default from the first to the last.
    pub fn of(
        l: &SliderCrank,
        pins: &[P2],
        sliders: &[P2],
        req: &Requirements,
        span: Option<(f64, f64)>,
    ) -> SliderChecks {
        let mut defects = Vec::new();
        let flip = if l.crank < 0.0 { PI } else { 0.0 };
        let raw: Vec<f64> = pins
            .iter()
            .map(|&p| wrap_pi(angle(sub(p, l.o2)) + flip))
            .collect();
        let branches: Vec<f64> = pins
            .iter()
            .zip(sliders)
            .map(|(&a, &b)| l.branch(a, b))
            .collect();
        let ahead = |k: usize, s: f64| mod_tau(s * (raw[k] - raw[0]));
        let in_order = |s: f64| (1..raw.len()).all(|k| ahead(k, s) > ahead(k - 1, s));
        let turning = match req.turning {
            Some(t) => t,
            None if in_order(1.0) || !in_order(-1.0) => Turning::Ccw,
            None => Turning::Cw,
        };
        let s = if turning == Turning::Ccw { 1.0 } else { -1.0 };
        if (1..raw.len()).any(|k| wrap_pi(raw[k] - raw[k - 1]).abs() <= 1e-12) {
            defects.push(Defect {
                kind: DefectKind::Order,
                message: "two poses need the same crank angle".into(),
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
        if branches.contains(&0.0) {
            defects.push(Defect {
                kind: DefectKind::Branch,
                message: "at a pose the coupler stands across the slide (a dead position)".into(),
            });
        } else if branches.iter().any(|&b| b != branches[0]) {
            defects.push(Defect {
                kind: DefectKind::Branch,
                message: "the poses lie on both sides of the crank pin along the slide: the \
                          slider cannot pass from one to the other"
                    .into(),
            });
        }
        let (from, to) = span.unwrap_or((crank_angles[0], crank_angles[crank_angles.len() - 1]));
        let hmax = l.max_offset(from, to);
        let transmission_min = if hmax < l.coupler {
            (hmax / l.coupler).acos()
        } else {
            0.0
        };
        if hmax >= l.coupler {
            defects.push(Defect {
                kind: DefectKind::DeadPosition,
                message: format!(
                    "turning {} from φ = {from:.4} to {to:.4} rad, the crank pin comes \
                     {hmax:.6} m from the slide, farther than the coupler's {:.6} m reaches",
                    turning.name(),
                    l.coupler
                ),
            });
        }
        if let Some(mu) = req.min_transmission {
            if transmission_min < mu {
                defects.push(Defect {
                    kind: DefectKind::Transmission,
                    message: format!(
                        "the transmission angle falls to {:.2}°; the problem asks for at least {:.2}°",
                        transmission_min.to_degrees(),
                        mu.to_degrees()
                    ),
                });
            }
        }
        let full_turn = l.crank_turns_fully();
        if req.full_turn && !full_turn {
            defects.push(Defect {
                kind: DefectKind::Grashof,
                message: "the crank does not turn fully: |offset| + crank ≥ coupler".into(),
            });
        }
        SliderChecks {
            crank_angles,
            branches,
            turning,
            transmission_min,
            full_turn,
            defects,
        }
    }
}

/// K of `K₁ s cos φ + K₂ sin φ − K₃ = s²` from (φ_j, s_j) (rad, m): exact
/// for three, least squares (Householder QR) for more.
pub fn solve_k(pairs: &[(f64, f64)], field: &str) -> Result<[f64; 3], SynthError> {
    if pairs.len() < 3 {
        return Err(SynthError::new(
            ErrorKind::Invalid,
            field,
            format!(
                "{} points; the slider-crank equation needs at least three",
                pairs.len()
            ),
        ));
    }
    let mut a: Vec<[f64; 3]> = pairs
        .iter()
        .map(|&(phi, s)| [s * phi.cos(), phi.sin(), -1.0])
        .collect();
    let mut r: Vec<f64> = pairs.iter().map(|&(_, s)| s * s).collect();
    let col: Vec<f64> = (0..3)
        .map(|j| a.iter().map(|row| row[j] * row[j]).sum::<f64>().sqrt())
        .collect();
    for j in 0..3 {
        let nrm = a[j..].iter().map(|row| row[j] * row[j]).sum::<f64>().sqrt();
        if nrm <= 1e-12 * col[j].max(1e-300) {
            return Err(SynthError::new(
                ErrorKind::NoSolution,
                field,
                "the points do not determine the slider-crank's K₁, K₂, K₃ (two share an input \
                 angle, or the crank angles differ by π); spread them out",
            ));
        }
        let alpha = if a[j][j] > 0.0 { -nrm } else { nrm };
        let mut v: Vec<f64> = a[j..].iter().map(|row| row[j]).collect();
        v[0] -= alpha;
        let vv: f64 = v.iter().map(|x| x * x).sum();
        for k in j..3 {
            let dot: f64 = v.iter().zip(&a[j..]).map(|(vi, row)| vi * row[k]).sum();
            for (vi, row) in v.iter().zip(a[j..].iter_mut()) {
                row[k] -= 2.0 * dot / vv * vi;
            }
        }
        let dot: f64 = v.iter().zip(&r[j..]).map(|(vi, ri)| vi * ri).sum();
        for (vi, ri) in v.iter().zip(r[j..].iter_mut()) {
            *ri -= 2.0 * dot / vv * vi;
        }
    }
    let mut k = [0.0; 3];
    for j in (0..3).rev() {
        let s: f64 = (j + 1..3).map(|i| a[j][i] * k[i]).sum();
        k[j] = (r[j] - s) / a[j][j];
    }
    Ok(k)
}

/// The offset slider-crank of K: O₂ = (0, 0), the slide y = e along +x.
pub fn linkage_of(k: [f64; 3], field: &str) -> Result<SliderCrank, SynthError> {
    let a = 0.5 * k[0];
    if a.is_nan() || a.abs() <= 1e-12 * (k[1].abs() + k[2].abs().sqrt()).max(1e-300) {
        return Err(SynthError::new(
            ErrorKind::NoSolution,
            field,
            format!(
                "the crank has no length (K₁ = {:e}): the points ask for no crank",
                k[0]
            ),
        ));
    }
    let e = k[1] / k[0];
    let b2 = a * a + e * e - k[2];
    if b2.is_nan() || b2 <= 0.0 {
        return Err(SynthError::new(
            ErrorKind::NoSolution,
            field,
            format!("no real coupler: b² = a² + e² − K₃ = {b2:.6e} m² is not positive"),
        ));
    }
    Ok(SliderCrank {
        o2: [0.0, 0.0],
        crank: a,
        coupler: b2.sqrt(),
        line: [0.0, e],
        dir: 0.0,
    })
}

/// Largest and RMS structural error (m) of a slider-crank function
/// generator at `samples` (φ, s) pairs asked for, and the first pair
/// index where it does not assemble.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SliderError {
    pub max: f64,
    pub at: usize,
    pub rms: f64,
    pub unassembled_at: Option<usize>,
}

pub fn structural_error(l: &SliderCrank, sigma: f64, asked: &[(f64, f64)]) -> SliderError {
    let (mut max, mut at, mut sum2, mut un) = (0.0f64, 0, 0.0, None);
    for (i, &(phi, s)) in asked.iter().enumerate() {
        match l.slider(phi, sigma) {
            Some(got) => {
                let e = got - s;
                sum2 += e * e;
                if e.abs() > max {
                    max = e.abs();
                    at = i;
                }
            }
            None => {
                un.get_or_insert(i);
            }
        }
    }
    SliderError {
        max,
        at,
        rms: (sum2 / asked.len().max(1) as f64).sqrt(),
        unassembled_at: un,
    }
}

/// A slider-crank guiding the coupler through two or three poses.
#[derive(Clone, Debug, PartialEq)]
pub struct SliderMotion {
    pub poses: Vec<Pose>,
    /// The crank pin A and the slider pin B in the coupler frame (m).
    pub moving: [P2; 2],
    pub linkage: SliderCrank,
    pub checks: SliderChecks,
}

/// How the slider point is chosen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SliderChoice {
    /// The slider's pin in the coupler frame (m): its positions must lie on
    /// a line (any point for two poses).
    Moving(P2),
    /// The slide's direction γ (rad): the pin is the coupler point whose
    /// three positions lie on a line of that direction.
    Direction(f64),
}

/// The slider point of three poses whose positions lie on a line of
/// direction `gamma`: with n = (−sin γ, cos γ), n·(B_j − B₁) = 0 for
/// j = 2, 3 is linear in b′: (A(θ_j) − A(θ₁))ᵀ n · b′ = −n·(r_j − r₁).
pub fn slider_point(poses: &[Pose], gamma: f64, field: &str) -> Result<P2, SynthError> {
    let n = [-gamma.sin(), gamma.cos()];
    let mut rows = [[0.0; 2]; 2];
    let mut rhs = [0.0; 2];
    for j in 1..3 {
        // (A(θ_j) − A(θ₁))ᵀ n, column by column.
        let e0 = sub(
            crate::fourbar::rotate(poses[j].theta, [1.0, 0.0]),
            crate::fourbar::rotate(poses[0].theta, [1.0, 0.0]),
        );
        let e1 = sub(
            crate::fourbar::rotate(poses[j].theta, [0.0, 1.0]),
            crate::fourbar::rotate(poses[0].theta, [0.0, 1.0]),
        );
        rows[j - 1] = [n[0] * e0[0] + n[1] * e0[1], n[0] * e1[0] + n[1] * e1[1]];
        let d = sub([poses[j].x, poses[j].y], [poses[0].x, poses[0].y]);
        rhs[j - 1] = -(n[0] * d[0] + n[1] * d[1]);
    }
    let det = rows[0][0] * rows[1][1] - rows[0][1] * rows[1][0];
    let size = rows.iter().flatten().map(|v| v.abs()).fold(0.0, f64::max);
    if det.is_nan() || det.abs() <= 1e-9 * size * size {
        return Err(SynthError::new(
            ErrorKind::NoSolution,
            field,
            "no coupler point moves on a line of this direction through the three poses (the \
             rotations leave the equations singular); choose another direction",
        ));
    }
    Ok([
        (rhs[0] * rows[1][1] - rhs[1] * rows[0][1]) / det,
        (rows[0][0] * rhs[1] - rows[1][0] * rhs[0]) / det,
    ])
}

/// The slider-crank through two or three `poses`: the crank chosen by
/// `crank` (with the bisector distance `along` for two poses, see
/// [`crate::two_positions`]), the slider by `slider`. `fields` names
/// (poses, crank, slider).
pub fn motion(
    poses: &[Pose],
    crank: Pivot,
    along: f64,
    slider: SliderChoice,
    req: &Requirements,
    fields: [&str; 3],
) -> Result<SliderMotion, SynthError> {
    let scale = crate::burmester::check_poses(poses, fields[0])?;
    let (a, o2) = match poses.len() {
        2 => {
            crate::two_positions::dyad(&[poses[0], poses[1]], crank, along, "A", fields[1], scale)?
        }
        3 => crate::motion::dyad(
            &[poses[0], poses[1], poses[2]],
            crank,
            "A",
            fields[1],
            scale,
        )?,
        n => {
            return Err(SynthError::new(
                ErrorKind::Invalid,
                fields[0],
                format!("{n} poses given; slider-crank motion generation takes two or three"),
            ))
        }
    };
    let b = match slider {
        SliderChoice::Moving(b) => b,
        SliderChoice::Direction(g) => {
            if poses.len() != 3 {
                return Err(SynthError::new(
                    ErrorKind::Invalid,
                    fields[2],
                    "with two poses give the slider's pin: slider = { moving = [x, y] } (m)",
                ));
            }
            slider_point(poses, g, fields[2])?
        }
    };
    let bs: Vec<P2> = poses.iter().map(|p| p.place(b)).collect();
    let span = sub(bs[bs.len() - 1], bs[0]);
    if norm(span) <= 1e-9 * scale.max(norm(b)) {
        return Err(SynthError::new(
            ErrorKind::Coincident,
            fields[2],
            "the slider's pin is at the same place at the first and last poses; it defines no slide",
        ));
    }
    let gamma = angle(span);
    let u = unit(gamma);
    for (k, p) in bs.iter().enumerate() {
        let off = cross(u, sub(*p, bs[0]));
        if off.abs() > 1e-9 * scale.max(norm(b)) {
            return Err(SynthError::new(
                ErrorKind::Collinear,
                fields[2],
                format!(
                    "the slider's pin at pose {} is {off:.3e} m off the line through its other \
                     positions: not a slider point; give slider = {{ angle = γ }} to have it found",
                    k + 1
                ),
            ));
        }
    }
    let a1 = poses[0].place(a);
    let linkage = SliderCrank {
        o2,
        crank: norm(sub(a1, o2)),
        coupler: norm(sub(b, a)),
        line: bs[0],
        dir: gamma,
    };
    let size = scale.max(norm(a)).max(norm(b));
    if linkage.crank <= 1e-9 * size {
        return Err(SynthError::new(
            ErrorKind::NoSolution,
            fields[1],
            "the crank has no length",
        ));
    }
    if linkage.coupler <= 1e-9 * size {
        return Err(SynthError::new(
            ErrorKind::NoSolution,
            fields[2],
            "the crank pin and the slider pin coincide",
        ));
    }
    let pins: Vec<P2> = poses.iter().map(|p| p.place(a)).collect();
    let checks = SliderChecks::of(&linkage, &pins, &bs, req, None);
    Ok(SliderMotion {
        poses: poses.to_vec(),
        moving: [a, b],
        linkage,
        checks,
    })
}

/// What the slider-crank model file needs besides the linkage.
pub struct SliderModel<'a> {
    pub name: &'a str,
    pub header: Vec<String>,
    pub linkage: &'a SliderCrank,
    /// A, B and the coupler point P in the coupler frame (m).
    pub coupler_points: [P2; 3],
    /// The coupler frame's pose at the first crank angle.
    pub coupler_start: Pose,
    /// s at the first crank angle (m).
    pub slider_start: f64,
    /// The crank angles the run must reach, unwrapped along the motion (rad).
    pub crank_angles: &'a [f64],
    pub stop: &'a str,
}

/// The model file of a slider-crank: bodies `crank` (frame at O₂, point
/// `A` = [a, 0]), `coupler` (points `A`, `B`, `P`) and `slider` (frame at
/// B, turned γ); revolutes `O2`, `A`, `B`; a translational joint `guide`
/// along the slide through C; the driver `motor` φ(t) = theta1 + w·t from
/// the first crank angle (t = 0) to the last (t = 1 s); output times 40
/// even steps with those of the crank angles added.
pub fn model_toml(spec: &SliderModel<'_>) -> String {
    let l = spec.linkage;
    let phi = spec.crank_angles;
    let times = crate::model_file::pose_times(phi);
    let b0 = l.pin(spec.slider_start);
    let mut s = String::new();
    crank_and_coupler(
        &mut s,
        &CrankCoupler {
            name: spec.name,
            header: &spec.header,
            crank_angles: phi,
            stop: spec.stop,
            start: "the start",
            ground: [("O2", l.o2), ("C", l.line)],
            crank: l.crank,
            coupler_start: spec.coupler_start,
            coupler_points: spec.coupler_points,
        },
    );
    let _ = writeln!(
        s,
        "[[bodies]]\nname = \"slider\"\nposition = {}\nangle = {}\npoints = {{ B = [0, 0] }}\n",
        pair(b0),
        num(l.dir)
    );
    for (name, bi, pi, bj, pj) in [
        ("O2", "ground", "O2", "crank", "O2"),
        ("A", "crank", "A", "coupler", "A"),
        ("B", "coupler", "B", "slider", "B"),
    ] {
        let _ = writeln!(
            s,
            "[[joints]]\nname = \"{name}\"\ntype = \"revolute\"\nbody_i = \"{bi}\"\npoint_i = \"{pi}\"\nbody_j = \"{bj}\"\npoint_j = \"{pj}\"\n"
        );
    }
    let _ = writeln!(
        s,
        "# The slider's B runs on the slide through C along u(γ); it does not turn.\n\
         [[joints]]\nname = \"guide\"\ntype = \"translational\"\nbody_i = \"ground\"\npoint_i = \"C\"\naxis = {}\nbody_j = \"slider\"\npoint_j = \"B\"\nangle = {}\n",
        pair(unit(l.dir)),
        num(l.dir)
    );
    let _ = writeln!(
        s,
        "[[drivers]]\nname = \"motor\"\ntype = \"revolute_angle\"\njoint = \"O2\"\nf = \"theta1 + w*t\"\n"
    );
    let mut t: Vec<f64> = (0..=40)
        .map(|k| k as f64 / 40.0)
        .filter(|s| times.iter().all(|p| (p - s).abs() > 1e-6))
        .chain(times.iter().copied())
        .collect();
    t.sort_by(f64::total_cmp);
    t.dedup();
    let _ = writeln!(
        s,
        "[analysis]\ntimes = [{}]\npoints = [\"coupler.P\", \"crank.A\", \"slider.B\"]",
        t.iter().map(|v| num(*v)).collect::<Vec<_>>().join(", ")
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn k_of_a_known_slider_crank_is_recovered() {
        // examples/slider_crank.toml: r = 0.05, l = 0.2, e = 0.01 m.
        let l = SliderCrank {
            o2: [0.0, 0.0],
            crank: 0.05,
            coupler: 0.2,
            line: [0.0, 0.01],
            dir: 0.0,
        };
        let pairs: Vec<(f64, f64)> = [0.3, 1.4, 2.9]
            .iter()
            .map(|&phi| (phi, l.slider(phi, 1.0).unwrap()))
            .collect();
        let m = linkage_of(solve_k(&pairs, "f").unwrap(), "f").unwrap();
        assert!((m.crank - 0.05).abs() < 1e-14);
        assert!((m.coupler - 0.2).abs() < 1e-14);
        assert!((m.line[1] - 0.01).abs() < 1e-14);
    }

    #[test]
    fn max_offset_matches_a_dense_scan() {
        let l = SliderCrank {
            o2: [0.01, -0.02],
            crank: 0.05,
            coupler: 0.2,
            line: [0.1, 0.03],
            dir: 0.4,
        };
        let (from, to) = (-0.5, 4.0);
        let n = 100_000;
        let dense = (0..=n)
            .map(|k| {
                let phi = from + (to - from) * k as f64 / n as f64;
                cross(unit(l.dir), sub(l.crank_pin(phi), l.line)).abs()
            })
            .fold(0.0, f64::max);
        assert!((l.max_offset(from, to) - dense).abs() < 1e-9);
    }
}
