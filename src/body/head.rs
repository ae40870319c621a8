//! The head's posture as ISO 11226 and the observational methods look at it: its inclination
//! against the vertical and its flexion and side bending against the trunk, each measured in the
//! head's own planes (forward = the horizontal direction the face points to; left = along the
//! ears), so that turning the head does not change how far it is bent (a head turned 50° and
//! tilted back is tilted back, not partly bent sideways). Its twist is the neck's axial-rotation
//! joint.

use nalgebra::{Matrix3, Vector3};

/// The head's angles \[rad\].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeadAngles {
    /// The head's long axis against the vertical in the head's sagittal plane (forward positive).
    pub inclination_rad: f64,
    /// The head's long axis against the trunk's, in the head's sagittal plane (forward positive).
    pub neck_flexion_rad: f64,
    /// The head's long axis out of its sagittal plane, against the trunk (to the left positive).
    pub neck_side_bend_rad: f64,
}

/// The head's ear-to-ear axis `y` with its vertical component dropped, normalised: the unit
/// vector pointing to the head's left in the horizontal plane of the frame `y` is expressed in
/// (that frame's y where the axis points straight up or down).
fn ear_axis(y: Vector3<f64>) -> Vector3<f64> {
    let h = Vector3::new(y.x, y.y, 0.0);
    if h.norm() > 1e-9 {
        h.normalize()
    } else {
        Vector3::y()
    }
}

impl HeadAngles {
    /// From the world rotations of the trunk and the head links (z along each one's long axis,
    /// x forward, y to the left).
    pub fn measure(r_trunk: &Matrix3<f64>, r_head: &Matrix3<f64>) -> Self {
        let b = r_head * Vector3::z();
        // in the world: the head's sagittal plane holds the vertical and the face's direction
        let left = ear_axis(r_head * Vector3::y());
        let fwd = left.cross(&Vector3::z());
        let inclination_rad = b.dot(&fwd).atan2(b.z);
        // against the trunk: the same in the trunk's frame
        let rt = r_trunk.transpose();
        let c = rt * b;
        let left_t = ear_axis(rt * r_head * Vector3::y());
        let fwd_t = left_t.cross(&Vector3::z());
        HeadAngles {
            inclination_rad,
            neck_flexion_rad: c.dot(&fwd_t).atan2(c.z),
            neck_side_bend_rad: c.dot(&left_t).clamp(-1.0, 1.0).asin(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Rotation3;

    fn deg(r: f64) -> f64 {
        r.to_degrees()
    }

    #[test]
    fn turning_the_head_does_not_change_how_far_it_is_bent() {
        let trunk = Matrix3::identity();
        // tilted back 20° (about y), then turned 50° to the left about its own long axis
        let back = Rotation3::from_axis_angle(&Vector3::y_axis(), -20f64.to_radians());
        for turn_deg in [0.0, 50.0, -50.0, 80.0] {
            let turn = Rotation3::from_axis_angle(&Vector3::z_axis(), f64::to_radians(turn_deg));
            // the head turns first (on the trunk), then tilts back in its own sagittal plane
            let head = (turn * back).into_inner();
            let a = HeadAngles::measure(&trunk, &head);
            assert!(
                (deg(a.inclination_rad) + 20.0).abs() < 1e-9,
                "{turn_deg}: {a:?}"
            );
            assert!(
                (deg(a.neck_flexion_rad) + 20.0).abs() < 1e-9,
                "{turn_deg}: {a:?}"
            );
            assert!(deg(a.neck_side_bend_rad).abs() < 1e-9, "{turn_deg}: {a:?}");
        }
        // bent 10° toward the left ear (a negative turn about x tips the top to the left)
        let side = Rotation3::from_axis_angle(&Vector3::x_axis(), -10f64.to_radians());
        let a = HeadAngles::measure(&trunk, &side.into_inner());
        assert!((deg(a.neck_side_bend_rad) - 10.0).abs() < 1e-9, "{a:?}");
        assert!(deg(a.neck_flexion_rad).abs() < 1e-9, "{a:?}");
    }

    #[test]
    fn a_bent_trunk_carries_the_head_with_it() {
        // trunk flexed 30°, head flexed 20° on it: inclined 50°, neck flexion 20°
        let t = Rotation3::from_axis_angle(&Vector3::y_axis(), 30f64.to_radians());
        let h = t * Rotation3::from_axis_angle(&Vector3::y_axis(), 20f64.to_radians());
        let a = HeadAngles::measure(&t.into_inner(), &h.into_inner());
        assert!((deg(a.inclination_rad) - 50.0).abs() < 1e-9);
        assert!((deg(a.neck_flexion_rad) - 20.0).abs() < 1e-9);
    }
}
