//! The retry policy of a forward-dynamics step: the ways of taking one
//! step of the generalized-α integrator ([`super::generalized_alpha`]),
//! tried in turn from the state at the start of the step until one
//! converges.
//!
//! A step on Φ alone takes the [`PLAIN`] ladder:
//!
//! 1. [`Way::Chord`]: Newton with the factorization kept from the steps
//!    before, from the predictor (quadratic or linear,
//!    `Integrator::predict`). Nearly every step ends here.
//! 2. [`Way::BranchAtSingular`]: a slow mechanism whose chord step found
//!    the Newton matrix singular (a bifurcation point reached at rest or
//!    nearly) is taken along the branch with its rows; if that fails, the
//!    next ways start from the consistent q̈ and λ.
//! 3. [`Way::Fresh`]: slow convergence with an old matrix: a fresh matrix
//!    each iteration, from the constant predictor.
//! 4. [`Way::BranchWhereLost`]: near a bifurcation point, along the branch
//!    when Φ_q has lost rank at the start of the step.
//!
//! A step inside a window of branch rows takes the [`ON_BRANCH`] ladder:
//! along the branch ([`Way::AlongBranch`], from the linear predictor, then
//! from the constant one), then [`Way::LeaveBranch`]: Φ alone from the
//! consistent q̈ and λ.
//!
//! Every way but the chord uses a fresh matrix each iteration, with
//! [`SINGULAR_ITER`] times the iterations (near a singular position Newton
//! converges only linearly). A step that no way takes fails with
//! `Kind::NotConverged`.

/// The retry of a step with a fresh matrix each iteration may take this
/// many times `max_iter` iterations.
pub const SINGULAR_ITER: usize = 4;

/// One way of taking a step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Way {
    /// Φ alone, the factorization kept (a chord iteration), from the
    /// predictor; a slow step that finds the matrix singular stops
    /// at once, for [`Way::BranchAtSingular`].
    Chord,
    /// Along the branch from the start of the step, when the chord step
    /// stopped at a singular matrix and Φ_q has lost rank; on failure the
    /// branch is left and the step starts again from the consistent q̈
    /// and λ.
    BranchAtSingular,
    /// Φ alone, a fresh matrix each iteration, from the constant predictor.
    Fresh,
    /// Along the branch, when Φ_q has lost rank at the start of the step.
    BranchWhereLost,
    /// Along the branch rows in use; on failure the next way starts from
    /// the constant predictor.
    AlongBranch,
    /// The branch left: Φ alone from the consistent q̈ and λ, a fresh
    /// matrix each iteration.
    LeaveBranch,
}

impl Way {
    /// True when the way keeps the factorization of the steps before.
    pub fn chord(self) -> bool {
        self == Way::Chord
    }

    /// True when the way takes the step along the branch rows (the step
    /// is then checked as one along the branch, else as one on Φ alone).
    pub fn along_branch(self) -> bool {
        matches!(
            self,
            Way::BranchAtSingular | Way::BranchWhereLost | Way::AlongBranch
        )
    }
}

/// The ways of a step on Φ alone, in order.
pub const PLAIN: [Way; 4] = [
    Way::Chord,
    Way::BranchAtSingular,
    Way::Fresh,
    Way::BranchWhereLost,
];

/// The ways of a step inside a window of branch rows, in order.
pub const ON_BRANCH: [Way; 3] = [Way::AlongBranch, Way::AlongBranch, Way::LeaveBranch];

/// The ladder of a step: [`ON_BRANCH`] when following a branch, else
/// [`PLAIN`].
pub fn ladder(on_branch: bool) -> &'static [Way] {
    if on_branch {
        &ON_BRANCH
    } else {
        &PLAIN
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every ladder starts with the cheapest way of its kind and ends on
    /// one that does not need the branch rows it started with.
    #[test]
    fn ladders_start_cheap() {
        assert_eq!(ladder(false)[0], Way::Chord);
        assert!(ladder(false)[1..].iter().all(|w| !w.chord()));
        assert!(ladder(true).iter().all(|w| !w.chord()));
        assert!(!ladder(true).last().unwrap().along_branch());
    }
}
