//! Full force balance of a four-bar and of a slider-crank by counterweights
//! (the linearly independent vectors method of Berkof and Lowen, 1969;
//! Norton, *Design of Machinery*, §12.4 and §13.8).
//!
//! The shaking force is −M ä_G for the total mass M and its centroid G;
//! the mechanism is force balanced when G stays put. Each link k gets a
//! link frame: origin at its first joint P_k, x axis towards its second
//! joint Q_k, length L_k = |P_k Q_k|; its centroid there is the complex
//! number p_k. With link angles θ₂, θ₃, θ₄ (e^{iθ} written E):
//!
//! - four-bar, crank a = O₂A, coupler b = AB, rocker c = O₄B, ground
//!   d = O₂O₄: the loop a E₂ + b E₃ = d + c E₄ removes E₃ from
//!   Σ m R_G, leaving E₂ (m₂p₂ + m₃a − m₃p₃a/b) + E₄ (m₄p₄ + m₃p₃c/b) +
//!   const, so G stays put when
//!   m₂p₂ = −m₃ a (1 − p₃/b) and m₄p₄ = −m₃ p₃ c/b;
//! - slider-crank, crank a = OA, rod b = AB, slider pin B on the guide:
//!   Σ m R_G = E₂ (m₂p₂ + (m₃ + m₄) a) + E₃ (m₃p₃ + m₄ b) + const, and
//!   E₃'s real part is not linear in E₂, so both must vanish: the rod
//!   carries the slider's moment (m₃p₃ = −m₄ b, its centroid with the
//!   slider's at the crank pin A), then the crank carries both
//!   (m₂p₂ = −(m₃ + m₄) a). The slider itself carries no counterweight.
//!
//! Each link whose first moment m_k p_k differs from the one required gets
//! a point mass m_c at radius L_k in its link frame, where
//! m_c p_c = (required − m_k p_k). The body's mass, centroid and
//! centroidal inertia become those of the body plus the point mass.

use crate::constraint::{BodyId, Constraint, Equations};
use crate::math::V2;
use crate::model::{Body, Model};

/// A counterweight: a point mass on a body, and the body's new mass
/// properties.
#[derive(Clone, Debug, PartialEq)]
pub struct Counterweight {
    pub body: String,
    /// m_c (kg).
    pub mass: f64,
    /// Where, in the body frame (m).
    pub at: V2,
    /// Its distance from the link's first joint (m).
    pub radius: f64,
    /// The body with the counterweight: mass (kg), centroid in the body
    /// frame (m), centroidal moment of inertia (kg·m²).
    pub new_mass: f64,
    pub new_centroid: V2,
    pub new_inertia: f64,
}

/// The counterweights that force balance a linkage.
#[derive(Clone, Debug, PartialEq)]
pub struct Balance {
    /// `"four_bar"` or `"slider_crank"`.
    pub linkage: &'static str,
    /// What the counterweights balance, in words.
    pub balanced: &'static str,
    pub counterweights: Vec<Counterweight>,
}

type C = (f64, f64);

fn mul(a: C, b: C) -> C {
    (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0)
}

fn scale(a: C, s: f64) -> C {
    (a.0 * s, a.1 * s)
}

/// A link in its body: first joint P and second joint Q (body frame, m).
#[derive(Clone, Copy)]
struct Link {
    body: BodyId,
    p: V2,
    q: V2,
}

impl Link {
    fn length(&self) -> f64 {
        (self.q[0] - self.p[0]).hypot(self.q[1] - self.p[1])
    }
    /// The unit vector P→Q as a complex number.
    fn dir(&self) -> C {
        let l = self.length();
        ((self.q[0] - self.p[0]) / l, (self.q[1] - self.p[1]) / l)
    }
    /// A body-frame point in the link frame.
    fn to_link(self, s: V2) -> C {
        let d = self.dir();
        mul((s[0] - self.p[0], s[1] - self.p[1]), (d.0, -d.1))
    }
    /// A link-frame point in the body frame.
    fn to_body(self, z: C) -> V2 {
        let w = mul(z, self.dir());
        [self.p[0] + w.0, self.p[1] + w.1]
    }
}

