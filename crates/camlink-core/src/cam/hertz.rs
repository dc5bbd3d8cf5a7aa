//! Hertz line contact of two cylinders and rolling-bearing life.
//!
//! Two cylinders of radii R₁, R₂ (m, signed: negative for a concave
//! surface, infinite for a flat), pressed together by a force F (N) along a
//! contact of length L (m), touch on a strip of half-width b with an
//! elliptical (semi-cylindrical) pressure of peak p_max (Shigley's
//! *Mechanical Engineering Design*, 10th ed., eqs. 3-73 and 3-74; Johnson,
//! *Contact Mechanics*, eq. 4.45):
//!
//!   b = √( 2F/(πL) · [(1 − ν₁²)/E₁ + (1 − ν₂²)/E₂] / (1/d₁ + 1/d₂) ),
//!   p_max = 2F/(π b L),
//!
//! d = 2R the diameters. With 1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂ and
//! 1/R = 1/R₁ + 1/R₂ this is b = √(4FR/(πLE*)).
//!
//! A cam against a roller is R₁ = ρ (the cam's local radius of curvature),
//! R₂ = the roller radius; against a flat face 1/R₂ = 0.
//!
//! Bearing life (ISO 281; Shigley eq. 11-3): L₁₀ = (C/P)^a million
//! revolutions, C the dynamic load rating (N), a = 3 for ball and 10/3 for
//! roller bearings, P the equivalent load: for a load that varies over the
//! revolutions, the cubic (a-th power) mean weighted by the revolutions
//! turned, P = (Σ Fᵢ^a nᵢ / Σ nᵢ)^(1/a).

use super::synthesis::CamError;

/// A material's elastic constants.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// Young's modulus E (Pa).
    pub young: f64,
    /// Poisson's ratio ν.
    pub poisson: f64,
    /// Shear modulus G (Pa).
    pub shear: f64,
    /// Density (kg/m³).
    pub density: f64,
}

/// Materials by name: E, ν, G from Shigley's *Mechanical Engineering
/// Design*, 10th ed., Table A-5 (physical constants of materials); density
/// from its unit weight w (kN/m³) as w/g, g = 9.80665 m/s².
pub const MATERIALS: &[(&str, Material)] = &[
    ("steel", mat(207.0, 0.292, 79.3, 76.5)),
    ("stainless-steel", mat(190.0, 0.305, 73.1, 76.0)),
    ("cast-iron", mat(100.0, 0.211, 41.4, 70.6)),
    ("aluminium", mat(71.7, 0.333, 26.9, 26.6)),
    ("brass", mat(106.0, 0.324, 40.1, 83.8)),
    ("phosphor-bronze", mat(111.0, 0.349, 41.4, 80.1)),
    ("beryllium-copper", mat(124.0, 0.285, 48.3, 80.6)),
    ("titanium", mat(114.0, 0.340, 42.4, 43.4)),
];

const fn mat(e_gpa: f64, nu: f64, g_gpa: f64, weight_kn: f64) -> Material {
    Material {
        young: e_gpa * 1e9,
        poisson: nu,
        shear: g_gpa * 1e9,
        density: weight_kn * 1e3 / 9.80665,
    }
}

/// The material of that name in [`MATERIALS`].
pub fn material(name: &str) -> Option<Material> {
    MATERIALS.iter().find(|(n, _)| *n == name).map(|(_, m)| *m)
}

/// Names of [`MATERIALS`], comma separated (for messages).
pub fn material_names() -> String {
    MATERIALS
        .iter()
        .map(|(n, _)| *n)
        .collect::<Vec<_>>()
        .join(", ")
}

/// The contact modulus E* (Pa): 1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂.
pub fn contact_modulus(a: &Material, b: &Material) -> f64 {
    1.0 / ((1.0 - a.poisson * a.poisson) / a.young + (1.0 - b.poisson * b.poisson) / b.young)
}

/// Line contact of two cylinders.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineContact {
    /// Half-width b of the contact strip (m).
    pub half_width: f64,
    /// Peak pressure p_max (Pa).
    pub max_pressure: f64,
}

