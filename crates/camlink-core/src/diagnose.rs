//! What a model's constraints allow: rank of Φ_q, degrees of freedom,
//! redundant equations and free motions, at the assembled initial
//! configuration.
//!
//! Counting equations against coordinates is not enough: a planar four-bar
//! with a fifth revolute, or a parallelogram linkage, has dependent
//! equations. The rank of Φ_q (from its singular values) gives the true
//! number of degrees of freedom, n − rank.

use faer::linalg::solvers::{Solve, SolveLstsq};
use faer::Mat;

use crate::assembly::Assembly;
use crate::constraint::{Constraint, Equations};
use crate::curve::contact::{sample_mean, side_of, solid_side};
use crate::curve::distance::Features;
use crate::fmt_num::num;
use crate::math::{norm2, perp, point, rot};
use crate::model::Model;

/// A unilateral contact whose gap at the model's placement exceeds this
/// (m) starts open: it removes no freedom until it closes. A smaller gap
/// is closed by the assembly.
pub const OPEN_AT_START: f64 = 1e-6;

/// The two features whose gap is measured while unilateral joint `j` is
/// open, with a face's normal on the side of the cam's mean point at body
/// coordinates `q` = (q_i, q_j); an error for a joint that cannot open (not
/// a cam contact, or no closed curve to tell the solid side).
pub fn gap_features(model: &Model, j: usize, q: [[f64; 3]; 2]) -> Result<Features, &'static str> {
    match &model.joints[j].constraint {
        Constraint::FlatFollower(f) => {
            if f.curve_i.orientation().is_none() {
                return Err("a unilateral flat_follower needs a closed cam curve");
            }
            let cam_mean = point(q[0], sample_mean(&f.curve_i));
            let face = point(q[1], f.s_j);
            let nf = perp(f.u_j);
            let s = side_of(rot(q[1][2], nf), face, cam_mean);
            Ok(Features::Face {
                curve: f.curve_i.clone(),
                point: f.s_j,
                m: [s * nf[0], s * nf[1]],
            })
        }
        Constraint::CamFollower(c) => {
            let curves = [c.curve_i.clone(), c.curve_j.clone()];
            match solid_side([c.curve_i.orientation(), c.curve_j.orientation()]) {
                Some((side, sigma)) => Ok(Features::Curves {
                    curves,
                    side,
                    sigma,
                }),
                None => Err("a unilateral cam_follower needs a closed curve on one side"),
            }
        }
        _ => Err("only cam_follower and flat_follower joints can be unilateral"),
    }
}

/// The gap (m) of unilateral joint `j` at the placement `q` (layout
/// `asm`), before any assembly: what a forward dynamics run starts from.
/// `None` for a joint that cannot open.
pub(crate) fn gap_at(model: &Model, asm: &Assembly, j: usize, q: &[f64]) -> Option<f64> {
    let mut qb = [[0.0; 3]; 2];
    for (s, b) in model.joints[j].constraint.bodies().iter().enumerate() {
        if let Some(c) = asm.body_col(b.0) {
            qb[s].copy_from_slice(&q[c..c + 3]);
        }
    }
    let features = gap_features(model, j, qb).ok()?;
    Some(features.gap(qb, [[0.0; 3]; 2], None).gap)
}

/// One equation that depends on others.
#[derive(Clone, Debug, PartialEq)]
pub struct Redundancy {
    /// `joint.equation`, e.g. `O4.y`.
    pub equation: String,
    /// The independent equations it is a combination of, with coefficients.
    pub depends_on: Vec<(String, f64)>,
}

/// A unilateral contact that removes no freedom at the start and is left
/// out of the analysis: one open at the placement (its gap above
/// [`OPEN_AT_START`]), as a forward dynamics run starts it, or a compliant
/// one, which acts through a force and is never a constraint.
#[derive(Clone, Debug, PartialEq)]
pub struct Released {
    /// The contact joint's name.
    pub joint: String,
    /// Its gap at the placement (m); `None` for a compliant contact.
    pub gap: Option<f64>,
    /// One line for a report, e.g. `contact 'floor': open at t = 0 s (gap
    /// 0.1 m): its 2 equations and 1 own coordinate are not counted`.
    pub text: String,
}

