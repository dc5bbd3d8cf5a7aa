//! Mechanisms with mass, built in code, shared by the dynamics tests and
//! benchmarks.
#![allow(dead_code)]

use camlink_core::constraint::relative::{RelCoord, RelativeCoord};
use camlink_core::constraint::revolute::Revolute;
use camlink_core::constraint::translational::Translational;
use camlink_core::{Body, BodyId, Model, Point, TimeFn};

/// Slider-crank: crank a, rod b (m).
pub const CRANK: f64 = 0.1;
pub const ROD: f64 = 0.3;

/// Masses (kg) and centroidal inertias (kg·m²) of crank, rod and slider.
pub const MASS: [f64; 3] = [1.0, 2.0, 0.5];
pub const INERTIA: [f64; 3] = [1.0e-3, 1.5e-2, 1.0e-3];
/// Centroid of the crank in its frame (frame at the ground pivot) and of
/// the rod in its frame (frame at its middle), m.
pub const CRANK_CENTROID: [f64; 2] = [0.05, 0.0];
pub const ROD_CENTROID: [f64; 2] = [0.03, 0.0];

pub fn rev(bi: BodyId, si: [f64; 2], bj: BodyId, sj: [f64; 2]) -> Revolute {
    Revolute {
        body_i: bi,
        s_i: si,
        body_j: bj,
        s_j: sj,
    }
}

pub fn body(name: &str, q0: [f64; 3], mass: f64, inertia: f64, centroid: [f64; 2]) -> Body {
    let mut b = Body::new(name, q0);
    b.mass = mass;
    b.inertia = inertia;
    b.centroid = centroid;
    b
}

/// Crank angle θ → (rod angle ψ, slider x) of the in-line slider-crank.
pub fn slider_crank_position(th: f64) -> (f64, f64) {
    let (a, b) = (CRANK, ROD);
    let h = (b * b - a * a * th.sin().powi(2)).sqrt();
    ((-a * th.sin()).atan2(h), a * th.cos() + h)
}

/// In-line slider-crank, placed exactly at crank angle `th0`: crank frame
/// at the ground pivot O, rod frame at its middle, slider frame at its pin
/// C on the x axis. `driver`: the crank turns at θ = θ₀ + ω t; otherwise
/// it starts with angular speed ω and the bodies' velocities are left at
/// zero for the projection to make consistent.
pub fn slider_crank(th0: f64, omega: f64, driver: bool) -> Model {
    let (a, b) = (CRANK, ROD);
    let (psi, xc) = slider_crank_position(th0);
    let bx = a * th0.cos();
    let by = a * th0.sin();
    let mut m = Model::new("slider-crank");
    let mut crank = body(
        "crank",
        [0.0, 0.0, th0],
        MASS[0],
        INERTIA[0],
        CRANK_CENTROID,
    );
    crank.qd0 = [0.0, 0.0, omega];
    let crank = m.add_body(crank);
    let rod = m.add_body(body(
        "rod",
        [0.5 * (bx + xc), 0.5 * by, psi],
        MASS[1],
        INERTIA[1],
        ROD_CENTROID,
    ));
    let slider = m.add_body(body(
        "slider",
        [xc, 0.0, 0.0],
        MASS[2],
        INERTIA[2],
        [0.0, 0.0],
    ));
    let g = BodyId::GROUND;
    m.add_joint("O", rev(g, [0.0, 0.0], crank, [0.0, 0.0]));
    m.add_joint("B", rev(crank, [a, 0.0], rod, [-b / 2.0, 0.0]));
    m.add_joint("C", rev(rod, [b / 2.0, 0.0], slider, [0.0, 0.0]));
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
    if driver {
        m.add_driver(
            "motor",
            RelativeCoord {
                body_i: g,
                s_i: [0.0, 0.0],
                body_j: crank,
                s_j: [0.0, 0.0],
                coord: RelCoord::Phi,
                f: TimeFn::Linear {
                    value: th0,
                    rate: omega,
                },
            },
        );
    }
    m
}

/// A chain of `n` links of length `l` (m), 1 kg each, hanging from the
/// ground at the origin and starting horizontal along +x: link k's frame is
/// at its middle, its ends at (∓l/2, 0).
pub fn chain(n: usize, l: f64) -> Model {
    let mut m = Model::new("chain");
    let mut prev = BodyId::GROUND;
    for k in 0..n {
        let mut b = body(
            &format!("link{k}"),
            [(k as f64 + 0.5) * l, 0.0, 0.0],
            1.0,
            l * l / 12.0,
            [0.0, 0.0],
        );
        b.points = vec![
            Point {
                name: "A".into(),
                s: [-l / 2.0, 0.0],
            },
            Point {
                name: "B".into(),
                s: [l / 2.0, 0.0],
            },
        ];
        let id = m.add_body(b);
        let sp = if prev.is_ground() {
            [0.0, 0.0]
        } else {
            [l / 2.0, 0.0]
        };
        m.add_joint(format!("J{k}"), rev(prev, sp, id, [-l / 2.0, 0.0]));
        prev = id;
    }
    m
}

/// A compound pendulum: one body pivoted at the origin, centroid at
/// distance `l` (m) from the pivot, starting at angle `th0` from the
/// downward vertical. `frame_at_pivot`: the body frame sits at the pivot
/// with the centroid offset (0, −l) when hanging; otherwise at the centroid.
pub fn pendulum(l: f64, mass: f64, inertia: f64, th0: f64, frame_at_pivot: bool) -> Model {
    let mut m = Model::new("pendulum");
    // Body angle φ = θ; the pivot-to-centroid vector is (0, −l) at φ = 0.
    let b = if frame_at_pivot {
        body("bob", [0.0, 0.0, th0], mass, inertia, [0.0, -l])
    } else {
        body(
            "bob",
            [l * th0.sin(), -l * th0.cos(), th0],
            mass,
            inertia,
            [0.0, 0.0],
        )
    };
    let id = m.add_body(b);
    let s = if frame_at_pivot { [0.0, 0.0] } else { [0.0, l] };
    m.add_joint("pivot", rev(BodyId::GROUND, [0.0, 0.0], id, s));
    m
}
