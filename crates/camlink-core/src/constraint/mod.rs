//! The constraint library.
//!
//! Every constraint provides, analytically and in this order, its residual
//! Φ, its Jacobian Φ_q, ν = −Φ_t,
//! γ = −(Φ_q q̇)_q q̇ − 2 Φ_qt q̇ − Φ_tt and, for the jerk analysis,
//! η = γ̇ − Φ̇_q q̈ (total time derivatives along the motion), the right side
//! of Φ_q q⃛ = η.
//!
//! A constraint sees only its own coordinates (a [`Local`] view): the two
//! bodies it joins, `i` and `j` (either may be ground, whose coordinates are
//! fixed at zero), and up to [`MAX_OWN`] coordinates of its own (a contact
//! parameter α, a centre-line angle θ). It writes per-body Jacobian blocks;
//! only assembly knows global indices.
//!
//! Adding a constraint is one new file (its equations and its drawing,
//! [`Equations::sketch`]) and one line in [`constraints!`];
//! `docs/adding-a-joint.md` lists the model-file side.

use crate::curve::Curve;
use crate::math::{point, rot_t, sub, V2};
use crate::motion;
use crate::quantity::Quantity;

pub mod absolute;
pub mod cam_follower;
pub mod composite;
pub mod flat_follower;
pub mod gear;
pub mod point_follower;
pub mod relative;
pub mod revolute;
pub mod sketch;
pub mod translational;

#[cfg(any(test, feature = "check"))]
pub mod check;

/// Index of a body in [`Model::bodies`](crate::model::Model::bodies); body
/// 0 is the ground.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct BodyId(pub usize);

impl BodyId {
    pub const GROUND: BodyId = BodyId(0);

    pub fn is_ground(self) -> bool {
        self == Self::GROUND
    }
}

/// What one body of a curve contact carries there, in its body frame.
#[derive(Clone, Copy, Debug)]
pub enum Feature<'a> {
    /// A curve; its parameter at the contact is one of the joint's own
    /// coordinates.
    Curve(&'a Curve),
    /// A point s′ (m): a pin.
    Point(V2),
    /// A straight face along the unit vector u′.
    Face(V2),
}

/// Most equations one constraint contributes.
pub(crate) const MAX_ROWS: usize = 3;
/// Most own coordinates one constraint carries.
pub const MAX_OWN: usize = 2;

/// A set of a constraint's local coordinates, bit k for local coordinate k:
/// 0–2 are (x, y, φ) of body i, 3–5 of body j, 6 and up its own.
pub(crate) type CoordMask = u8;
/// Every local coordinate.
pub(crate) const ALL_COORDS: CoordMask = CoordMask::MAX;

/// Number of local coordinates: (x, y, φ) of bodies i and j, then the
/// constraint's own.
pub(crate) const LOCAL_COORDS: usize = 6 + MAX_OWN;

/// A square block over the local coordinates.
pub(crate) type LocalBlock = [[f64; LOCAL_COORDS]; LOCAL_COORDS];

/// Values of a constraint's equations; entries past `rows()` are unused.
pub type Rows = [f64; MAX_ROWS];

/// What a constraint sees of the state.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Local {
    /// Time t (s).
    pub t: f64,
    /// Coordinates (x, y, φ) of body i and body j (m, m, rad).
    pub q: [[f64; 3]; 2],
    /// Their velocities (ẋ, ẏ, φ̇) (m/s, m/s, rad/s).
    pub qd: [[f64; 3]; 2],
    /// The constraint's own coordinates.
    pub own: [f64; MAX_OWN],
    /// Their time derivatives.
    pub own_d: [f64; MAX_OWN],
    /// Accelerations (ẍ, ÿ, φ̈) of bodies i and j (m/s², m/s², rad/s²),
    /// read by η only.
    pub qdd: [[f64; 3]; 2],
    /// Second time derivatives of the own coordinates, read by η only.
    pub own_dd: [f64; MAX_OWN],
}

