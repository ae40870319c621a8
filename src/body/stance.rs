//! Standing on both feet: where the feet are, how the floor shares the load between them, the
//! centre of pressure and the balance margin.
//!
//! A body with a floating base (unactuated root joints) stands when the floor's reactions at
//! the two soles balance gravity and the hand loads. Two feet make the reaction statically
//! indeterminate; posture-opt splits it **by where the centre of pressure lies between the
//! feet**, as 3DSSPP does, and directs each foot's force toward a common point above the feet,
//! as the ground reactions of standing people converge near the centre of mass:
//!
//! 1. the total reaction `(F, M)` about the world origin is minus the sum of gravity and the hand
//!    loads; its centre of pressure on the floor is `p = (−M_y/F_z, M_x/F_z)` and the free moment
//!    about the vertical `T = M_z − (p × F)_z`;
//! 2. `s`, the share of the left foot, is the position of `p` projected on the segment from the
//!    right sole centre `c_R` to the left one `c_L` (clamped to 0..1) — the lever rule of a beam on
//!    two supports;
//! 3. each foot carries its share of the vertical load and of the free moment at its own centre
//!    of pressure `p_i = c_i + δ`, where `δ = p − (s c_L + (1 − s) c_R)` is the part of `p` off that
//!    segment, and its force points from `p_i` to the point `A = p + F·h/F_z` of the resultant's
//!    line of action at the height `h` of the centre of mass: `F_i = s_i F_z (A − p_i)/h`.
//!
//! 4. what statics leaves open between two feet — how hard they push toward or away from each
//!    other along the line joining them, and how each foot's centre of pressure moves on its
//!    sole — is settled as the body does with least effort: the internal force `λ e` (`e` the
//!    horizontal unit vector from the right to the left sole, `+λe` on the left foot, `−λe` on
//!    the right) and the internal moment pair `±m` (horizontal, world axes: `+m` on the left
//!    foot) minimise the sum of squared torques of the joints that carry a foot, a 3×3
//!    least-squares problem ([`settle_internal_force`]); it changes no torque above the pelvis;
//! 5. a horizontal moment on a foot is its centre of pressure moving on the sole (by
//!    `(−m_y, m_x)/F_z`), so the soles bound the moments: they are scaled down by the largest
//!    factor in 0..1 that keeps each foot's centre of pressure on its sole (and λ is chosen again
//!    for them). With the feet wider than the hips the legs stand as an A-frame and the forces
//!    lean inward; the centres of pressure move a few millimetres inward to pass under the
//!    ankles, as a standing person's do, instead of loading the ankle evertors.
//!
//! The reactions then balance the body exactly (`Σ F_i = F` and `Σ p_i × F_i = p × F`), so the
//! torques of the unactuated root joints vanish — a check the tests make against Pinocchio's
//! inverse dynamics with the same foot forces. With the feet apart, the forces lean inward toward
//! the body instead of standing vertical, as measured ground reactions do, which keeps a wide
//! stance from loading the hips sideways. Balance: `p` must lie inside the support polygon, the
//! convex hull of both soles, by a margin. For loads that hang from the hands (`F` vertical) `p` is
//! the floor projection of the centre of mass of body and load together.

use super::model::{BodyError, BodyModel};
use super::seat::{Seat, SeatReaction};
use super::statics::{PointLoad, StaticsData};
use nalgebra::{Isometry3, Matrix3, Point3, Translation3, UnitQuaternion, Vector2, Vector3};

/// A foot: its link and the sole, the bottom face of the link's collision box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Foot {
    pub link: usize,
    /// Sole centre in the link frame (bottom face of the box).
    pub sole_center_in_link_m: Vector3<f64>,
    pub half_length_m: f64,
    pub half_width_m: f64,
}

impl Foot {
    /// The foot of link `name`: its first collision box, whose bottom face (in the link frame at
    /// q = 0, z down) is the sole.
    pub fn from_link(model: &BodyModel, name: &str) -> Result<Self, BodyError> {
        let link = model.frame_link(name)?;
        let b = model.links[link]
            .boxes
            .first()
            .ok_or_else(|| BodyError::Invalid {
                path: model.name.clone(),
                element: format!("link '{name}'"),
                problem: "a foot needs a <collision> box: its bottom face is the sole".into(),
            })?;
        let c = b.link_from_box * Point3::new(0.0, 0.0, -b.half_extents_m.z);
        Ok(Foot {
            link,
            sole_center_in_link_m: c.coords,
            half_length_m: b.half_extents_m.x,
            half_width_m: b.half_extents_m.y,
        })
    }
}

/// Where the two feet stand: their nominal poses (sole centre frames, z up), the support
/// polygon there, and — when the planner places the feet — where they may go. Index 0 is the
/// left foot, 1 the right.
#[derive(Debug, Clone, PartialEq)]
pub struct Stance {
    pub feet: [Foot; 2],
    /// World pose of each foot's link frame in the nominal stance (flat, on the floor): the
    /// feet's pose when they are fixed, and at rest.
    pub world_from_foot: [Isometry3<f64>; 2],
    /// Support polygon of the nominal stance (convex hull of both soles), counter-clockwise,
    /// world x-y \[m\].
    pub support_polygon_m: Vec<Vector2<f64>>,
    /// The polygon's edges as (outward unit normal, offset), computed once.
    edges_m: Vec<(Vector2<f64>, f64)>,
    /// Where the feet may be placed; `None`: the feet stay at `world_from_foot`.
    pub placement: Option<Placement>,
    /// The seat the worker sits on (`None`: standing).
    pub seat: Option<Seat>,
}