/// The line contact of cylinders of radii `r1`, `r2` (m; negative for a
/// concave surface, `f64::INFINITY` for a flat) pressed by `force` (N) over
/// `length` (m), contact modulus `e_star` (Pa). `None` where the curvature
/// sum 1/R₁ + 1/R₂ is not positive (conforming or diverging surfaces: no
/// Hertz contact) or the force is not positive.
pub fn line_contact(r1: f64, r2: f64, force: f64, length: f64, e_star: f64) -> Option<LineContact> {
    let curvature = 1.0 / r1 + 1.0 / r2;
    if !(curvature > 0.0 && force > 0.0 && curvature.is_finite()) {
        return None;
    }
    let b = (4.0 * force / (curvature * std::f64::consts::PI * length * e_star)).sqrt();
    Some(LineContact {
        half_width: b,
        max_pressure: 2.0 * force / (std::f64::consts::PI * b * length),
    })
}

/// Complete elliptic integrals K(m), E(m) of parameter m = e² in [0, 1)
/// by the arithmetic–geometric mean (Abramowitz & Stegun 17.6).
pub fn elliptic_ke(m: f64) -> (f64, f64) {
    let (mut a, mut b) = (1.0f64, (1.0 - m).sqrt());
    let mut sum = 0.5 * m; // 2^(n−1) c_n² at n = 0, c₀² = m
    let mut pow = 0.5;
    for _ in 0..60 {
        let c = 0.5 * (a - b);
        pow *= 2.0;
        sum += pow * c * c;
        let (an, bn) = (0.5 * (a + b), (a * b).sqrt());
        a = an;
        b = bn;
        if c.abs() < 1e-17 * a {
            break;
        }
    }
    let k = std::f64::consts::FRAC_PI_2 / a;
    (k, k * (1.0 - sum))
}

/// Elliptical (point) contact of two bodies.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointContact {
    /// Semi-axis a (m) along the direction of the smaller curvature sum.
    pub semi_major: f64,
    /// Semi-axis b (m) along the larger.
    pub semi_minor: f64,
    /// Peak pressure p₀ = 3F/(2π a b) (Pa).
    pub max_pressure: f64,
}

/// Hertz point contact (Johnson, *Contact Mechanics*, §4.2, eqs. 4.39–4.41)
/// under `force` (N), contact modulus `e_star` (Pa), with the curvature
/// sums of the two principal planes `a_sum` = ½(1/R₁ₓ + 1/R₂ₓ) and
/// `b_sum` = ½(1/R₁ᵧ + 1/R₂ᵧ) (1/m; the planes aligned). With A ≤ B the
/// smaller and larger, the ellipse's eccentricity e (b/a = √(1 − e²))
/// solves B/A = (E(e)/(1 − e²) − K(e))/(K(e) − E(e)), and
/// a³ = 3F (K − E)/(2π E* e² A), p₀ = 3F/(2π a b). A crowned roller of
/// radius R_r and crown radius R_c on a cam of radius ρ (straight along
/// its axis): ½(1/ρ + 1/R_r) and ½(1/R_c). `None` without a positive
/// force or positive sums.
pub fn point_contact(a_sum: f64, b_sum: f64, force: f64, e_star: f64) -> Option<PointContact> {
    let (lo, hi) = (a_sum.min(b_sum), a_sum.max(b_sum));
    if !(lo > 0.0 && hi.is_finite() && force > 0.0) {
        return None;
    }
    let ratio = hi / lo;
    let km = |m: f64| {
        let (k, e) = elliptic_ke(m);
        // (K − E)/m, by its series where m is tiny.
        let ke = if m < 1e-6 {
            std::f64::consts::FRAC_PI_4 * (1.0 + 0.375 * m)
        } else {
            (k - e) / m
        };
        (k, e, ke)
    };
    // Bisection on ln(b/a) in [ln 1e-9, 0]: the ratio grows as b/a falls.
    let f = |kp: f64| {
        let m = 1.0 - kp * kp;
        let (k, e, ke) = km(m);
        (e / (kp * kp) - k) / (ke * m)
    };
    let kp = if ratio <= 1.0 + 1e-12 {
        1.0
    } else {
        let (mut x0, mut x1) = ((1e-9f64).ln(), 0.0f64);
        for _ in 0..200 {
            let x = 0.5 * (x0 + x1);
            if f(x.exp()) > ratio {
                x0 = x;
            } else {
                x1 = x;
            }
        }
        (0.5 * (x0 + x1)).exp()
    };
    let (_, _, ke) = km(1.0 - kp * kp);
    let a = (3.0 * force * ke / (2.0 * std::f64::consts::PI * e_star * lo)).cbrt();
    let b = a * kp;
    Some(PointContact {
        semi_major: a,
        semi_minor: b,
        max_pressure: 3.0 * force / (2.0 * std::f64::consts::PI * a * b),
    })
}

