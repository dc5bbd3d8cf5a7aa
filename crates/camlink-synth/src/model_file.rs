//! A synthesised four-bar written as a camlink model file (TOML) that
//! `camlink run` runs as is.
//!
//! Bodies: `crank` (frame at O₂, x along its axis, point `A` = [a, 0] with
//! a signed), `coupler` (points `A`, `B` and the coupler point `P` in its
//! frame) and `rocker` (frame at O₄, point `B` = [c, 0]). Joints: revolutes
//! `O2`, `A`, `B`, `O4`. Driver `motor`: the crank angle
//! φ(t) = theta1 + w·t (rad), which takes the crank from the first of its
//! given angles (t = 0) to the last (t = 1 s). Each body is placed where it is at the
//! first pose, exactly. The output times are 40 even steps over [0, 1] s
//! with the time of every given crank angle added.

use std::fmt::Write;

use crate::fourbar::{FourBar, P2};
use crate::motion::Pose;

/// What the model file needs besides the linkage.
#[derive(Clone, Debug)]
pub struct ModelSpec<'a> {
    /// The model's name.
    pub name: &'a str,
    /// Comment lines written at the top (without `#`).
    pub header: Vec<String>,
    pub linkage: &'a FourBar,
    /// A, B and P in the coupler frame (m).
    pub coupler_points: [P2; 3],
    /// The coupler frame's pose at the first pose.
    pub coupler_start: Pose,
    /// The crank angle at each pose, unwrapped along the motion (rad).
    pub crank_angles: &'a [f64],
    /// The rocker angle at the first pose (rad).
    pub rocker_start: f64,
    /// What the crank angles mark, for the file's comments ("the poses").
    pub stop: &'a str,
}

/// Output steps over the motion.
const STEPS: usize = 40;

/// The time (s) at which the driven crank reaches each of `crank_angles`.
pub fn pose_times(crank_angles: &[f64]) -> Vec<f64> {
    let first = crank_angles[0];
    let sweep = crank_angles[crank_angles.len() - 1] - first;
    crank_angles
        .iter()
        .map(|&phi| {
            // + 0.0 turns −0 into 0.
            if sweep == 0.0 {
                0.0
            } else {
                (phi - first) / sweep + 0.0
            }
        })
        .collect()
}

/// Even steps over [0, 1] s with the pose times added, increasing; an even
/// step within 1e-6 s of a pose time gives way to it.
fn output_times(poses: &[f64]) -> Vec<f64> {
    let mut t: Vec<f64> = (0..=STEPS)
        .map(|k| k as f64 / STEPS as f64)
        .filter(|s| poses.iter().all(|p| (p - s).abs() > 1e-6))
        .chain(poses.iter().copied())
        .collect();
    t.sort_by(f64::total_cmp);
    t.dedup();
    t
}

pub(crate) fn num(x: f64) -> String {
    // Rust prints the shortest decimal that reads back to the same f64;
    // TOML reads "1" as an integer, which model files accept as a number.
    if x == 0.0 {
        "0".to_string()
    } else {
        format!("{x}")
    }
}

pub(crate) fn pair(p: P2) -> String {
    format!("[{}, {}]", num(p[0]), num(p[1]))
}

