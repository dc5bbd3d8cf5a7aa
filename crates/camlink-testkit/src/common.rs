//! Mechanisms built in code, shared by integration tests and benchmarks.

use camlink_core::constraint::relative::{RelCoord, RelativeCoord};
use camlink_core::constraint::revolute::Revolute;
use camlink_core::{Body, BodyId, Model, Point, TimeFn};

/// Four-bar link lengths (m): ground d, crank a, coupler b, rocker c.
pub const FOUR_BAR: [f64; 4] = [0.4, 0.1, 0.35, 0.3];

/// Crank speed ω₂ (rad/s) and starting angle θ₂(0) (rad).
pub const CRANK_SPEED: f64 = 2.0 * std::f64::consts::PI;
pub const CRANK_START: f64 = 0.3;

fn body(name: &str, q0: [f64; 3], points: &[(&str, [f64; 2])]) -> Body {
    let mut b = Body::new(name, q0);
    b.mass = 1.0;
    b.inertia = 0.01;
    b.points = points
        .iter()
        .map(|(n, s)| Point {
            name: n.to_string(),
            s: *s,
        })
        .collect();
    b
}

/// A crank-rocker: crank O2–B, coupler B–C, rocker O4–C, ground O2–O4, with
/// body frames at each link's middle and the crank driven at θ₂ = θ₀ + ω t
/// by the relative angle of its ground revolute. Bodies are placed roughly
/// (a few degrees and millimetres off), as a user would.
pub fn four_bar() -> Model {
    let [d, a, b, c] = FOUR_BAR;
    let mut m = Model::new("four-bar");
    let crank = m.add_body(body(
        "crank",
        [
            0.5 * a * CRANK_START.cos(),
            0.5 * a * CRANK_START.sin(),
            CRANK_START,
        ],
        &[("O2", [-a / 2.0, 0.0]), ("B", [a / 2.0, 0.0])],
    ));
    let coupler = m.add_body(body(
        "coupler",
        [0.22, 0.14, 0.3],
        &[("B", [-b / 2.0, 0.0]), ("C", [b / 2.0, 0.0])],
    ));
    let rocker = m.add_body(body(
        "rocker",
        [0.43, 0.14, 1.4],
        &[("O4", [-c / 2.0, 0.0]), ("C", [c / 2.0, 0.0])],
    ));
    let g = BodyId::GROUND;
    m.add_joint("O2", rev(g, [0.0, 0.0], crank, [-a / 2.0, 0.0]));
    m.add_joint("B", rev(crank, [a / 2.0, 0.0], coupler, [-b / 2.0, 0.0]));
    m.add_joint("C", rev(coupler, [b / 2.0, 0.0], rocker, [c / 2.0, 0.0]));
    m.add_joint("O4", rev(g, [d, 0.0], rocker, [-c / 2.0, 0.0]));
    m.add_driver("motor", crank_motor(crank, CRANK_START, CRANK_SPEED));
    m
}

/// Freudenstein's closed form for the four-bar [d, a, b, c] at crank angle
/// θ₂ and speed ω₂ (α₂ = 0): ([θ₃, θ₄], [ω₃, ω₄], [α₃, α₄]), open branch
/// (`sign` = −1) or crossed (+1).
pub fn freudenstein(l: [f64; 4], th2: f64, w2: f64, sign: f64) -> ([f64; 2], [f64; 2], [f64; 2]) {
    let [d, a, b, c] = l;
    let (k1, k2, k4) = (d / a, d / c, d / b);
    let k3 = (a * a - b * b + c * c + d * d) / (2.0 * a * c);
    let k5 = (c * c - d * d - a * a - b * b) / (2.0 * a * b);
    let (cs, sn) = (th2.cos(), th2.sin());
    let (aa, bb, cc) = (cs - k1 - k2 * cs + k3, -2.0 * sn, k1 - (k2 + 1.0) * cs + k3);
    let th4 = 2.0 * (-bb + sign * (bb * bb - 4.0 * aa * cc).sqrt()).atan2(2.0 * aa);
    let (dd, ee, ff) = (cs - k1 + k4 * cs + k5, -2.0 * sn, k1 + (k4 - 1.0) * cs + k5);
    let th3 = 2.0 * (-ee + sign * (ee * ee - 4.0 * dd * ff).sqrt()).atan2(2.0 * dd);
    // Velocity loop: a ω₂ e^{iθ₂}i + b ω₃ e^{iθ₃}i = c ω₄ e^{iθ₄}i.
    let w3 = a * w2 * (th4 - th2).sin() / (b * (th3 - th4).sin());
    let w4 = a * w2 * (th2 - th3).sin() / (c * (th4 - th3).sin());
    // Acceleration loop, α₂ = 0: b α₃ i e^{iθ₃} − c α₄ i e^{iθ₄} = r, with
    // r = a ω₂² e^{iθ₂} + b ω₃² e^{iθ₃} − c ω₄² e^{iθ₄}; solved by Cramer.
    let rx = a * w2 * w2 * th2.cos() + b * w3 * w3 * th3.cos() - c * w4 * w4 * th4.cos();
    let ry = a * w2 * w2 * th2.sin() + b * w3 * w3 * th3.sin() - c * w4 * w4 * th4.sin();
    let (m11, m12) = (-b * th3.sin(), c * th4.sin());
    let (m21, m22) = (b * th3.cos(), -c * th4.cos());
    let det = m11 * m22 - m12 * m21;
    let al3 = (rx * m22 - m12 * ry) / det;
    let al4 = (m11 * ry - rx * m21) / det;
    ([th3, th4], [w3, w4], [al3, al4])
}