/// The unilateral contacts of `model` that are open at the placement or
/// compliant, at time `t` (s, for the text), with their joint indices.
pub(crate) fn released_at_start(model: &Model, t: f64) -> Vec<(usize, Released)> {
    let asm = Assembly::new(model);
    let q = asm.initial_q(model);
    let mut out = Vec::new();
    for (j, joint) in model.joints.iter().enumerate() {
        let Some(law) = joint.unilateral else {
            continue;
        };
        if joint.driver {
            continue;
        }
        let name = &joint.name;
        let (rows, own) = (joint.constraint.rows(), joint.constraint.own_count());
        let not_counted = format!(
            "its {rows} equation{} and {own} own coordinate{} are not counted",
            if rows == 1 { "" } else { "s" },
            if own == 1 { "" } else { "s" }
        );
        if law.compliant.is_some() {
            out.push((
                j,
                Released {
                    joint: name.clone(),
                    gap: None,
                    text: format!(
                        "contact '{name}': compliant, a force from the overlap rather than a \
                         constraint: {not_counted}"
                    ),
                },
            ));
            continue;
        }
        let Some(gap) = gap_at(model, &asm, j, &q) else {
            continue;
        };
        if gap > OPEN_AT_START {
            out.push((
                j,
                Released {
                    joint: name.clone(),
                    gap: Some(gap),
                    text: format!(
                        "contact '{name}': open at t = {} s (gap {} m): {not_counted}",
                        num(t),
                        num(gap)
                    ),
                },
            ));
        }
    }
    out
}

/// The result of [`diagnose`].
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnosis {
    pub coordinates: usize,
    pub equations: usize,
    /// Rank of Φ_q at the initial configuration.
    pub rank: usize,
    /// Degrees of freedom, coordinates − rank.
    pub dof: usize,
    /// Equations that depend on earlier ones (in model order).
    pub redundant: Vec<Redundancy>,
    /// The drivers among the `redundant` equations and the equations they
    /// depend on, each once, in the order `redundant` names them: a driver
    /// there fixes a motion the other equations fix already (the model is
    /// over-driven). Empty when none is.
    pub redundant_drivers: Vec<String>,
    /// A basis of the motions the constraints leave free, each as the
    /// coordinates that move most (name, relative amount; largest = ±1).
    pub free_motions: Vec<Vec<(String, f64)>>,
    /// Largest |Φ| after assembly; above the tolerance the configuration
    /// could not be assembled and the rank is that of the placement.
    pub residual: f64,
    /// σ_max / σ_min of the nonzero singular values.
    pub condition: f64,
    /// When assembly failed (`residual` above the tolerance): each joint
    /// whose equations stay open, with its largest |Φ| (m or rad), largest
    /// first.
    pub open_joints: Vec<(String, f64)>,
    /// False for a model too large for the dense rank analysis (more than
    /// [`DENSE_MAX`] coordinates): rank and degrees of freedom then come from
    /// counting, and no redundancy or free motion is reported.
    pub exact: bool,
    /// The unilateral contacts left out because they remove no freedom at
    /// the start ([`released_at_start`]); `coordinates`, `equations`,
    /// `rank` and `dof` are those of the model without them.
    pub released: Vec<Released>,
}

/// Largest model (coordinates) analysed by a dense singular value
/// decomposition; its memory grows as n².
pub(crate) const DENSE_MAX: usize = 2000;

/// Relative size under which a singular value counts as zero.
const RANK_TOL: f64 = 1e-9;

/// Assembles in the least-squares sense from the model's placement (so that
/// an under-driven model assembles too), then analyses Φ_q at time `t`.
///
/// Unilateral contacts that are open at the placement, or compliant, remove
/// no freedom at the start: they are left out ([`Diagnosis::released`]).
pub fn diagnose(model: &Model, t: f64, tol: f64) -> Diagnosis {
    let released = released_at_start(model, t);
    if released.is_empty() {
        return diagnose_all(model, t, tol);
    }
    let mut reduced = model.clone();
    reduced.joints = model
        .joints
        .iter()
        .enumerate()
        .filter(|(j, _)| !released.iter().any(|(r, _)| r == j))
        .map(|(_, joint)| joint.clone())
        .collect();
    let mut d = diagnose_all(&reduced, t, tol);
    d.released = released.into_iter().map(|(_, r)| r).collect();
    d
}

