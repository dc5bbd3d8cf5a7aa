//! Problem kinds of two-position and Burmester (four- and five-pose)
//! motion generation and of slider-cranks (motion and function
//! generation): their fields, their solutions' model files and reports.
//! Fields are documented in `docs/synthesis.md`.

use std::f64::consts::PI;

use serde::Deserialize;
use serde_json::{json, Value};

use super::{
    checks_json, invalid, links_json, pivot, requirements, value, values, Outcome, Solution, Table,
    DEFAULT_FIT_POINTS, DEFAULT_SAMPLES, MOST_POINTS,
};
use crate::burmester::{self, Candidate, Dyad, Equations, Limits, Tally};
use crate::error::{ErrorKind, SynthError};
use crate::fourbar::P2;
use crate::function::chebyshev;
use crate::model_file::{model_toml, pose_times, ModelSpec};
use crate::motion::{MotionSolution, Pose};
use crate::slider_crank::{self, SliderChecks, SliderChoice, SliderCrank, SliderModel};
use crate::two_positions::two_positions;

/// `slider = { moving = [x, y] }` or `slider = { angle = γ }`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SliderTable {
    moving: Option<Vec<Num>>,
    angle: Option<Num>,
}

use camlink_model::file::Num;

/// Default dyads sampled per branch of a four-pose problem's curve.
pub const DEFAULT_DYADS: usize = 36;
/// Default samples of β₂ per branch of the curves in the report.
pub const DEFAULT_CURVE_SAMPLES: usize = 360;
/// Default number of solutions written.
pub const DEFAULT_KEEP: usize = 5;
/// Steps of β₂ scanned for the Burmester points of five poses.
pub const BURMESTER_SCAN: usize = 4096;

/// The poses, `lo` to `hi` of them.
fn poses(t: &Table, lo: usize, hi: usize, kind: &str) -> Result<Vec<Pose>, SynthError> {
    let what = if lo == hi {
        format!("{lo}")
    } else {
        format!("{lo} to {hi}")
    };
    let Some(list) = &t.poses else {
        return Err(invalid(
            "synthesis.poses",
            format!("missing; give {what} poses [x (m), y (m), θ (rad)]"),
        ));
    };
    if !(lo..=hi).contains(&list.len()) {
        return Err(invalid(
            "synthesis.poses",
            format!("{} poses given; a {kind} problem takes {what}", list.len()),
        ));
    }
    let mut out = Vec::with_capacity(list.len());
    for (k, p) in list.iter().enumerate() {
        let [x, y, theta] =
            values::<3>(p, &format!("synthesis.poses[{k}]"), "x (m), y (m), θ (rad)")?;
        out.push(Pose { x, y, theta });
    }
    Ok(out)
}

fn poses_json(poses: &[Pose]) -> Vec<[f64; 3]> {
    poses.iter().map(|p| [p.x, p.y, p.theta]).collect()
}

