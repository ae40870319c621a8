//! Sitting: a seat the worker's pelvis rests on, beside the two feet on the floor.
//!
//! A seat is a horizontal top at a height and a rectangle in plan (no backrest yet: the trunk
//! holds itself, as on a stool). The worker sits
//! when the point of the pelvis that rests on a seat — the midpoint of the ischial tuberosities,
//! [`ISCHIA_BELOW_HIPS_PER_STATURE`] below the hip joint centres — lies on the seat's top and
//! inside its outline. The seat then carries part of the body's weight; how the floor's and the
//! seat's reactions share it is in [`super::stance`] (a lever rule over three supports).

use nalgebra::{Vector2, Vector3};

/// Depth of the ischial tuberosities' contact below the hip joint centres, per metre of
/// stature (0.055: 9.6 cm for a 1.75 m man). ASSUMPTION: the order of the 8–10 cm between the
/// hip joint centre and a hard seat's surface under the tuberosities seen in seated-occupant
/// pelvis measurements (Brodeur, Cui & Reynolds 1995, ERL-TR-95-003, H-point and D-point in
/// the pelvis); no tabulated mean per stature was reached, so it is scaled with stature.
pub const ISCHIA_BELOW_HIPS_PER_STATURE: f64 = 0.055;

/// A seat: its top's height and outline, and the pelvis point that rests on it.
#[derive(Debug, Clone, PartialEq)]
pub struct Seat {
    /// The link that sits (the pelvis) and its resting point in that link's frame \[m\].
    pub link: usize,
    pub contact_in_link_m: Vector3<f64>,
    /// Height of the seat's top above the floor \[m\].
    pub height_m: f64,
    /// The top's outline in plan, counter-clockwise \[m\].
    pub outline_m: Vec<Vector2<f64>>,
    edges_m: Vec<(Vector2<f64>, f64)>,
}

impl Seat {
    /// A seat whose top, centred at `centre_m` and turned by `yaw_rad`, is `size_m` = (depth
    /// along its facing direction, width).
    pub fn new(
        link: usize,
        contact_in_link_m: Vector3<f64>,
        height_m: f64,
        centre_m: Vector2<f64>,
        [depth_m, width_m]: [f64; 2],
        yaw_rad: f64,
    ) -> Self {
        let rot = nalgebra::Rotation2::new(yaw_rad);
        let outline_m: Vec<Vector2<f64>> = [(1.0, -1.0), (1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0)]
            .iter()
            .map(|(sx, sy)| centre_m + rot * Vector2::new(sx * depth_m / 2.0, sy * width_m / 2.0))
            .collect();
        let edges_m = super::stance::polygon_edges(&outline_m);
        Seat {
            link,
            contact_in_link_m,
            height_m,
            outline_m,
            edges_m,
        }
    }

    /// The outline's edges as (outward unit normal n, offset d): inside means `n·p ≤ d`.
    #[inline]
    pub fn edges(&self) -> impl Iterator<Item = (Vector2<f64>, f64)> + '_ {
        self.edges_m.iter().copied()
    }

    /// Signed distance \[m\] of `p` from the outline: positive inside.
    pub fn margin_m(&self, p: &Vector2<f64>) -> f64 {
        self.edges()
            .map(|(n, d)| d - n.dot(p))
            .fold(f64::INFINITY, f64::min)
    }
}

/// The seat's reaction on the pelvis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeatReaction {
    /// Force on the pelvis \[N\], world axes.
    pub force_n: Vector3<f64>,
    /// Its centre of pressure on the seat's top \[m\].
    pub cop_m: Vector3<f64>,
    /// Its free moment about the vertical \[N·m\].
    pub free_moment_nm: f64,
    /// Share of the vertical load on the seat, 0..1.
    pub share: f64,
}