/// [`diagnose`] with every joint counted.
fn diagnose_all(model: &Model, t: f64, tol: f64) -> Diagnosis {
    let asm = Assembly::new(model);
    let (n, m) = (asm.n, asm.m);
    if n > DENSE_MAX {
        return Diagnosis {
            coordinates: n,
            equations: m,
            rank: m.min(n),
            dof: n - m.min(n),
            redundant: Vec::new(),
            redundant_drivers: Vec::new(),
            free_motions: Vec::new(),
            residual: f64::NAN,
            condition: f64::NAN,
            open_joints: Vec::new(),
            exact: false,
            released: Vec::new(),
        };
    }
    let mut q = asm.initial_q(model);
    let residual = least_squares_assembly(model, &asm, &mut q, t, tol);
    let open_joints = if residual > tol {
        open_joints(model, &asm, &q, t, tol)
    } else {
        Vec::new()
    };
    let j = dense_jacobian(model, &asm, &q, t);

    let (rank, condition, null) = if m == 0 || n == 0 {
        (0, 1.0, (0..n).map(|k| unit(n, k)).collect())
    } else {
        svd_rank(&j)
    };
    let redundant = redundant_rows(model, &asm, &j);
    let redundant_drivers = drivers_among(model, &redundant);
    let free_motions = null
        .iter()
        .map(|v| describe_motion(model, &asm, v))
        .collect();
    Diagnosis {
        coordinates: n,
        equations: m,
        rank,
        dof: n - rank,
        redundant,
        redundant_drivers,
        free_motions,
        residual,
        condition,
        open_joints,
        exact: true,
        released: Vec::new(),
    }
}

/// The equations of Φ_q at `q` (m × n, dense) that are combinations of
/// earlier independent ones, in model order: the rows an analysis must
/// drop or regularise. Empty for a model too large for the dense analysis
/// (more than [`DENSE_MAX`] coordinates).
pub(crate) fn redundant_equations(
    model: &Model,
    asm: &Assembly,
    q: &[f64],
    t: f64,
) -> Vec<Redundancy> {
    if asm.n > DENSE_MAX || asm.m == 0 {
        return Vec::new();
    }
    redundant_rows(model, asm, &dense_jacobian(model, asm, q, t))
}

/// A joint counts among the weakest when its share of the weakest
/// combination of equations is at least this fraction of the largest share.
const WEAK_SHARE: f64 = 0.1;

/// The joints whose equations lose rank first at `q` (m or rad), time `t`
/// (s), in model order: u, the left singular vector of Φ_q for its
/// smallest singular value among the min(m, n) largest, is the
/// combination of equations that is nearest to dependent (Φ_qᵀu = σ_min v);
/// a joint is named when the norm of u over its rows is at least
/// [`WEAK_SHARE`] of the largest such norm. Empty for a model larger than
/// [`DENSE_MAX`] coordinates or without equations.
pub(crate) fn weakest_joints(model: &Model, asm: &Assembly, q: &[f64], t: f64) -> Vec<String> {
    let (n, m) = (asm.n, asm.m);
    if n > DENSE_MAX || m == 0 || n == 0 {
        return Vec::new();
    }
    let j = dense_jacobian(model, asm, q, t);
    let Ok(svd) = j.svd() else {
        return Vec::new();
    };
    let s = svd.S().column_vector();
    let k = (0..s.nrows().min(m).min(n))
        .min_by(|&a, &b| s[a].total_cmp(&s[b]))
        .unwrap_or(0);
    let u = svd.U();
    let share: Vec<f64> = (0..model.joints.len())
        .map(|jt| {
            asm.rows_of(jt)
                .map(|r| u[(r, k)] * u[(r, k)])
                .sum::<f64>()
                .sqrt()
        })
        .collect();
    let big = share.iter().fold(0.0f64, |a, &b| a.max(b));
    model
        .joints
        .iter()
        .zip(&share)
        .filter(|&(_, &w)| big > 0.0 && w >= WEAK_SHARE * big)
        .map(|(jt, _)| jt.name.clone())
        .collect()
}

/// The clause of a warning naming the joints whose equations lose rank
/// (empty when none are known): ` at joints O2, A, B, O4 (their equations
/// lose rank)`.
pub(crate) fn losing_rank(joints: &[String]) -> String {
    if joints.is_empty() {
        String::new()
    } else {
        format!(
            " at joint{} {} (their equations lose rank)",
            if joints.len() > 1 { "s" } else { "" },
            joints.join(", ")
        )
    }
}