/// What the model files of a four-bar and a slider-crank share: what the
/// crank is, where the coupler starts and what it carries.
pub(crate) struct CrankCoupler<'a> {
    pub name: &'a str,
    /// Comment lines written at the top (without `#`).
    pub header: &'a [String],
    /// The crank angles the run reaches, unwrapped along the motion (rad).
    pub crank_angles: &'a [f64],
    /// What the crank angles mark, for the file's comments.
    pub stop: &'a str,
    /// Where the comment of `theta1` says the crank angle is taken.
    pub start: &'a str,
    /// The ground points: O₂ and the other ground point, by name (m).
    pub ground: [(&'a str, P2); 2],
    /// The crank's length a (m).
    pub crank: f64,
    /// The coupler frame's pose at the first crank angle.
    pub coupler_start: Pose,
    /// A, B and P in the coupler frame (m).
    pub coupler_points: [P2; 3],
}

/// The header comments, `[model]`, `[parameters]`, `[ground]` and the
/// bodies `crank` and `coupler` of a synthesised model file.
pub(crate) fn crank_and_coupler(s: &mut String, m: &CrankCoupler<'_>) {
    let phi = m.crank_angles;
    let first = phi[0];
    let sweep = phi[phi.len() - 1] - first;
    let times = pose_times(phi);
    let [pa, pb, pp] = m.coupler_points;
    let c0 = m.coupler_start;
    for line in m.header {
        let line: String = line
            .chars()
            .map(|c| if c.is_control() { ' ' } else { c })
            .collect();
        let _ = writeln!(s, "# {line}");
    }
    let _ = writeln!(
        s,
        "#\n# The crank is driven at constant speed from t = 0 to t = 1 s;\n\
         # {what} are reached at t = {} s.\n# Units: m, rad, s.\n",
        times.iter().map(|t| num(*t)).collect::<Vec<_>>().join(", "),
        what = m.stop,
    );
    let name = toml::Value::String(m.name.to_string());
    let _ = writeln!(s, "[model]\nname = {name}\n");
    let _ = writeln!(
        s,
        "[parameters]\ntheta1 = {}        # crank angle at {} (rad)\nw = {}        # crank speed (rad/s)\n",
        num(first),
        m.start,
        num(sweep)
    );
    let [(n2, o2), (n4, o4)] = m.ground;
    let _ = writeln!(
        s,
        "[ground]\npoints = {{ {n2} = {}, {n4} = {} }}\n",
        pair(o2),
        pair(o4)
    );
    let _ = writeln!(
        s,
        "[[bodies]]\nname = \"crank\"\nposition = {}\nangle = \"theta1\"\npoints = {{ O2 = [0, 0], A = [{}, 0] }}\n",
        pair(o2),
        num(m.crank)
    );
    let _ = writeln!(
        s,
        "[[bodies]]\nname = \"coupler\"\nposition = {}\nangle = {}\npoints = {{ A = {}, B = {}, P = {} }}\n",
        pair([c0.x, c0.y]),
        num(c0.theta),
        pair(pa),
        pair(pb),
        pair(pp)
    );
}

/// The model file's text.
pub fn model_toml(spec: &ModelSpec<'_>) -> String {
    let l = spec.linkage;
    let phi = spec.crank_angles;
    let times = pose_times(phi);
    let mut s = String::new();
    crank_and_coupler(
        &mut s,
        &CrankCoupler {
            name: spec.name,
            header: &spec.header,
            crank_angles: phi,
            stop: spec.stop,
            start: "the first pose",
            ground: [("O2", l.o2), ("O4", l.o4)],
            crank: l.crank,
            coupler_start: spec.coupler_start,
            coupler_points: spec.coupler_points,
        },
    );
    let _ = writeln!(
        s,
        "[[bodies]]\nname = \"rocker\"\nposition = {}\nangle = {}\npoints = {{ O4 = [0, 0], B = [{}, 0] }}\n",
        pair(l.o4),
        num(spec.rocker_start),
        num(l.rocker)
    );
    for (name, bi, pi, bj, pj) in [
        ("O2", "ground", "O2", "crank", "O2"),
        ("A", "crank", "A", "coupler", "A"),
        ("B", "coupler", "B", "rocker", "B"),
        ("O4", "ground", "O4", "rocker", "O4"),
    ] {
        let _ = writeln!(
            s,
            "[[joints]]\nname = \"{name}\"\ntype = \"revolute\"\nbody_i = \"{bi}\"\npoint_i = \"{pi}\"\nbody_j = \"{bj}\"\npoint_j = \"{pj}\"\n"
        );
    }
    let _ = writeln!(
        s,
        "[[drivers]]\nname = \"motor\"\ntype = \"revolute_angle\"\njoint = \"O2\"\nf = \"theta1 + w*t\"\n"
    );
    let _ = writeln!(
        s,
        "[analysis]\ntimes = [{}]\npoints = [\"coupler.P\", \"crank.A\", \"rocker.B\"]",
        output_times(&times)
            .iter()
            .map(|t| num(*t))
            .collect::<Vec<_>>()
            .join(", ")
    );
    s
}

/// The coupler frame's pose for a coupler whose frame sits at A with x
/// towards B (m, rad).
pub fn coupler_along(a: P2, b: P2) -> Pose {
    let theta = (b[1] - a[1]).atan2(b[0] - a[0]);
    Pose {
        x: a[0],
        y: a[1],
        theta,
    }
}
