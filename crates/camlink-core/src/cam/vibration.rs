//! Follower-train vibration: a chain of lumped masses driven by the cam.
//!
//! The train is n masses m₁ … m_n (kg, or kg·m² for an oscillating
//! follower) in series: element i (stiffness k_i, N/m, and viscous damping
//! c_i, N·s/m) joins mass i to mass i − 1, element 1 joins m₁ to the cam's
//! displacement u(t) (the cam contact, held closed: a linear model), and
//! the return spring (rate k_s, preload F₀) pushes the last mass back
//! (Norton, *Cam Design and Manufacturing Handbook*, ch. 10, the one- and
//! two-degree-of-freedom lumped models of DYNACAM):
//!
//!   m_i ẍ_i = k_i (x_{i−1} − x_i) + c_i (ẋ_{i−1} − ẋ_i)
//!           − k_{i+1} (x_i − x_{i+1}) − c_{i+1} (ẋ_i − ẋ_{i+1})
//!           [− k_s x_n − F₀ on the last mass],  x₀ = u.
//!
//! The cam turns at constant ω, u(t) = s(ωt) from the motion program. The
//! dynamic contact force is F_c = k₁ (u − x₁) + c₁ (u̇ − ẋ₁) (the contact
//! opens where it is negative; the model does not follow it off the cam).
//!
//! Integration is the exact discretisation of the linear system over each
//! step, the input taken as its Taylor polynomial of degree 5 in time from
//! the program's exact derivatives at the step's start: the state z = (x, ẋ)
//! and the input jet w = (u, u̇, …, u⁽⁵⁾, 1) form one linear system
//! d/dt (z, w) = [[A, B], [0, N]] (z, w) with N the shift, whose matrix
//! exponential over the step h (scaling and squaring of its Taylor series)
//! maps the state exactly when the input is that polynomial. Steps are laid
//! per segment so that none crosses a segment boundary; the error per step
//! is that of the input's Taylor remainder, O(h⁶ u⁽⁶⁾).
//!
//! The train starts at rest in static equilibrium at θ = 0 and runs
//! `turns` turns; the last turn is reported. The quasi-static position of
//! the last mass for a cam displacement u is
//! x_n* = (u − F₀ S)/(1 + k_s S), S = Σ 1/k_i; the **deviation**
//! x_n − x_n* is the vibration, and the **residual vibration** after a rise
//! or return is the largest |deviation| over the dwell that follows it.

use std::f64::consts::TAU;

use super::motion::Program;
use super::synthesis::CamError;

/// The follower train.
#[derive(Clone, Debug, PartialEq)]
pub struct Chain {
    /// Masses m_i (kg or kg·m²), from the cam outwards.
    pub masses: Vec<f64>,
    /// Stiffness k_i (N/m or N·m/rad) of the element before mass i.
    pub stiffness: Vec<f64>,
    /// Damping c_i (N·s/m or N·m·s/rad) of the element before mass i.
    pub damping: Vec<f64>,
    /// Return spring rate k_s on the last mass.
    pub spring_rate: f64,
    /// Return spring preload F₀ at x_n = 0.
    pub preload: f64,
}

/// The largest |deviation| over a dwell after a rise or return.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Residual {
    /// The rise or return segment.
    pub segment: usize,
    /// Largest |x_n − x_n*| over the dwell that follows (m or rad).
    pub amplitude: f64,
    /// Cam angle (rad) where it occurs.
    pub theta: f64,
}

/// The train's motion over the last turn, sampled at the integration
/// steps (θ from 0 to 2π inclusive).
#[derive(Clone, Debug, PartialEq)]
pub struct Response {
    pub omega: f64,
    /// Cam angle θ (rad).
    pub theta: Vec<f64>,
    /// Cam displacement u.
    pub input: Vec<f64>,
    /// Positions x_i and velocities ẋ_i of each mass: `[mass][sample]`.
    pub position: Vec<Vec<f64>>,
    pub velocity: Vec<Vec<f64>>,
    /// x_n − x_n*.
    pub deviation: Vec<f64>,
    /// Dynamic contact force F_c (N or N·m).
    pub contact: Vec<f64>,
    /// After each rise or return that a dwell follows.
    pub residual: Vec<Residual>,
}

