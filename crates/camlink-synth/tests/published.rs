//! Burmester points against a published worked example with numbers:
//! the steering linkage of McCarthy & Soh, *Geometric Design of Linkages*
//! (2nd ed., 2011), §6.3 "Example: A Steering Linkage", Tables 6.1–6.3,
//! read in the chapter's text kept in the public repository
//! `haijunsu-osu/gdl_llm_reproduction` (ch6/Ch6_GDL.txt, commit
//! bbf8c38f, the book's pages 135–138).
//!
//! The book designs a Watt Ia six-bar by adding two RR chains to a 3R
//! chain C₁C₂C₃ (links a₁₂ = a₂₃ = 274 mm, base C₁ = (−153, 1241) mm,
//! end effector at the translation (−133, 0) mm from C₃) that reaches
//! five task positions (φ, x, y) of Table 6.1. Step 1 solves the 3R
//! chain (elbow C₂ = (6.6, 1463.7) at position 1); step 2 finds the RR
//! chains G₁W₁ that guide the link B₂ = C₂C₃ through its five positions
//! (five-position Burmester points; C₁C₂ is one of them); step 3 those
//! G₂W₂ that guide the end effector through its five positions relative
//! to the link B₄ = G₁W₁ chosen in step 2. Table 6.2 prints every pivot
//! at position 1 to 0.1 mm; Table 6.3 the six-bar's angles at the task
//! positions to 0.01°. All lengths here are in mm and angles in degrees
//! unless stated; the model run by the kinematics is in m and rad.

use camlink_core::kinematics;
use camlink_core::run::{Settings, Table};
use camlink_model::{load_str, Format};
use camlink_synth::burmester::{Dyad, Equations};
use camlink_synth::fourbar::{wrap_pi, P2};
use camlink_synth::motion::Pose;

use crate::burmester::{at, TOL};

/// Table 6.1: the five task positions (φ in degrees, x, y in mm) of the
/// end effector.
const TASKS: [(f64, f64, f64); 5] = [
    (43.9, -325.0, 1511.0),
    (20.0, -432.0, 1562.0),
    (0.0, -559.0, 1588.0),
    (-15.9, -689.0, 1542.0),
    (-29.1, -751.0, 1473.0),
];
/// The 3R chain: base pivot C₁ (mm), a₁₂ = a₂₃ (mm), and C₃'s distance
/// from the end effector's origin along its x axis (the book's moving
/// pivot [H] = (0°, −133, 0) mm).
const C1: P2 = [-153.0, 1241.0];
const A: f64 = 274.0;
const H: f64 = 133.0;

/// Table 6.2, step 1: C₂ and C₃ at position 1 (mm).
const STEP1: [P2; 2] = [[6.6, 1463.7], [-229.2, 1603.2]];
/// Table 6.2, step 2: the four RR chains (G₁, W₁) of link B₂ (mm).
const STEP2: [[P2; 2]; 4] = [
    [[-153.0, 1241.0], [6.6, 1463.7]],
    [[-93.6, 936.0], [-64.9, 918.0]],
    [[-84.3, 1294.9], [150.7, 1570.3]],
    [[74.5, 861.6], [172.6, 805.0]],
];
/// The chain of step 2 the book selects (its row 3; its W₁ is the G₂ of
/// step 3's row 4, the chain W₁C₃ on link B₂).
const SELECTED: usize = 2;
/// Table 6.2, step 3: the four RR chains (G₂, W₂) from link B₄ to the
/// end effector (mm).
const STEP3: [[P2; 2]; 4] = [
    [[-148.9, 1442.1], [-198.2, 1735.8]],
    [[424.6, 962.0], [-244.2, 1668.3]],
    [[-221.7, 1794.7], [-197.7, 1669.5]],
    [[150.7, 1570.3], [-229.2, 1603.2]],
];
/// Table 6.3: the six-bar's angles θ₁…θ₅ (degrees) at the five task
/// positions.
const ANGLES: [[f64; 5]; 5] = [
    [16.26, 111.28, -43.06, 66.37, -63.49],
    [31.19, 118.18, -36.16, 70.35, -55.85],
    [53.76, 126.41, -27.93, 83.67, -39.56],
    [81.50, 136.38, -17.96, 106.03, -16.23],
    [101.28, 144.20, -10.14, 125.43, 2.08],
];