/// Where the planner may place the feet: a standing area on the floor and the ranges of a
/// human stance (see `docs/worker.md`, "Stepping and turning", for the sources).
#[derive(Debug, Clone, PartialEq)]
pub struct Placement {
    /// The standing area: a convex polygon on the floor, counter-clockwise \[m\]. Every sole
    /// corner stays inside it.
    pub area_m: Vec<Vector2<f64>>,
    area_edges_m: Vec<(Vector2<f64>, f64)>,
    /// Lateral distance between the sole centres across the feet's mean heading \[m\].
    pub width_range_m: (f64, f64),
    /// Largest fore-aft offset between the sole centres along the mean heading \[m\].
    pub stagger_max_m: f64,
    /// The left foot's yaw minus the right's \[rad\] (toe-out positive).
    pub relative_yaw_range_rad: (f64, f64),
}

impl Placement {
    /// A placement in the convex hull of `area_m` (given in either orientation).
    pub fn new(
        area_m: &[Vector2<f64>],
        width_range_m: (f64, f64),
        stagger_max_m: f64,
        relative_yaw_range_rad: (f64, f64),
    ) -> Self {
        let area = convex_hull(area_m.to_vec());
        let area_edges_m = polygon_edges(&area);
        Placement {
            area_m: area,
            area_edges_m,
            width_range_m,
            stagger_max_m,
            relative_yaw_range_rad,
        }
    }

    /// The area's edges as (outward unit normal n, offset d): inside means `n·p ≤ d`.
    #[inline]
    pub fn area_edges(&self) -> impl Iterator<Item = (Vector2<f64>, f64)> + '_ {
        self.area_edges_m.iter().copied()
    }

    /// Largest violation of the placement by `feet` \[m\] (0 when every bound holds): a sole
    /// corner outside the area, the width, stagger or relative yaw (as the arc at the sole's
    /// half-length) outside their ranges.
    pub fn violation_m(&self, feet: &FeetNow, half_length_m: f64) -> f64 {
        let mut v = 0.0f64;
        for corners in &feet.corner_m {
            for c in corners {
                for (n, d) in self.area_edges() {
                    v = v.max(n.dot(c) - d);
                }
            }
        }
        let g = feet.geometry();
        v = v
            .max(self.width_range_m.0 - g.width_m)
            .max(g.width_m - self.width_range_m.1)
            .max(g.stagger_m.abs() - self.stagger_max_m)
            .max(half_length_m * (self.relative_yaw_range_rad.0 - g.relative_yaw_rad))
            .max(half_length_m * (g.relative_yaw_rad - self.relative_yaw_range_rad.1));
        v.max(0.0)
    }
}

/// The feet where a posture puts them (floor projections): sole centres, yaws, sole corners.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FeetNow {
    /// Sole centres (left, right), world \[m\].
    pub sole_center_m: [Vector2<f64>; 2],
    /// Yaw of each foot link's x axis about the vertical \[rad\].
    pub yaw_rad: [f64; 2],
    /// Each sole's corners, world \[m\], in the sole's axes' order (+x+y, +x−y, −x−y, −x+y).
    pub corner_m: [[Vector2<f64>; 4]; 2],
}

/// The corner offsets of a sole in its link's axes, as multiples of (half-length, half-width).
pub const SOLE_CORNERS: [(f64, f64); 4] = [(1.0, 1.0), (1.0, -1.0), (-1.0, -1.0), (-1.0, 1.0)];

/// Width, stagger and relative yaw of two feet, in the frame of their mean heading.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StanceGeometry {
    /// Mean heading of the feet \[rad\] (the right foot's yaw plus half the relative yaw).
    pub heading_rad: f64,
    /// Left sole centre minus right, across the heading (to the left positive) \[m\].
    pub width_m: f64,
    /// Left sole centre minus right, along the heading (left ahead positive) \[m\].
    pub stagger_m: f64,
    /// Left yaw minus right yaw, wrapped to (−π, π] \[rad\].
    pub relative_yaw_rad: f64,
}

impl FeetNow {
    /// The feet at the forward kinematics in `data`.
    pub fn at(model: &BodyModel, data: &StaticsData, feet: &[Foot; 2]) -> Self {
        let mut out = FeetNow {
            sole_center_m: [Vector2::zeros(); 2],
            yaw_rad: [0.0; 2],
            corner_m: [[Vector2::zeros(); 4]; 2],
        };
        for (i, f) in feet.iter().enumerate() {
            let (rot, pos) = data.link_pose(model, f.link);
            let c = pos + rot * f.sole_center_in_link_m;
            out.sole_center_m[i] = Vector2::new(c.x, c.y);
            out.yaw_rad[i] = rot[(1, 0)].atan2(rot[(0, 0)]);
            for (k, (sx, sy)) in SOLE_CORNERS.iter().enumerate() {
                let p = pos
                    + rot
                        * (f.sole_center_in_link_m
                            + Vector3::new(sx * f.half_length_m, sy * f.half_width_m, 0.0));
                out.corner_m[i][k] = Vector2::new(p.x, p.y);
            }
        }
        out
    }

