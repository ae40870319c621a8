//! Headings on the floor: where the pelvis faces and how far it is turned against the feet.
//!
//! The plan's acceptable zones ([`crate::plan`]) and the assessment's angles
//! ([`crate::assess`]) both measure the trunk's turn against the feet from these, so that the
//! turn the planner keeps within its zone is the turn the verdict judges.

use nalgebra::{Matrix3, Vector3};

/// The unit horizontal heading of a link's x axis, or `None` when that axis is (nearly)
/// vertical.
fn x_heading(r: &Matrix3<f64>) -> Option<Vector3<f64>> {
    let x = r * Vector3::x();
    Vector3::new(x.x, x.y, 0.0).try_normalize(1e-9)
}

/// The pelvis's forward heading on the floor, square to its hip axis: `R ŷ` with its z dropped,
/// normalised, crossed with `ẑ`. A stoop, a tilt about the hip axis, leaves it level, where the
/// pelvis's x axis projected on the floor shortens and flips as the tilt passes 90° (which made
/// the trunk's inclination, measured against it, jump by its whole value). The x axis's heading
/// when the hip axis is vertical; world x when that axis is vertical too.
pub fn pelvis_forward(r_pelvis: &Matrix3<f64>) -> Vector3<f64> {
    let y = r_pelvis * Vector3::y();
    Vector3::new(y.x, y.y, 0.0)
        .try_normalize(1e-9)
        .map(|y| y.cross(&Vector3::z()))
        .or_else(|| x_heading(r_pelvis))
        .unwrap_or_else(Vector3::x)
}

/// The pelvis's turn against the feet [rad], toward the left positive: the pelvis's heading
/// taken square to its hip axis (which a stoop, a tilt about that axis, leaves level; the
/// forward heading when the hip axis is vertical) against the mean of the feet's headings (the
/// world rotations of the foot links; a foot whose x axis is vertical is left out). 0 without
/// feet: a body with nothing to turn against.
pub fn pelvis_turn_rad(
    r_pelvis: &Matrix3<f64>,
    feet: impl IntoIterator<Item = Matrix3<f64>>,
) -> f64 {
    let feet: Vector3<f64> = feet.into_iter().filter_map(|r| x_heading(&r)).sum();
    let hips = pelvis_forward(r_pelvis);
    if feet.norm() > 1e-9 {
        feet.cross(&hips).z.atan2(feet.dot(&hips))
    } else {
        0.0
    }
}