/// Half a unit of the last printed digit of Table 6.2 (mm): a value
/// camlink computes agrees with a printed one when it rounds to it.
const PRINTED_MM: f64 = 0.05;
/// Half a unit of the last printed digit of Table 6.3 (degrees).
const PRINTED_DEG: f64 = 0.005;

/// The frame of the link from `p` towards `q`: origin `p`, x axis along
/// p→q.
fn link(p: P2, q: P2) -> Pose {
    Pose {
        x: p[0],
        y: p[1],
        theta: (q[1] - p[1]).atan2(q[0] - p[0]),
    }
}

/// The poses of `b` seen from the frames `a` (a_j⁻¹ b_j).
fn relative(a: &[Pose], b: &[Pose]) -> Vec<Pose> {
    a.iter()
        .zip(b)
        .map(|(a, b)| {
            let o = a.local([b.x, b.y]);
            Pose {
                x: o[0],
                y: o[1],
                theta: b.theta - a.theta,
            }
        })
        .collect()
}

/// The elbow of a two-link chain from `c1` to `c3` with links `a12`,
/// `a23` (any length unit): the one to the right of c1→c3.
fn elbow(c1: P2, c3: P2, a12: f64, a23: f64) -> P2 {
    let d = [c3[0] - c1[0], c3[1] - c1[1]];
    let l2 = d[0] * d[0] + d[1] * d[1];
    // Along c1→c3 by u·l, to its right by v·l.
    let u = 0.5 + (a12 * a12 - a23 * a23) / (2.0 * l2);
    let v = (a12 * a12 / l2 - u * u).sqrt();
    [c1[0] + u * d[0] + v * d[1], c1[1] + u * d[1] - v * d[0]]
}

/// The five positions of the 3R chain solved from Table 6.1 (step 1):
/// the end effector's frames T_j (mm, rad), C₂_j and C₃_j (mm). C₂ is the
/// elbow to the right of C₁→C₃ (the book's choice, C₂ = (6.6, 1463.7)
/// at position 1).
fn three_r() -> (Vec<Pose>, Vec<P2>, Vec<P2>) {
    let (mut t, mut c2, mut c3) = (Vec::new(), Vec::new(), Vec::new());
    for &(phi, x, y) in &TASKS {
        let (s, c) = phi.to_radians().sin_cos();
        let p3 = [x + H * c, y + H * s];
        c2.push(elbow(C1, p3, A, A));
        c3.push(p3);
        t.push(Pose {
            x,
            y,
            theta: phi.to_radians(),
        });
    }
    (t, c2, c3)
}

/// The Burmester points of `poses`, seen from the frames `base`, as
/// (G, W) at position 1 in the ground frame, with their dyads; each dyad
/// meets the five circle conditions to 1e-9 relative.
fn points(base: &[Pose], poses: &[Pose]) -> Vec<([P2; 2], Dyad)> {
    let eq = Equations::new(poses, "poses").unwrap();
    eq.burmester_points(4096)
        .into_iter()
        .map(|d| {
            let size = d.length().max(eq.scale);
            assert!(d.circle_residual(poses) <= TOL * size, "{d:?}");
            ([base[0].place(d.centre), base[0].place(d.circle)], d)
        })
        .collect()
}