/// The body-frame points of the revolute joint between bodies a and b
/// (on a, on b), if there is one.
fn revolute(model: &Model, a: BodyId, b: BodyId) -> Option<(V2, V2)> {
    model
        .joints
        .iter()
        .filter(|j| !j.driver)
        .find_map(|j| match &j.constraint {
            Constraint::Revolute(r) if r.body_i == a && r.body_j == b => Some((r.s_i, r.s_j)),
            Constraint::Revolute(r) if r.body_i == b && r.body_j == a => Some((r.s_j, r.s_i)),
            _ => None,
        })
}

/// The bodies other than `not` joined to `a` by a revolute joint.
fn partners(model: &Model, a: BodyId, not: BodyId) -> Vec<BodyId> {
    let mut out = Vec::new();
    for j in model.joints.iter().filter(|j| !j.driver) {
        if let Constraint::Revolute(r) = &j.constraint {
            let [bi, bj] = [r.body_i, r.body_j];
            if bi == a && bj != not {
                out.push(bj);
            } else if bj == a && bi != not {
                out.push(bi);
            }
        }
    }
    out
}

/// A translational joint between the ground and `b`.
fn guided(model: &Model, b: BodyId) -> bool {
    model.joints.iter().filter(|j| !j.driver).any(|j| {
        matches!(&j.constraint, Constraint::Translational(_))
            && j.constraint.bodies().contains(&b)
            && j.constraint.bodies().contains(&BodyId::GROUND)
    })
}

/// The counterweights that fully force balance the four-bar or
/// slider-crank whose input link is `crank` (pinned to the ground), or why
/// the model is neither.
pub fn full_force_balance(model: &Model, crank: BodyId) -> Result<Balance, String> {
    let g = BodyId::GROUND;
    let moving = model.bodies.len() - 1;
    let joints = model.joints.iter().filter(|j| !j.driver).count();
    let not = || {
        "balancing by counterweights needs a four-bar (three moving links, four revolute \
         joints) or an in-line or offset slider-crank (crank, rod, slider on a guide)"
            .to_string()
    };
    if moving != 3 || joints != 4 {
        return Err(not());
    }
    let (o2, _) = revolute(model, crank, g).ok_or_else(not)?;
    let [mid] = partners(model, crank, g)[..] else {
        return Err(not());
    };
    let (a_on_crank, a_on_mid) = revolute(model, crank, mid).ok_or_else(not)?;
    let [last] = partners(model, mid, crank)[..] else {
        return Err(not());
    };
    let (b_on_mid, b_on_last) = revolute(model, mid, last).ok_or_else(not)?;
    let l2 = Link {
        body: crank,
        p: o2,
        q: a_on_crank,
    };
    let l3 = Link {
        body: mid,
        p: a_on_mid,
        q: b_on_mid,
    };
    let mass = |b: BodyId| model.bodies[b.0].mass;
    let moment = |l: &Link| scale(l.to_link(model.bodies[l.body.0].centroid), mass(l.body));
    let (a, b) = (l2.length(), l3.length());
    let (m3, p3) = (mass(mid), l3.to_link(model.bodies[mid.0].centroid));
    if let Some((o4, _)) = revolute(model, last, g) {
        let l4 = Link {
            body: last,
            p: o4,
            q: b_on_last,
        };
        let c = l4.length();
        // m₂p₂ = −m₃ a (1 − p₃/b), m₄p₄ = −m₃ p₃ c/b.
        let need2 = scale((1.0 - p3.0 / b, -p3.1 / b), -m3 * a);
        let need4 = scale(p3, -m3 * c / b);
        Ok(Balance {
            linkage: "four_bar",
            balanced: "the shaking force (the total centroid stays put); counterweights on the \
                       crank and the rocker, the coupler unchanged",
            counterweights: [(l2, need2), (l4, need4)]
                .iter()
                .filter_map(|(l, need)| counterweight(model, l, moment(l), *need))
                .collect(),
        })
    } else if guided(model, last) {
        // The rod first: m₃p₃ = −m₄ b; then the crank: m₂p₂ = −(m₃′ + m₄) a.
        let m4 = mass(last);
        let rod = counterweight(model, &l3, moment(&l3), (-m4 * b, 0.0));
        let m3_new = rod.as_ref().map_or(m3, |c| c.new_mass);
        let crank_cw = counterweight(model, &l2, moment(&l2), (-(m3_new + m4) * a, 0.0));
        Ok(Balance {
            linkage: "slider_crank",
            balanced: "the shaking force (the total centroid stays put); a counterweight on the \
                       rod puts the rod and slider's centroid at the crank pin, one on the crank \
                       puts the whole centroid at the crank's pivot; the slider carries none",
            counterweights: [rod, crank_cw].into_iter().flatten().collect(),
        })
    } else {
        Err(not())
    }
}

