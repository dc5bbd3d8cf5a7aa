//! Complex numbers for the dyad equations of the standard form
//! (Sandor & Erdman): a point or a vector of the plane x + i y (m), and
//! e^{iθ} for a rotation by θ (rad).

use crate::fourbar::P2;

/// A complex number, for the dyad equations.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct C(pub(crate) f64, pub(crate) f64);

impl C {
    pub(crate) fn cis(t: f64) -> C {
        let (s, c) = t.sin_cos();
        C(c, s)
    }
    pub(crate) fn abs(self) -> f64 {
        self.0.hypot(self.1)
    }
    pub(crate) fn abs2(self) -> f64 {
        self.0 * self.0 + self.1 * self.1
    }
    pub(crate) fn arg(self) -> f64 {
        self.1.atan2(self.0)
    }
    pub(crate) fn scale(self, k: f64) -> C {
        C(self.0 * k, self.1 * k)
    }
    pub(crate) fn div(self, o: C) -> C {
        let d = o.abs2();
        C(
            (self.0 * o.0 + self.1 * o.1) / d,
            (self.1 * o.0 - self.0 * o.1) / d,
        )
    }
    pub(crate) fn p(self) -> P2 {
        [self.0, self.1]
    }
}

impl std::ops::Add for C {
    type Output = C;
    fn add(self, o: C) -> C {
        C(self.0 + o.0, self.1 + o.1)
    }
}

impl std::ops::Sub for C {
    type Output = C;
    fn sub(self, o: C) -> C {
        C(self.0 - o.0, self.1 - o.1)
    }
}

impl std::ops::Mul for C {
    type Output = C;
    fn mul(self, o: C) -> C {
        C(self.0 * o.0 - self.1 * o.1, self.0 * o.1 + self.1 * o.0)
    }
}