fn fmt_poses(poses: &[Pose]) -> String {
    poses
        .iter()
        .map(|p| format!("({}, {}, {})", p.x, p.y, p.theta))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The model file of a four-bar guiding the coupler through `poses`.
fn guidance_model(
    name: &str,
    header: Vec<String>,
    s: &MotionSolution,
    crank_angles: &[f64],
) -> String {
    let l = &s.linkage;
    let b1 = s.poses[0].place(s.moving[1]);
    model_toml(&ModelSpec {
        name,
        header,
        linkage: l,
        coupler_points: [s.moving[0], s.moving[1], [0.0, 0.0]],
        coupler_start: s.poses[0],
        crank_angles,
        rocker_start: (b1[1] - l.o4[1]).atan2(b1[0] - l.o4[0]),
        stop: "the poses",
    })
}

pub(super) fn solve_two(t: &Table, name: &str) -> Result<Outcome, SynthError> {
    let p = poses(t, 2, 2, "two_positions")?;
    let req = requirements(t)?;
    let crank = pivot(&t.crank, "crank")?;
    let rocker = pivot(&t.rocker, "rocker")?;
    let along = match &t.along {
        None => [0.0, 0.0],
        Some(v) => values::<2>(v, "synthesis.along", "t_crank, t_rocker (m)")?,
    };
    let s = two_positions(
        &[p[0], p[1]],
        crank,
        rocker,
        along,
        &req,
        ["synthesis.poses", "synthesis.crank", "synthesis.rocker"],
    )?;
    let header = vec![
        format!(
            "{name}: a four-bar synthesised by camlink to guide its coupler through two poses."
        ),
        "The coupler's frame is the coupler line: at each pose its origin (point P)".into(),
        "and its angle are those prescribed.".into(),
        format!("Poses (x, y, θ): {}.", fmt_poses(&s.poses)),
    ];
    let model = guidance_model(name, header, &s, &s.checks.crank_angles);
    let report = json!({
        "name": name,
        "method": "two_positions",
        "links": links_json(&s.linkage),
        "moving_pivots": { "A": s.moving[0], "B": s.moving[1] },
        "along": along,
        "poses": poses_json(&s.poses),
        "pose_times": pose_times(&s.checks.crank_angles),
        "checks": checks_json(&s.checks),
    });
    Ok(Outcome {
        kind: "two_positions".into(),
        solutions: vec![Solution {
            name: name.to_string(),
            model,
            report,
        }],
    })
}

fn dyad_json(d: &Dyad) -> Value {
    json!({
        "centre": d.centre, "circle": d.circle, "moving": d.moving,
        "beta": d.beta, "beta2": d.beta2, "branch": d.branch,
    })
}

fn tally_json(t: &Tally) -> Value {
    json!({
        "pairs": t.pairs,
        "kept": t.kept,
        "removed": t.removed.iter().map(|(k, n)| json!({"check": k, "pairs": n})).collect::<Vec<_>>(),
    })
}

/// Why no pair of dyads is kept: the checks that removed them.
fn none_kept(t: &Tally, dyads: usize) -> SynthError {
    let all: Vec<&str> = t
        .removed
        .iter()
        .filter(|(_, n)| *n == t.pairs)
        .map(|(k, _)| k.as_str())
        .collect();
    let counts = t
        .removed
        .iter()
        .map(|(k, n)| format!("{k} {n}"))
        .collect::<Vec<_>>()
        .join(", ");
    let lead = if all.is_empty() {
        String::new()
    } else {
        format!("the {} check removed every one; ", all.join(" and the "))
    };
    SynthError::new(
        ErrorKind::NoSolution,
        "synthesis.poses",
        format!(
            "none of the {} four-bars paired from {dyads} dyads passes the checks: {lead}pairs \
             removed by each check: {counts}",
            t.pairs
        ),
    )
}

pub(super) fn solve_burmester(t: &Table, name: &str) -> Result<Outcome, SynthError> {
    let p = poses(t, 4, 5, "burmester")?;
    let req = requirements(t)?;
    let keep = t.keep.unwrap_or(DEFAULT_KEEP);
    if !(1..=1000).contains(&keep) {
        return Err(invalid(
            "synthesis.keep",
            format!("{keep}; expected 1 to 1000"),
        ));
    }
    let curve_samples = t.curve_samples.unwrap_or(DEFAULT_CURVE_SAMPLES);
    if !(8..=MOST_POINTS).contains(&curve_samples) {
        return Err(invalid(
            "synthesis.curve_samples",
            format!("{curve_samples}; expected 8 to {MOST_POINTS}"),
        ));
    }
    if p.len() == 5 && t.dyads.is_some() {
        return Err(invalid(
            "synthesis.dyads",
            "five poses have finitely many dyads (the Burmester points); dyads is for four poses",
        ));
    }
    let per_branch = t.dyads.unwrap_or(DEFAULT_DYADS);
    if !(2..=1000).contains(&per_branch) {
        return Err(invalid(
            "synthesis.dyads",
            format!("{per_branch}; expected 2 to 1000"),
        ));
    }
    let mut limits = Limits::default();
    if let Some(v) = &t.region {
        let r = values::<4>(v, "synthesis.region", "x_min, y_min, x_max, y_max (m)")?;
        if !(r[0] < r[2] && r[1] < r[3]) {
            return Err(invalid(
                "synthesis.region",
                "expected x_min < x_max and y_min < y_max (m)",
            ));
        }
        limits.region = Some(r);
    }
    if let Some(n) = &t.max_link_ratio {
        let m = value(n, "synthesis.max_link_ratio")?;
        if m.is_nan() || m < 1.0 {
            return Err(invalid(
                "synthesis.max_link_ratio",
                format!("{m}; a ratio of the longest link to the shortest is at least 1"),
            ));
        }
        limits.max_link_ratio = Some(m);
    }
    let eq = Equations::new(&p, "synthesis.poses")?;
    let (dyads, method) = if p.len() == 4 {
        (burmester::sample_dyads(&eq, per_branch), "burmester_four")
    } else {
        let pts = eq.burmester_points(BURMESTER_SCAN);
        if pts.len() < 2 {
            return Err(SynthError::new(
                ErrorKind::NoSolution,
                "synthesis.poses",
                format!(
                    "the five poses have {} real Burmester point{}: no four-bar guides the \
                     coupler through them (a four-bar needs two); move a pose or use four",
                    pts.len(),
                    if pts.len() == 1 { "" } else { "s" }
                ),
            ));
        }
        (pts, "burmester_five")
    };
    let (kept, tally) = burmester::pair(&p, &dyads, &req, &limits);
    if kept.is_empty() {
        return Err(none_kept(&tally, dyads.len()));
    }
    let eq4 = if p.len() == 4 {
        eq.clone()
    } else {
        Equations::new(&p[..4], "synthesis.poses")?
    };
    let curves = eq4.curves(curve_samples);
    let curves_json = json!({
        "centre": curves.iter().map(|l| l.iter().map(|d| d.centre).collect::<Vec<P2>>()).collect::<Vec<_>>(),
        "circle": curves.iter().map(|l| l.iter().map(|d| d.circle).collect::<Vec<P2>>()).collect::<Vec<_>>(),
    });
    let mut solutions = Vec::new();
    for (rank, c) in kept.iter().take(keep).enumerate() {
        let sname = format!("{name}_{}", rank + 1);
        solutions.push(burmester_solution(
            &sname,
            method,
            rank,
            c,
            &p,
            &dyads,
            &tally,
            &curves_json,
        ));
    }
    Ok(Outcome {
        kind: "burmester".into(),
        solutions,
    })
}

#[allow(clippy::too_many_arguments)]
fn burmester_solution(
    name: &str,
    method: &str,
    rank: usize,
    c: &Candidate,
    poses: &[Pose],
    dyads: &[Dyad],
    tally: &Tally,
    curves: &Value,
) -> Solution {
    let s = MotionSolution {
        poses: poses.to_vec(),
        moving: c.moving,
        linkage: c.linkage,
        checks: c.checks.clone(),
    };
    let header = vec![
        format!(
            "{name}: a four-bar synthesised by camlink (Burmester theory) to guide its coupler \
             through {} poses; rank {} by the least transmission angle.",
            poses.len(),
            rank + 1
        ),
        "The coupler's frame is the coupler line: at each pose its origin (point P)".into(),
        "and its angle are those prescribed.".into(),
        format!("Poses (x, y, θ): {}.", fmt_poses(poses)),
    ];
    let model = guidance_model(name, header, &s, &c.checks.crank_angles);
    let mut report = json!({
        "name": name,
        "method": method,
        "rank": rank + 1,
        "quality": {
            "figure": "least transmission angle from the in-line positions over the motion, min(μ_min, π − μ_max) (rad); larger is better",
            "value": c.quality,
            "link_ratio": c.link_ratio,
        },
        "links": links_json(&c.linkage),
        "moving_pivots": { "A": c.moving[0], "B": c.moving[1] },
        "dyads": { "crank": dyad_json(&dyads[c.dyads[0]]), "rocker": dyad_json(&dyads[c.dyads[1]]) },
        "poses": poses_json(poses),
        "pose_times": pose_times(&c.checks.crank_angles),
        "candidates": tally_json(tally),
        "curves": curves,
        "checks": checks_json(&c.checks),
    });
    if poses.len() == 5 {
        report["burmester_points"] = Value::Array(dyads.iter().map(dyad_json).collect());
    }
    Solution {
        name: name.to_string(),
        model,
        report,
    }
}

fn slider_checks_json(c: &SliderChecks) -> Value {
    json!({
        "grashof": if c.full_turn { "slider-crank (crank turns fully)" } else { "slider-crank (crank rocks)" },
        "turning": c.turning.name(),
        "crank_angles": c.crank_angles,
        "branches": c.branches,
        "transmission": { "min": c.transmission_min, "max": PI / 2.0 },
        "defects": c.defects.iter().map(|d| json!({"kind": d.kind.name(), "message": d.message})).collect::<Vec<_>>(),
    })
}

fn slider_links_json(l: &SliderCrank) -> Value {
    json!({
        "crank": l.crank.abs(),
        "coupler": l.coupler,
        // The slide's signed distance from O₂ along its left normal (m): e
        // for the slide y = e of function generation.
        "offset": -l.offset(),
        "O2": l.o2,
        "slide": { "point": l.line, "angle": l.dir },
    })
}

pub(super) fn solve_slider_motion(t: &Table, name: &str) -> Result<Outcome, SynthError> {
    let p = poses(t, 2, 3, "slider_motion")?;
    let req = requirements(t)?;
    let crank = pivot(&t.crank, "crank")?;
    let along = match (&t.along, p.len()) {
        (None, _) => 0.0,
        (Some(v), 2) => values::<1>(v, "synthesis.along", "t_crank (m)")?[0],
        (Some(_), _) => {
            return Err(invalid(
                "synthesis.along",
                "three poses fix the crank's pivot; along is for two",
            ))
        }
    };
    let choice = match &t.slider {
        None => {
            return Err(invalid(
                "synthesis.slider",
                "missing; give the slider's pin in the coupler frame (moving = [x, y], m) or \
                 the slide's direction (angle = γ, rad; three poses)",
            ))
        }
        Some(SliderTable {
            moving: Some(m),
            angle: None,
        }) => SliderChoice::Moving(values::<2>(m, "synthesis.slider.moving", "x, y (m)")?),
        Some(SliderTable {
            moving: None,
            angle: Some(a),
        }) => SliderChoice::Direction(value(a, "synthesis.slider.angle")?),
        Some(_) => {
            return Err(invalid(
                "synthesis.slider",
                "give exactly one of moving = [x, y] (m) and angle = γ (rad)",
            ))
        }
    };
    let s = slider_crank::motion(
        &p,
        crank,
        along,
        choice,
        &req,
        ["synthesis.poses", "synthesis.crank", "synthesis.slider"],
    )?;
    let l = &s.linkage;
    let b1 = p[0].place(s.moving[1]);
    let header = vec![
        format!(
            "{name}: a slider-crank synthesised by camlink to guide its coupler through {} poses.",
            p.len()
        ),
        "The coupler's frame is the coupler line: at each pose its origin (point P)".into(),
        "and its angle are those prescribed; B runs on the slide.".into(),
        format!("Poses (x, y, θ): {}.", fmt_poses(&p)),
    ];
    let model = slider_crank::model_toml(&SliderModel {
        name,
        header,
        linkage: l,
        coupler_points: [s.moving[0], s.moving[1], [0.0, 0.0]],
        coupler_start: p[0],
        slider_start: {
            let d = crate::fourbar::sub(b1, l.line);
            d[0] * l.dir.cos() + d[1] * l.dir.sin()
        },
        crank_angles: &s.checks.crank_angles,
        stop: "the poses",
    });
    let report = json!({
        "name": name,
        "method": "slider_motion",
        "links": slider_links_json(l),
        "moving_pivots": { "A": s.moving[0], "B": s.moving[1] },
        "poses": poses_json(&p),
        "pose_times": pose_times(&s.checks.crank_angles),
        "checks": slider_checks_json(&s.checks),
    });
    Ok(Outcome {
        kind: "slider_motion".into(),
        solutions: vec![Solution {
            name: name.to_string(),
            model,
            report,
        }],
    })
}

pub(super) fn solve_slider_function(t: &Table, name: &str) -> Result<Outcome, SynthError> {
    let missing =
        |f: &str, what: &str| invalid(&format!("synthesis.{f}"), format!("missing; give {what}"));
    let src = t
        .function
        .as_deref()
        .ok_or_else(|| missing("function", "y = f(x) as an expression in x"))?;
    let f = camlink_expr::Expr::parse(src, "x")
        .map_err(|e| invalid("synthesis.function", e.render(src)))?;
    let x = values::<2>(
        t.x.as_deref()
            .ok_or_else(|| missing("x", "[x_start, x_end]"))?,
        "synthesis.x",
        "x_start, x_end",
    )?;
    let input = values::<2>(
        t.input
            .as_deref()
            .ok_or_else(|| missing("input", "the crank angles [φ_start, φ_end] (rad)"))?,
        "synthesis.input",
        "φ_start, φ_end (rad)",
    )?;
    let output = values::<2>(
        t.output
            .as_deref()
            .ok_or_else(|| missing("output", "the slider positions [s_start, s_end] (m)"))?,
        "synthesis.output",
        "s_start, s_end (m)",
    )?;
    if x[0] == x[1] {
        return Err(invalid("synthesis.x", "x_start equals x_end; give a range"));
    }
    if input[0] == input[1] {
        return Err(invalid(
            "synthesis.input",
            "φ_start equals φ_end; the crank must turn",
        ));
    }
    if output[0] == output[1] {
        return Err(invalid(
            "synthesis.output",
            "s_start equals s_end; the slider must move",
        ));
    }
    let samples = t.samples.unwrap_or(DEFAULT_SAMPLES);
    if !(2..=MOST_POINTS).contains(&samples) {
        return Err(invalid(
            "synthesis.samples",
            format!("{samples}; expected 2 to {MOST_POINTS}"),
        ));
    }
    let xs_dense: Vec<f64> = (0..samples)
        .map(|i| x[0] + (x[1] - x[0]) * i as f64 / (samples - 1) as f64)
        .collect();
    for &xi in &xs_dense {
        if let Err(e) = f.check(xi) {
            return Err(invalid("synthesis.function", e.to_string()));
        }
    }
    let (ys, ye) = (f.eval(x[0]), f.eval(x[1]));
    let largest = xs_dense
        .iter()
        .map(|&v| f.eval(v).abs())
        .fold(0.0, f64::max);
    if (ye - ys).abs() <= 1e-12 * largest {
        return Err(invalid(
            "synthesis.function",
            "f(x_start) equals f(x_end), so the output range cannot be mapped to the slider",
        ));
    }
    let map = |xv: f64| {
        (
            input[0] + (xv - x[0]) / (x[1] - x[0]) * (input[1] - input[0]),
            output[0] + (f.eval(xv) - ys) / (ye - ys) * (output[1] - output[0]),
        )
    };
    let method = t.method.as_deref().unwrap_or("three_point");
    let given_points = match &t.points {
        None => None,
        Some(pts) => {
            let mut v = Vec::new();
            let (lo, hi) = (x[0].min(x[1]), x[0].max(x[1]));
            for (k, n) in pts.iter().enumerate() {
                let field = format!("synthesis.points[{k}]");
                let xv = value(n, &field)?;
                if !(lo..=hi).contains(&xv) {
                    return Err(invalid(
                        &field,
                        format!("x = {xv} lies outside the range [{lo}, {hi}]"),
                    ));
                }
                v.push(xv);
            }
            v.sort_by(|p, q| (p - x[0]).abs().total_cmp(&(q - x[0]).abs()));
            Some(v)
        }
    };
    let pts = match method {
        "three_point" => {
            if t.count.is_some() {
                return Err(invalid(
                    "synthesis.count",
                    "a least_squares field; three_point uses three points",
                ));
            }
            let v = given_points.unwrap_or_else(|| chebyshev(3, x[0], x[1]));
            if v.len() != 3 {
                return Err(invalid(
                    "synthesis.points",
                    format!("{} points; three_point takes three", v.len()),
                ));
            }
            v
        }
        "least_squares" => {
            let v = match (given_points, t.count) {
                (Some(_), Some(_)) => {
                    return Err(invalid("synthesis.count", "give points or count, not both"))
                }
                (Some(v), None) => v,
                (None, n) => {
                    let n = n.unwrap_or(DEFAULT_FIT_POINTS);
                    if !(3..=MOST_POINTS).contains(&n) {
                        return Err(invalid(
                            "synthesis.count",
                            format!("{n}; expected 3 to {MOST_POINTS}"),
                        ));
                    }
                    chebyshev(n, x[0], x[1])
                }
            };
            if v.len() < 3 {
                return Err(invalid(
                    "synthesis.points",
                    format!("{} points; least_squares needs at least three", v.len()),
                ));
            }
            v
        }
        other => {
            return Err(invalid(
                "synthesis.method",
                format!("'{other}'; expected \"three_point\" or \"least_squares\""),
            ))
        }
    };
    let mut sorted = pts.clone();
    sorted.sort_by(f64::total_cmp);
    if sorted.windows(2).any(|w| w[0] == w[1]) {
        return Err(SynthError::new(
            ErrorKind::Coincident,
            "synthesis.points",
            "two points have the same x",
        ));
    }
    let field = if t.points.is_some() {
        "synthesis.points"
    } else {
        "synthesis.function"
    };
    let pairs: Vec<(f64, f64)> = pts.iter().map(|&xv| map(xv)).collect();
    let k = slider_crank::solve_k(&pairs, field)?;
    let l = slider_crank::linkage_of(k, field)?;
    let req = requirements(t)?;
    let pins: Vec<P2> = pairs.iter().map(|&(phi, _)| l.crank_pin(phi)).collect();
    let sliders: Vec<P2> = pairs.iter().map(|&(_, s)| l.pin(s)).collect();
    let checks = SliderChecks::of(&l, &pins, &sliders, &req, Some((input[0], input[1])));
    let sigma = if checks.branches[0] != 0.0 {
        checks.branches[0]
    } else {
        1.0
    };
    let asked: Vec<(f64, f64)> = xs_dense.iter().map(|&xv| map(xv)).collect();
    let err = slider_crank::structural_error(&l, sigma, &asked);
    let mut angles = vec![input[0]];
    angles.extend(pairs.iter().map(|p| p.0));
    angles.push(input[1]);
    let a0 = l.crank_pin(input[0]);
    let s0 = l.slider(input[0], sigma).unwrap_or(output[0]);
    let b0 = l.pin(s0);
    let method_name = if method == "three_point" {
        "slider_three_point"
    } else {
        "slider_least_squares"
    };
    let header = vec![
        format!("{name}: an offset slider-crank function generator synthesised by camlink ({method})."),
        format!(
            "y = {src} for x from {} to {}; crank angle φ from {} to {} rad (from +x), slider position s from {} to {} m",
            x[0], x[1], input[0], input[1], output[0], output[1]
        ),
        "along the slide y = e through C = (0, e); s is the slider body's x.".into(),
        "A negative crank length points the crank against its body axis.".into(),
    ];
    let model = slider_crank::model_toml(&SliderModel {
        name,
        header,
        linkage: &l,
        coupler_points: [[0.0, 0.0], [l.coupler, 0.0], [0.5 * l.coupler, 0.0]],
        coupler_start: crate::model_file::coupler_along(a0, b0),
        slider_start: s0,
        crank_angles: &angles,
        stop: "φ_start, the points fitted and φ_end",
    });
    let times = pose_times(&angles);
    let report = json!({
        "name": name,
        "method": method_name,
        "function": src,
        "links": slider_links_json(&l),
        "signed": { "crank": l.crank, "offset": l.line[1] },
        "k": k,
        "x": pts,
        "pairs": pairs.iter().map(|p| [p.0, p.1]).collect::<Vec<_>>(),
        "point_times": &times[1..times.len() - 1],
        "branch": sigma,
        "structural_error": {
            "max": err.max, "at_x": xs_dense[err.at], "rms": err.rms, "samples": samples,
            "unassembled_at": err.unassembled_at.map(|i| xs_dense[i]),
            "units": "m",
        },
        "checks": slider_checks_json(&checks),
    });
    Ok(Outcome {
        kind: "slider_function".into(),
        solutions: vec![Solution {
            name: name.to_string(),
            model,
            report,
        }],
    })
}