/// Φ_q as a dense m × n matrix.
pub fn dense_jacobian(model: &Model, asm: &Assembly, q: &[f64], t: f64) -> Mat<f64> {
    let mut j = Mat::zeros(asm.m, asm.n);
    asm.jacobian(model, q, t, |r, c, v| j[(r, c)] = v);
    j
}

/// The Levenberg–Marquardt step δ = (JᵀJ + μ s I)⁻¹ Jᵀ Φ into `out`, with
/// μ relative to s, the largest diagonal entry of JᵀJ; q − δ lowers ‖Φ‖²
/// where J is rank deficient or not square.
pub(crate) fn levenberg_marquardt(j: &Mat<f64>, phi: &[f64], mu: f64, out: &mut [f64]) {
    let jtj = j.transpose() * j;
    let scale = (0..jtj.nrows()).fold(1e-12f64, |a, k| a.max(jtj[(k, k)]));
    let a = Mat::from_fn(jtj.nrows(), jtj.ncols(), |r, c| {
        jtj[(r, c)] + if r == c { mu * scale } else { 0.0 }
    });
    let f = Mat::from_fn(phi.len(), 1, |r, _| phi[r]);
    let x = a.partial_piv_lu().solve(j.transpose() * &f);
    for (k, o) in out.iter_mut().enumerate() {
        *o = x[(k, 0)];
    }
}

/// Levenberg–Marquardt on ‖Φ‖² from q; returns the final max |Φ|.
fn least_squares_assembly(model: &Model, asm: &Assembly, q: &mut [f64], t: f64, tol: f64) -> f64 {
    let mut phi = vec![0.0; asm.m];
    let mut trial = q.to_vec();
    let mut trial_phi = phi.clone();
    let mut dq = vec![0.0; asm.n];
    let mut mu = 1e-6;
    asm.phi(model, q, t, &mut phi);
    for _ in 0..200 {
        let r = phi.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        if r <= tol || r.is_nan() {
            break;
        }
        let j = dense_jacobian(model, asm, q, t);
        levenberg_marquardt(&j, &phi, mu, &mut dq);
        // The step keeps its direction, shortened so that no angle turns by
        // more than MAX_TURN; lengths are not limited, whatever their unit
        // (a course model in mm moves its bodies by hundreds).
        let turn = angle_columns(model, asm).fold(0.0f64, |a, c| a.max(dq[c].abs()));
        let scale = if turn > MAX_TURN {
            MAX_TURN / turn
        } else {
            1.0
        };
        for k in 0..asm.n {
            trial[k] = q[k] - scale * dq[k];
        }
        asm.phi(model, &trial, t, &mut trial_phi);
        if norm2(&trial_phi) < norm2(&phi) {
            q.copy_from_slice(&trial);
            phi.copy_from_slice(&trial_phi);
            mu = (mu * 0.3).max(1e-12);
        } else {
            mu *= 10.0;
            if mu > 1e6 {
                break;
            }
        }
    }
    phi.iter().fold(0.0f64, |a, x| a.max(x.abs()))
}

/// Largest turn (rad) of a body in one step of [`least_squares_assembly`].
const MAX_TURN: f64 = 0.5;

/// The columns of the bodies' angles φ in q.
fn angle_columns<'a>(model: &'a Model, asm: &'a Assembly) -> impl Iterator<Item = usize> + 'a {
    (0..model.bodies.len()).filter_map(|b| asm.body_col(b).map(|c| c + 2))
}

fn unit(n: usize, k: usize) -> Vec<f64> {
    let mut v = vec![0.0; n];
    v[k] = 1.0;
    v
}

/// Rank, condition number and a basis of the null space of `j`.
pub(crate) fn svd_rank(j: &Mat<f64>) -> (usize, f64, Vec<Vec<f64>>) {
    let n = j.ncols();
    let svd = match j.svd() {
        Ok(svd) => svd,
        Err(_) => return (0, f64::INFINITY, Vec::new()),
    };
    let s = svd.S().column_vector();
    let smax = (0..s.nrows()).fold(0.0f64, |a, k| a.max(s[k]));
    let cut = RANK_TOL * smax.max(1e-300) * (j.nrows().max(n) as f64);
    let rank = (0..s.nrows()).filter(|&k| s[k] > cut).count();
    let smin = (0..s.nrows())
        .filter(|&k| s[k] > cut)
        .fold(f64::INFINITY, |a, k| a.min(s[k]));
    let v = svd.V();
    let null = (rank..n)
        .map(|c| (0..n).map(|r| v[(r, c)]).collect())
        .collect();
    (rank, smax / smin, null)
}

