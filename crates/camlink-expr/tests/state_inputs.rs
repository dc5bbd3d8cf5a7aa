//! Multi-input expressions (forces that read the motion) and the contact
//! and friction functions `impact` and `coulomb` (issue 30).

use std::collections::HashMap;

use camlink_expr::Expr;

use crate::common::{assert_close, richardson};

fn parse(src: &str, inputs: &[&str]) -> Expr {
    Expr::parse_inputs(src, inputs, &HashMap::from([("k".to_string(), 3.0)]))
        .unwrap_or_else(|e| panic!("{}", e.render(src)))
}

#[test]
fn issue30_inputs_evaluate_by_position() {
    let f = parse(
        "if(ram_vx > 0, -500, 0) + k*crank_phi",
        &["crank_phi", "ram_vx"],
    );
    assert_eq!(f.inputs(), ["crank_phi", "ram_vx"]);
    assert_eq!(f.eval_inputs(&[2.0, 0.5]), -494.0);
    assert_eq!(f.eval_inputs(&[2.0, -0.5]), 6.0);
    assert!(!f.is_constant());
}

#[test]
fn issue30_gradient_matches_finite_differences() {
    let src = "k*sin(a)*b^2 + coulomb(b, 2, 0.1) + impact(a, b, 1, 1000, 1.5, 20, 0.05) + step(a, 0, 0, 2, 1)*exp(-b)";
    let f = parse(src, &["a", "b"]);
    for &(a, b) in &[
        (0.3, 0.04),
        (0.97, -0.3),
        (0.5, 0.2),
        (1.2, 0.08),
        (0.99, 0.01),
    ] {
        let u = [a, b];
        let mut g = [0.0; 2];
        let v = f.gradient(&u, &mut g);
        assert_eq!(v, f.eval_inputs(&u), "the value of the gradient pass");
        for k in 0..2 {
            let fd = richardson(
                |x| {
                    let mut w = u;
                    w[k] = x;
                    f.eval_inputs(&w)
                },
                u[k],
                1e-4,
            );
            assert_close(g[k], fd, 1e-7, &format!("d f / d u{k} at {u:?}"));
        }
    }
}

#[test]
fn issue30_impact_is_adams_impact() {
    let f = parse("impact(x, v, 1, 1000, 1, 10, 0.01)", &["x", "v"]);
    // Out of contact: nothing.
    assert_eq!(f.eval_inputs(&[1.2, -3.0]), 0.0);
    // Deeper than d: full damping.
    assert_eq!(f.eval_inputs(&[0.5, -2.0]), 500.0 + 20.0);
    // Inside the damping ramp: u = (0.995 − 0.99)/0.01 = 1/2, STEP = cmax/2.
    assert_close(
        f.eval_inputs(&[0.995, -2.0]),
        5.0 + 5.0 * 2.0,
        1e-12,
        "ramp",
    );
    // Leaving fast: the damping would pull, the force is held at 0.
    assert_eq!(f.eval_inputs(&[0.999, 50.0]), 0.0);
}

#[test]
fn issue30_coulomb_is_sign_outside_the_transition() {
    let f = parse("coulomb(v, 2, 0.1)", &["v"]);
    assert_eq!(f.eval_inputs(&[0.1]), 2.0);
    assert_eq!(f.eval_inputs(&[-5.0]), -2.0);
    assert_eq!(f.eval_inputs(&[0.0]), 0.0);
    assert_close(f.eval_inputs(&[-0.05]), -1.375, 1e-15, "cubic");
}

#[test]
fn issue30_input_checks_name_the_operation_and_inputs() {
    let f = parse("log(a - b)", &["a", "b"]);
    let e = f.check_inputs(&[1.0, 2.0]).unwrap_err();
    assert_eq!(
        e.message,
        "log of a negative number (-1) in `log(a - b)` at a = 1, b = 2"
    );
    let g = parse("coulomb(a, 1, b)", &["a", "b"]);
    assert!(g
        .check_inputs(&[1.0, 0.0])
        .unwrap_err()
        .message
        .contains("vs ≤ 0"));
    assert!(g.check_inputs(&[1.0, 0.1]).is_ok());
}

#[test]
fn issue30_parameters_shadow_inputs_and_unknown_names_are_refused() {
    let f = parse("k + a", &["a", "k"]);
    assert_eq!(f.eval_inputs(&[1.0, 100.0]), 4.0);
    let e = Expr::parse_inputs("a + bb", &["a", "b"], &HashMap::new()).unwrap_err();
    assert!(e.message.contains("did you mean 'b'"), "{}", e.message);
}
