//! What any four-bar is, in closed form: its Grashof class, the crank's
//! limits (if it does not turn fully), the transmission angle's extremes
//! over all the positions it reaches, and its toggle positions.
//!
//! Symbols as in [`crate::fourbar`]: θ_d is the angle of O₄ − O₂, and
//! - E² = d² + a² − 2ad cos(φ − θ_d), a signed, so the crank stops where
//!   the coupler and the rocker fall in line, E = b + |c| or |b − |c||;
//! - |B − O₂|² = d² + c² + 2cd cos(ψ − θ_d), c signed, so the rocker stops
//!   where the crank and the coupler fall in line, |B − O₂| = b + |a|
//!   (extended) or |b − |a|| (folded).

use serde_json::{json, Value};

use crate::fourbar::{angle, mod_tau, sub, wrap_pi, FourBar, Grashof};

/// A toggle position.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Toggle {
    /// `crank_limit` (coupler and rocker in line: the crank cannot pass
    /// when it drives) or `rocker_extreme` (crank and coupler in line: the
    /// rocker stops and turns back).
    pub kind: &'static str,
    /// `extended` or `folded`.
    pub shape: &'static str,
    /// Crank angle φ and rocker angle ψ there (rad, in (−π, π]).
    pub phi: f64,
    pub psi: f64,
    /// The assembly branch σ the toggle lies on (0 at a crank limit, where
    /// the two branches meet).
    pub branch: f64,
}

/// The properties of a four-bar.
#[derive(Clone, Debug, PartialEq)]
pub struct Properties {
    pub grashof: Grashof,
    /// Whether the crank turns fully.
    pub crank_turns: bool,
    /// The transmission angle's extremes over every position reached (rad).
    pub transmission_min: f64,
    pub transmission_max: f64,
    pub toggles: Vec<Toggle>,
}

/// The properties of `l`; `None` if it assembles nowhere.
pub fn properties(l: &FourBar) -> Option<Properties> {
    let [d, _, b, c_abs] = l.lengths();
    let (a, c) = (l.crank, l.rocker);
    let theta = angle(sub(l.o4, l.o2));
    let e_lo = (d - a.abs()).abs().max((b - c_abs).abs());
    let e_hi = (d + a.abs()).min(b + c_abs);
    if e_lo > e_hi || d == 0.0 || a == 0.0 || c == 0.0 {
        return None;
    }
    let mut toggles = Vec::new();
    // Crank limits: E = b + |c| (extended) or |b − |c|| (folded).
    for (e, shape) in [(b + c_abs, "extended"), ((b - c_abs).abs(), "folded")] {
        let k = (d * d + a * a - e * e) / (2.0 * a * d);
        if (-1.0..=1.0).contains(&k) {
            for s in [1.0, -1.0] {
                let phi = wrap_pi(theta + s * k.acos());
                // Both branches meet at a toggle: either gives ψ.
                if let Some(p) = l.position(phi, 1.0) {
                    toggles.push(Toggle {
                        kind: "crank_limit",
                        shape,
                        phi,
                        psi: p.psi,
                        branch: 0.0,
                    });
                }
                if k.abs() == 1.0 {
                    break;
                }
            }
        }
    }
    // Rocker extremes: |B − O₂| = b + |a| or |b − |a||.
    for (len, shape) in [(b + a.abs(), "extended"), ((b - a.abs()).abs(), "folded")] {
        let k = (len * len - d * d - c * c) / (2.0 * c * d);
        if (-1.0..=1.0).contains(&k) {
            for s in [1.0, -1.0] {
                let psi = wrap_pi(theta + s * k.acos());
                let bp = [l.o4[0] + c * psi.cos(), l.o4[1] + c * psi.sin()];
                let towards = angle(sub(bp, l.o2));
                // A on the ray O₂→B when extended (or b < |a|), else opposite;
                // a negative crank points the other way along its body.
                let mut phi = towards;
                if shape == "folded" && b > a.abs() {
                    phi += std::f64::consts::PI;
                }
                if a < 0.0 {
                    phi += std::f64::consts::PI;
                }
                let phi = wrap_pi(phi);
                toggles.push(Toggle {
                    kind: "rocker_extreme",
                    shape,
                    phi,
                    psi: wrap_pi(psi),
                    branch: l.branch(l.crank_pin(phi), bp),
                });
                if k.abs() == 1.0 {
                    break;
                }
            }
        }
    }
    toggles.sort_by(|p, q| mod_tau(p.phi).total_cmp(&mod_tau(q.phi)));
    let grashof = l.grashof();
    Some(Properties {
        grashof,
        crank_turns: grashof.crank_turns_fully(),
        transmission_min: l.transmission(e_lo),
        transmission_max: l.transmission(e_hi),
        toggles,
    })
}