/// Equations (in model order) that are combinations of earlier independent
/// ones, found by Gram–Schmidt on the rows of Φ_q.
/// The joints with an equation |Φ| above `tol` at `q`, with their largest
/// |Φ|, largest first.
fn open_joints(model: &Model, asm: &Assembly, q: &[f64], t: f64, tol: f64) -> Vec<(String, f64)> {
    let mut phi = vec![0.0; asm.m];
    asm.phi(model, q, t, &mut phi);
    let mut out: Vec<(String, f64)> = (0..model.joints.len())
        .filter_map(|j| {
            let worst = asm.rows_of(j).map(|r| phi[r].abs()).fold(0.0, f64::max);
            (worst > tol).then(|| (model.joints[j].name.clone(), worst))
        })
        .collect();
    out.sort_by(|a, b| b.1.total_cmp(&a.1));
    out
}

fn redundant_rows(model: &Model, asm: &Assembly, j: &Mat<f64>) -> Vec<Redundancy> {
    let (m, n) = (j.nrows(), j.ncols());
    let mut basis: Vec<Vec<f64>> = Vec::new();
    let mut independent: Vec<usize> = Vec::new();
    let mut out = Vec::new();
    let row_scale = (0..m)
        .map(|r| (0..n).map(|c| j[(r, c)].powi(2)).sum::<f64>().sqrt())
        .fold(0.0f64, f64::max);
    for r in 0..m {
        let row: Vec<f64> = (0..n).map(|c| j[(r, c)]).collect();
        let mut v = row.clone();
        for _ in 0..2 {
            for b in &basis {
                let d: f64 = v.iter().zip(b).map(|(x, y)| x * y).sum();
                v.iter_mut().zip(b).for_each(|(x, y)| *x -= d * y);
            }
        }
        let len = norm2(&v);
        if len > 1e-8 * row_scale.max(1e-300) {
            basis.push(v.iter().map(|x| x / len).collect());
            independent.push(r);
            continue;
        }
        // Coefficients c with J_Iᵀ c = J_r, by least squares.
        let a = Mat::from_fn(n, independent.len(), |c, k| j[(independent[k], c)]);
        let b = Mat::from_fn(n, 1, |c, _| row[c]);
        let coef = if independent.is_empty() {
            Mat::zeros(0, 1)
        } else {
            a.qr().solve_lstsq(&b)
        };
        let cmax = (0..coef.nrows()).fold(0.0f64, |x, k| x.max(coef[(k, 0)].abs()));
        let depends_on = (0..coef.nrows())
            .filter(|&k| coef[(k, 0)].abs() > 1e-6 * cmax.max(1e-300))
            .map(|k| (equation_name(model, asm, independent[k]), coef[(k, 0)]))
            .collect();
        out.push(Redundancy {
            equation: equation_name(model, asm, r),
            depends_on,
        });
    }
    out
}

/// The joint of an equation name `joint.equation` (`O4` of `O4.x`).
fn joint_of(equation: &str) -> &str {
    equation.rsplit_once('.').map_or(equation, |(j, _)| j)
}

/// The drivers whose equations are among `redundant` (the dependent
/// equations and those they depend on), each once, in the order the
/// redundancies name them.
fn drivers_among(model: &Model, redundant: &[Redundancy]) -> Vec<String> {
    let mut drivers: Vec<String> = Vec::new();
    let named = redundant.iter().flat_map(|r| {
        std::iter::once(r.equation.as_str()).chain(r.depends_on.iter().map(|(e, _)| e.as_str()))
    });
    for joint in named.map(joint_of) {
        let driver = model.joints.iter().any(|j| j.driver && j.name == joint);
        if driver && !drivers.iter().any(|d| d == joint) {
            drivers.push(joint.to_string());
        }
    }
    drivers
}