    /// Width, stagger and relative yaw.
    pub fn geometry(&self) -> StanceGeometry {
        let rel = wrap_pi(self.yaw_rad[0] - self.yaw_rad[1]);
        let heading = self.yaw_rad[1] + rel / 2.0;
        let d = self.sole_center_m[0] - self.sole_center_m[1];
        let (s, c) = heading.sin_cos();
        StanceGeometry {
            heading_rad: wrap_pi(heading),
            width_m: -s * d.x + c * d.y,
            stagger_m: c * d.x + s * d.y,
            relative_yaw_rad: rel,
        }
    }

    /// The support polygon: the convex hull of both soles.
    pub fn support(&self) -> SupportHull {
        let mut pts = [(Vector2::zeros(), 0u8); 8];
        for i in 0..2 {
            for k in 0..4 {
                pts[4 * i + k] = (self.corner_m[i][k], (4 * i + k) as u8);
            }
        }
        SupportHull::of(&self.corner_m, &mut pts)
    }
}

/// An angle wrapped to (−π, π].
pub fn wrap_pi(a: f64) -> f64 {
    let t = std::f64::consts::TAU;
    let w = a - t * (a / t).round();
    if w <= -std::f64::consts::PI { w + t } else { w }
}

/// The convex hull of the two soles' eight corners, counter-clockwise, as corner indices
/// (`4 × foot + corner`) — so that its edges' motion can be followed to the feet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SupportHull {
    pub vertex: [u8; 8],
    pub len: usize,
    pub corner_m: [[Vector2<f64>; 4]; 2],
}

impl SupportHull {
    fn of(corner_m: &[[Vector2<f64>; 4]; 2], pts: &mut [(Vector2<f64>, u8); 8]) -> Self {
        pts.sort_by(|a, b| a.0.x.total_cmp(&b.0.x).then(a.0.y.total_cmp(&b.0.y)));
        let cross = |o: &Vector2<f64>, a: &Vector2<f64>, b: &Vector2<f64>| {
            (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x)
        };
        let mut hull = [0u8; 17];
        let mut pos = [Vector2::zeros(); 17];
        let mut n = 0usize;
        for &(p, id) in pts.iter() {
            while n >= 2 && cross(&pos[n - 2], &pos[n - 1], &p) <= 1e-15 {
                n -= 1;
            }
            pos[n] = p;
            hull[n] = id;
            n += 1;
        }
        let lower = n + 1;
        for &(p, id) in pts.iter().rev().skip(1) {
            while n >= lower && cross(&pos[n - 2], &pos[n - 1], &p) <= 1e-15 {
                n -= 1;
            }
            pos[n] = p;
            hull[n] = id;
            n += 1;
        }
        n -= 1; // the first point again
        let mut vertex = [0u8; 8];
        let len = n.min(8);
        vertex[..len].copy_from_slice(&hull[..len]);
        SupportHull {
            vertex,
            len,
            corner_m: *corner_m,
        }
    }

    /// World position of hull vertex `v` \[m\].
    #[inline]
    pub fn point(&self, v: usize) -> Vector2<f64> {
        let id = self.vertex[v] as usize;
        self.corner_m[id / 4][id % 4]
    }

    /// The edges as (start corner id, end corner id, outward unit normal n, offset d): inside
    /// means `n·p ≤ d`. Degenerate (zero-length) edges are skipped.
    pub fn edges(&self) -> impl Iterator<Item = (usize, usize, Vector2<f64>, f64)> + '_ {
        (0..self.len).filter_map(move |i| {
            let j = (i + 1) % self.len;
            let (a, b) = (self.point(i), self.point(j));
            let t = b - a;
            let l = t.norm();
            (l > 1e-12).then(|| {
                let t = t / l;
                let n = Vector2::new(t.y, -t.x);
                (
                    self.vertex[i] as usize,
                    self.vertex[j] as usize,
                    n,
                    n.dot(&a),
                )
            })
        })
    }

    /// Signed distance \[m\] of `p` from the hull's boundary: positive inside.
    pub fn margin_m(&self, p: &Vector2<f64>) -> f64 {
        self.edges()
            .map(|(_, _, n, d)| d - n.dot(p))
            .fold(f64::INFINITY, f64::min)
    }

    /// The hull's vertices, counter-clockwise \[m\].
    pub fn polygon_m(&self) -> Vec<Vector2<f64>> {
        (0..self.len).map(|v| self.point(v)).collect()
    }
}

/// Outward unit normals and offsets of a counter-clockwise convex polygon's edges.
pub(crate) fn polygon_edges(v: &[Vector2<f64>]) -> Vec<(Vector2<f64>, f64)> {
    (0..v.len())
        .map(|i| {
            let (a, b) = (v[i], v[(i + 1) % v.len()]);
            let t = (b - a).normalize();
            let n = Vector2::new(t.y, -t.x);
            (n, n.dot(&a))
        })
        .collect()
}

