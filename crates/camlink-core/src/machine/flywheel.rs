//! Flywheel sizing from the input torque over one cycle at the design
//! speed (Norton, *Design of Machinery*, §11.11; Shigley, *Mechanical
//! Engineering Design*, §16-12).
//!
//! With the input torque T(θ) (N·m) over one cycle θ₀ … θ₀ + 2π and its
//! mean T̄, the energy E(θ) = ∫_{θ₀}^{θ} (T − T̄) dθ (J) swings by
//! ΔE = max E − min E. A flywheel of inertia I (kg·m²) turning at mean
//! speed ω̄ = (ω_max + ω_min)/2 takes up ΔE = ½ I (ω_max² − ω_min²)
//! = I C_s ω̄², with the coefficient of speed fluctuation
//! C_s = (ω_max − ω_min)/ω̄, so I = ΔE / (C_s ω̄²).

/// The energy fluctuation of a torque over one cycle.
#[derive(Clone, Debug, PartialEq)]
pub struct Fluctuation {
    /// T̄ (N·m): the cycle mean of the torque.
    pub mean_torque: f64,
    /// ΔE = max E − min E (J).
    pub delta_e: f64,
    /// E(θ) at each sample (J), E(θ₀) = 0.
    pub energy: Vec<f64>,
    /// θ (rad) where E is largest and least. For the torque a load needs,
    /// driven by a constant torque T̄, the flywheel has given up most energy
    /// where E is largest: the speed is lowest there and highest where E is
    /// least.
    pub theta_max: f64,
    pub theta_min: f64,
}

/// The fluctuation of `torque` (N·m) sampled at `theta` (rad), increasing
/// over exactly one cycle, both ends included (the last sample repeats the
/// first a cycle on). Trapezoidal rule: for a smooth periodic torque the
/// mean is exact to rounding; E and ΔE are second order in the step.
pub fn fluctuation(theta: &[f64], torque: &[f64]) -> Fluctuation {
    assert!(theta.len() == torque.len() && theta.len() >= 2);
    let span = theta[theta.len() - 1] - theta[0];
    let mut area = 0.0;
    for k in 1..theta.len() {
        area += 0.5 * (torque[k] + torque[k - 1]) * (theta[k] - theta[k - 1]);
    }
    let mean = area / span;
    let mut energy = vec![0.0; theta.len()];
    for k in 1..theta.len() {
        let dt = theta[k] - theta[k - 1];
        energy[k] = energy[k - 1] + 0.5 * (torque[k] + torque[k - 1] - 2.0 * mean) * dt;
    }
    let (mut kmax, mut kmin) = (0, 0);
    for (k, e) in energy.iter().enumerate() {
        if *e > energy[kmax] {
            kmax = k;
        }
        if *e < energy[kmin] {
            kmin = k;
        }
    }
    Fluctuation {
        mean_torque: mean,
        delta_e: energy[kmax] - energy[kmin],
        theta_max: theta[kmax],
        theta_min: theta[kmin],
        energy,
    }
}

/// I = ΔE / (C_s ω̄²) (kg·m²) for an energy fluctuation ΔE (J), a
/// coefficient of speed fluctuation C_s > 0 and a mean speed ω̄ (rad/s).
pub fn inertia(delta_e: f64, cs: f64, omega: f64) -> f64 {
    delta_e / (cs * omega * omega)
}

/// The speed band of a flywheel: ω_max − ω_min = ΔE / (I ω̄) (rad/s).
pub fn band(delta_e: f64, inertia: f64, omega: f64) -> f64 {
    delta_e / (inertia * omega)
}