/// The cam displacement as a function of segment and θ: `[u, u′, …, u⁽⁵⁾]`
/// with respect to θ inside segment k.
pub type Input<'a> = dyn Fn(usize, f64) -> [f64; 6] + 'a;

impl Chain {
    fn check(&self) -> Result<(), CamError> {
        let n = self.masses.len();
        if n == 0 || self.stiffness.len() != n || self.damping.len() != n {
            return Err(CamError(format!(
                "a follower train needs as many stiffnesses and dampings as masses, got {} \
                 masses, {} stiffnesses, {} dampings",
                n,
                self.stiffness.len(),
                self.damping.len()
            )));
        }
        for (what, v) in self
            .masses
            .iter()
            .map(|m| ("mass", *m))
            .chain(self.stiffness.iter().map(|k| ("stiffness", *k)))
        {
            if !(v > 0.0 && v.is_finite()) {
                return Err(CamError(format!("{what} must be positive, got {v}")));
            }
        }
        for (what, v) in self
            .damping
            .iter()
            .map(|c| ("damping", *c))
            .chain([("spring rate", self.spring_rate), ("preload", self.preload)])
        {
            if !(v >= 0.0 && v.is_finite()) {
                return Err(CamError(format!(
                    "{what} must be zero or positive, got {v}"
                )));
            }
        }
        Ok(())
    }

    /// S = Σ 1/k_i.
    fn compliance(&self) -> f64 {
        self.stiffness.iter().map(|k| 1.0 / k).sum()
    }

    /// Quasi-static positions of the masses for cam displacement `u`.
    pub fn statics(&self, u: f64) -> Vec<f64> {
        let s = self.compliance();
        let xn = (u - self.preload * s) / (1.0 + self.spring_rate * s);
        let t = self.spring_rate * xn + self.preload;
        let mut x = Vec::with_capacity(self.masses.len());
        let mut prev = u;
        for k in &self.stiffness {
            prev -= t / k;
            x.push(prev);
        }
        x
    }

    /// The augmented matrix [[A, B], [0, N]] (row-major, size 2n + 7) for
    /// cam speed ω (the input jet in time).
    fn system(&self) -> (usize, Vec<f64>) {
        let n = self.masses.len();
        let dim = 2 * n + 7;
        let mut a = vec![0.0; dim * dim];
        let mut set = |r: usize, c: usize, v: f64| a[r * dim + c] += v;
        let (u, du, one) = (2 * n, 2 * n + 1, 2 * n + 6);
        for i in 0..n {
            set(i, n + i, 1.0);
            let m = self.masses[i];
            let r = n + i;
            // Element i, between mass i − 1 (or the cam) and mass i.
            let (k, c) = (self.stiffness[i], self.damping[i]);
            set(r, i, -k / m);
            set(r, n + i, -c / m);
            if i == 0 {
                set(r, u, k / m);
                set(r, du, c / m);
            } else {
                set(r, i - 1, k / m);
                set(r, n + i - 1, c / m);
            }
            // Element i + 1, or the return spring.
            if i + 1 < n {
                let (k, c) = (self.stiffness[i + 1], self.damping[i + 1]);
                set(r, i, -k / m);
                set(r, n + i, -c / m);
                set(r, i + 1, k / m);
                set(r, n + i + 1, c / m);
            } else {
                set(r, i, -self.spring_rate / m);
                set(r, one, -self.preload / m);
            }
        }
        for j in 0..5 {
            set(u + j, u + j + 1, 1.0);
        }
        (dim, a)
    }
}