impl Stance {
    /// Feet flat on the floor, the left and right sole centres at `(forward_m, ±width_m/2, 0)`,
    /// each turned outward by `toe_out_rad`.
    pub fn new(feet: [Foot; 2], width_m: f64, forward_m: f64, toe_out_rad: f64) -> Self {
        let mut world_from_foot = [Isometry3::identity(); 2];
        let mut corners = Vec::with_capacity(8);
        for (i, f) in feet.iter().enumerate() {
            let side = if i == 0 { 1.0 } else { -1.0 };
            let rot = UnitQuaternion::from_euler_angles(0.0, 0.0, side * toe_out_rad);
            let sole_w = Vector3::new(forward_m, side * width_m / 2.0, 0.0);
            // link origin so that the sole centre lands on sole_w
            let origin = sole_w - rot * f.sole_center_in_link_m;
            world_from_foot[i] = Isometry3::from_parts(Translation3::from(origin), rot);
            for (dx, dy) in [(1.0, 1.0), (1.0, -1.0), (-1.0, -1.0), (-1.0, 1.0)] {
                let c = sole_w + rot * Vector3::new(dx * f.half_length_m, dy * f.half_width_m, 0.0);
                corners.push(Vector2::new(c.x, c.y));
            }
        }
        let v = convex_hull(corners);
        let edges_m = polygon_edges(&v);
        Stance {
            feet,
            world_from_foot,
            support_polygon_m: v,
            edges_m,
            placement: None,
            seat: None,
        }
    }

    /// The same stance sitting on `seat`: the support polygon becomes the convex hull of both
    /// soles and the seat's outline.
    pub fn with_seat(mut self, seat: Seat) -> Self {
        let mut pts = self.support_polygon_m.clone();
        pts.extend_from_slice(&seat.outline_m);
        self.support_polygon_m = convex_hull(pts);
        self.edges_m = polygon_edges(&self.support_polygon_m);
        self.seat = Some(seat);
        self
    }

    /// The same nominal stance with the feet placed by the planner within `placement`.
    pub fn with_placement(mut self, placement: Placement) -> Self {
        self.placement = Some(placement);
        self
    }

    /// Signed distance \[m\] of point `p` from the support polygon's boundary: positive inside.
    #[inline]
    pub fn margin_m(&self, p: &Vector2<f64>) -> f64 {
        self.edges()
            .map(|(n, d)| d - n.dot(p))
            .fold(f64::INFINITY, f64::min)
    }

    /// The polygon's edges as (outward unit normal n, offset d): inside means `n·p ≤ d`.
    #[inline]
    pub fn edges(&self) -> impl Iterator<Item = (Vector2<f64>, f64)> + '_ {
        self.edges_m.iter().copied()
    }
}

/// Counter-clockwise convex hull (Andrew's monotone chain).
fn convex_hull(mut pts: Vec<Vector2<f64>>) -> Vec<Vector2<f64>> {
    pts.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    pts.dedup_by(|a, b| (*a - *b).norm() < 1e-12);
    if pts.len() < 3 {
        return pts;
    }
    let cross = |o: &Vector2<f64>, a: &Vector2<f64>, b: &Vector2<f64>| {
        (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x)
    };
    let mut hull: Vec<Vector2<f64>> = Vec::with_capacity(2 * pts.len());
    for p in &pts {
        while hull.len() >= 2 && cross(&hull[hull.len() - 2], &hull[hull.len() - 1], p) <= 0.0 {
            hull.pop();
        }
        hull.push(*p);
    }
    let lower = hull.len() + 1;
    for p in pts.iter().rev().skip(1) {
        while hull.len() >= lower && cross(&hull[hull.len() - 2], &hull[hull.len() - 1], p) <= 0.0 {
            hull.pop();
        }
        hull.push(*p);
    }
    hull.pop();
    hull
}

/// The floor's reaction on both feet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GroundReaction {
    /// Force on each foot (left, right) \[N\], world axes.
    pub force_n: [Vector3<f64>; 2],
    /// Each foot's centre of pressure on the floor \[m\].
    pub cop_m: [Vector3<f64>; 2],
    /// Each foot's free moment about the vertical \[N·m\].
    pub free_moment_nm: [f64; 2],
    /// Centre of pressure of the whole reaction \[m\] (floor plane).
    pub cop_total_m: Vector2<f64>,
    /// Share of the vertical load on the left foot, 0..1.
    pub left_share: f64,
    /// Balance margin: distance of the centre of pressure inside the support polygon \[m\]
    /// (negative: outside).
    pub margin_m: f64,
    /// False when the loads lift the body (no upward reaction): no stance can hold it.
    pub supported: bool,
    /// Where the feet stand.
    pub feet: FeetNow,
    /// The support polygon of the feet where they stand.
    pub support: SupportHull,
    /// The seat's reaction on the pelvis (a seated worker).
    pub seat: Option<SeatReaction>,
}

