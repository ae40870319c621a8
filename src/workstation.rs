//! The workstation: obstacles (boxes, cylinders, planes) and their clearance to the body's
//! collision capsules. The only user of parry3d; poses cross from nalgebra to glam here.

use nalgebra::{UnitQuaternion, Vector3};
use parry3d_f64::math::{Pose, Vector};
use parry3d_f64::query::contact;
use parry3d_f64::shape::{Capsule as PCapsule, Cuboid, Cylinder, HalfSpace, Shape};
use serde::{Deserialize, Serialize};

/// An obstacle as written in a task file (metres, radians, world frame).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ObstacleSpec {
    pub name: String,
    #[serde(flatten)]
    pub shape: ShapeSpec,
    /// Centre (box, cylinder) or a point on the plane.
    #[serde(default)]
    pub position_m: [f64; 3],
    /// Roll, pitch, yaw (URDF convention).
    #[serde(default)]
    pub rpy_rad: [f64; 3],
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum ShapeSpec {
    /// Full edge lengths along the obstacle's x, y, z.
    Box { size_m: [f64; 3] },
    /// Axis along the obstacle's z.
    Cylinder { radius_m: f64, height_m: f64 },
    /// The solid half-space behind the plane: points p with (p − position)·normal ≤ 0.
    Plane { normal: [f64; 3] },
}

/// Largest obstacle dimension accepted \[m\].
pub const MAX_SIZE_M: f64 = 1000.0;
/// Largest obstacle coordinate accepted \[m\].
pub const MAX_COORDINATE_M: f64 = 1000.0;

/// Why an obstacle was refused.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("obstacle '{name}': {problem}")]
pub struct ObstacleError {
    pub name: String,
    pub problem: String,
}

/// A checked obstacle.
pub struct Obstacle {
    pub spec: ObstacleSpec,
    pose: Pose,
    shape: Box<dyn Shape>,
    /// For planes: (point on the plane, unit normal toward free space). Capsule–plane clearance
    /// is computed in closed form (parry 0.31's capsule–half-space contact misplaces a half-space
    /// whose pose is not at the origin; `tests/suite/workstation.rs` pins the expected values).
    plane: Option<(Vector3<f64>, Vector3<f64>)>,
}

impl Clone for Obstacle {
    fn clone(&self) -> Self {
        Obstacle {
            spec: self.spec.clone(),
            pose: self.pose,
            shape: self.shape.clone_dyn(),
            plane: self.plane,
        }
    }
}

impl std::fmt::Debug for Obstacle {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Obstacle")
            .field("spec", &self.spec)
            .finish()
    }
}

/// Clearance between a capsule and an obstacle: signed distance (negative = penetration), the
/// unit normal pointing from the capsule toward the obstacle, and the witness point on the
/// capsule surface, world frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Clearance {
    pub obstacle: usize,
    pub distance_m: f64,
    pub normal: Vector3<f64>,
    pub point_m: Vector3<f64>,
}

fn v(x: &Vector3<f64>) -> Vector {
    Vector::new(x.x, x.y, x.z)
}

fn nv(x: Vector) -> Vector3<f64> {
    Vector3::new(x.x, x.y, x.z)
}

impl Obstacle {
    /// The obstacle's frame in the world (position and roll-pitch-yaw of its spec).
    pub fn world_from_obstacle(&self) -> nalgebra::Isometry3<f64> {
        let [x, y, z] = self.spec.position_m;
        let [r, p, yaw] = self.spec.rpy_rad;
        nalgebra::Isometry3::from_parts(
            nalgebra::Translation3::new(x, y, z),
            UnitQuaternion::from_euler_angles(r, p, yaw),
        )
    }

