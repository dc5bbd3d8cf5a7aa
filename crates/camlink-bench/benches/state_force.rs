//! A spring and damper written as a force of state against the built-in
//! one: Q and its derivatives for a torsion spring–damper between two
//! bodies, and for a translational one on a slide.
//!
//! `cargo bench -p camlink-bench --bench state_force`

use std::collections::HashMap;
use std::sync::Arc;

use camlink_core::constraint::{BodyId, Local};
use camlink_core::force::rsda::Rsda;
use camlink_core::force::state::{Channel, StateExpr, StateForce};
use camlink_core::force::tsda::Tsda;
use camlink_core::force::{Applied, BodyJac, BodyQ};
use camlink_core::TimeFn;
use camlink_expr::Expr;
use divan::black_box;

fn main() {
    divan::main();
}

fn state() -> Local {
    let mut x = Local {
        t: 0.3,
        ..Local::default()
    };
    x.q = [[0.1, 0.2, 0.3], [0.9, -0.1, -0.4]];
    x.qd = [[0.5, -0.2, 1.1], [0.3, 0.4, -0.7]];
    x
}

fn rsda() -> Rsda {
    Rsda {
        body_i: BodyId(1),
        body_j: BodyId(2),
        stiffness: 40.0,
        free_angle: 0.3,
        damping: 0.7,
        actuator: TimeFn::Const(0.0),
    }
}

/// The RSDA as a torque on body i with the reaction on body j.
fn rsda_of_state() -> StateForce {
    let channels = vec![
        Channel::Angle {
            a: 0,
            b: 1,
            rate: false,
        },
        Channel::Angle {
            a: 0,
            b: 1,
            rate: true,
        },
    ];
    let expr =
        Expr::parse_inputs("40*(th - 0.3) + 0.7*thd", &["th", "thd"], &HashMap::new()).unwrap();
    StateForce {
        reads: Vec::new(),
        body_i: BodyId(1),
        s_i: [0.0; 2],
        body_j: BodyId(2),
        s_j: [0.0; 2],
        f: [None, None],
        torque: Some(StateExpr {
            expr: Arc::new(expr),
            channels,
        }),
        local: false,
    }
}

/// A TSDA from the ground origin to body j's origin, along x.
fn tsda() -> Tsda {
    Tsda {
        body_i: BodyId(0),
        s_i: [0.0; 2],
        body_j: BodyId(2),
        s_j: [0.0; 2],
        stiffness: 40.0,
        free_length: 0.5,
        damping: 0.7,
        actuator: TimeFn::Const(0.0),
    }
}

/// The same spring as a force of state on a slide's stroke, on body j.
fn slide_of_state() -> StateForce {
    let channels = vec![
        Channel::Stroke {
            a: 1,
            s_a: [0.0; 2],
            v_a: [1.0, 0.0],
            b: 0,
            s_b: [0.0; 2],
            rate: false,
        },
        Channel::Stroke {
            a: 1,
            s_a: [0.0; 2],
            v_a: [1.0, 0.0],
            b: 0,
            s_b: [0.0; 2],
            rate: true,
        },
    ];
    let expr =
        Expr::parse_inputs("-(40*(s - 0.5) + 0.7*sd)", &["s", "sd"], &HashMap::new()).unwrap();
    StateForce {
        reads: Vec::new(),
        body_i: BodyId(2),
        s_i: [0.0; 2],
        body_j: BodyId(0),
        s_j: [0.0; 2],
        f: [
            Some(StateExpr {
                expr: Arc::new(expr),
                channels,
            }),
            None,
        ],
        torque: None,
        local: false,
    }
}

fn q_of(f: &impl Applied, x: &Local) -> BodyQ {
    let mut q = BodyQ::default();
    f.generalized(black_box(x), &mut q).unwrap();
    q
}

fn jac_of(f: &impl Applied, x: &Local) -> (BodyJac, BodyJac) {
    let (mut a, mut b) = (BodyJac::default(), BodyJac::default());
    f.derivatives(black_box(x), &mut a, &mut b);
    (a, b)
}

#[divan::bench]
fn rsda_q_built_in(b: divan::Bencher) {
    let (f, x) = (rsda(), state());
    b.bench_local(|| q_of(&f, &x));
}

#[divan::bench]
fn rsda_q_of_state(b: divan::Bencher) {
    let (f, x) = (rsda_of_state(), state());
    b.bench_local(|| q_of(&f, &x));
}

#[divan::bench]
fn rsda_derivatives_built_in(b: divan::Bencher) {
    let (f, x) = (rsda(), state());
    b.bench_local(|| jac_of(&f, &x));
}

#[divan::bench]
fn rsda_derivatives_of_state(b: divan::Bencher) {
    let (f, x) = (rsda_of_state(), state());
    b.bench_local(|| jac_of(&f, &x));
}

#[divan::bench]
fn spring_q_built_in_tsda(b: divan::Bencher) {
    let (f, x) = (tsda(), state());
    b.bench_local(|| q_of(&f, &x));
}

#[divan::bench]
fn spring_q_of_state_stroke(b: divan::Bencher) {
    let (f, x) = (slide_of_state(), state());
    b.bench_local(|| q_of(&f, &x));
}

#[divan::bench]
fn spring_derivatives_built_in_tsda(b: divan::Bencher) {
    let (f, x) = (tsda(), state());
    b.bench_local(|| jac_of(&f, &x));
}

#[divan::bench]
fn spring_derivatives_of_state_stroke(b: divan::Bencher) {
    let (f, x) = (slide_of_state(), state());
    b.bench_local(|| jac_of(&f, &x));
}