impl Local {
    /// The body point s′ of body k (0 for i, 1 for j) with its time
    /// derivatives, for η.
    #[inline]
    pub(crate) fn point_path(&self, k: usize, s: V2) -> motion::Path {
        motion::body_point(self.q[k], self.qd[k], self.qdd[k], s)
    }

    /// A vector w′ fixed in body k, A_k w′, with its time derivatives.
    #[inline]
    pub(crate) fn vector_path(&self, k: usize, w: V2) -> motion::Path {
        motion::rotated(
            [self.q[k][2], self.qd[k][2], self.qdd[k][2]],
            &motion::constant(w),
        )
    }

    /// Own coordinate o's `[value, rate, second derivative]`.
    #[inline]
    pub(crate) fn own_path(&self, o: usize) -> [f64; 3] {
        [self.own[o], self.own_d[o], self.own_dd[o]]
    }

    /// A point of body i (`s_i`, body i frame) expressed in body j's frame,
    /// at the current configuration (m).
    pub(crate) fn on_j(&self, s_i: V2) -> V2 {
        let (qi, qj) = (self.q[0], self.q[1]);
        rot_t(qj[2], sub(point(qi, s_i), [qj[0], qj[1]]))
    }
}

/// Jacobian blocks of one constraint: `body[k][r][c]` = ∂Φ_r/∂q_k,c for
/// body k ∈ {i, j} and coordinate c ∈ {x, y, φ}; `own[r][c]` = ∂Φ_r/∂own_c.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Jac {
    pub body: [[[f64; 3]; MAX_ROWS]; 2],
    pub own: [[f64; MAX_OWN]; MAX_ROWS],
}