    /// Checks sizes and builds the parry shape.
    pub fn new(spec: ObstacleSpec) -> Result<Self, ObstacleError> {
        let bad = |problem: String| ObstacleError {
            name: spec.name.clone(),
            problem,
        };
        let finite = |a: &[f64]| a.iter().all(|x| x.is_finite());
        if !finite(&spec.position_m) || !finite(&spec.rpy_rad) {
            return Err(bad("position_m and rpy_rad must be finite".into()));
        }
        if spec.position_m.iter().any(|x| x.abs() > MAX_COORDINATE_M) {
            return Err(bad(format!(
                "position_m must be within ±{MAX_COORDINATE_M} m, got {:?}",
                spec.position_m
            )));
        }
        let q =
            UnitQuaternion::from_euler_angles(spec.rpy_rad[0], spec.rpy_rad[1], spec.rpy_rad[2]);
        let mut rot = parry3d_f64::glamx::DQuat::from_xyzw(q.i, q.j, q.k, q.w);
        let mut plane = None;
        let shape: Box<dyn Shape> = match &spec.shape {
            ShapeSpec::Box { size_m } => {
                if !size_m
                    .iter()
                    .all(|s| s.is_finite() && *s > 0.0 && *s <= MAX_SIZE_M)
                {
                    return Err(bad(format!(
                        "box size_m must be within 0..{MAX_SIZE_M} m, got {size_m:?}"
                    )));
                }
                Box::new(Cuboid::new(Vector::new(
                    size_m[0] / 2.0,
                    size_m[1] / 2.0,
                    size_m[2] / 2.0,
                )))
            }
            ShapeSpec::Cylinder { radius_m, height_m } => {
                if !(radius_m.is_finite()
                    && *radius_m > 0.0
                    && *radius_m <= MAX_SIZE_M
                    && height_m.is_finite()
                    && *height_m > 0.0
                    && *height_m <= MAX_SIZE_M)
                {
                    return Err(bad(format!(
                        "cylinder radius_m and height_m must be within 0..{MAX_SIZE_M} m, got {radius_m}, {height_m}"
                    )));
                }
                // parry's cylinder runs along its y axis; ours along z: turn +90° about x.
                rot *= parry3d_f64::glamx::DQuat::from_rotation_x(std::f64::consts::FRAC_PI_2);
                Box::new(Cylinder::new(height_m / 2.0, *radius_m))
            }
            ShapeSpec::Plane { normal } => {
                let n = Vector3::from(*normal);
                if !finite(normal) || n.norm() < 1e-9 {
                    return Err(bad(format!(
                        "plane normal must be finite and non-zero, got {normal:?}"
                    )));
                }
                let n = q * n.normalize();
                rot = parry3d_f64::glamx::DQuat::IDENTITY;
                plane = Some((Vector3::from(spec.position_m), n));
                Box::new(HalfSpace::new(v(&n)))
            }
        };
        let p = spec.position_m;
        let pose = Pose::from_parts(Vector::new(p[0], p[1], p[2]), rot);
        Ok(Obstacle {
            spec,
            pose,
            shape,
            plane,
        })
    }

    /// Signed clearance of the capsule `a`–`b` (world, radius `radius_m`) from this obstacle, if
    /// below `within_m`.
    pub fn clearance(
        &self,
        index: usize,
        a: &Vector3<f64>,
        b: &Vector3<f64>,
        radius_m: f64,
        within_m: f64,
    ) -> Option<Clearance> {
        if let Some((p0, n)) = &self.plane {
            let (da, db) = (n.dot(&(a - p0)), n.dot(&(b - p0)));
            let (d, end) = if da <= db { (da, a) } else { (db, b) };
            let distance_m = d - radius_m;
            return (distance_m <= within_m).then(|| Clearance {
                obstacle: index,
                distance_m,
                normal: -n,
                point_m: end - n * radius_m,
            });
        }
        let cap = PCapsule::new(v(a), v(b), radius_m);
        let c = contact(
            &Pose::identity(),
            &cap,
            &self.pose,
            self.shape.as_ref(),
            within_m,
        )
        .ok()
        .flatten()?;
        if c.dist <= 1e-9
            && let ShapeSpec::Cylinder {
                radius_m: rc,
                height_m,
            } = self.spec.shape
        {
            // parry reports a capsule whose axis lies inside a cylinder as touching (depth 0):
            // the depth is the deepest axis point's distance to the cylinder's surface (a
            // concave function along the segment: ternary search), plus the radius.
            return Some(self.capsule_in_cylinder(index, a, b, radius_m, rc, height_m, c));
        }
        Some(Clearance {
            obstacle: index,
            distance_m: c.dist,
            normal: nv(c.normal1),
            point_m: nv(c.point1),
        })
    }

