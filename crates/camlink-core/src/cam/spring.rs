//! Helical compression springs (Shigley's *Mechanical Engineering
//! Design*, 10th ed., ch. 10).
//!
//! Wire diameter d, mean coil diameter D, active coils N_a, total coils
//! N_t, free length L₀ (m), shear modulus G (Pa), density ϱ (kg/m³):
//! - rate k = G d⁴/(8 D³ N_a) (eq. 10-9), N/m;
//! - solid height L_s = d N_t (squared and ground ends, Table 10-1), m;
//! - the spring's active mass m_s = ϱ (π d²/4)(π D N_a) (eq. 10-28), kg;
//! - surge (first natural) frequency between two fixed ends
//!   f = ½ √(k/m_s) Hz (eq. 10-27);
//! - spring index C = D/d.
//!
//! Installed at length L_i it pushes with F₀ = k (L₀ − L_i); lifted by
//! s_max it is L_i − s_max long, and the coil-clash margin is
//! L_i − s_max − L_s (positive: the coils never touch).

use super::synthesis::CamError;
use crate::fmt_num::num;

/// A helical compression spring's geometry and material.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Helical {
    /// Wire diameter d (m).
    pub wire: f64,
    /// Mean coil diameter D (m).
    pub mean_diameter: f64,
    /// Active coils N_a.
    pub active_coils: f64,
    /// Total coils N_t.
    pub total_coils: f64,
    /// Free length L₀ (m).
    pub free_length: f64,
    /// Shear modulus G (Pa).
    pub shear_modulus: f64,
    /// Density ϱ (kg/m³).
    pub density: f64,
}

/// What a spring installed in a cam's follower train does.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Installed {
    /// Rate k (N/m).
    pub rate: f64,
    /// Preload F₀ (N) at the installed length.
    pub preload: f64,
    /// Solid height L_s (m).
    pub solid: f64,
    /// Length at the largest lift (m).
    pub shortest: f64,
    /// Coil-clash margin L_i − s_max − L_s (m).
    pub clash_margin: f64,
    /// Active mass m_s (kg).
    pub mass: f64,
    /// Surge frequency (Hz), fixed–fixed.
    pub surge: f64,
    /// Spring index C = D/d.
    pub index: f64,
}

/// Why a spring cannot be used, naming the field of the design file.
#[derive(Clone, Debug, PartialEq)]
pub struct SpringError {
    /// The field at fault (`wire_diameter`, `free_length`, …).
    pub field: &'static str,
    pub message: String,
}

impl From<SpringError> for CamError {
    fn from(e: SpringError) -> CamError {
        CamError(format!("{}: {}", e.field, e.message))
    }
}

impl Helical {
    /// Rate k = G d⁴/(8 D³ N_a) (N/m).
    pub fn rate(&self) -> f64 {
        self.shear_modulus * self.wire.powi(4)
            / (8.0 * self.mean_diameter.powi(3) * self.active_coils)
    }

    /// Solid height L_s = d N_t (m).
    pub fn solid_height(&self) -> f64 {
        self.wire * self.total_coils
    }

    /// Active mass m_s = ϱ π² d² D N_a / 4 (kg).
    pub fn mass(&self) -> f64 {
        let pi2 = std::f64::consts::PI * std::f64::consts::PI;
        self.density * pi2 * self.wire * self.wire * self.mean_diameter * self.active_coils / 4.0
    }

    /// Surge frequency f = ½ √(k/m_s) (Hz), both ends fixed.
    pub fn surge_frequency(&self) -> f64 {
        0.5 * (self.rate() / self.mass()).sqrt()
    }

