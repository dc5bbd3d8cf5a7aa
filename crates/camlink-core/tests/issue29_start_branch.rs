//! A kinematic run assembled from given coordinates (`run_from`) stays on
//! their branch: the four-bar placed on one branch and started from the
//! other follows Freudenstein's closed form of the other branch.

use crate::common;

use camlink_core::kinematics::{coordinate_names, run, run_from};
use camlink_core::run::{time_grid, Kind, Settings, Table};
use common::{four_bar, freudenstein, CRANK_SPEED, CRANK_START, FOUR_BAR};

fn wrap(a: f64) -> f64 {
    (a + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI) - std::f64::consts::PI
}

/// q of `common::four_bar` (bodies centred on their links) at θ₂ on the
/// branch `sign`, each coordinate off by `off` (m or rad).
fn q_on_branch(sign: f64, off: f64) -> Vec<f64> {
    let [d, a, b, c] = FOUR_BAR;
    let th2 = CRANK_START;
    let ([th3, th4], _, _) = freudenstein(FOUR_BAR, th2, CRANK_SPEED, sign);
    let (bx, by) = (a * th2.cos(), a * th2.sin());
    [
        0.5 * a * th2.cos(),
        0.5 * a * th2.sin(),
        th2,
        bx + 0.5 * b * th3.cos(),
        by + 0.5 * b * th3.sin(),
        th3,
        d + 0.5 * c * th4.cos(),
        0.5 * c * th4.sin(),
        th4,
    ]
    .iter()
    .map(|v| v + off)
    .collect()
}

#[test]
fn issue29_run_from_keeps_the_given_branch() {
    let model = four_bar();
    assert_eq!(
        coordinate_names(&model),
        [
            "crank.x",
            "crank.y",
            "crank.phi",
            "coupler.x",
            "coupler.y",
            "coupler.phi",
            "rocker.x",
            "rocker.y",
            "rocker.phi"
        ]
    );
    let times = time_grid(1.0, 1e-2).unwrap();
    let settings = Settings::default();
    let mut placed = Table::default();
    run(&model, &times, &settings, &[], &mut placed).unwrap();
    // The branch of the placement, then the other one from `start`.
    let th4 = placed.channel("rocker.phi").unwrap()[0];
    let here =
        if wrap(freudenstein(FOUR_BAR, CRANK_START, CRANK_SPEED, -1.0).0[1] - th4).abs() < 1e-6 {
            -1.0
        } else {
            1.0
        };
    for sign in [-here, here] {
        let mut table = Table::default();
        let start = q_on_branch(sign, 0.01);
        run_from(&model, &times, &settings, &[], &mut table, Some(&start)).unwrap();
        let (th3, th4) = (
            table.channel("coupler.phi").unwrap(),
            table.channel("rocker.phi").unwrap(),
        );
        for (k, &t) in table.t.iter().enumerate() {
            let th = freudenstein(FOUR_BAR, CRANK_START + CRANK_SPEED * t, CRANK_SPEED, sign).0;
            assert!(
                wrap(th3[k] - th[0]).abs() < 1e-9,
                "θ₃ at t = {t}, branch {sign}"
            );
            assert!(
                wrap(th4[k] - th[1]).abs() < 1e-9,
                "θ₄ at t = {t}, branch {sign}"
            );
        }
    }
}

#[test]
fn issue29_run_from_refuses_a_wrong_start() {
    let model = four_bar();
    let refused = |start: &[f64]| {
        let mut table = Table::default();
        let e = run_from(
            &model,
            &[0.0, 0.1],
            &Settings::default(),
            &[],
            &mut table,
            Some(start),
        );
        let e = e.unwrap_err();
        assert_eq!(e.kind, Kind::InvalidInput);
        e.message
    };
    let message = refused(&[0.0; 8]);
    assert!(
        message.contains("8 values") && message.contains("9 coordinates"),
        "{message}"
    );
    let mut q = q_on_branch(1.0, 0.0);
    q[5] = f64::NAN;
    let message = refused(&q);
    assert!(message.contains("coupler.phi"), "{message}");
}