    /// Clearance of a capsule that penetrates the cylinder (radius `rc`, height `h`).
    #[allow(clippy::too_many_arguments)]
    fn capsule_in_cylinder(
        &self,
        index: usize,
        a: &Vector3<f64>,
        b: &Vector3<f64>,
        radius_m: f64,
        rc: f64,
        h: f64,
        touching: parry3d_f64::query::Contact,
    ) -> Clearance {
        let world_from_cyl = self.world_from_obstacle();
        // depth of a world point inside the cylinder (negative outside) and the outward normal
        // of the nearest face
        let depth = |p: &Vector3<f64>| -> (f64, Vector3<f64>) {
            let l = world_from_cyl
                .inverse_transform_point(&nalgebra::Point3::from(*p))
                .coords;
            let r = (l.x * l.x + l.y * l.y).sqrt();
            let side = rc - r;
            let cap = 0.5 * h - l.z.abs();
            let local_n = if side < cap {
                if r > 1e-12 {
                    Vector3::new(l.x / r, l.y / r, 0.0)
                } else {
                    Vector3::x()
                }
            } else {
                Vector3::new(0.0, 0.0, l.z.signum())
            };
            (side.min(cap), world_from_cyl.rotation * local_n)
        };
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        for _ in 0..60 {
            let m1 = lo + (hi - lo) / 3.0;
            let m2 = hi - (hi - lo) / 3.0;
            if depth(&(a + (b - a) * m1)).0 < depth(&(a + (b - a) * m2)).0 {
                lo = m1;
            } else {
                hi = m2;
            }
        }
        let p = a + (b - a) * (0.5 * (lo + hi));
        let (d, outward) = depth(&p);
        if d <= 0.0 {
            // the axis stays outside: parry's touching contact stands
            return Clearance {
                obstacle: index,
                distance_m: touching.dist,
                normal: nv(touching.normal1),
                point_m: nv(touching.point1),
            };
        }
        Clearance {
            obstacle: index,
            distance_m: -d - radius_m,
            normal: -outward,
            point_m: p - outward * radius_m,
        }
    }
}

impl Obstacle {
    /// Signed clearance of a box (world pose, half extents) from this obstacle, if below
    /// `within_m`; the witness point is on the box.
    pub fn box_clearance(
        &self,
        index: usize,
        world_from_box: &nalgebra::Isometry3<f64>,
        half_extents_m: &Vector3<f64>,
        within_m: f64,
    ) -> Option<Clearance> {
        if let Some((p0, n)) = &self.plane {
            // The corner deepest toward the plane: centre offset minus the half extents
            // projected on the normal.
            let r = world_from_box.rotation;
            let centre = world_from_box.translation.vector;
            let mut corner = centre;
            for i in 0..3 {
                let axis = r * Vector3::ith(i, 1.0);
                corner -= axis * (axis.dot(n).signum() * half_extents_m[i]);
            }
            let distance_m = n.dot(&(corner - p0));
            return (distance_m <= within_m).then(|| Clearance {
                obstacle: index,
                distance_m,
                normal: -n,
                point_m: corner,
            });
        }
        let t = world_from_box.translation.vector;
        let q = world_from_box.rotation;
        let pose = Pose::from_parts(
            Vector::new(t.x, t.y, t.z),
            parry3d_f64::glamx::DQuat::from_xyzw(q.i, q.j, q.k, q.w),
        );
        let cube = Cuboid::new(v(half_extents_m));
        let c = contact(&pose, &cube, &self.pose, self.shape.as_ref(), within_m)
            .ok()
            .flatten()?;
        Some(Clearance {
            obstacle: index,
            distance_m: c.dist,
            normal: nv(c.normal1),
            point_m: nv(c.point1),
        })
    }

    /// Whether world point `p` lies inside the obstacle.
    pub fn contains(&self, p: &Vector3<f64>) -> bool {
        if let Some((p0, n)) = &self.plane {
            return n.dot(&(p - p0)) < 0.0;
        }
        self.shape.contains_point(&self.pose, v(p))
    }

    /// A plane with an upward normal at or below z = 0: the floor the feet stand on.
    pub fn is_floor(&self) -> bool {
        matches!(self.plane, Some((p0, n)) if n.z > 0.999 && p0.z <= 1e-3)
    }
}

/// All obstacles of a task.
#[derive(Debug, Default, Clone)]
pub struct Workstation {
    pub obstacles: Vec<Obstacle>,
}

impl Workstation {
    pub fn new(specs: Vec<ObstacleSpec>) -> Result<Self, ObstacleError> {
        Ok(Workstation {
            obstacles: specs
                .into_iter()
                .map(Obstacle::new)
                .collect::<Result<_, _>>()?,
        })
    }

    /// Clearances of one capsule from every obstacle closer than `within_m`, appended to `out`.
    pub fn clearances(
        &self,
        a: &Vector3<f64>,
        b: &Vector3<f64>,
        radius_m: f64,
        within_m: f64,
        out: &mut Vec<Clearance>,
    ) {
        for (i, o) in self.obstacles.iter().enumerate() {
            if let Some(c) = o.clearance(i, a, b, radius_m, within_m) {
                out.push(c);
            }
        }
    }
}
