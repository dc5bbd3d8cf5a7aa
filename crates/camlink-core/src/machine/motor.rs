//! Motor sizing: the input torque of a cycle seen at the motor shaft
//! through a gear of ratio n = ω_motor / ω_input (no losses):
//! T_m = T / n, ω_m = n ω.

/// A motor: its torque–speed curve and its gear.
#[derive(Clone, Debug, PartialEq)]
pub struct Motor {
    /// The torque the motor can give (N·m) at its shaft speed (rad/s):
    /// `(speed, torque)` pairs, speeds increasing from 0 or above;
    /// linear between them.
    pub curve: Vec<(f64, f64)>,
    /// n = ω_motor / ω_input (1 for a direct drive).
    pub gear_ratio: f64,
    /// Continuous (rated) torque (N·m) the RMS torque is held to.
    pub rated_torque: Option<f64>,
    /// Rated power (W) the peak power is held to.
    pub rated_power: Option<f64>,
}

impl Motor {
    /// The curve's torque at motor speed `w` (rad/s); `None` past its
    /// ends.
    pub fn available(&self, w: f64) -> Option<f64> {
        let c = &self.curve;
        let (first, last) = (c.first()?, c.last()?);
        if w < first.0 || w > last.0 {
            return None;
        }
        for p in c.windows(2) {
            let ((w0, t0), (w1, t1)) = (p[0], p[1]);
            if w <= w1 {
                let u = if w1 > w0 { (w - w0) / (w1 - w0) } else { 1.0 };
                return Some(t0 + u * (t1 - t0));
            }
        }
        Some(last.1)
    }

    /// The highest speed of the curve (rad/s).
    pub fn top_speed(&self) -> f64 {
        self.curve.last().map_or(0.0, |p| p.0)
    }
}

/// Peak and RMS of the motor torque and the peak power over a cycle.
#[derive(Clone, Debug, PartialEq)]
pub struct Duty {
    /// max |T_m| (N·m) and the input angle (rad) where it occurs.
    pub peak_torque: f64,
    pub peak_at: f64,
    /// √(mean T_m²) over the cycle (N·m), by the trapezoidal rule in θ.
    pub rms_torque: f64,
    /// max |T_m ω_m| (W).
    pub peak_power: f64,
    /// (ω_m, T_m) at each sample (rad/s, N·m).
    pub points: Vec<(f64, f64)>,
}

/// The duty of a motor with gear ratio `n` driving the input torque
/// `torque` (N·m) at input speeds `speed` (rad/s), sampled at input angles
/// `theta` (rad) over one cycle, both ends included.
pub fn duty(n: f64, theta: &[f64], speed: &[f64], torque: &[f64]) -> Duty {
    let points: Vec<(f64, f64)> = speed
        .iter()
        .zip(torque)
        .map(|(w, t)| (n * w, t / n))
        .collect();
    let (mut peak, mut at, mut power, mut sq) = (0.0f64, theta[0], 0.0f64, 0.0);
    for (k, &(w, t)) in points.iter().enumerate() {
        if t.abs() > peak {
            peak = t.abs();
            at = theta[k];
        }
        power = power.max((t * w).abs());
        if k > 0 {
            let t0 = points[k - 1].1;
            sq += 0.5 * (t * t + t0 * t0) * (theta[k] - theta[k - 1]);
        }
    }
    let span = theta[theta.len() - 1] - theta[0];
    Duty {
        peak_torque: peak,
        peak_at: at,
        rms_torque: (sq / span).sqrt(),
        peak_power: power,
        points,
    }
}