/// The non-ground loads' resultant about the world origin: gravity on the whole body (after
/// [`super::statics::mass_moments`]) and the `hands`' loads (world points from `data`).
pub fn external_resultant(
    model: &BodyModel,
    data: &StaticsData,
    hands: &[PointLoad],
    gravity_m_s2: &Vector3<f64>,
) -> (Vector3<f64>, Vector3<f64>) {
    let m = model.mass_kg;
    let mut f = m * gravity_m_s2;
    let mut mo = (m * data.com_m).cross(gravity_m_s2);
    for h in hands {
        let p = data.link_point(model, h.link, &h.point_in_link_m);
        f += h.force_n;
        mo += p.cross(&h.force_n) + h.moment_nm;
    }
    (f, mo)
}

/// Splits the floor's reaction between the feet (see the module docs). Needs forward kinematics
/// and mass moments in `data`.
pub fn ground_reaction(
    model: &BodyModel,
    data: &StaticsData,
    stance: &Stance,
    hands: &[PointLoad],
    gravity_m_s2: &Vector3<f64>,
) -> GroundReaction {
    let (f_ext, m_ext) = external_resultant(model, data, hands, gravity_m_s2);
    let (fg, mg) = (-f_ext, -m_ext);
    let sole = |i: usize| {
        let f = &stance.feet[i];
        data.link_point(model, f.link, &f.sole_center_in_link_m)
    };
    let (cl, cr) = (sole(0), sole(1));
    let (cl2, cr2) = (Vector2::new(cl.x, cl.y), Vector2::new(cr.x, cr.y));
    let feet_now = FeetNow::at(model, data, &stance.feet);
    let support = feet_now.support();
    let supported = fg.z > 1e-9 * f_ext.norm().max(1.0);
    let p = if supported {
        Vector2::new(-mg.y / fg.z, mg.x / fg.z)
    } else {
        (cl2 + cr2) / 2.0
    };
    let t_z = mg.z - (p.x * fg.y - p.y * fg.x);
    if let Some(seat) = &stance.seat {
        let margin_m = stance.margin_m(&p);
        let s3 = data.link_point(model, seat.link, &seat.contact_in_link_m);
        // each support's point moved along the reaction's direction to the floor
        let floor = |x: &Vector3<f64>| {
            if supported {
                Vector2::new(x.x - fg.x * x.z / fg.z, x.y - fg.y * x.z / fg.z)
            } else {
                x.xy()
            }
        };
        let (w, q) = barycentric_clamped(&p, &[floor(&s3), floor(&cl), floor(&cr)]);
        let d = p - q;
        let d3 = Vector3::new(d.x, d.y, 0.0);
        return GroundReaction {
            force_n: [w[1] * fg, w[2] * fg],
            cop_m: [
                Vector3::new(cl.x + d.x, cl.y + d.y, 0.0),
                Vector3::new(cr.x + d.x, cr.y + d.y, 0.0),
            ],
            free_moment_nm: [w[1] * t_z, w[2] * t_z],
            cop_total_m: p,
            left_share: w[1],
            margin_m,
            supported,
            feet: feet_now,
            support,
            seat: Some(SeatReaction {
                force_n: w[0] * fg,
                cop_m: s3 + d3,
                free_moment_nm: w[0] * t_z,
                share: w[0],
            }),
        };
    }
    let lr = cl2 - cr2;
    let s = if lr.norm_squared() > 0.0 {
        ((p - cr2).dot(&lr) / lr.norm_squared()).clamp(0.0, 1.0)
    } else {
        0.5
    };
    let delta = p - (s * cl2 + (1.0 - s) * cr2);
    let shares = [s, 1.0 - s];
    let cop = [
        Vector3::new(cl.x + delta.x, cl.y + delta.y, 0.0),
        Vector3::new(cr.x + delta.x, cr.y + delta.y, 0.0),
    ];
    // the common point on the resultant's line of action, at the centre of mass's height
    let h = data.com_m.z.max(0.05);
    let apex = if supported {
        Vector3::new(p.x, p.y, 0.0) + fg * (h / fg.z)
    } else {
        Vector3::new(p.x, p.y, h)
    };
    let force = |i: usize| {
        if supported {
            shares[i] * fg.z * (apex - cop[i]) / h
        } else {
            shares[i] * fg
        }
    };
    GroundReaction {
        force_n: [force(0), force(1)],
        cop_m: cop,
        free_moment_nm: [shares[0] * t_z, shares[1] * t_z],
        cop_total_m: p,
        left_share: s,
        // fixed feet stand on the nominal polygon; placed ones where they are
        margin_m: if stance.placement.is_some() {
            support.margin_m(&p)
        } else {
            stance.margin_m(&p)
        },
        supported,
        feet: feet_now,
        support,
        seat: None,
    }
}