/// The properties as the report's JSON (`null` if it assembles nowhere).
pub fn properties_json(l: &FourBar) -> Value {
    match properties(l) {
        None => Value::Null,
        Some(p) => json!({
            "grashof": p.grashof.name(),
            "crank_turns_fully": p.crank_turns,
            "transmission": { "min": p.transmission_min, "max": p.transmission_max },
            "toggles": p.toggles.iter().map(|t| json!({
                "kind": t.kind, "shape": t.shape, "crank_angle": t.phi, "rocker_angle": t.psi,
                "branch": t.branch,
            })).collect::<Vec<_>>(),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fourbar::{cross, norm};
    use std::f64::consts::TAU;

    /// At each toggle the links named are in line (cross product 0), and
    /// the transmission extremes equal those of a dense scan of the crank.
    #[test]
    fn issue31_toggles_and_transmission_extremes() {
        let cases = [
            // crank-rocker: two rocker extremes, no crank limit
            FourBar {
                o2: [0.0, 0.0],
                o4: [0.4, 0.0],
                crank: 0.12,
                coupler: 0.38,
                rocker: 0.3,
            },
            // triple-rocker: the crank stops at limits
            FourBar {
                o2: [0.1, 0.2],
                o4: [0.5, 0.1],
                crank: 0.3,
                coupler: 0.35,
                rocker: 0.32,
            },
        ];
        for l in cases {
            let p = properties(&l).unwrap();
            let (mut rocker, mut limit) = (0, 0);
            for t in &p.toggles {
                let a = l.crank_pin(t.phi);
                let b = [
                    l.o4[0] + l.rocker * t.psi.cos(),
                    l.o4[1] + l.rocker * t.psi.sin(),
                ];
                // The linkage closes there.
                assert!((norm(sub(b, a)) - l.coupler).abs() < 1e-12, "{t:?}");
                let x = if t.kind == "rocker_extreme" {
                    rocker += 1;
                    cross(sub(a, l.o2), sub(b, a))
                } else {
                    limit += 1;
                    cross(sub(b, a), sub(b, l.o4))
                };
                assert!(x.abs() < 1e-12, "{t:?}: cross {x}");
            }
            if p.crank_turns {
                // Two extremes on each branch.
                assert_eq!((rocker, limit), (4, 0));
                for sigma in [1.0, -1.0] {
                    let on = p.toggles.iter().filter(|t| t.branch == sigma).count();
                    assert_eq!(on, 2);
                }
            } else {
                assert!(limit >= 2);
            }
            // Dense scan of μ over every crank angle where it assembles.
            let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
            for k in 0..200_000 {
                let phi = TAU * k as f64 / 200_000.0;
                let e = norm(sub(l.o4, l.crank_pin(phi)));
                let mu = l.transmission(e);
                if mu.is_finite() {
                    lo = lo.min(mu);
                    hi = hi.max(mu);
                }
            }
            // Where the crank stops at a limit μ reaches 0 or π there, and a
            // scan approaches it as the square root of its step: the closed
            // form bounds the scan and lies within 0.01 rad of it.
            let tol = if p.crank_turns { 1e-4 } else { 1e-2 };
            assert!(p.transmission_min <= lo + 1e-12 && lo - p.transmission_min < tol);
            assert!(p.transmission_max >= hi - 1e-12 && p.transmission_max - hi < tol);
        }
    }
}