/// The counterweight that changes link `l`'s first moment from `has` to
/// `need` (kg·m, link frame), at radius L; `None` when they agree to
/// rounding.
fn counterweight(model: &Model, l: &Link, has: C, need: C) -> Option<Counterweight> {
    let d = (need.0 - has.0, need.1 - has.1);
    let size = d.0.hypot(d.1);
    let body = &model.bodies[l.body.0];
    if size <= 1e-12 * (has.0.hypot(has.1) + need.0.hypot(need.1)) {
        return None;
    }
    let r = l.length();
    Some(point_mass(body, size / r, l.to_body(scale(d, r / size)), r))
}

/// A point mass `mc` (kg) at `at` (body frame, m; `radius` from the link's
/// first joint) on `body`, and the body's mass properties with it.
fn point_mass(body: &Body, mc: f64, at: V2, radius: f64) -> Counterweight {
    let m = body.mass + mc;
    let c = body.centroid;
    let nc = [
        (body.mass * c[0] + mc * at[0]) / m,
        (body.mass * c[1] + mc * at[1]) / m,
    ];
    let sq = |p: V2| (p[0] - nc[0]).powi(2) + (p[1] - nc[1]).powi(2);
    Counterweight {
        body: body.name.clone(),
        mass: mc,
        at,
        radius,
        new_mass: m,
        new_centroid: nc,
        new_inertia: body.inertia + body.mass * sq(c) + mc * sq(at),
    }
}

/// A partial balance: the counterweights of the full balance `full`, the
/// one on link k with its mass times the factor `k[k]` ≥ 0 at the same
/// place (so its first moment is that fraction of the full balance's), on
/// the bodies of `model`. Factors of 1 give `full` again; 0 leaves a link
/// as it is. An error names a factor that is negative or missing.
pub fn scaled(model: &Model, full: &Balance, k: &[f64]) -> Result<Balance, String> {
    if k.len() != full.counterweights.len() {
        return Err(format!(
            "{} factors for {} counterweights",
            k.len(),
            full.counterweights.len()
        ));
    }
    let mut counterweights = Vec::with_capacity(k.len());
    for (cw, &f) in full.counterweights.iter().zip(k) {
        if !(f >= 0.0 && f.is_finite()) {
            return Err(format!(
                "the factor of the counterweight on '{}' must be a number ≥ 0, not {f}",
                cw.body
            ));
        }
        let body = model
            .bodies
            .iter()
            .find(|b| b.name == cw.body)
            .ok_or_else(|| format!("no body '{}'", cw.body))?;
        counterweights.push(point_mass(body, f * cw.mass, cw.at, cw.radius));
    }
    Ok(Balance {
        linkage: full.linkage,
        balanced: "part of the shaking force: each counterweight of the full balance scaled by \
                   its factor",
        counterweights,
    })
}

/// `model` with the counterweights of `balance` on its bodies.
pub fn apply(model: &Model, balance: &Balance) -> Model {
    let mut out = model.clone();
    for cw in &balance.counterweights {
        if let Some(b) = out.bodies.iter_mut().find(|b| b.name == cw.body) {
            b.mass = cw.new_mass;
            b.centroid = cw.new_centroid;
            b.inertia = cw.new_inertia;
        }
    }
    out
}
