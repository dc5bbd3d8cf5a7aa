//! The four-bar crank-rocker against Freudenstein's closed form.

use crate::common;

use camlink_core::kinematics::run;
use camlink_core::run::{time_grid, PointOutput, Settings, Table};
use common::{four_bar, freudenstein, CRANK_SPEED, CRANK_START, FOUR_BAR};

fn wrap(a: f64) -> f64 {
    (a + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI) - std::f64::consts::PI
}

#[test]
fn crank_rocker_matches_freudenstein() {
    let model = four_bar();
    let times = time_grid(2.0, 1e-3).unwrap();
    let mut table = Table::default();
    let points = [PointOutput {
        body: model.body_id("coupler").unwrap(),
        name: "coupler.C".into(),
        s: [FOUR_BAR[2] / 2.0, 0.0],
    }];
    let summary = run(&model, &times, &Settings::default(), &points, &mut table).unwrap();
    assert_eq!(summary.steps, times.len());
    let ch = |n: &str| table.channel(n).unwrap();
    let (th3, th4) = (ch("coupler.phi"), ch("rocker.phi"));
    let (w3, w4) = (ch("coupler.omega"), ch("rocker.omega"));
    let (a3, a4) = (ch("coupler.alpha"), ch("rocker.alpha"));
    let (cx, cy) = (ch("coupler.C.x"), ch("coupler.C.y"));
    // The branch the model was placed on, fixed for the whole run.
    let open = freudenstein(FOUR_BAR, CRANK_START, CRANK_SPEED, -1.0).0;
    let sign = if (wrap(open[1] - th4[0])).abs() < 0.1 {
        -1.0
    } else {
        1.0
    };
    for (k, &t) in table.t.iter().enumerate() {
        let th2 = CRANK_START + CRANK_SPEED * t;
        let (th, w, al) = freudenstein(FOUR_BAR, th2, CRANK_SPEED, sign);
        assert!(wrap(th3[k] - th[0]).abs() < 1e-9, "θ₃ at t = {t}");
        assert!(wrap(th4[k] - th[1]).abs() < 1e-9, "θ₄ at t = {t}");
        let rel = |got: f64, want: f64| (got - want).abs() <= 1e-7 * want.abs().max(1.0);
        assert!(rel(w3[k], w[0]) && rel(w4[k], w[1]), "ω at t = {t}");
        assert!(
            rel(a3[k], al[0]) && rel(a4[k], al[1]),
            "α at t = {t}: {} vs {}",
            a4[k],
            al[1]
        );
        // Point C of the coupler is on the rocker's tip.
        let (d, c) = (FOUR_BAR[0], FOUR_BAR[3]);
        assert!((cx[k] - (d + c * th[1].cos())).abs() < 1e-9);
        assert!((cy[k] - c * th[1].sin()).abs() < 1e-9);
    }
    // The model is placed roughly: assembly reports moving the coupler and
    // rocker, and not the crank, which was placed exactly.
    let moved: Vec<&str> = summary
        .assembly_moves
        .iter()
        .map(|(b, _)| b.as_str())
        .collect();
    assert_eq!(moved, ["coupler", "rocker"], "{:?}", summary.assembly_moves);
    // One factorization per step once running.
    assert!(
        summary.factorizations <= 2 * summary.steps + 10,
        "{summary:?}"
    );
}