/// The weights (non-negative, summing to 1) of the point of triangle `v` nearest to `p`, and
/// that point: `p`'s barycentric coordinates when it lies inside.
fn barycentric_clamped(p: &Vector2<f64>, v: &[Vector2<f64>; 3]) -> ([f64; 3], Vector2<f64>) {
    let (e1, e2) = (v[1] - v[0], v[2] - v[0]);
    let det = e1.x * e2.y - e1.y * e2.x;
    let scale = e1.norm_squared().max(e2.norm_squared()).max(1e-300);
    if det.abs() > 1e-9 * scale {
        let r = p - v[0];
        let b1 = (r.x * e2.y - r.y * e2.x) / det;
        let b2 = (e1.x * r.y - e1.y * r.x) / det;
        let b0 = 1.0 - b1 - b2;
        if b0 >= 0.0 && b1 >= 0.0 && b2 >= 0.0 {
            return ([b0, b1, b2], *p);
        }
    }
    // outside (or a flat triangle): the nearest point of the three edges
    let mut best = (f64::INFINITY, [1.0, 0.0, 0.0], v[0]);
    for (i, j) in [(0usize, 1usize), (1, 2), (2, 0)] {
        let e = v[j] - v[i];
        let t = if e.norm_squared() > 0.0 {
            ((p - v[i]).dot(&e) / e.norm_squared()).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let q = v[i] + t * e;
        let dist = (p - q).norm_squared();
        if dist < best.0 {
            let mut w = [0.0; 3];
            w[i] = 1.0 - t;
            w[j] = t;
            best = (dist, w, q);
        }
    }
    (best.1, best.2)
}

/// The seat's reaction as a point load on the pelvis, for the statics (a seated worker).
pub fn seat_load(
    model: &BodyModel,
    data: &StaticsData,
    stance: &Stance,
    r: &GroundReaction,
) -> Option<PointLoad> {
    let (seat, reaction) = (stance.seat.as_ref()?, r.seat?);
    let (rot, pos) = data.link_pose(model, seat.link);
    Some(PointLoad {
        link: seat.link,
        point_in_link_m: rot.transpose() * (reaction.cop_m - pos),
        force_n: reaction.force_n,
        moment_nm: Vector3::new(0.0, 0.0, reaction.free_moment_nm),
    })
}

/// The two foot reactions as point loads on the foot links, for the statics.
pub fn foot_loads(
    model: &BodyModel,
    data: &StaticsData,
    stance: &Stance,
    r: &GroundReaction,
) -> [PointLoad; 2] {
    let load = |i: usize| {
        let link = stance.feet[i].link;
        let (rot, pos) = data.link_pose(model, link);
        PointLoad {
            link,
            point_in_link_m: rot.transpose() * (r.cop_m[i] - pos),
            force_n: r.force_n[i],
            moment_nm: Vector3::new(0.0, 0.0, r.free_moment_nm[i]),
        }
    };
    [load(0), load(1)]
}

/// The internal wrench settled between the feet (steps 4 and 5 of the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct InternalWrench {
    /// Force `+λe` on the left foot, `−λe` on the right \[N\].
    pub lambda_n: f64,
    /// Moment `+m` (world x, y) on the left foot, `−m` on the right \[N·m\].
    pub moment_nm: Vector2<f64>,
    /// The share of the least-effort moments the soles allow, 0..1 (1: unbounded optimum).
    pub sole_factor: f64,
}