/// `joint.equation` for row `r`, e.g. `O4.x`.
pub(crate) fn equation_name(model: &Model, asm: &Assembly, r: usize) -> String {
    let (j, e) = asm.joint_of_row(r);
    let joint = &model.joints[j];
    let names = joint.constraint.equations();
    format!("{}.{}", joint.name, names.get(e).copied().unwrap_or("?"))
}

/// The coordinates that move most in the motion `v`.
fn describe_motion(model: &Model, asm: &Assembly, v: &[f64]) -> Vec<(String, f64)> {
    let vmax = v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let mut parts: Vec<(usize, f64)> = v
        .iter()
        .enumerate()
        .filter(|(_, x)| x.abs() > 0.05 * vmax)
        .map(|(k, x)| (k, x / vmax))
        .collect();
    // Sign so that the largest component is positive.
    if let Some(&(_, big)) = parts.iter().max_by(|a, b| a.1.abs().total_cmp(&b.1.abs())) {
        if big < 0.0 {
            parts.iter_mut().for_each(|p| p.1 = -p.1);
        }
    }
    parts.sort_by(|a, b| b.1.abs().total_cmp(&a.1.abs()));
    parts
        .into_iter()
        .map(|(k, x)| (asm.coordinate_name(model, k), x))
        .collect()
}

/// The independent equations of a model with redundant ones, for an
/// analysis that needs a square Φ_q (kinematics): the redundant rows
/// (dependent on earlier rows at the assembled configuration, as
/// [`diagnose`] finds them) are left out of the solve; being combinations
/// of the rows kept, they hold wherever those do.
#[derive(Clone, Debug)]
pub(crate) struct KeptRows {
    /// The rows kept, in model order: reduced row k is row `keep[k]`.
    keep: Vec<usize>,
    /// For each of the m rows, its reduced index (None: left out).
    map: Vec<Option<usize>>,
    /// Scratch of length m.
    full: Vec<f64>,
    /// The redundant equations (`joint.equation`), in model order.
    pub equations: Vec<String>,
    /// The joints of the redundant rows and of the rows they depend on,
    /// in model order: their reactions are not unique.
    pub joints: Vec<String>,
}

impl KeptRows {
    /// The rows to keep for a model with more equations than coordinates,
    /// from its [`diagnose`] at time `t` (s) with assembly tolerance `tol`:
    /// an error message when the dependent equations do not make up the
    /// excess (a model that is locked or singular, not only redundant), or
    /// the model is too large for the dense analysis.
    pub(crate) fn find(
        model: &Model,
        asm: &Assembly,
        t: f64,
        tol: f64,
    ) -> Result<KeptRows, String> {
        let (n, m) = (asm.n, asm.m);
        let d = diagnose(model, t, tol);
        if !d.exact {
            return Err(format!(
                "{n} coordinates but {m} equations, and the model is too large (more than \
                 {DENSE_MAX} coordinates) to find its redundant equations; remove {} \
                 equation(s)",
                m - n
            ));
        }
        if d.residual > tol {
            return Err(format!(
                "{n} coordinates but {m} equations, and the model does not assemble \
                 (largest |Φ| {:.3e}), so its redundant equations cannot be told apart",
                d.residual
            ));
        }
        if d.rank < n || d.redundant.len() != m - n {
            return Err(format!(
                "{n} coordinates but {m} equations of rank {}: {} equation(s) too many \
                 and {} degree(s) of freedom left; remove redundant joints or drivers \
                 (`camlink check` names them)",
                d.rank,
                m - d.rank,
                n - d.rank
            ));
        }
        // A driver among the dependent equations fixes a motion that the
        // others fix already: over-driven, consistent at most at time t.
        if !d.redundant_drivers.is_empty() {
            return Err(format!(
                "{n} coordinates but {m} equations: over-driven, driver(s) {} fix a motion \
                 that the other equations fix already; remove one (`camlink check` names \
                 the redundant equations)",
                d.redundant_drivers.join(", ")
            ));
        }
        let equations: Vec<String> = d.redundant.iter().map(|r| r.equation.clone()).collect();
        let dropped: Vec<usize> = (0..m)
            .filter(|&r| equations.contains(&equation_name(model, asm, r)))
            .collect();
        let keep: Vec<usize> = (0..m).filter(|r| !dropped.contains(r)).collect();
        let mut map = vec![None; m];
        for (k, &r) in keep.iter().enumerate() {
            map[r] = Some(k);
        }
        let involved: Vec<&str> = d
            .redundant
            .iter()
            .flat_map(|r| {
                std::iter::once(joint_of(&r.equation))
                    .chain(r.depends_on.iter().map(|(e, _)| joint_of(e)))
            })
            .collect();
        let joints = model
            .joints
            .iter()
            .filter(|j| involved.contains(&j.name.as_str()))
            .map(|j| j.name.clone())
            .collect();
        Ok(KeptRows {
            keep,
            map,
            full: vec![0.0; m],
            equations,
            joints,
        })
    }

