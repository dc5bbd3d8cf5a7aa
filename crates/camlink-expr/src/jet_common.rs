//! What jets of every order share: construction, the operations with a
//! constant, sums and negation, and the functions built from other jet
//! operations (uᵛ, atan2, hypot, mod). [`Jet`](crate::Jet) (third order)
//! and [`Jet4`](crate::Jet4) (fourth order) each add their own chain rule
//! (`compose`), products, quotients and elementary functions.
//!
//! Each value component is the `f64` operation value-only evaluation uses.

/// Declares the shared methods and `Add`, `Sub`, `Neg` of a jet type
/// `$jet(pub [f64; $n])`, a value and its first `$n − 1` derivatives.
macro_rules! jet_common {
    ($jet:ident, $n:literal) => {
        impl $jet {
            /// The jet of the zero function.
            pub(crate) const ZERO: $jet = $jet([0.0; $n]);

            /// The jet of a constant c: `[c, 0, …]`.
            #[inline]
            pub const fn constant(c: f64) -> $jet {
                let mut a = [0.0; $n];
                a[0] = c;
                $jet(a)
            }

            /// The jet of the variable itself at x: `[x, 1, 0, …]`.
            #[inline]
            pub const fn variable(x: f64) -> $jet {
                let mut a = [0.0; $n];
                a[0] = x;
                a[1] = 1.0;
                $jet(a)
            }

            /// The value u.
            #[inline]
            pub fn value(self) -> f64 {
                self.0[0]
            }

            /// True when every derivative is zero (u does not vary at this
            /// point).
            #[inline]
            pub(crate) fn is_flat(self) -> bool {
                self.0[1..].iter().all(|&d| d == 0.0)
            }

            /// The first component that is not finite, as (order, value).
            pub(crate) fn first_non_finite(self) -> Option<(usize, f64)> {
                self.0
                    .iter()
                    .enumerate()
                    .find(|(_, v)| !v.is_finite())
                    .map(|(k, v)| (k, *v))
            }

            /// Applies `f` to every component.
            #[inline]
            fn map(self, f: impl Fn(f64) -> f64) -> $jet {
                $jet(self.0.map(f))
            }

            /// u + c.
            #[inline]
            pub(crate) fn add_c(self, c: f64) -> $jet {
                let mut w = self;
                w.0[0] += c;
                w
            }

            /// u · c.
            #[inline]
            pub(crate) fn mul_c(self, c: f64) -> $jet {
                self.map(|u| u * c)
            }

            /// u / c.
            #[inline]
            pub(crate) fn div_c(self, c: f64) -> $jet {
                self.map(|u| u / c)
            }

            /// c − u.
            #[inline]
            pub(crate) fn rsub_c(self, c: f64) -> $jet {
                let mut w = -self;
                w.0[0] = c - self.0[0];
                w
            }

            /// uᵛ for two jets: the constant-exponent rule when v is flat,
            /// otherwise exp(v ln u), with the value taken from `powf`.
            pub fn pow(self, v: $jet) -> $jet {
                if v.is_flat() {
                    return self.pow_c(v.0[0]);
                }
                let mut w = (v * self.ln()).exp();
                w.0[0] = self.0[0].powf(v.0[0]);
                w
            }

            /// atan2(y, x) with y = self: the angle of the point (x, y).
            ///
            /// Its derivatives are those of atan(y/x) where |x| ≥ |y| and
            /// those of −atan(x/y) elsewhere (the two differ by a constant
            /// there).
            pub fn atan2(self, x: $jet) -> $jet {
                let y = self;
                let mut w = if x.0[0].abs() >= y.0[0].abs() {
                    (y / x).atan()
                } else {
                    -(x / y).atan()
                };
                w.0[0] = y.0[0].atan2(x.0[0]);
                w
            }

            /// √(u² + v²) with the value from `hypot`.
            pub fn hypot(self, v: $jet) -> $jet {
                let mut w = (self * self + v * v).sqrt();
                w.0[0] = self.0[0].hypot(v.0[0]);
                w
            }

            /// u mod v, floored: u − k v with k = ⌊u/v⌋ held constant, so
            /// the result has the sign of v and its derivatives are
            /// u⁽ⁱ⁾ − k v⁽ⁱ⁾.
            pub fn modulo(self, v: $jet) -> $jet {
                let (u0, v0) = (self.0[0], v.0[0]);
                let r = $crate::jet::floor_mod(u0, v0);
                let mut w = if v.is_flat() {
                    self
                } else {
                    let k = ((u0 - r) / v0).round();
                    self - v.mul_c(k)
                };
                w.0[0] = r;
                w
            }
        }

        impl std::ops::Add for $jet {
            type Output = $jet;
            #[inline]
            fn add(self, o: $jet) -> $jet {
                $jet(std::array::from_fn(|k| self.0[k] + o.0[k]))
            }
        }

        impl std::ops::Sub for $jet {
            type Output = $jet;
            #[inline]
            fn sub(self, o: $jet) -> $jet {
                $jet(std::array::from_fn(|k| self.0[k] - o.0[k]))
            }
        }

        impl std::ops::Neg for $jet {
            type Output = $jet;
            #[inline]
            fn neg(self) -> $jet {
                self.map(|u| -u)
            }
        }
    };
}