/// Settles what statics leaves open between the feet (steps 4 and 5 of the module docs): after
/// [`super::statics::apply_loads`] with [`foot_loads`] of `r`, adds the internal force `λ e` and
/// the internal moment pair `±m` that minimise the sum of squared torques of the `actuated`
/// joints, with the moments bounded so that each foot's centre of pressure stays on its sole.
/// Updates the torques in `data` and the forces, centres of pressure and free moments in `r` (the
/// same wrench as force at the moved centre of pressure plus free moment). `g` is scratch
/// (3×nq).
pub fn settle_internal_force(
    model: &BodyModel,
    data: &mut StaticsData,
    stance: &Stance,
    r: &mut GroundReaction,
    actuated: &[bool],
    g: &mut nalgebra::Matrix3xX<f64>,
) -> InternalWrench {
    let sole = |data: &StaticsData, i: usize| {
        let f = &stance.feet[i];
        data.link_point(model, f.link, &f.sole_center_in_link_m)
    };
    let (c_l, c_r) = (sole(data, 0), sole(data, 1));
    let d = c_l - c_r;
    let d = Vector3::new(d.x, d.y, 0.0);
    if d.norm() < 1e-9 {
        return InternalWrench::default();
    }
    let e = d / d.norm();
    // columns of G: ∂τ/∂λ, ∂τ/∂m_x, ∂τ/∂m_y (left foot +, right foot −), nonzero only for the
    // joints that move a foot: a revolute joint's column is (e·(a × (p − o)), a_x, a_y), a
    // prismatic one's (e·a, 0, 0)
    let paths = stance
        .feet
        .map(|f| model.q_path_of_body(model.link_in_body[f.link].body));
    // ∂τ_k/∂(λ, m) of a unit internal wrench on foot i (left −, right + along e)
    let unit = |i: usize, k: usize| {
        let a = data.axis_w[k];
        if model.q_joint(k).kind == super::model::JointKind::Prismatic {
            Vector3::new(e.dot(&a), 0.0, 0.0)
        } else {
            Vector3::new(e.dot(&a.cross(&(r.cop_m[i] - data.origin_w[k]))), a.x, a.y)
        }
    };
    // Both paths start at the root, so they share a prefix and then part: G is zero outside
    // their union, and every sum below runs over the union only (columns elsewhere in `g` are
    // left as they were).
    let shared = paths[0]
        .iter()
        .zip(paths[1])
        .take_while(|(a, b)| a == b)
        .count();
    let carrying = || paths[0].iter().chain(&paths[1][shared..]).copied();
    let mut gtg = Matrix3::<f64>::zeros();
    let mut gtt = Vector3::<f64>::zeros();
    for (n, k) in carrying().enumerate() {
        let col = if n < shared {
            // a joint that moves both feet: the pair's moments cancel, the forces' levers differ
            // by the feet's separation
            let a = data.axis_w[k];
            if model.q_joint(k).kind == super::model::JointKind::Prismatic {
                Vector3::zeros()
            } else {
                Vector3::new(e.dot(&a.cross(&(r.cop_m[1] - r.cop_m[0]))), 0.0, 0.0)
            }
        } else if n < paths[0].len() {
            -unit(0, k)
        } else {
            unit(1, k)
        };
        g.fixed_view_mut::<3, 1>(0, k).copy_from(&col);
        if actuated[k] {
            gtg += col * col.transpose();
            gtt += col * data.tau_nm[k];
        }
    }
    let mut w = min_norm_solve(&gtg, &gtt);
    let m_opt = Vector2::new(w.y, w.z);
    let alpha = if m_opt == Vector2::zeros() {
        1.0
    } else if !r.supported {
        0.0
    } else {
        sole_factor(model, data, stance, r, [c_l, c_r], &m_opt)
    };
    if alpha < 1.0 {
        let m = alpha * m_opt;
        let (mut num, mut den) = (0.0, 0.0);
        for k in carrying().filter(|&k| actuated[k]) {
            let gl = g[(0, k)];
            num += gl * (data.tau_nm[k] + m.x * g[(1, k)] + m.y * g[(2, k)]);
            den += gl * gl;
        }
        let lambda = if den > 0.0 { -num / den } else { 0.0 };
        w = Vector3::new(lambda, m.x, m.y);
    }
    for k in carrying() {
        let dt = g.column(k).dot(&w);
        data.tau_nm[k] += dt;
        data.tau_load_nm[k] += dt;
    }
    r.force_n[0] += w.x * e;
    r.force_n[1] -= w.x * e;
    let m = Vector2::new(w.y, w.z);
    for (i, sigma) in [(0usize, 1.0), (1usize, -1.0)] {
        let fz = r.force_n[i].z;
        if m != Vector2::zeros() && fz > 0.0 {
            let shift = sigma * Vector3::new(-m.y, m.x, 0.0) / fz;
            r.free_moment_nm[i] -= shift.cross(&r.force_n[i]).z;
            r.cop_m[i] += shift;
        }
    }
    InternalWrench {
        lambda_n: w.x,
        moment_nm: m,
        sole_factor: alpha,
    }
}

/// The minimum-norm least-squares `w` with `A w = −b` for symmetric positive semi-definite
/// 3 × 3 `A`: eigen-directions with eigenvalues below 1e-12 × the largest count as zero. When
/// every eigenvalue clears that bound — certified by `λ_min ≥ 4 det / tr²` and `λ_max ≤ tr` —
/// the matrix is inverted directly (the same solution, without the eigen-decomposition).
fn min_norm_solve(a: &Matrix3<f64>, b: &Vector3<f64>) -> Vector3<f64> {
    let tr = a.trace();
    if tr <= 0.0 {
        return Vector3::zeros();
    }
    let det = a.determinant();
    if 4.0 * det > 1e-12 * tr * tr * tr
        && let Some(inv) = a.try_inverse()
    {
        return -(inv * b);
    }
    let eig = nalgebra::SymmetricEigen::new(*a);
    let top = eig.eigenvalues.iter().copied().fold(0.0, f64::max);
    let mut w = Vector3::zeros();
    if top > 0.0 {
        for j in 0..3 {
            let ev = eig.eigenvalues[j];
            if ev > 1e-12 * top {
                let v = eig.eigenvectors.column(j).into_owned();
                w -= v * (v.dot(b) / ev);
            }
        }
    }
    w
}

/// The largest `α` in 0..1 for which the moments `±α m` keep each foot's centre of pressure on
/// its sole (or no farther off it than it already is); 0 when a foot carries no weight.
fn sole_factor(
    model: &BodyModel,
    data: &StaticsData,
    stance: &Stance,
    r: &GroundReaction,
    centres: [Vector3<f64>; 2],
    m: &Vector2<f64>,
) -> f64 {
    let mut alpha: f64 = 1.0;
    for (i, sigma) in [(0usize, 1.0), (1usize, -1.0)] {
        let fz = r.force_n[i].z;
        if fz <= 0.0 {
            return 0.0;
        }
        let foot = &stance.feet[i];
        let shift = sigma * Vector2::new(-m.y, m.x) / fz;
        let offset = r.cop_m[i] - centres[i];
        let offset = Vector2::new(offset.x, offset.y);
        let (rot, _) = data.link_pose(model, foot.link);
        for (col, half) in [(0, foot.half_length_m), (1, foot.half_width_m)] {
            let axis = Vector2::new(rot[(0, col)], rot[(1, col)]);
            if axis.norm() < 1e-9 {
                continue;
            }
            let axis = axis / axis.norm();
            let (o, s) = (offset.dot(&axis), shift.dot(&axis));
            let bound = half.max(o.abs());
            if s > 0.0 {
                alpha = alpha.min((bound - o) / s);
            } else if s < 0.0 {
                alpha = alpha.min((bound + o) / -s);
            }
        }
    }
    alpha.clamp(0.0, 1.0)
}