/// e^M (row-major, size `dim`) by scaling and squaring of its Taylor
/// series, summed until a term no longer changes the sum.
fn expm(dim: usize, m: &[f64]) -> Vec<f64> {
    let norm = (0..dim)
        .map(|r| {
            m[r * dim..(r + 1) * dim]
                .iter()
                .map(|v| v.abs())
                .sum::<f64>()
        })
        .fold(0.0, f64::max);
    let mut squarings = 0;
    let mut scale = 1.0;
    while norm * scale > 0.25 {
        scale *= 0.5;
        squarings += 1;
    }
    let mul = |a: &[f64], b: &[f64]| {
        let mut c = vec![0.0; dim * dim];
        for i in 0..dim {
            for k in 0..dim {
                let aik = a[i * dim + k];
                if aik != 0.0 {
                    for j in 0..dim {
                        c[i * dim + j] += aik * b[k * dim + j];
                    }
                }
            }
        }
        c
    };
    let ms: Vec<f64> = m.iter().map(|v| v * scale).collect();
    let mut sum = vec![0.0; dim * dim];
    for i in 0..dim {
        sum[i * dim + i] = 1.0;
    }
    let mut term = sum.clone();
    for k in 1..40 {
        term = mul(&term, &ms);
        let inv = 1.0 / k as f64;
        term.iter_mut().for_each(|v| *v *= inv);
        let mut changed = false;
        for (s, t) in sum.iter_mut().zip(&term) {
            let before = *s;
            *s += t;
            changed |= *s != before;
        }
        if !changed {
            break;
        }
    }
    for _ in 0..squarings {
        sum = mul(&sum, &sum);
    }
    sum
}

/// The train driven by the motion program at cam speed `omega` (rad/s):
/// about `steps_per_turn` steps per turn, `turns` turns, the last reported.
pub fn simulate(
    program: &Program,
    chain: &Chain,
    omega: f64,
    steps_per_turn: usize,
    turns: usize,
) -> Result<Response, CamError> {
    simulate_input(
        program,
        &|k, t| program.eval_in(k, t),
        chain,
        omega,
        steps_per_turn,
        turns,
    )
}

/// [`simulate`] with another cam displacement on the program's segments
/// (a corrected program, [`polydyne`]).
pub fn simulate_input(
    program: &Program,
    input: &Input<'_>,
    chain: &Chain,
    omega: f64,
    steps_per_turn: usize,
    turns: usize,
) -> Result<Response, CamError> {
    chain.check()?;
    if !(omega > 0.0 && omega.is_finite()) {
        return Err(CamError(format!(
            "the cam speed must be positive, got {omega} rad/s"
        )));
    }
    if !(1..=10_000_000).contains(&steps_per_turn) || !(1..=1000).contains(&turns) {
        return Err(CamError(format!(
            "steps per turn must be 1 to 10⁷ and turns 1 to 1000, got {steps_per_turn} and \
             {turns}"
        )));
    }
    let n = chain.masses.len();
    let (dim, a) = chain.system();
    let starts = program.starts();
    let specs = program.specs();
    // Per segment: steps, and the state map [Φ Γ] over one step.
    let maps: Vec<(usize, Vec<f64>)> = specs
        .iter()
        .map(|sp| {
            let steps = ((sp.span / TAU * steps_per_turn as f64).ceil() as usize).max(1);
            let h = sp.span / (steps as f64 * omega);
            let m: Vec<f64> = a.iter().map(|v| v * h).collect();
            (steps, expm(dim, &m))
        })
        .collect();
    let jet = |k: usize, t: f64| {
        let d = input(k, t);
        let mut w = [0.0; 7];
        let mut p = 1.0;
        for j in 0..6 {
            w[j] = d[j] * p;
            p *= omega;
        }
        w[6] = 1.0;
        w
    };
    let x0 = chain.statics(input(0, 0.0)[0]);
    let mut z = vec![0.0; 2 * n];
    z[..n].copy_from_slice(&x0);
    let mut out = Response {
        omega,
        theta: Vec::new(),
        input: Vec::new(),
        position: vec![Vec::new(); n],
        velocity: vec![Vec::new(); n],
        deviation: Vec::new(),
        contact: Vec::new(),
        residual: Vec::new(),
    };
    let s_total = chain.compliance();
    let record = |out: &mut Response, z: &[f64], theta: f64, w: &[f64; 7]| {
        out.theta.push(theta);
        out.input.push(w[0]);
        for i in 0..n {
            out.position[i].push(z[i]);
            out.velocity[i].push(z[n + i]);
        }
        let star = (w[0] - chain.preload * s_total) / (1.0 + chain.spring_rate * s_total);
        out.deviation.push(z[n - 1] - star);
        out.contact
            .push(chain.stiffness[0] * (w[0] - z[0]) + chain.damping[0] * (w[1] - z[n]));
    };
    let mut next = vec![0.0; 2 * n];
    let mut seg_first = Vec::with_capacity(specs.len());
    for turn in 0..turns {
        let last = turn + 1 == turns;
        for (k, (steps, e)) in maps.iter().enumerate() {
            if last {
                seg_first.push(out.theta.len());
            }
            for j in 0..*steps {
                let theta = starts[k] + specs[k].span * j as f64 / *steps as f64;
                let w = jet(k, theta);
                if last {
                    record(&mut out, &z, theta, &w);
                }
                for (r, nr) in next.iter_mut().enumerate() {
                    let row = &e[r * dim..(r + 1) * dim];
                    *nr = row[..2 * n].iter().zip(&z).map(|(a, b)| a * b).sum::<f64>()
                        + row[2 * n..].iter().zip(&w).map(|(a, b)| a * b).sum::<f64>();
                }
                std::mem::swap(&mut z, &mut next);
            }
        }
    }
    // The end of the turn, θ = 2π, with the input of the last segment.
    let kl = specs.len() - 1;
    let w = jet(kl, TAU);
    record(&mut out, &z, TAU, &w);
    seg_first.push(out.theta.len());
    for k in 0..specs.len() {
        let nk = (k + 1) % specs.len();
        if specs[k].lift != 0.0 && specs[nk].lift == 0.0 {
            // The dwell's samples, its end included.
            let (a, b) = if nk == 0 {
                (0, seg_first[1] + 1)
            } else {
                (seg_first[nk], seg_first[nk + 1] + 1)
            };
            let b = b.min(out.theta.len());
            let (i, v) = (a..b)
                .map(|i| (i, out.deviation[i].abs()))
                .max_by(|x, y| x.1.total_cmp(&y.1))
                .expect("a dwell has samples");
            out.residual.push(Residual {
                segment: k,
                amplitude: v,
                theta: out.theta[i],
            });
        }
    }
    Ok(out)
}

