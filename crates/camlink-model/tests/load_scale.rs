//! Loading is linear in the size of the file: a long chain of parameters
//! that refer to each other and a model of many bodies, generated here.
//!
//! These tests assert no time; they load sizes at which a resolution that is
//! quadratic or worse in the file's size would not finish in a test run
//! (a 5,000-parameter chain used to take more than 15 minutes).

use camlink_model::{load_str, Format};

/// `p0 = "p1+1"`, `p1 = "p2+1"`, …, `p{n-1} = 0`: each parameter needs the
/// next one, so a resolver that sweeps the list in name order resolves one
/// per sweep.
fn parameter_chain(n: usize) -> String {
    let mut s = String::from("[parameters]\n");
    for i in 0..n - 1 {
        s.push_str(&format!("p{i} = \"p{}+1\"\n", i + 1));
    }
    s.push_str(&format!("p{} = 0\n", n - 1));
    s.push_str(
        "\n[[bodies]]\nname = \"arm\"\npoints = { O = [0, 0], A = [\"p0\", 0] }\n\n\
         [[joints]]\nname = \"pin\"\ntype = \"revolute\"\nbody_i = \"ground\"\npoint_i = [0, 0]\n\
         body_j = \"arm\"\npoint_j = \"O\"\n\n\
         [[drivers]]\nname = \"motor\"\ntype = \"revolute_angle\"\njoint = \"pin\"\nf = \"t\"\n",
    );
    s
}

/// A pendulum chain of `n` links of 0.1 m pinned end to end, the first to
/// the ground, each link's angle driven.
fn body_chain(n: usize) -> String {
    let mut s = String::from("[parameters]\nl = 0.1\n\n");
    for i in 0..n {
        s.push_str(&format!(
            "[[bodies]]\nname = \"link{i}\"\nmass = 1.0\ninertia = 0.001\n\
             points = {{ O = [0, 0], A = [\"l\", 0] }}\nposition = [{}, 0]\n\n",
            0.1 * i as f64
        ));
    }
    for i in 0..n {
        let (body_i, point_i) = if i == 0 {
            ("ground".to_string(), "[0, 0]")
        } else {
            (format!("link{}", i - 1), "\"A\"")
        };
        s.push_str(&format!(
            "[[joints]]\nname = \"pin{i}\"\ntype = \"revolute\"\nbody_i = \"{body_i}\"\n\
             point_i = {point_i}\nbody_j = \"link{i}\"\npoint_j = \"O\"\n\n"
        ));
        s.push_str(&format!(
            "[[drivers]]\nname = \"drive{i}\"\ntype = \"revolute_angle\"\njoint = \"pin{i}\"\nf = \"0.1*t\"\n\n"
        ));
    }
    s
}

#[test]
fn a_chain_of_10000_parameters_loads() {
    let n = 10_000;
    let loaded = load_str(&parameter_chain(n), Format::Toml, "chain.toml").unwrap();
    // p0 = n - 1 after n - 1 additions of 1.
    let arm = &loaded.model.bodies[1];
    assert_eq!(arm.point("A"), Some([(n - 1) as f64, 0.0]));
}

#[test]
fn a_model_of_10000_bodies_loads() {
    let n = 10_000;
    let loaded = load_str(&body_chain(n), Format::Toml, "bodies.toml").unwrap();
    assert_eq!(loaded.model.bodies.len(), n + 1);
    assert_eq!(loaded.model.joints.len(), 2 * n);
}

#[test]
fn a_cycle_in_a_long_chain_names_its_members() {
    // p0 → p1 → … → p9 → p0, plus a parameter that only depends on the cycle.
    let mut s = String::from("[parameters]\n");
    for i in 0..10 {
        s.push_str(&format!("p{i} = \"p{}+1\"\n", (i + 1) % 10));
    }
    s.push_str("q = \"p3\"\n");
    let e = load_str(&s, Format::Toml, "cycle.toml").unwrap_err();
    let text = e.to_string();
    assert!(text.contains("cycle"), "{text}");
    for i in 0..10 {
        assert!(text.contains(&format!("p{i}")), "p{i} missing: {text}");
    }
    assert!(!text.contains(" q"), "q is not in the cycle: {text}");
}