    /// The reduced index of row `r`, None when it is left out.
    #[inline]
    pub(crate) fn reduced(&self, r: usize) -> Option<usize> {
        self.map[r]
    }

    /// The full row of reduced row `k`.
    #[inline]
    pub(crate) fn full_row(&self, k: usize) -> usize {
        self.keep[k]
    }

    /// Fills the full scratch (length m) with `fill`, then copies the kept
    /// rows into `out` (length m − redundant).
    #[inline]
    pub(crate) fn gather(&mut self, fill: impl FnOnce(&mut [f64]), out: &mut [f64]) {
        fill(&mut self.full);
        for (o, &r) in out.iter_mut().zip(&self.keep) {
            *o = self.full[r];
        }
    }

    /// The warning of a run that left the redundant equations out, at time
    /// `t` (s).
    pub(crate) fn warning(&self, t: f64) -> crate::run::Warning {
        crate::run::Warning {
            kind: crate::run::Kind::Redundant,
            time: t,
            joints: self.joints.clone(),
            message: format!(
                "{} redundant constraint equation(s) ({}) left out of the solve (they hold \
                 wherever the others do): the motion is determined, but the reactions of \
                 joints {} are not unique; the minimum-norm split is reported",
                self.equations.len(),
                self.equations.join(", "),
                self.joints.join(", ")
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constraint::absolute::{AbsoluteCoord, Coord};
    use crate::constraint::revolute::Revolute;
    use crate::function::TimeFn;
    use crate::model::{Body, BodyId};

    /// A four-bar with its links placed exactly, undriven.
    fn four_bar(parallelogram: bool) -> Model {
        let (a, b, c, d) = if parallelogram {
            (0.2, 0.5, 0.2, 0.5)
        } else {
            (0.1, 0.35, 0.3, 0.4)
        };
        // Exact placement for crank angle 90° (parallelogram) or by solving.
        let th2: f64 = 1.2;
        let bx = a * th2.cos();
        let by = a * th2.sin();
        // Rocker angle from the circle intersection.
        let (dx, dy) = (d - bx, -by);
        let l = (dx * dx + dy * dy).sqrt();
        let ang = dy.atan2(dx);
        let beta = ((l * l + c * c - b * b) / (2.0 * l * c)).acos();
        let th4 = std::f64::consts::PI + ang - beta;
        let cx = d + c * th4.cos();
        let cy = c * th4.sin();
        let th3 = (cy - by).atan2(cx - bx);
        let mut m = Model::new("four-bar");
        let crank = m.add_body(Body::new("crank", [0.0, 0.0, th2]));
        let coupler = m.add_body(Body::new("coupler", [bx, by, th3]));
        let rocker = m.add_body(Body::new("rocker", [d, 0.0, th4]));
        let g = BodyId::GROUND;
        let rev = |bi, si, bj, sj| Revolute {
            body_i: bi,
            s_i: si,
            body_j: bj,
            s_j: sj,
        };
        m.add_joint("O2", rev(g, [0.0, 0.0], crank, [0.0, 0.0]));
        m.add_joint("B", rev(crank, [a, 0.0], coupler, [0.0, 0.0]));
        m.add_joint("C", rev(coupler, [b, 0.0], rocker, [c, 0.0]));
        m.add_joint("O4", rev(g, [d, 0.0], rocker, [0.0, 0.0]));
        m
    }

    /// The four-bar with a fifth revolute at the rocker pivot, `O4_again`,
    /// whose equations duplicate O4's.
    fn four_bar_with_second_rocker_pivot() -> Model {
        let mut m = four_bar(false);
        let rocker = m.body_id("rocker").unwrap();
        m.add_joint(
            "O4_again",
            Revolute {
                body_i: BodyId::GROUND,
                s_i: [0.4, 0.0],
                body_j: rocker,
                s_j: [0.0, 0.0],
            },
        );
        m
    }

    #[test]
    fn four_bar_has_one_dof_and_no_redundancy() {
        let d = diagnose(&four_bar(false), 0.0, 1e-10);
        assert_eq!((d.coordinates, d.equations), (9, 8));
        // A planar four-bar: 8 independent equations, 1 DOF, nothing redundant.
        assert_eq!(d.rank, 8);
        assert_eq!(d.dof, 1);
        assert!(d.redundant.is_empty(), "{:?}", d.redundant);
        assert_eq!(d.free_motions.len(), 1);
        assert!(d.residual < 1e-10);
    }

    #[test]
    fn a_model_too_large_for_the_dense_analysis_is_counted() {
        // A chain of pendulums: 3 coordinates and 2 equations per link.
        let mut m = Model::new("chain");
        let mut prev = BodyId::GROUND;
        for k in 0..(DENSE_MAX / 3 + 1) {
            let b = m.add_body(Body::new(format!("link{k}"), [k as f64, 0.0, 0.0]));
            m.add_joint(
                format!("j{k}"),
                Revolute {
                    body_i: prev,
                    s_i: [if prev.is_ground() { 0.0 } else { 0.5 }, 0.0],
                    body_j: b,
                    s_j: [-0.5, 0.0],
                },
            );
            prev = b;
        }
        let d = diagnose(&m, 0.0, 1e-10);
        assert!(!d.exact);
        assert_eq!(d.coordinates, 3 * (DENSE_MAX / 3 + 1));
        assert_eq!(d.dof, d.coordinates / 3);
    }

    #[test]
    fn extra_revolute_is_named_redundant() {
        let m = four_bar_with_second_rocker_pivot();
        let d = diagnose(&m, 0.0, 1e-10);
        assert_eq!(d.equations, 10);
        assert_eq!(d.rank, 8);
        assert_eq!(d.dof, 1);
        let names: Vec<&str> = d.redundant.iter().map(|r| r.equation.as_str()).collect();
        assert_eq!(names, ["O4_again.x", "O4_again.y"]);
        assert!(d.redundant[0].depends_on.iter().any(|(e, _)| e == "O4.x"));
    }

    #[test]
    fn a_redundant_joint_involves_no_driver() {
        let mut m = four_bar_with_second_rocker_pivot();
        let crank = m.body_id("crank").unwrap();
        m.add_driver("motor", crank_angle(crank, 1.2));
        let d = diagnose(&m, 0.0, 1e-10);
        assert_eq!(d.dof, 0);
        assert_eq!(d.redundant.len(), 2);
        assert!(d.redundant_drivers.is_empty(), "{:?}", d.redundant_drivers);
    }

    #[test]
    fn two_drivers_on_one_angle_are_named_redundant_drivers() {
        // The second driver's equation depends on the first's.
        let mut m = four_bar(false);
        let crank = m.body_id("crank").unwrap();
        m.add_driver("brake", crank_angle(crank, 1.2));
        m.add_driver("motor", crank_angle(crank, 1.2));
        let d = diagnose(&m, 0.0, 1e-10);
        let names: Vec<&str> = d.redundant.iter().map(|r| r.equation.as_str()).collect();
        assert_eq!(names, ["motor.phi"]);
        assert_eq!(d.redundant_drivers, ["motor", "brake"]);
    }

    /// The crank's absolute angle φ = `phi` (rad) as a driver.
    fn crank_angle(crank: BodyId, phi: f64) -> AbsoluteCoord {
        AbsoluteCoord {
            body: crank,
            s: [0.0, 0.0],
            coord: Coord::Phi,
            f: TimeFn::Const(phi),
        }
    }

    #[test]
    fn free_motion_of_an_undriven_crank_names_the_links() {
        let d = diagnose(&four_bar(false), 0.0, 1e-10);
        let motion: Vec<&str> = d.free_motions[0].iter().map(|(n, _)| n.as_str()).collect();
        assert!(motion.contains(&"crank.phi"), "{motion:?}");
        assert!(motion.contains(&"rocker.phi"), "{motion:?}");
    }
}