/// The equivalent load P (N) of loads `forces` (N, negative ones count as
/// zero) each held over `revolutions` (any unit), for life exponent `a`.
pub fn equivalent_load(forces: &[f64], revolutions: &[f64], a: f64) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for (f, n) in forces.iter().zip(revolutions) {
        num += f.max(0.0).powf(a) * n;
        den += n;
    }
    (num / den).powf(1.0 / a)
}

/// L₁₀ life (revolutions) for dynamic rating `rating` (N), equivalent
/// load `load` (N) and exponent `a`.
pub fn l10(rating: f64, load: f64, a: f64) -> Result<f64, CamError> {
    if !(rating > 0.0 && rating.is_finite()) {
        return Err(CamError(format!(
            "the bearing's dynamic rating must be positive, got {rating} N"
        )));
    }
    Ok((rating / load).powf(a) * 1e6)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against the closed form as Shigley writes it, with diameters
    /// (10th ed., eqs. 3-73 and 3-74), spelt out here independently of
    /// [`line_contact`]'s form with radii: convex–convex, convex on a flat,
    /// convex in a concave cylinder.
    #[test]
    fn issue32_hertz_two_cylinders_match_shigley_closed_form() {
        let s = material("steel").unwrap();
        let ci = material("cast-iron").unwrap();
        let (f, l) = (1500.0, 0.02);
        for (d1, d2, a, b) in [
            (0.05, 0.1, s, s),
            (0.03, f64::INFINITY, s, ci),
            (0.04, -0.2, ci, s),
        ] {
            let num = 2.0 * f / (std::f64::consts::PI * l)
                * ((1.0 - a.poisson.powi(2)) / a.young + (1.0 - b.poisson.powi(2)) / b.young);
            let want_b = (num / (1.0 / d1 + 1.0 / d2)).sqrt();
            let want_p = 2.0 * f / (std::f64::consts::PI * want_b * l);
            let got = line_contact(d1 / 2.0, d2 / 2.0, f, l, contact_modulus(&a, &b)).unwrap();
            assert!((got.half_width - want_b).abs() < 1e-14 * want_b, "{got:?}");
            assert!((got.max_pressure - want_p).abs() < 1e-12 * want_p);
        }
        assert!(line_contact(0.02, -0.02, f, l, 1e11).is_none());
    }

    /// Equal steel cylinders: p_max = √(F E*/(π L R)) with 1/R = 2/R₁, and
    /// the load spread over the strip, ∫ p dx = (π/2) b p_max = F/L.
    #[test]
    fn line_contact_equilibrium() {
        let s = material("steel").unwrap();
        let e = contact_modulus(&s, &s);
        let c = line_contact(0.01, 0.01, 800.0, 0.015, e).unwrap();
        let want = (800.0 * e / (std::f64::consts::PI * 0.015 * 0.005)).sqrt();
        assert!((c.max_pressure - want).abs() < 1e-12 * want);
        let area = std::f64::consts::FRAC_PI_2 * c.half_width * c.max_pressure;
        assert!((area - 800.0 / 0.015).abs() < 1e-9 * area);
    }

    /// Elliptic integrals at known values: K(0) = E(0) = π/2, and
    /// K(½) = 1.854 074 677 301 372, E(½) = 1.350 643 881 047 675 (A&S
    /// Table 17.1).
    #[test]
    fn elliptic_integrals_known_values() {
        let (k, e) = elliptic_ke(0.0);
        assert!((k - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        assert!((e - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        let (k, e) = elliptic_ke(0.5);
        assert!((k - 1.854_074_677_301_372).abs() < 1e-14, "{k}");
        assert!((e - 1.350_643_881_047_675).abs() < 1e-14, "{e}");
    }

    /// Crowned-roller point contact: the sphere limit (A = B) is Hertz's
    /// a = (3FR/(4E*))^⅓, R = 1/(2A); and for an elongated ellipse the
    /// surface displacement under the pressure p₀√(1 − x²/a² − y²/b²),
    /// integrated numerically (u = (1/(πE*)) ∬ p/r dA, in polar
    /// coordinates about the field point), falls from the centre by A x²
    /// and B y² (Johnson §4.2) — an independent check of the solved axes.
    #[test]
    fn issue32_point_contact_sphere_limit_and_surface_displacement() {
        let e = 1.1e11;
        let f = 500.0;
        let s = point_contact(25.0, 25.0, f, e).unwrap();
        let want = (3.0 * f * 0.02 / (4.0 * e)).cbrt();
        assert!((s.semi_major - want).abs() < 1e-12 * want);
        let s = point_contact(25.0, 25.0 * (1.0 + 1e-7), f, e).unwrap();
        assert!((s.semi_major - want).abs() < 1e-6 * want, "{s:?}");
        let (aa, bb) = (2.0, 45.0); // 1/m: a crown of 0.25 m, a ρ–roller sum of 90
        let c = point_contact(aa, bb, f, e).unwrap();
        let (a, b, p0) = (c.semi_major, c.semi_minor, c.max_pressure);
        assert!(a > b);
        let u = |x: f64, y: f64| {
            let n = 4000;
            let mut total = 0.0;
            for i in 0..n {
                let phi = (i as f64 + 0.5) / n as f64 * std::f64::consts::TAU;
                let (c, sn) = (phi.cos(), phi.sin());
                // Along the ray: 1 − (x + r c)²/a² − (y + r s)²/b² = α + β r − γ r².
                let alpha = 1.0 - x * x / (a * a) - y * y / (b * b);
                let beta = -2.0 * (x * c / (a * a) + y * sn / (b * b));
                let gamma = c * c / (a * a) + sn * sn / (b * b);
                let root = (beta + (beta * beta + 4.0 * alpha * gamma).sqrt()) / (2.0 * gamma);
                // ∫₀^R √(γ (r − r₋)(R − r)) dr, r₋ the other root, by
                // Gauss–Chebyshev of the second kind on [r₋, R] split at 0.
                let rm = -alpha / (gamma * root);
                let m = 400;
                let mut sum = 0.0;
                for j in 1..=m {
                    // Midpoint in t on r = 0 … R with the √ weight exact.
                    let t = (j as f64 - 0.5) / m as f64;
                    let r = root * (1.0 - (1.0 - t) * (1.0 - t));
                    let dr = 2.0 * root * (1.0 - t) / m as f64;
                    sum += (gamma * (r - rm) * (root - r)).max(0.0).sqrt() * dr;
                }
                total += sum;
            }
            p0 * total * std::f64::consts::TAU / n as f64 / (std::f64::consts::PI * e)
        };
        let u0 = u(0.0, 0.0);
        let (x, y) = (0.5 * a, 0.5 * b);
        let ax = (u0 - u(x, 0.0)) / (x * x);
        let by = (u0 - u(0.0, y)) / (y * y);
        assert!((ax - aa).abs() < 1e-4 * aa, "A {ax} vs {aa}");
        assert!((by - bb).abs() < 1e-4 * bb, "B {by} vs {bb}");
    }

    #[test]
    fn equivalent_load_and_life() {
        // A constant load is its own equivalent.
        assert!((equivalent_load(&[300.0; 5], &[1.0; 5], 3.0) - 300.0).abs() < 1e-12);
        // Half the revolutions at F, half at zero: P = F / 2^(1/3).
        let p = equivalent_load(&[100.0, 0.0], &[1.0, 1.0], 3.0);
        assert!((p - 100.0 / 2f64.cbrt()).abs() < 1e-12);
        assert!((l10(1000.0, 100.0, 3.0).unwrap() - 1e9).abs() < 1e-3);
        assert!(l10(0.0, 1.0, 3.0).is_err());
    }
}
