//! The scale check: a model whose bodies differ in size by [`SPAN`] or
//! more is warned about, naming the bodies far from the typical size (a
//! length in millimetres among lengths in metres).

use camlink_core::fmt_num::num;
use camlink_core::math::{norm, sub, V2};
use camlink_core::{Model, ModelWarning};

/// Warning kind of the scale check.
pub(crate) const KIND: &str = "length_scale";

/// Ratio of the largest to the smallest body size from which a model is
/// taken to mix scales: three orders of magnitude (a link of 100 among
/// links of 0.1, millimetres written as metres, is warned about).
const SPAN: f64 = 1e3;

/// The size of a body (m): the largest distance between two of its points,
/// its frame origin counted as one; 0 for a body with no point away from
/// the origin.
fn size(points: &[V2]) -> f64 {
    let mut largest = 0.0_f64;
    for (k, a) in points.iter().enumerate() {
        largest = largest.max(norm(*a));
        for b in &points[k + 1..] {
            largest = largest.max(norm(sub(*a, *b)));
        }
    }
    largest
}

/// Adds a [`KIND`] warning to `model` for each body whose size is more
/// than √[`SPAN`] away from the median size, when the sizes span [`SPAN`]
/// or more. Bodies with a single point (at the origin) have no size.
pub(crate) fn check(model: &mut Model) {
    let sizes: Vec<(usize, f64)> = model
        .bodies
        .iter()
        .enumerate()
        .map(|(k, b)| (k, size(&b.points.iter().map(|p| p.s).collect::<Vec<_>>())))
        .filter(|&(_, s)| s > 0.0 && s.is_finite())
        .collect();
    let (Some(lo), Some(hi)) = (
        sizes.iter().map(|s| s.1).reduce(f64::min),
        sizes.iter().map(|s| s.1).reduce(f64::max),
    ) else {
        return;
    };
    if hi < SPAN * lo {
        return;
    }
    let mut sorted: Vec<f64> = sizes.iter().map(|s| s.1).collect();
    sorted.sort_by(f64::total_cmp);
    let median = sorted[sorted.len() / 2];
    let far = SPAN.sqrt();
    for &(k, s) in &sizes {
        if s > far * median || s * far < median {
            let name = &model.bodies[k].name;
            let field = if k == 0 {
                "ground.points".to_string()
            } else {
                format!("bodies[{}].points", k - 1)
            };
            model.warnings.push(ModelWarning {
                kind: KIND,
                field,
                message: format!(
                    "body '{name}' spans {} m, while the bodies typically span {} m \
                     (sizes from {} m to {} m): is a length in another unit \
                     (mm for m)?",
                    num(s),
                    num(median),
                    num(lo),
                    num(hi)
                ),
            });
        }
    }
}
