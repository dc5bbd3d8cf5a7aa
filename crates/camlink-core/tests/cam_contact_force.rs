//! The cam design's contact force (the follower's inverse dynamics,
//! Q = m ω² s″ + c ω s′ + F₀ + k s, F = Q/cos φ) against camlink's own
//! multibody inverse dynamics of the synthesised mechanism with the same
//! mass, spring and damper.

use std::f64::consts::TAU;
use std::sync::Arc;

use camlink_core::cam::{Cam, Follower, LawKind, Program, SegmentSpec};
use camlink_core::cam_limits::{force, Train};
use camlink_core::cam_mechanism::mechanism;
use camlink_core::dynamics::inverse::run;
use camlink_core::force::tsda::Tsda;
use camlink_core::run::{Settings, Table};
use camlink_core::Force;
use camlink_core::{BodyId, TimeFn};

#[test]
fn contact_force_matches_multibody_inverse_dynamics() {
    let d = |x: f64| x.to_radians();
    let program = Program::new(&[
        SegmentSpec::new(LawKind::Dwell, d(90.0), 0.0),
        SegmentSpec::new(LawKind::Cycloidal, d(100.0), 0.01),
        SegmentSpec::new(LawKind::Dwell, d(20.0), 0.0),
        SegmentSpec::new(LawKind::Poly345, d(150.0), -0.01),
    ])
    .unwrap();
    let offset = 0.004;
    for (follower, ccw) in [
        (Follower::TranslatingFlat, true),
        (
            Follower::TranslatingRoller {
                offset,
                roller: 0.008,
            },
            false,
        ),
    ] {
        let rb = 0.03;
        let cam = Arc::new(Cam::new(program.clone(), follower, rb, ccw).unwrap());
        let train = Train {
            mass: 0.4,
            spring_rate: 5000.0,
            preload: 80.0,
            damping: 3.0,
        };
        let omega = 60.0;
        let mut model = mechanism(&cam, omega);
        model.gravity = [0.0, 0.0];
        for b in model.bodies.iter_mut().skip(1) {
            b.mass = if b.name == "follower" {
                train.mass
            } else {
                1.0
            };
            b.inertia = 1e-3;
        }
        // A spring pulling the follower down its stem from an anchor 0.2 m
        // below the cam centre: tension F₀ + k s at the follower's height
        // y₀ + s (y₀ = R_b for the face, √(R_p² − ε²) for the roller).
        let x = model.bodies[2].q0[0];
        let y0 = cam.follower_coordinate(0.0)[0];
        model.add_force(Force::new(
            "spring",
            Tsda {
                body_i: BodyId::GROUND,
                s_i: [x, -0.2],
                body_j: BodyId(2),
                s_j: [0.0, 0.0],
                stiffness: train.spring_rate,
                free_length: y0 + 0.2 - train.preload / train.spring_rate,
                damping: train.damping,
                actuator: TimeFn::Const(0.0),
            },
        ));
        let n = 360;
        let times: Vec<f64> = (0..n)
            .map(|k| (k as f64 + 0.3) / n as f64 * TAU / omega)
            .collect();
        let mut table = Table::default();
        run(&model, &times, &Settings::default(), &[], &mut table)
            .unwrap_or_else(|e| panic!("{e}"));
        let got = table.channel("contact.normal_force").unwrap();
        let f = force(&cam, &train, omega).unwrap();
        let peak = f.normal.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        // The design report's force is the same formula at its own angles.
        let q_of = |th: f64| {
            let c = cam.contact(th);
            let [s, s1, s2, _] = c.motion;
            let q = train.mass * omega * omega * s2
                + train.damping * omega * s1
                + train.preload
                + train.spring_rate * s;
            q / c.pressure_angle.cos()
        };
        for k in (0..f.theta.len()).step_by(97) {
            assert!((f.normal[k] - q_of(f.theta[k])).abs() < 1e-9 * peak);
        }
        for (k, &t) in times.iter().enumerate() {
            let th = omega * t;
            let want = q_of(th);
            assert!(
                (got[k] - want).abs() < 1e-7 * peak,
                "{} at θ = {th}: camlink {} vs {want}",
                follower.name(),
                got[k]
            );
        }
    }
}