/// Every published pair of `table` is one of `found`, coordinate by
/// coordinate within half a unit of the printed digit, and no other pair
/// was found.
fn assert_matches(step: &str, found: &[([P2; 2], Dyad)], table: &[[P2; 2]]) {
    assert_eq!(found.len(), table.len(), "{step}: {found:?}");
    for (k, pub_pair) in table.iter().enumerate() {
        let off = |f: &[P2; 2]| {
            (0..2)
                .flat_map(|i| (0..2).map(move |j| (f[i][j] - pub_pair[i][j]).abs()))
                .fold(0.0, f64::max)
        };
        let best = found
            .iter()
            .map(|(f, _)| off(f))
            .fold(f64::INFINITY, f64::min);
        assert!(
            best <= PRINTED_MM,
            "{step}, row {}: {pub_pair:?} is {best} mm from the nearest of {:?}",
            k + 1,
            found.iter().map(|(f, _)| f).collect::<Vec<_>>()
        );
    }
}

/// The link frames of the book's design: the crank B₁ (C₁→C₂), B₂
/// (C₂→C₃), the selected B₄ (G₁→W₁) and the end effector T, at the five
/// task positions (mm, rad), with the Burmester points of steps 2 and 3
/// (step 3's dyads seen from B₄).
struct Design {
    t: Vec<Pose>,
    b1: Vec<Pose>,
    b2: Vec<Pose>,
    b4: Vec<Pose>,
    /// The selected dyad of step 2 (moving pivot W₁ in B₂'s frame).
    chosen: Dyad,
    step2: Vec<([P2; 2], Dyad)>,
    step3: Vec<([P2; 2], Dyad)>,
}

fn design() -> Design {
    let (t, c2, c3) = three_r();
    let b1: Vec<Pose> = c2.iter().map(|&p| link(C1, p)).collect();
    let b2: Vec<Pose> = c2.iter().zip(&c3).map(|(&p, &q)| link(p, q)).collect();
    let ground = vec![link([0.0, 0.0], [1.0, 0.0]); 5];
    let step2 = points(&ground, &b2);
    let chosen = step2[row_of(&step2, STEP2[SELECTED])].1.clone();
    let g1 = chosen.centre;
    let b4: Vec<Pose> = b2
        .iter()
        .map(|p| link(g1, p.place(chosen.moving)))
        .collect();
    let step3 = points(&b4, &relative(&b4, &t));
    Design {
        t,
        b1,
        b2,
        b4,
        chosen,
        step2,
        step3,
    }
}

/// Steps 1–3 of the example solved by camlink from the printed task
/// positions: the 3R chain's C₂ and C₃ at position 1, the four Burmester
/// points of link B₂ and the four of the end effector relative to B₄
/// (with the book's selected G₁W₁) each round to Table 6.2's printed
/// values (0.1 mm; the largest difference is 0.0499 mm, W₁ of row 2), and
/// no other real Burmester point is found. Each point meets its five
/// circle conditions to 1e-9 relative.
#[test]
fn burmester_points_match_the_published_steering_linkage() {
    let (_, c2, c3) = three_r();
    for (p, q) in [c2[0], c3[0]].iter().zip(STEP1) {
        assert!(
            (p[0] - q[0]).abs() <= PRINTED_MM && (p[1] - q[1]).abs() <= PRINTED_MM,
            "step 1: {p:?} against {q:?}"
        );
    }
    let d = design();
    assert_matches("step 2", &d.step2, &STEP2);
    assert_matches("step 3", &d.step3, &STEP3);
}