    /// The spring installed at `installed` (m) and compressed by a further
    /// `max_lift` (m); an error names the field when the numbers are not a
    /// spring or it goes solid.
    pub fn install(&self, installed: f64, max_lift: f64) -> Result<Installed, SpringError> {
        let err = |field, message: String| Err(SpringError { field, message });
        for (field, v) in [
            ("wire_diameter", self.wire),
            ("mean_diameter", self.mean_diameter),
            ("active_coils", self.active_coils),
            ("total_coils", self.total_coils),
            ("free_length", self.free_length),
            ("shear_modulus", self.shear_modulus),
            ("density", self.density),
            ("installed_length", installed),
        ] {
            if !(v > 0.0 && v.is_finite()) {
                return err(field, format!("must be positive, got {v}"));
            }
        }
        if self.mean_diameter <= self.wire {
            return err(
                "mean_diameter",
                format!(
                    "{} m must exceed the wire diameter {} m",
                    self.mean_diameter, self.wire
                ),
            );
        }
        if self.total_coils < self.active_coils {
            return err(
                "total_coils",
                format!(
                    "{} is fewer than the active coils {}",
                    self.total_coils, self.active_coils
                ),
            );
        }
        let solid = self.solid_height();
        if self.free_length <= solid {
            return err(
                "free_length",
                format!(
                    "{} m is not longer than the solid height d·N_t = {} m",
                    num(self.free_length),
                    num(solid)
                ),
            );
        }
        if installed > self.free_length {
            return err(
                "installed_length",
                format!(
                    "{installed} m is longer than the free length {} m (no preload)",
                    self.free_length
                ),
            );
        }
        let shortest = installed - max_lift;
        if shortest <= solid {
            return err(
                "installed_length",
                format!(
                    "the spring goes solid: at the largest lift {} m it would be {} m long, \
                     below its solid height d·N_t = {} m (lengthen installed_length or \
                     free_length, or use fewer total_coils)",
                    num(max_lift),
                    num(shortest),
                    num(solid)
                ),
            );
        }
        let rate = self.rate();
        Ok(Installed {
            rate,
            preload: rate * (self.free_length - installed),
            solid,
            shortest,
            clash_margin: shortest - solid,
            mass: self.mass(),
            surge: self.surge_frequency(),
            index: self.mean_diameter / self.wire,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A music-wire valve spring worked by hand from Shigley's equations
    /// (10-9, 10-27, 10-28, Table 10-1): d = 4 mm, D = 28 mm, N_a = 6,
    /// N_t = 8, G = 79.3 GPa, ϱ = 7800 kg/m³:
    /// k = 79.3e9 · 0.004⁴ / (8 · 0.028³ · 6) = 19 266.3 N/m;
    /// L_s = 0.032 m; m_s = 7800 · π² · 0.004² · 0.028 · 6 / 4 = 0.05173 kg;
    /// f = ½ √(19 266.3/0.05173) = 305.1 Hz.
    #[test]
    fn issue32_spring_rate_solid_height_and_surge_by_hand() {
        let s = Helical {
            wire: 0.004,
            mean_diameter: 0.028,
            active_coils: 6.0,
            total_coils: 8.0,
            free_length: 0.06,
            shear_modulus: 79.3e9,
            density: 7800.0,
        };
        assert!((s.rate() - 19_266.3).abs() < 0.1, "{}", s.rate());
        assert!((s.solid_height() - 0.032).abs() < 1e-15);
        assert!((s.mass() - 0.051_73).abs() < 1e-5, "{}", s.mass());
        assert!(
            (s.surge_frequency() - 305.1).abs() < 0.1,
            "{}",
            s.surge_frequency()
        );
        // Exactly the formulas.
        let k = 79.3e9 * 0.004f64.powi(4) / (8.0 * 0.028f64.powi(3) * 6.0);
        let ms = 7800.0 * std::f64::consts::PI.powi(2) * 0.004f64.powi(2) * 0.028 * 6.0 / 4.0;
        assert!((s.rate() - k).abs() < 1e-9 * k);
        assert!((s.surge_frequency() - 0.5 * (k / ms).sqrt()).abs() < 1e-9);
        let i = s.install(0.05, 0.009).unwrap();
        assert!((i.preload - k * 0.01).abs() < 1e-9);
        assert!((i.clash_margin - (0.05 - 0.009 - 0.032)).abs() < 1e-15);
        // Goes solid: named.
        let e = s.install(0.04, 0.009).unwrap_err();
        assert_eq!(e.field, "installed_length");
        assert!(e.message.contains("goes solid"), "{}", e.message);
        let e = Helical {
            free_length: 0.03,
            ..s
        }
        .install(0.03, 0.0)
        .unwrap_err();
        assert_eq!(e.field, "free_length");
    }
}