/// The equations of one constraint.
pub trait Equations {
    /// Short kind name used in reports, e.g. `"revolute"`.
    fn kind(&self) -> &'static str;
    /// Names of the equations in order, e.g. `["x", "y"]`; the length is the
    /// number of equations m ≤ [`MAX_ROWS`].
    fn equations(&self) -> &'static [&'static str];
    /// The bodies i and j this constraint joins.
    fn bodies(&self) -> [BodyId; 2];
    /// Number of own coordinates (≤ [`MAX_OWN`]).
    fn own_count(&self) -> usize {
        0
    }
    /// Names of the own coordinates, used in output channels
    /// (`<joint>.<name>`); as many as [`own_count`](Self::own_count).
    fn own_names(&self) -> &'static [&'static str] {
        &[]
    }
    /// What own coordinate `k` measures (its output channel's quantity).
    fn own_quantity(&self, _k: usize) -> Quantity {
        Quantity::Dimensionless
    }
    /// A starting value for the own coordinates from the body coordinates
    /// in `x`, refined from `guess` when there is one.
    fn initial_own(&self, _x: &Local, guess: Option<[f64; MAX_OWN]>) -> [f64; MAX_OWN] {
        guess.unwrap_or_default()
    }
    /// Checks the functions the constraint evaluates (of time, of a curve
    /// parameter) at `x`, naming the operation that fails.
    fn check_functions(&self, _x: &Local) -> Result<(), String> {
        Ok(())
    }
    /// For a curve contact, what bodies i and j carry ([`Feature`]); own
    /// coordinate k is the parameter of the k-th curve of the two. `None`
    /// for every other joint. [`crate::contact::ContactView`] builds on it.
    fn contact_sides(&self) -> Option<[Feature<'_>; 2]> {
        None
    }
    /// Where the joint's reaction acts on bodies i and j, each in its own
    /// body frame (m): the joint points, or the current contact point.
    fn joint_points(&self, x: &Local) -> [V2; 2];
    /// What a drawing shows of the joint ([`sketch::Mark`]); empty for a
    /// constraint with nothing to draw (a held coordinate or distance).
    fn sketch(&self) -> sketch::Sketch<'_>;
    /// ∂Φ/∂f, how a driver's equation changes with the value of its
    /// function f(t): −1 for Φ = g(q) − f(t), −2f for a distance driven
    /// through Φ = dᵀd − f². Used to turn λ into a driver's effort.
    fn driver_slope(&self, _t: f64) -> f64 {
        -1.0
    }
    /// What the coordinate a driver prescribes measures; a length unless
    /// the driver says otherwise. Its effort is the generalized force
    /// conjugate to it (N for a length, N·m for an angle).
    fn driven_quantity(&self) -> Quantity {
        Quantity::Length
    }
    /// The local coordinates Φ depends on nonlinearly: Φ_q changes with
    /// these only, so the curvature (Φ_qᵀλ)_q vanishes outside their rows
    /// and columns. Every coordinate unless a constraint declares fewer;
    /// the finite-difference check verifies a declaration.
    fn nonlinear(&self) -> CoordMask {
        ALL_COORDS
    }
    /// For each equation, the local coordinates its row of Φ_q may be
    /// nonzero in; entries outside are exactly zero and are left out of
    /// every matrix. Every coordinate unless a constraint declares fewer;
    /// the finite-difference check verifies a declaration.
    fn jacobian_pattern(&self) -> [CoordMask; MAX_ROWS] {
        [ALL_COORDS; MAX_ROWS]
    }
    /// The curvature (Φ_qᵀλ)_q = Σ_r λ_r ∂²Φ_r/∂z∂z over the local
    /// coordinates z, written into `out` (zeroed by the caller; only
    /// entries between [`nonlinear`](Self::nonlinear) coordinates are
    /// read). Returns false, the default, to have it differentiated
    /// numerically from Φ_q instead; the finite-difference check verifies
    /// an analytic one.
    fn curvature(&self, _x: &Local, _lambda: &Rows, _out: &mut LocalBlock) -> bool {
        false
    }
    /// Φ.
    fn phi(&self, x: &Local, out: &mut Rows);
    /// Φ_q as per-body blocks (every entry of `out` is written).
    fn jacobian(&self, x: &Local, out: &mut Jac);

    /// Φ into `phi` and Φ_q into `jac`, the same values as
    /// [`phi`](Self::phi) and [`jacobian`](Self::jacobian) to the last
    /// bit: a constraint whose two share their rotations evaluates them
    /// once (the residual of dynamics needs both at every iterate).
    #[inline]
    fn phi_and_jacobian(&self, x: &Local, phi: &mut Rows, jac: &mut Jac) {
        self.phi(x, phi);
        self.jacobian(x, jac);
    }
    /// ν = −Φ_t.
    fn nu(&self, x: &Local, out: &mut Rows);
    /// γ = −(Φ_q q̇)_q q̇ − 2 Φ_qt q̇ − Φ_tt.
    fn gamma(&self, x: &Local, out: &mut Rows);
    /// η, the right side of Φ_q q⃛ = η: η = −d³Φ/dt³ along the motion with
    /// the jerks q⃛ set to zero (= γ̇ − Φ̇_q q̈); reads q̈ from `x.qdd` and
    /// `x.own_dd`. See [`motion`](crate::motion).
    fn eta(&self, x: &Local, out: &mut Rows);
    /// Number of equations m.
    fn rows(&self) -> usize {
        self.equations().len()
    }
}