/// The polydyne correction of the program for a one-mass train at cam
/// speed ω (rad/s): the cam displacement y = s + (m ω² s″ + k_s s)/k₁
/// (damping neglected) makes the mass follow s exactly (offset by the
/// static −F₀/(k₁ + k_s)) at that speed. Its derivatives to the third,
/// from the program's to the fifth; the fourth and fifth are set to zero.
pub fn polydyne<'a>(
    program: &'a Program,
    chain: &Chain,
    omega: f64,
) -> Result<impl Fn(usize, f64) -> [f64; 6] + 'a, CamError> {
    chain.check()?;
    if chain.masses.len() != 1 {
        return Err(CamError(format!(
            "the polydyne correction takes a one-mass train, got {} masses",
            chain.masses.len()
        )));
    }
    let (m, k, ks) = (chain.masses[0], chain.stiffness[0], chain.spring_rate);
    let a = m * omega * omega / k;
    let b = ks / k;
    Ok(move |seg: usize, t: f64| {
        let d = program.eval_in(seg, t);
        let mut y = [0.0; 6];
        for j in 0..4 {
            y[j] = d[j] * (1.0 + b) + a * d[j + 2];
        }
        y
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cam::{LawKind, SegmentSpec};
    use std::f64::consts::PI;

    fn program(lift: f64, rise: f64) -> Program {
        Program::new(&[
            SegmentSpec::new(LawKind::Cycloidal, rise, lift),
            SegmentSpec::new(LawKind::Dwell, PI - rise, 0.0),
            SegmentSpec::new(LawKind::Cycloidal, rise, -lift),
            SegmentSpec::new(LawKind::Dwell, PI - rise, 0.0),
        ])
        .unwrap()
    }

    /// The exponential of a 2×2 rotation generator is the rotation.
    #[test]
    fn expm_of_a_rotation() {
        let w = 7.3;
        let e = expm(2, &[0.0, w, -w, 0.0]);
        let want = [w.cos(), w.sin(), -w.sin(), w.cos()];
        for (g, x) in e.iter().zip(want) {
            assert!((g - x).abs() < 1e-13, "{e:?}");
        }
    }

    /// One undamped mass on a stiff link driven by a cycloidal rise of
    /// lift h over time T (Koster, *Vibrations of Cam Mechanisms*, the
    /// residual response; derived here): with e = x − s, ë + ω_n² e = −s̈,
    /// s̈ = a₀ sin Ωτ, a₀ = 2πh/T², Ω = 2π/T, from rest, Duhamel's integral
    /// gives at the end of the rise
    ///   e(T) = a₀ Ω sin(ω_n T)/(ω_n (ω_n² − Ω²)),
    ///   ė(T) = −a₀ Ω (1 − cos ω_n T)/(ω_n² − Ω²),
    /// and the free vibration over the dwell that follows has amplitude
    ///   A = √(e² + (ė/ω_n)²) = h |sin πr| / (π r |r² − 1|), r = ω_n T/(2π).
    #[test]
    fn issue32_residual_vibration_after_a_cycloidal_rise_matches_closed_form() {
        let (lift, beta) = (0.01, PI / 3.0);
        for (m, k, omega) in [
            (0.2, 4.0e5, 150.0),
            (0.5, 2.0e5, 300.0),
            (0.1, 1.0e6, 100.0),
        ] {
            let chain = Chain {
                masses: vec![m],
                stiffness: vec![k],
                damping: vec![0.0],
                spring_rate: 0.0,
                preload: 0.0,
            };
            let p = program(lift, beta);
            let steps = 36_000;
            let r = simulate(&p, &chain, omega, steps, 1).unwrap();
            let wn: f64 = (k / m).sqrt();
            let t = beta / omega;
            let big = 2.0 * PI / t;
            let a0 = 2.0 * PI * lift / (t * t);
            let e_t = a0 * big * (wn * t).sin() / (wn * (wn * wn - big * big));
            let de_t = -a0 * big * (1.0 - (wn * t).cos()) / (wn * wn - big * big);
            // The sample at θ = β, the dwell's first.
            let i = r
                .theta
                .iter()
                .position(|&x| (x - beta).abs() < 1e-12)
                .unwrap();
            let (e, de) = (r.position[0][i] - lift, r.velocity[0][i]);
            assert!((e - e_t).abs() < 1e-9 * lift, "{e} vs {e_t}");
            assert!((de - de_t).abs() < 1e-9 * lift * wn, "{de} vs {de_t}");
            let ratio = wn * t / (2.0 * PI);
            let amp = lift * (PI * ratio).sin().abs() / (PI * ratio * (ratio * ratio - 1.0).abs());
            assert!(((e * e + (de / wn).powi(2)).sqrt() - amp).abs() < 1e-9 * lift);
            // The sampled peak over the dwell: at most A, at least A cos(ω_n h/2).
            let res = r.residual.iter().find(|x| x.segment == 0).unwrap();
            // The dwell's time step.
            let dwell = PI - beta;
            let h = dwell / ((dwell / TAU * steps as f64).ceil() * omega);
            assert!(
                res.amplitude <= amp * (1.0 + 1e-9),
                "{} vs {amp}",
                res.amplitude
            );
            assert!(res.amplitude >= amp * (wn * h / 2.0).cos() - 1e-9 * lift);
        }
    }

    /// Two masses with damping against an independent classical RK4 on a
    /// step 1/20 of the exact discretisation's (the input evaluated from
    /// the program at every stage).
    #[test]
    fn issue32_two_mass_train_matches_runge_kutta() {
        let p = program(0.008, 1.2);
        let chain = Chain {
            masses: vec![0.08, 0.12],
            stiffness: vec![3.0e6, 6.0e5],
            damping: vec![40.0, 15.0],
            spring_rate: 2.0e4,
            preload: 250.0,
        };
        let omega = 200.0;
        let r = simulate(&p, &chain, omega, 3600, 2).unwrap();
        // RK4 over two turns, segment by segment on the same grid / 20.
        let f = |k: usize, t: f64, z: &[f64; 4]| {
            let th = omega * t;
            let d = p.eval_in(k, th);
            let (u, du) = (d[0], omega * d[1]);
            let (m1, m2) = (chain.masses[0], chain.masses[1]);
            let (k1, k2, c1, c2) = (3.0e6, 6.0e5, 40.0, 15.0);
            let f1 = k1 * (u - z[0]) + c1 * (du - z[2]) - k2 * (z[0] - z[1]) - c2 * (z[2] - z[3]);
            let f2 = k2 * (z[0] - z[1]) + c2 * (z[2] - z[3]) - 2.0e4 * z[1] - 250.0;
            [z[2], z[3], f1 / m1, f2 / m2]
        };
        let x0 = chain.statics(0.0);
        let mut z = [x0[0], x0[1], 0.0, 0.0];
        let starts = p.starts();
        let specs = p.specs();
        let mut at_end = Vec::new();
        for _turn in 0..2 {
            for (k, sp) in specs.iter().enumerate() {
                let n = ((sp.span / TAU * 3600.0).ceil() as usize) * 20;
                let h = sp.span / (n as f64 * omega);
                for j in 0..n {
                    let t = (starts[k] + sp.span * j as f64 / n as f64) / omega;
                    let add = |a: &[f64; 4], b: &[f64; 4], s: f64| {
                        [
                            a[0] + s * b[0],
                            a[1] + s * b[1],
                            a[2] + s * b[2],
                            a[3] + s * b[3],
                        ]
                    };
                    let k1 = f(k, t, &z);
                    let k2 = f(k, t + h / 2.0, &add(&z, &k1, h / 2.0));
                    let k3 = f(k, t + h / 2.0, &add(&z, &k2, h / 2.0));
                    let k4 = f(k, t + h, &add(&z, &k3, h));
                    for i in 0..4 {
                        z[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
                    }
                }
                at_end.push(z);
            }
        }
        // Ends of the segments of the last turn.
        let n = r.theta.len();
        for (k, zk) in at_end[specs.len()..].iter().enumerate() {
            let th = if k + 1 == specs.len() {
                TAU
            } else {
                starts[k + 1]
            };
            let i = (0..n).find(|&i| (r.theta[i] - th).abs() < 1e-12).unwrap();
            for m in 0..2 {
                assert!(
                    (r.position[m][i] - zk[m]).abs() < 1e-10,
                    "mass {m} at {th}: {} vs {}",
                    r.position[m][i],
                    zk[m]
                );
                assert!((r.velocity[m][i] - zk[2 + m]).abs() < 1e-7);
            }
        }
        // A stiff train follows nearly rigidly: contact force near the
        // rigid one m s̈ + k_s s + F₀ where s is still.
        assert!(r.contact.iter().all(|c| c.is_finite()));
    }

    /// The polydyne program makes the single mass follow s (offset by the
    /// static −F₀/(k + k_s)) at its design speed; the plain program leaves
    /// it vibrating.
    #[test]
    fn issue32_polydyne_correction_removes_the_vibration() {
        let p = Program::new(&[
            SegmentSpec::new(LawKind::Poly4567, 1.5, 0.01),
            SegmentSpec::new(LawKind::Dwell, PI - 1.5, 0.0),
            SegmentSpec::new(LawKind::Poly4567, 1.5, -0.01),
            SegmentSpec::new(LawKind::Dwell, PI - 1.5, 0.0),
        ])
        .unwrap();
        let chain = Chain {
            masses: vec![0.15],
            stiffness: vec![2.0e5],
            damping: vec![0.0],
            spring_rate: 2.5e4,
            preload: 200.0,
        };
        let omega = 250.0;
        let y = polydyne(&p, &chain, omega).unwrap();
        let corrected = simulate_input(&p, &y, &chain, omega, 36_000, 1).unwrap();
        let plain = simulate(&p, &chain, omega, 36_000, 1).unwrap();
        let offset = -200.0 / (2.0e5 + 2.5e4);
        let err = |r: &Response| {
            (0..r.theta.len())
                .map(|i| (r.position[0][i] - offset - p.eval(r.theta[i] % TAU)[0]).abs())
                .fold(0.0, f64::max)
        };
        assert!(err(&corrected) < 1e-8, "{}", err(&corrected));
        assert!(err(&plain) > 1e-4, "{}", err(&plain));
    }
}