/// d(centre of pressure)/dq (2×nq, into `out`) for fixed hand forces: from the centre of mass's
/// and the hands' Jacobians. Needs `data` after the statics; `jac` is scratch (3×nq).
pub fn cop_jacobian(
    model: &BodyModel,
    data: &StaticsData,
    hands: &[PointLoad],
    gravity_m_s2: &Vector3<f64>,
    jac: &mut nalgebra::Matrix3xX<f64>,
    out: &mut nalgebra::Matrix2xX<f64>,
) {
    let (f_ext, _) = external_resultant(model, data, hands, gravity_m_s2);
    let fz = -f_ext.z;
    let m = model.mass_kg;
    let nq = model.nq();
    // dM_g/dq_k = −(M J_com,k × g + Σ_h J_h,k × F_h)
    let mut dmg = nalgebra::Matrix3xX::<f64>::zeros(nq);
    for k in 0..nq {
        let c = data.com_jacobian.column(k).into_owned();
        let col = -(m * c).cross(gravity_m_s2);
        dmg.fixed_view_mut::<3, 1>(0, k).copy_from(&col);
    }
    for h in hands {
        let p = data.link_point(model, h.link, &h.point_in_link_m);
        data.point_jacobian(model, h.link, &p, jac);
        for k in 0..nq {
            let c = jac.column(k).into_owned();
            let col = dmg.column(k).into_owned() - c.cross(&h.force_n);
            dmg.fixed_view_mut::<3, 1>(0, k).copy_from(&col);
        }
    }
    for k in 0..nq {
        out[(0, k)] = -dmg[(1, k)] / fz;
        out[(1, k)] = dmg[(0, k)] / fz;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The direct solve and the eigen fallback agree with the SVD pseudo-inverse on full-rank,
    /// rank-2, rank-1 and badly conditioned matrices.
    #[test]
    fn min_norm_solve_is_the_pseudo_inverse_solution() {
        let mut seed = 7_u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for case in 0..400 {
            let rank = 1 + case % 3;
            let scale = [1.0, 1e-3, 1e4][case % 3];
            let mut a = Matrix3::zeros();
            for r in 0..rank {
                let v = Vector3::new(next(), next(), next());
                a += v * v.transpose() * scale * if r == 2 && case % 7 == 0 { 1e-9 } else { 1.0 };
            }
            let b = Vector3::new(next(), next(), next()) * scale;
            let w = min_norm_solve(&a, &b);
            let svd = a.svd(true, true);
            let (top, low) = (svd.singular_values.max(), svd.singular_values.min());
            let want = -(svd.pseudo_inverse(1e-12 * top).unwrap() * b);
            // backward stable: the same fit A w = −(b's part in A's range), to rounding of the
            // size ‖A‖‖w‖ ε
            let fit_tol = 1e-12 * a.norm() * (w.norm() + want.norm());
            assert!(
                (a * (w - want)).norm() <= fit_tol,
                "case {case}: {w} against {want}"
            );
            if low > 1e-6 * top {
                // well conditioned: the same solution, to rounding times the condition number
                let tol = 1e-12 * (top / low) * want.norm();
                assert!((w - want).norm() <= tol, "case {case}: {w} against {want}");
            }
        }
        assert_eq!(
            min_norm_solve(&Matrix3::zeros(), &Vector3::x()),
            Vector3::zeros()
        );
    }

    #[test]
    fn hull_of_two_feet_and_margins() {
        let foot = Foot {
            link: 0,
            sole_center_in_link_m: Vector3::new(0.05, 0.0, -0.07),
            half_length_m: 0.13,
            half_width_m: 0.05,
        };
        let s = Stance::new([foot, foot], 0.3, 0.0, 0.0);
        // a rectangle from x −0.13..0.13, y −0.2..0.2
        assert_eq!(s.support_polygon_m.len(), 4);
        assert!((s.margin_m(&Vector2::new(0.0, 0.0)) - 0.13).abs() < 1e-12);
        assert!((s.margin_m(&Vector2::new(0.0, 0.19)) - 0.01).abs() < 1e-12);
        assert!((s.margin_m(&Vector2::new(0.2, 0.0)) + 0.07).abs() < 1e-12);
        // the left foot's link sits so that its sole centre is at (0, 0.15, 0)
        let p = s.world_from_foot[0] * Point3::from(foot.sole_center_in_link_m);
        assert!((p.coords - Vector3::new(0.0, 0.15, 0.0)).norm() < 1e-12);
    }
}