/// Declares the [`Constraint`] enum and dispatches [`Equations`] to its
/// variants statically.
macro_rules! constraints {
    ($($variant:ident($ty:ty)),* $(,)?) => {
        /// Every constraint camlink knows.
        #[derive(Clone, Debug)]
        pub enum Constraint {
            $($variant($ty),)*
        }

        $(impl From<$ty> for Constraint {
            fn from(c: $ty) -> Self {
                Constraint::$variant(c)
            }
        })*

        impl Equations for Constraint {
            fn kind(&self) -> &'static str {
                match self { $(Constraint::$variant(c) => c.kind(),)* }
            }
            fn equations(&self) -> &'static [&'static str] {
                match self { $(Constraint::$variant(c) => c.equations(),)* }
            }
            fn bodies(&self) -> [BodyId; 2] {
                match self { $(Constraint::$variant(c) => c.bodies(),)* }
            }
            fn own_count(&self) -> usize {
                match self { $(Constraint::$variant(c) => c.own_count(),)* }
            }
            fn check_functions(&self, x: &Local) -> Result<(), String> {
                match self { $(Constraint::$variant(c) => c.check_functions(x),)* }
            }
            fn contact_sides(&self) -> Option<[Feature<'_>; 2]> {
                match self { $(Constraint::$variant(c) => c.contact_sides(),)* }
            }
            fn joint_points(&self, x: &Local) -> [V2; 2] {
                match self { $(Constraint::$variant(c) => c.joint_points(x),)* }
            }
            fn sketch(&self) -> sketch::Sketch<'_> {
                match self { $(Constraint::$variant(c) => c.sketch(),)* }
            }
            fn driver_slope(&self, t: f64) -> f64 {
                match self { $(Constraint::$variant(c) => c.driver_slope(t),)* }
            }
            fn driven_quantity(&self) -> Quantity {
                match self { $(Constraint::$variant(c) => c.driven_quantity(),)* }
            }
            fn nonlinear(&self) -> CoordMask {
                match self { $(Constraint::$variant(c) => c.nonlinear(),)* }
            }
            fn jacobian_pattern(&self) -> [CoordMask; MAX_ROWS] {
                match self { $(Constraint::$variant(c) => c.jacobian_pattern(),)* }
            }
            fn curvature(&self, x: &Local, lambda: &Rows, out: &mut LocalBlock) -> bool {
                match self { $(Constraint::$variant(c) => c.curvature(x, lambda, out),)* }
            }
            fn own_names(&self) -> &'static [&'static str] {
                match self { $(Constraint::$variant(c) => c.own_names(),)* }
            }
            fn own_quantity(&self, k: usize) -> Quantity {
                match self { $(Constraint::$variant(c) => c.own_quantity(k),)* }
            }
            fn initial_own(&self, x: &Local, guess: Option<[f64; MAX_OWN]>) -> [f64; MAX_OWN] {
                match self { $(Constraint::$variant(c) => c.initial_own(x, guess),)* }
            }
            #[inline]
            fn phi(&self, x: &Local, out: &mut Rows) {
                match self { $(Constraint::$variant(c) => c.phi(x, out),)* }
            }
            #[inline]
            fn jacobian(&self, x: &Local, out: &mut Jac) {
                match self { $(Constraint::$variant(c) => c.jacobian(x, out),)* }
            }
            #[inline]
            fn phi_and_jacobian(&self, x: &Local, phi: &mut Rows, jac: &mut Jac) {
                match self { $(Constraint::$variant(c) => c.phi_and_jacobian(x, phi, jac),)* }
            }
            #[inline]
            fn nu(&self, x: &Local, out: &mut Rows) {
                match self { $(Constraint::$variant(c) => c.nu(x, out),)* }
            }
            #[inline]
            fn gamma(&self, x: &Local, out: &mut Rows) {
                match self { $(Constraint::$variant(c) => c.gamma(x, out),)* }
            }
            #[inline]
            fn eta(&self, x: &Local, out: &mut Rows) {
                match self { $(Constraint::$variant(c) => c.eta(x, out),)* }
            }
        }
    };
}

constraints! {
    Revolute(revolute::Revolute),
    AbsoluteCoord(absolute::AbsoluteCoord),
    AbsoluteDistance(absolute::AbsoluteDistance),
    RelativeCoord(relative::RelativeCoord),
    RelativeDistance(relative::RelativeDistance),
    Translational(translational::Translational),
    RevoluteRevolute(composite::RevoluteRevolute),
    RevoluteTranslational(composite::RevoluteTranslational),
    Gear(gear::Gear),
    RackPinion(gear::RackPinion),
    CamFollower(cam_follower::CamFollower),
    FlatFollower(flat_follower::FlatFollower),
    PointFollower(point_follower::PointFollower),
}