/// The crank's angle relative to the ground driven at θ = `start` + ω t.
pub fn crank_motor(crank: BodyId, start: f64, omega: f64) -> RelativeCoord {
    RelativeCoord {
        body_i: BodyId::GROUND,
        s_i: [0.0, 0.0],
        body_j: crank,
        s_j: [0.0, 0.0],
        coord: RelCoord::Phi,
        f: TimeFn::Linear {
            value: start,
            rate: omega,
        },
    }
}

fn rev(bi: BodyId, si: [f64; 2], bj: BodyId, sj: [f64; 2]) -> Revolute {
    Revolute {
        body_i: bi,
        s_i: si,
        body_j: bj,
        s_j: sj,
    }
}

/// A four-bar with link lengths [d, a, b, c] (ground, crank, coupler,
/// rocker), body frames at each link's first joint, placed at crank angle
/// `th2` on the open branch (exactly), the crank driven at θ₂ = th2 + ω t.
pub fn four_bar_with(l: [f64; 4], th2: f64, omega: f64) -> Model {
    let [d, a, b, c] = l;
    let (th, _, _) = freudenstein(l, th2, omega, -1.0);
    let mut m = Model::new("four-bar");
    let crank = m.add_body(body("crank", [0.0, 0.0, th2], &[]));
    let bx = a * th2.cos();
    let by = a * th2.sin();
    let coupler = m.add_body(body("coupler", [bx, by, th[0]], &[]));
    let rocker = m.add_body(body("rocker", [d, 0.0, th[1]], &[]));
    let g = BodyId::GROUND;
    m.add_joint("O2", rev(g, [0.0, 0.0], crank, [0.0, 0.0]));
    m.add_joint("B", rev(crank, [a, 0.0], coupler, [0.0, 0.0]));
    m.add_joint("C", rev(coupler, [b, 0.0], rocker, [c, 0.0]));
    m.add_joint("O4", rev(g, [d, 0.0], rocker, [0.0, 0.0]));
    m.add_driver("motor", crank_motor(crank, th2, omega));
    m
}

/// A slider-crank (crank r, rod l, slider on the x axis), body frames at
/// the crank pivot, the crank pin and the slider pin, placed exactly at
/// crank angle `th`. No driver.
pub fn slider_crank(r: f64, l: f64, th: f64) -> Model {
    use camlink_core::constraint::translational::Translational;
    let mut m = Model::new("slider-crank");
    let (bx, by) = (r * th.cos(), r * th.sin());
    let x = bx + (l * l - by * by).sqrt();
    let crank = m.add_body(body("crank", [0.0, 0.0, th], &[]));
    let rod = m.add_body(body("rod", [bx, by, (-by).atan2(x - bx)], &[]));
    let slider = m.add_body(body("slider", [x, 0.0, 0.0], &[]));
    let g = BodyId::GROUND;
    m.add_joint("O", rev(g, [0.0, 0.0], crank, [0.0, 0.0]));
    m.add_joint("A", rev(crank, [r, 0.0], rod, [0.0, 0.0]));
    m.add_joint("B", rev(rod, [l, 0.0], slider, [0.0, 0.0]));
    m.add_joint(
        "slide",
        Translational {
            body_i: g,
            s_i: [0.0, 0.0],
            v_i: [1.0, 0.0],
            body_j: slider,
            s_j: [0.0, 0.0],
            angle: 0.0,
        },
    );
    m
}

/// The number in the environment variable `key`, or `default` when it is
/// not set (for probes run by hand); panics on a value that is not a
/// number, naming the variable.
pub fn env_number(key: &str, default: f64) -> f64 {
    match std::env::var(key) {
        Ok(v) => v
            .parse()
            .unwrap_or_else(|_| panic!("{key}={v} is not a number")),
        Err(_) => default,
    }
}
