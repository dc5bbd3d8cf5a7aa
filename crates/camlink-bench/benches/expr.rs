//! Evaluation speed of the expressions camlink evaluates every step.
//!
//! Run with `cargo bench -p camlink-bench`.

use camlink_expr::Expr;
use divan::black_box;

fn main() {
    divan::main();
}

/// The seed's cam profile ρ₁(α).
const PROFILE: &str = "if(a <= 2*pi/3, 5/4 - cos(3*a)/4, 1)";
/// The seed's crank driver.
const DRIVER: &str = "pi/6 + 2*pi*t";
/// A dwell-rise-dwell-return cam built from motion laws.
const LAWS: &str = "cycloidal(a, 0, 0, 2*pi/3, 0.01) - poly345(a, pi, 0, 5*pi/3, 0.01)";

/// Points spread over both branches of the profile.
fn points() -> Vec<f64> {
    (0..64).map(|i| i as f64 * 0.1).collect()
}

#[divan::bench(sample_count = 200, sample_size = 256)]
fn profile_jet(b: divan::Bencher) {
    let e = Expr::parse(PROFILE, "a").unwrap();
    let xs = points();
    let mut i = 0;
    b.bench_local(|| {
        i = (i + 1) & 63;
        e.jet(black_box(xs[i]))
    });
}

/// The fourth-order jet the jerk analysis evaluates (the usual step uses
/// `profile_jet`).
#[divan::bench(sample_count = 200, sample_size = 256)]
fn profile_jet4(b: divan::Bencher) {
    let e = Expr::parse(PROFILE, "a").unwrap();
    let xs = points();
    let mut i = 0;
    b.bench_local(|| {
        i = (i + 1) & 63;
        e.jet4(black_box(xs[i]))
    });
}

#[divan::bench(sample_count = 200, sample_size = 256)]
fn profile_eval(b: divan::Bencher) {
    let e = Expr::parse(PROFILE, "a").unwrap();
    let xs = points();
    let mut i = 0;
    b.bench_local(|| {
        i = (i + 1) & 63;
        e.eval(black_box(xs[i]))
    });
}

#[divan::bench(sample_count = 200, sample_size = 256)]
fn driver_jet(b: divan::Bencher) {
    let e = Expr::parse(DRIVER, "t").unwrap();
    b.bench_local(|| e.jet(black_box(0.37)));
}

#[divan::bench(sample_count = 200, sample_size = 256)]
fn motion_laws_jet(b: divan::Bencher) {
    let e = Expr::parse(LAWS, "a").unwrap();
    let xs = points();
    let mut i = 0;
    b.bench_local(|| {
        i = (i + 1) & 63;
        e.jet(black_box(xs[i]))
    });
}

#[divan::bench(sample_count = 200, sample_size = 256)]
fn profile_parse() -> Expr {
    Expr::parse(black_box(PROFILE), "a").unwrap()
}