/// A model file (m, rad) of a linkage drawn at position 1: `ground`
/// points, then bodies given by their frame and their points, all in the
/// ground frame in the problem's length unit (`unit` m each); every joint
/// is a revolute at the point of its name on both bodies. The crank
/// joint `crank` is driven from the angle `from` (t = 0 s) to `to`
/// (t = 1 s) (rad).
fn model(
    unit: f64,
    ground: &[(&str, P2)],
    bodies: &[(&str, Pose, Vec<(&str, P2)>)],
    joints: &[(&str, &str, &str)],
    crank: &str,
    from: f64,
    to: f64,
) -> String {
    let xy = |p: P2| format!("[{:?}, {:?}]", p[0] * unit, p[1] * unit);
    let list = |f: &Pose, pts: &[(&str, P2)]| {
        pts.iter()
            .map(|&(n, p)| format!("{n} = {}", xy(f.local(p))))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let origin = Pose {
        x: 0.0,
        y: 0.0,
        theta: 0.0,
    };
    let mut s = format!(
        "[model]\nname = \"published\"\n\n[ground]\npoints = {{ {} }}\n\n",
        list(&origin, ground)
    );
    for (name, f, pts) in bodies {
        s += &format!(
            "[[bodies]]\nname = \"{name}\"\nposition = {}\nangle = {:?}\npoints = {{ {} }}\n\n",
            xy([f.x, f.y]),
            f.theta,
            list(f, pts)
        );
    }
    for (name, i, j) in joints {
        s += &format!(
            "[[joints]]\nname = \"{name}\"\ntype = \"revolute\"\nbody_i = \"{i}\"\npoint_i = \"{name}\"\nbody_j = \"{j}\"\npoint_j = \"{name}\"\n\n"
        );
    }
    s + &format!(
        "[[drivers]]\nname = \"crank\"\ntype = \"revolute_angle\"\njoint = \"{crank}\"\nf = \"{from:?} + {:?}*t\"\n",
        to - from
    )
}

/// The book's Watt Ia six-bar as a model file: the 3R chain (crank
/// C₁C₂, link B₂ = C₂C₃ carrying W₁, end effector E carrying C₃ and W₂),
/// the selected chain G₁W₁ (link B₄, carrying G₂) and the chain G₂W₂ of
/// the step-3 dyad `e` (link B₅); driven at C₁ from position 1 (t = 0 s)
/// to position 5 (t = 1 s).
fn six_bar(d: &Design, e: &Dyad) -> String {
    let (b1, b2, b4, t) = (d.b1[0], d.b2[0], d.b4[0], d.t[0]);
    let g1 = [b4.x, b4.y];
    let (c2, c3, w1) = ([b2.x, b2.y], b2.place([A, 0.0]), d.chosen.circle);
    let (g2, w2) = (b4.place(e.centre), t.place(e.moving));
    model(
        1e-3,
        &[("C1", C1), ("G1", g1)],
        &[
            ("crank", b1, vec![("C1", C1), ("C2", c2)]),
            ("b2", b2, vec![("C2", c2), ("C3", c3), ("W1", w1)]),
            ("b4", b4, vec![("G1", g1), ("W1", w1), ("G2", g2)]),
            ("b5", link(g2, w2), vec![("G2", g2), ("W2", w2)]),
            ("effector", t, vec![("C3", c3), ("W2", w2)]),
        ],
        &[
            ("C1", "ground", "crank"),
            ("C2", "crank", "b2"),
            ("C3", "b2", "effector"),
            ("G1", "ground", "b4"),
            ("W1", "b4", "b2"),
            ("G2", "b4", "b5"),
            ("W2", "b5", "effector"),
        ],
        "C1",
        d.b1[0].theta,
        d.b1[4].theta,
    )
}

/// The crank angle's fraction of its travel from position 1 to 5 at each
/// task position, `crank` its frames: the time (s) a model driven by
/// `model` reaches it.
fn task_times(crank: &[Pose]) -> Vec<f64> {
    let th = |k: usize| crank[k].theta;
    (0..5).map(|k| (th(k) - th(0)) / (th(4) - th(0))).collect()
}

/// Runs `text` at 0, 0.01, …, 1 s and at `extra` (s); the solver stops
/// at max |Φ| ≤ 1e-12.
fn run_text(text: &str, extra: &[f64]) -> Table {
    let loaded = load_str(text, Format::Toml, "published.toml")
        .unwrap_or_else(|e| panic!("the model does not load: {e}\n{text}"));
    let mut times: Vec<f64> = (0..=100).map(|k| k as f64 / 100.0).collect();
    times.extend_from_slice(extra);
    times.sort_by(f64::total_cmp);
    times.dedup();
    let settings = Settings {
        tol: 1e-12,
        max_iter: 25,
        jerk: false,
    };
    let mut table = Table::default();
    kinematics::run(&loaded.model, &times, &settings, &[], &mut table)
        .unwrap_or_else(|e| panic!("the model does not run: {e}\n{text}"));
    table
}

/// The body `name` of `table` is at the frame `p` (in `unit` m) at time
/// `t`, to 1e-9 m and rad.
fn assert_at(table: &Table, name: &str, t: f64, p: &Pose, unit: f64, what: &str) {
    let ex = at(table, &format!("{name}.x"), t) - p.x * unit;
    let ey = at(table, &format!("{name}.y"), t) - p.y * unit;
    let et = wrap_pi(at(table, &format!("{name}.phi"), t) - p.theta);
    assert!(
        ex.abs() < TOL && ey.abs() < TOL && et.abs() < TOL,
        "{what}: off by ({ex:e}, {ey:e}) m, {et:e} rad"
    );
}

/// The index in `found` of the pair that rounds to `row` (Table 6.2).
fn row_of(found: &[([P2; 2], Dyad)], row: [P2; 2]) -> usize {
    found
        .iter()
        .position(|(f, _)| {
            (0..2).all(|i| (0..2).all(|j| (f[i][j] - row[i][j]).abs() <= PRINTED_MM))
        })
        .unwrap_or_else(|| panic!("{row:?} not found"))
}

/// The six-bars of the book's design completed by step 3's rows 1 and 2
/// (the chains G₂W₂ other than W₁C₃, which only duplicates link B₂),
/// written as model files and run by camlink's kinematics with the crank
/// driven from position 1 to 5: the end effector passes the five task
/// positions of Table 6.1 to 1e-9 m and rad. (With row 3 the kinematics
/// stop at t = 0.549 s, between task positions 3 and 4, at a position the
/// mechanism cannot reach, so that six-bar is not run.) Along the way, the
/// rotations from position 1 of the crank (θ₁ of Table 6.3) and of link
/// B₂ (θ₂, and θ₃, which differs from θ₂ by −154.34° in every row) agree
/// with the differences of Table 6.3's printed angles to 0.01° (two
/// printed values each within 0.005°). Table 6.3's θ₄ and θ₅ follow the
/// book's loop equations (6.14)–(6.15) and match neither the rotation of
/// G₁W₁ nor that of any chain G₂W₂, so they are not compared.
#[test]
fn steering_six_bars_reach_the_published_task_positions() {
    let d = design();
    let times = task_times(&d.b1);
    for row in [0, 1] {
        let e = &d.step3[row_of(&d.step3, STEP3[row])].1;
        let text = six_bar(&d, e);
        let table = run_text(&text, &times);
        for (k, &t) in times.iter().enumerate() {
            let what = format!("row {}, task position {}\n{text}", row + 1, k + 1);
            assert_at(&table, "effector", t, &d.t[k], 1e-3, &what);
            let turned =
                |name: &str| wrap_pi(at(&table, name, t) - at(&table, name, 0.0)).to_degrees();
            let printed = |i: usize| ANGLES[k][i] - ANGLES[0][i];
            for (name, i) in [("crank.phi", 0), ("b2.phi", 1), ("b2.phi", 2)] {
                assert!(
                    (turned(name) - printed(i)).abs() <= 2.0 * PRINTED_DEG,
                    "θ{} at task position {}: {} against {}",
                    i + 1,
                    k + 1,
                    turned(name),
                    printed(i)
                );
            }
        }
    }
}
