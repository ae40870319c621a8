//! The immutable body model: a kinematic tree loaded from URDF.
//!
//! Only what statics needs is kept: joint origins, axes, types and limits; link masses and
//! centres of mass; collision capsules (from `<capsule>` or `<cylinder>` collision geometry). Links without `<inertial>` are massless; inertia tensors
//! are ignored (they do not enter statics). Joints are stored in topological order (a joint's
//! parent link is reached by joints that come before it), so one forward pass is forward
//! kinematics and one backward pass accumulates subtree masses.

use nalgebra::{Isometry3, Matrix3, Point3, Translation3, UnitQuaternion, Vector3};
use std::path::Path;

/// Why a URDF could not become a body model. Every message names the element.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BodyError {
    #[error("{path}: cannot read: {message}")]
    Io { path: String, message: String },
    #[error("{path}: not a valid URDF: {message}")]
    Urdf { path: String, message: String },
    #[error("{path}: {element}: {problem}")]
    Invalid {
        path: String,
        element: String,
        problem: String,
    },
    #[error("unknown frame '{0}': not a link or joint of the model")]
    UnknownFrame(String),
    #[error("unknown joint '{0}': not a moving joint of the model")]
    UnknownJoint(String),
}

/// Joint kinds supported for statics.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum JointKind {
    Revolute,
    Continuous,
    Prismatic,
    Fixed,
}

/// A collision capsule in a link's frame: segment from `a` to `b`, radius `radius_m`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Capsule {
    pub a: Point3<f64>,
    pub b: Point3<f64>,
    pub radius_m: f64,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Link {
    pub name: String,
    pub mass_kg: f64,
    /// Centre of mass in the link frame.
    pub com_m: Point3<f64>,
    /// The joint whose child this link is (None for the root).
    pub parent_joint: Option<usize>,
    pub capsules: Vec<Capsule>,
    /// Collision boxes (e.g. feet: the sole is a box's bottom face).
    pub boxes: Vec<LinkBox>,
}

/// A collision box in a link's frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinkBox {
    pub link_from_box: Isometry3<f64>,
    pub half_extents_m: Vector3<f64>,
}

/// Largest collision shape dimension accepted \[m\] (a body segment, not a building).
pub const MAX_SHAPE_SIZE_M: f64 = 10.0;
/// Largest joint offset, centre-of-mass offset or prismatic limit accepted \[m\].
pub const MAX_OFFSET_M: f64 = 100.0;
/// Largest link mass accepted \[kg\].
pub const MAX_LINK_MASS_KG: f64 = 10_000.0;
/// Most moving joints a body may have (statics, evaluate; `plan` takes fewer:
/// `plan::task::MAX_PLAN_MOVING_JOINTS`).
pub const MAX_MOVING_JOINTS: usize = 512;
/// Most joints of any kind (fixed ones included) and most links a body may have.
pub const MAX_JOINTS: usize = 4096;

#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    pub name: String,
    pub kind: JointKind,
    pub parent_link: usize,
    pub child_link: usize,
    /// Pose of the joint frame in the parent link frame (URDF `<origin>`).
    pub parent_from_joint: Isometry3<f64>,
    /// The same rotation as a matrix (precomputed for the hot loop), and whether it is identity.
    pub parent_rot_joint: Matrix3<f64>,
    pub origin_rotates: bool,
    /// Unit axis in the joint frame.
    pub axis: Vector3<f64>,
    /// `Some((k, sign))` when the axis is `sign · e_k` (a coordinate axis): a faster rotation.
    pub axis_coordinate: Option<(usize, f64)>,
    /// Index into q for moving joints.
    pub q_index: Option<usize>,
    pub lower_rad: f64,
    pub upper_rad: f64,
    /// URDF `<limit effort>` [N·m or N]; 0 when absent.
    pub effort: f64,
}

/// The immutable body model.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyModel {
    pub name: String,
    pub links: Vec<Link>,
    /// Topological order.
    pub joints: Vec<Joint>,
    /// For each q index, the joint index.
    pub joint_of_q: Vec<usize>,
    /// Joints are in depth-first preorder, so joint i's subtree is the joints `i..subtree_end[i]`:
    /// joint i is joint j or an ancestor of it iff `i <= j < subtree_end[i]` (memory linear in
    /// the joints, not quadratic).
    subtree_end: Vec<usize>,
    /// `q_ancestor[a * nq + b]`: the joint of q index a is that of q index b or an ancestor.
    q_ancestor: Vec<bool>,
    /// Rigid bodies: fixed joints folded into their parents (as Pinocchio does). Body 0 is the
    /// root; body `k + 1` is moved by the joint of q index `k`.
    pub bodies: Vec<RigidBody>,
    /// For each link: its body and its pose in that body's frame.
    pub link_in_body: Vec<LinkInBody>,
    /// Per q index: the body the joint hangs from and the joint frame's pose in that body.
    pub q_parent_body: Vec<usize>,
    pub q_body_rot_joint: Vec<Matrix3<f64>>,
    pub q_body_pos_joint: Vec<Vector3<f64>>,
    /// Per q index: whether the joint frame's rotation in its parent body is exactly the identity
    /// (the generated worker's always is), so forward kinematics can skip the product.
    pub q_body_rot_is_identity: Vec<bool>,
    /// Per q index: whether the joint frame sits at its parent body's origin.
    pub q_body_pos_is_zero: Vec<bool>,
    /// The q indices that move each rigid body, root first: body b's are
    /// `body_q_path[body_q_path_start[b]..body_q_path_start[b + 1]]`.
    body_q_path: Vec<usize>,
    body_q_path_start: Vec<usize>,
    /// Mass below each moving joint \[kg\] (posture-independent), per q index.
    pub q_subtree_mass_kg: Vec<f64>,
    /// Total mass \[kg\].
    pub mass_kg: f64,
}

/// A rigid body: links joined by fixed joints.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidBody {
    pub mass_kg: f64,
    /// Centre of mass in the body frame (zero when massless).
    pub com_m: Vector3<f64>,
}

/// Where a link sits: its rigid body and its pose in the body frame.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkInBody {
    pub body: usize,
    pub rot: Matrix3<f64>,
    pub pos: Vector3<f64>,
}

fn vec3(v: &[f64; 3]) -> Vector3<f64> {
    Vector3::new(v[0], v[1], v[2])
}

fn pose(p: &urdf_rs::Pose) -> Isometry3<f64> {
    let rot = UnitQuaternion::from_euler_angles(p.rpy[0], p.rpy[1], p.rpy[2]);
    Isometry3::from_parts(Translation3::from(vec3(&p.xyz)), rot)
}

/// Deepest element nesting accepted in a URDF (a URDF needs about 5: robot, link, collision,
/// geometry, shape); the XML reader recurses per level, so far deeper nesting overflowed its
/// stack.
pub const MAX_URDF_NESTING: usize = 100;

/// Refuses XML elements nested deeper than [`MAX_URDF_NESTING`], naming the line, before the
/// recursive XML reader sees them. A light scan: comments, processing instructions, declarations
/// (a DOCTYPE's internal subset too), CDATA and quoted attribute values are skipped.
fn check_nesting(text: &str, origin: &str) -> Result<(), BodyError> {
    let b = text.as_bytes();
    let (mut i, mut depth, mut line) = (0usize, 0usize, 1usize);
    let skip_to = |from: usize, end: &[u8]| {
        b[from..]
            .windows(end.len())
            .position(|w| w == end)
            .map_or(b.len(), |p| from + p + end.len())
    };
    let lines_in = |from: usize, to: usize| b[from..to].iter().filter(|&&c| c == b'\n').count();
    while i < b.len() {
        if b[i] == b'\n' {
            line += 1;
        }
        if b[i] != b'<' {
            i += 1;
            continue;
        }
        let rest = &b[i..];
        let end = if rest.starts_with(b"<!--") {
            skip_to(i + 4, b"-->")
        } else if rest.starts_with(b"<![CDATA[") {
            skip_to(i + 9, b"]]>")
        } else if rest.starts_with(b"<?") {
            skip_to(i + 2, b"?>")
        } else if rest.starts_with(b"<!") {
            // a declaration; a DOCTYPE's internal subset ends with "]>"
            let gt = skip_to(i + 2, b">");
            if b[i..gt.min(b.len())].contains(&b'[') {
                skip_to(i + 2, b"]>")
            } else {
                gt
            }
        } else {
            // a start or end tag: to its '>' outside quotes
            let mut k = i + 1;
            let mut quote = None;
            while k < b.len() {
                match (quote, b[k]) {
                    (None, b'"' | b'\'') => quote = Some(b[k]),
                    (Some(q), c) if c == q => quote = None,
                    (None, b'>') => break,
                    _ => {}
                }
                k += 1;
            }
            if b.get(i + 1) == Some(&b'/') {
                depth = depth.saturating_sub(1);
            } else if k < b.len() && b[k - 1] != b'/' {
                depth += 1;
                if depth > MAX_URDF_NESTING {
                    return Err(BodyError::Invalid {
                        path: origin.into(),
                        element: format!("line {line}"),
                        problem: format!(
                            "elements nested more than {MAX_URDF_NESTING} deep (a URDF needs about 5)"
                        ),
                    });
                }
            }
            (k + 1).min(b.len())
        };
        line += lines_in(i, end.min(b.len()));
        i = end;
    }
    Ok(())
}

/// What a load does with mesh collision shapes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Meshes {
    /// Refused (planning checks collisions with primitive shapes only).
    Refuse,
    /// Left out (statics never uses collision geometry).
    Ignore,
}

impl BodyModel {
    /// Loads a URDF file.
    pub fn from_urdf_file(path: impl AsRef<Path>) -> Result<Self, BodyError> {
        Self::from_urdf_file_with(path, Meshes::Refuse)
    }

    /// Loads a URDF file for statics alone (no collision checks): mesh collision shapes, which
    /// only collision checking would use, are left out instead of refused (a standard robot's
    /// URDF, such as a UR5's, has them).
    pub fn from_urdf_file_for_statics(path: impl AsRef<Path>) -> Result<Self, BodyError> {
        Self::from_urdf_file_with(path, Meshes::Ignore)
    }

    fn from_urdf_file_with(path: impl AsRef<Path>, meshes: Meshes) -> Result<Self, BodyError> {
        let path = path.as_ref();
        let p = path.display().to_string();
        let text = crate::io::read_text(path).map_err(|e| BodyError::Io {
            path: p.clone(),
            message: e.to_string(),
        })?;
        Self::from_urdf_str_with(&text, &p, meshes)
    }

    /// Loads URDF text; `origin` names the source in error messages.
    pub fn from_urdf_str(text: &str, origin: &str) -> Result<Self, BodyError> {
        Self::from_urdf_str_with(text, origin, Meshes::Refuse)
    }

    fn from_urdf_str_with(text: &str, origin: &str, meshes: Meshes) -> Result<Self, BodyError> {
        check_nesting(text, origin)?;
        let robot = urdf_rs::read_from_string(text).map_err(|e| BodyError::Urdf {
            path: origin.into(),
            message: e.to_string(),
        })?;
        Self::from_robot_with(&robot, origin, meshes)
    }

    /// Builds the model from a parsed URDF.
    pub fn from_robot(robot: &urdf_rs::Robot, origin: &str) -> Result<Self, BodyError> {
        Self::from_robot_with(robot, origin, Meshes::Refuse)
    }

    fn from_robot_with(
        robot: &urdf_rs::Robot,
        origin: &str,
        meshes: Meshes,
    ) -> Result<Self, BodyError> {
        let invalid = |element: String, problem: String| BodyError::Invalid {
            path: origin.into(),
            element,
            problem,
        };
        let finite3 = |v: &[f64; 3]| v.iter().all(|x| x.is_finite());
        if robot.links.is_empty() {
            return Err(invalid("robot".into(), "has no <link>".into()));
        }
        if robot.links.len() > MAX_JOINTS + 1 || robot.joints.len() > MAX_JOINTS {
            return Err(invalid(
                "robot".into(),
                format!(
                    "has {} links and {} joints; at most {MAX_JOINTS} joints (fixed ones included) are read",
                    robot.links.len(),
                    robot.joints.len()
                ),
            ));
        }
        let mut link_index = std::collections::HashMap::new();
        let mut links = Vec::with_capacity(robot.links.len());
        for l in &robot.links {
            if link_index.insert(l.name.clone(), links.len()).is_some() {
                return Err(invalid(
                    format!("link '{}'", l.name),
                    "is defined twice".into(),
                ));
            }
            let m = l.inertial.mass.value;
            if !m.is_finite() || !(0.0..=MAX_LINK_MASS_KG).contains(&m) {
                return Err(invalid(
                    format!("link '{}' <inertial><mass>", l.name),
                    format!("mass must be within 0..{MAX_LINK_MASS_KG} kg, got {m}"),
                ));
            }
            let (xyz, rpy) = (&l.inertial.origin.xyz, &l.inertial.origin.rpy);
            if !finite3(xyz) || !finite3(rpy) || xyz.iter().any(|x| x.abs() > MAX_OFFSET_M) {
                return Err(invalid(
                    format!("link '{}' <inertial><origin>", l.name),
                    format!(
                        "must be finite and within {MAX_OFFSET_M} m, got {:?}",
                        xyz.0
                    ),
                ));
            }
            let mut capsules = Vec::new();
            let mut boxes = Vec::new();
            for (ci, c) in l.collision.iter().enumerate() {
                let el = || format!("link '{}' <collision>[{ci}]", l.name);
                if !finite3(&c.origin.xyz) || !finite3(&c.origin.rpy) {
                    return Err(invalid(el(), "<origin> has a non-finite value".into()));
                }
                let iso = pose(&c.origin);
                let size_ok = |x: f64| x.is_finite() && x > 0.0 && x <= MAX_SHAPE_SIZE_M;
                match c.geometry {
                    // Capsules, and cylinders read as capsules (standard URDF has no capsule; a
                    // cylinder's capsule has the same axis segment and radius, so it is slightly
                    // longer: conservative for clearance). Spheres are capsules of zero length.
                    urdf_rs::Geometry::Capsule { radius, length }
                    | urdf_rs::Geometry::Cylinder { radius, length } => {
                        if !(size_ok(radius)
                            && length.is_finite()
                            && (0.0..=MAX_SHAPE_SIZE_M).contains(&length))
                        {
                            return Err(invalid(
                                el(),
                                format!(
                                    "capsule/cylinder radius must be in (0, {MAX_SHAPE_SIZE_M}] m and length in [0, {MAX_SHAPE_SIZE_M}] m, got {radius}, {length}"
                                ),
                            ));
                        }
                        // URDF capsules (like cylinders) lie along the z axis of their origin frame.
                        capsules.push(Capsule {
                            a: iso * Point3::new(0.0, 0.0, -length / 2.0),
                            b: iso * Point3::new(0.0, 0.0, length / 2.0),
                            radius_m: radius,
                        });
                    }
                    urdf_rs::Geometry::Sphere { radius } => {
                        if !size_ok(radius) {
                            return Err(invalid(
                                el(),
                                format!(
                                    "sphere radius must be in (0, {MAX_SHAPE_SIZE_M}] m, got {radius}"
                                ),
                            ));
                        }
                        let p = iso * Point3::origin();
                        capsules.push(Capsule {
                            a: p,
                            b: p,
                            radius_m: radius,
                        });
                    }
                    urdf_rs::Geometry::Box { ref size } => {
                        if !size.iter().all(|&x| size_ok(x)) {
                            return Err(invalid(
                                el(),
                                format!(
                                    "box size must be in (0, {MAX_SHAPE_SIZE_M}] m, got {:?}",
                                    size.0
                                ),
                            ));
                        }
                        boxes.push(LinkBox {
                            link_from_box: iso,
                            half_extents_m: Vector3::new(
                                size[0] / 2.0,
                                size[1] / 2.0,
                                size[2] / 2.0,
                            ),
                        });
                    }
                    urdf_rs::Geometry::Mesh { .. } if meshes == Meshes::Ignore => {}
                    urdf_rs::Geometry::Mesh { ref filename, .. } => {
                        return Err(invalid(
                            el(),
                            format!(
                                "mesh collision geometry ('{filename}') is not supported for planning (collision checks use box, cylinder, capsule or sphere shapes; `posture-opt statics` accepts meshes and ignores them)"
                            ),
                        ));
                    }
                }
            }
            links.push(Link {
                name: l.name.clone(),
                mass_kg: m,
                com_m: Point3::from(vec3(xyz)),
                parent_joint: None,
                capsules,
                boxes,
            });
        }

        // Parent/child relations, checked.
        let mut joint_names = std::collections::HashSet::new();
        let mut child_of: Vec<Option<usize>> = vec![None; links.len()];
        for (ji, j) in robot.joints.iter().enumerate() {
            let el = || format!("joint '{}'", j.name);
            if !joint_names.insert(j.name.clone()) {
                return Err(invalid(el(), "is defined twice".into()));
            }
            let kind = match j.joint_type {
                urdf_rs::JointType::Revolute => JointKind::Revolute,
                urdf_rs::JointType::Continuous => JointKind::Continuous,
                urdf_rs::JointType::Prismatic => JointKind::Prismatic,
                urdf_rs::JointType::Fixed => JointKind::Fixed,
                ref other => {
                    return Err(invalid(
                        el(),
                        format!(
                            "unsupported type '{}' (revolute, continuous, prismatic or fixed)",
                            format!("{other:?}").to_lowercase()
                        ),
                    ));
                }
            };
            let parent = *link_index.get(&j.parent.link).ok_or_else(|| {
                invalid(
                    el(),
                    format!("parent link '{}' does not exist", j.parent.link),
                )
            })?;
            let child = *link_index.get(&j.child.link).ok_or_else(|| {
                invalid(
                    el(),
                    format!("child link '{}' does not exist", j.child.link),
                )
            })?;
            if parent == child {
                return Err(invalid(
                    el(),
                    "is its own parent (parent link = child link)".into(),
                ));
            }
            if let Some(other) = child_of[child] {
                return Err(invalid(
                    el(),
                    format!(
                        "link '{}' already has parent joint '{}'",
                        j.child.link, robot.joints[other].name
                    ),
                ));
            }
            child_of[child] = Some(ji);
            if !finite3(&j.origin.xyz)
                || !finite3(&j.origin.rpy)
                || j.origin.xyz.iter().any(|x| x.abs() > MAX_OFFSET_M)
            {
                return Err(invalid(
                    format!("joint '{}' <origin>", j.name),
                    format!(
                        "must be finite and within {MAX_OFFSET_M} m, got {:?}",
                        j.origin.xyz.0
                    ),
                ));
            }
            if kind != JointKind::Fixed {
                let a = vec3(&j.axis.xyz);
                if !finite3(&j.axis.xyz) || a.norm() < 1e-12 {
                    return Err(invalid(
                        format!("joint '{}' <axis>", j.name),
                        format!("axis must be finite and non-zero, got {:?}", j.axis.xyz.0),
                    ));
                }
            }
            let _ = kind;
        }
        let roots: Vec<usize> = (0..links.len())
            .filter(|&l| child_of[l].is_none())
            .collect();
        if roots.is_empty() {
            return Err(invalid(
                "robot".into(),
                "has no root link: the joints form a cycle".into(),
            ));
        }
        if roots.len() > 1 {
            let names: Vec<&str> = roots.iter().map(|&l| links[l].name.as_str()).collect();
            return Err(invalid(
                "robot".into(),
                format!(
                    "must have one root link, found {}: {} (a joint is missing, or the joints form a cycle)",
                    names.len(),
                    names.join(", ")
                ),
            ));
        }

        // Topological order: depth-first preorder from the root, so that along a chain each
        // joint's parent is the previous joint's child (kept in registers by forward kinematics).
        let mut children: Vec<Vec<usize>> = vec![Vec::new(); links.len()];
        for (ji, j) in robot.joints.iter().enumerate() {
            children[link_index[&j.parent.link]].push(ji);
        }
        let mut order = Vec::with_capacity(robot.joints.len());
        let mut stack: Vec<usize> = children[roots[0]].iter().rev().copied().collect();
        while let Some(ji) = stack.pop() {
            order.push(ji);
            let child = link_index[&robot.joints[ji].child.link];
            stack.extend(children[child].iter().rev().copied());
        }
        if order.len() != robot.joints.len() {
            let reached: std::collections::HashSet<usize> = order.iter().copied().collect();
            let stray = (0..robot.joints.len())
                .find(|j| !reached.contains(j))
                .unwrap_or(0);
            return Err(invalid(
                format!("joint '{}'", robot.joints[stray].name),
                "is part of a cycle not connected to the root".into(),
            ));
        }

        let mut joints = Vec::with_capacity(order.len());
        let mut joint_of_q = Vec::new();
        for &ji in &order {
            let j = &robot.joints[ji];
            let kind = match j.joint_type {
                urdf_rs::JointType::Revolute => JointKind::Revolute,
                urdf_rs::JointType::Continuous => JointKind::Continuous,
                urdf_rs::JointType::Prismatic => JointKind::Prismatic,
                _ => JointKind::Fixed,
            };
            let moving = kind != JointKind::Fixed;
            let axis = if moving {
                vec3(&j.axis.xyz).normalize()
            } else {
                Vector3::x()
            };
            let (lower, upper) = match kind {
                JointKind::Revolute | JointKind::Prismatic => (j.limit.lower, j.limit.upper),
                _ => (f64::NEG_INFINITY, f64::INFINITY),
            };
            if moving && (lower.is_nan() || upper.is_nan() || lower > upper) {
                return Err(invalid(
                    format!("joint '{}' <limit>", j.name),
                    format!("lower {lower} must not exceed upper {upper}"),
                ));
            }
            if kind == JointKind::Prismatic
                && !(lower.abs() <= MAX_OFFSET_M && upper.abs() <= MAX_OFFSET_M)
            {
                return Err(invalid(
                    format!("joint '{}' <limit>", j.name),
                    format!(
                        "a prismatic joint's limits must be within ±{MAX_OFFSET_M} m, got {lower}..{upper}"
                    ),
                ));
            }
            if moving && joint_of_q.len() >= MAX_MOVING_JOINTS {
                return Err(invalid(
                    "robot".into(),
                    format!("has more than {MAX_MOVING_JOINTS} moving joints"),
                ));
            }
            let q_index = moving.then(|| {
                joint_of_q.push(joints.len());
                joint_of_q.len() - 1
            });
            let child = link_index[&j.child.link];
            links[child].parent_joint = Some(joints.len());
            let parent_from_joint = pose(&j.origin);
            let parent_rot_joint = *parent_from_joint.rotation.to_rotation_matrix().matrix();
            joints.push(Joint {
                name: j.name.clone(),
                kind,
                parent_link: link_index[&j.parent.link],
                child_link: child,
                origin_rotates: parent_rot_joint != Matrix3::identity(),
                axis_coordinate: (0..3).find_map(|k| {
                    let mut e = Vector3::zeros();
                    e[k] = 1.0;
                    if axis == e {
                        Some((k, 1.0))
                    } else if axis == -e {
                        Some((k, -1.0))
                    } else {
                        None
                    }
                }),
                parent_rot_joint,
                parent_from_joint,
                axis,
                q_index,
                lower_rad: lower,
                upper_rad: upper,
                effort: if j.limit.effort.is_finite() {
                    j.limit.effort.max(0.0)
                } else {
                    0.0
                },
            });
        }

        let nj = joints.len();
        // preorder: a joint's subtree follows it; its end is the largest end among its children
        let mut subtree_end: Vec<usize> = (1..=nj).collect();
        for j in (0..nj).rev() {
            if let Some(p) = links[joints[j].parent_link].parent_joint {
                subtree_end[p] = subtree_end[p].max(subtree_end[j]);
            }
        }
        let nq = joint_of_q.len();
        let mut q_ancestor = vec![false; nq * nq];
        for a in 0..nq {
            let ja = joint_of_q[a];
            for b in 0..nq {
                let jb = joint_of_q[b];
                q_ancestor[a * nq + b] = ja <= jb && jb < subtree_end[ja];
            }
        }
        // Fold fixed joints: walk joints in topological order, placing each link in its body.
        let root = roots[0];
        let mut link_in_body = vec![
            LinkInBody {
                body: 0,
                rot: Matrix3::identity(),
                pos: Vector3::zeros()
            };
            links.len()
        ];
        let (mut q_parent_body, mut q_body_rot_joint, mut q_body_pos_joint) = (
            vec![0; nq],
            vec![Matrix3::identity(); nq],
            vec![Vector3::zeros(); nq],
        );
        for j in &joints {
            let parent = link_in_body[j.parent_link].clone();
            let rot = parent.rot * j.parent_rot_joint;
            let pos = parent.pos + parent.rot * j.parent_from_joint.translation.vector;
            link_in_body[j.child_link] = match j.q_index {
                None => LinkInBody {
                    body: parent.body,
                    rot,
                    pos,
                },
                Some(k) => {
                    q_parent_body[k] = parent.body;
                    q_body_rot_joint[k] = rot;
                    q_body_pos_joint[k] = pos;
                    LinkInBody {
                        body: k + 1,
                        rot: Matrix3::identity(),
                        pos: Vector3::zeros(),
                    }
                }
            };
        }
        debug_assert_eq!(link_in_body[root].body, 0);
        let mut bodies = vec![
            RigidBody {
                mass_kg: 0.0,
                com_m: Vector3::zeros()
            };
            nq + 1
        ];
        let mut moment = vec![Vector3::zeros(); nq + 1];
        for (l, link) in links.iter().enumerate() {
            let lb = &link_in_body[l];
            bodies[lb.body].mass_kg += link.mass_kg;
            moment[lb.body] += link.mass_kg * (lb.rot * link.com_m.coords + lb.pos);
        }
        for (b, body) in bodies.iter_mut().enumerate() {
            if body.mass_kg > 0.0 {
                body.com_m = moment[b] / body.mass_kg;
            }
        }
        let q_subtree_mass_kg = (0..nq)
            .map(|k| {
                (0..nq)
                    .filter(|&b| q_ancestor[k * nq + b])
                    .map(|b| bodies[b + 1].mass_kg)
                    .sum()
            })
            .collect();
        let mass_kg = links.iter().map(|l| l.mass_kg).sum();
        let q_body_rot_is_identity = q_body_rot_joint
            .iter()
            .map(|r| *r == Matrix3::identity())
            .collect();
        let q_body_pos_is_zero = q_body_pos_joint
            .iter()
            .map(|p| *p == Vector3::zeros())
            .collect();
        let (mut body_q_path, mut body_q_path_start) = (Vec::new(), vec![0]);
        for b in 0..=nq {
            let start = body_q_path.len();
            let mut body = b;
            while body > 0 {
                body_q_path.push(body - 1);
                body = q_parent_body[body - 1];
            }
            body_q_path[start..].reverse();
            body_q_path_start.push(body_q_path.len());
        }
        Ok(BodyModel {
            name: robot.name.clone(),
            links,
            joints,
            joint_of_q,
            subtree_end,
            q_ancestor,
            bodies,
            link_in_body,
            q_parent_body,
            q_body_rot_joint,
            q_body_pos_joint,
            q_body_rot_is_identity,
            q_body_pos_is_zero,
            body_q_path,
            body_q_path_start,
            q_subtree_mass_kg,
            mass_kg,
        })
    }

    /// Number of moving joints (the length of q).
    #[inline]
    pub fn nq(&self) -> usize {
        self.joint_of_q.len()
    }

    /// The moving joint at q index `i`.
    #[inline]
    pub fn q_joint(&self, i: usize) -> &Joint {
        &self.joints[self.joint_of_q[i]]
    }

    /// q index of a moving joint by name.
    pub fn q_index(&self, name: &str) -> Result<usize, BodyError> {
        self.joints
            .iter()
            .find(|j| j.name == name)
            .and_then(|j| j.q_index)
            .ok_or_else(|| BodyError::UnknownJoint(name.to_string()))
    }

    /// The link that carries a frame given by link name or joint name (a joint's frame is its
    /// child link's frame).
    pub fn frame_link(&self, name: &str) -> Result<usize, BodyError> {
        if let Some(l) = self.links.iter().position(|l| l.name == name) {
            return Ok(l);
        }
        self.joints
            .iter()
            .find(|j| j.name == name)
            .map(|j| j.child_link)
            .ok_or_else(|| BodyError::UnknownFrame(name.to_string()))
    }

    /// Whether joint `i` is joint `j` or one of its ancestors.
    #[inline]
    pub fn is_ancestor_or_self(&self, i: usize, j: usize) -> bool {
        i <= j && j < self.subtree_end[i]
    }

    /// Whether the joint of q index `a` is that of q index `b` or one of its ancestors.
    #[inline]
    pub fn q_is_ancestor_or_self(&self, a: usize, b: usize) -> bool {
        self.q_ancestor[a * self.joint_of_q.len() + b]
    }

    /// Whether the joint of q index `k` moves rigid body `b`.
    #[inline]
    pub fn q_moves_body(&self, k: usize, b: usize) -> bool {
        b > 0 && self.q_is_ancestor_or_self(k, b - 1)
    }

    /// The q indices of the joints that move rigid body `b`, in increasing order (root first):
    /// exactly the `k` with `q_moves_body(k, b)`.
    #[inline]
    pub fn q_path_of_body(&self, b: usize) -> &[usize] {
        &self.body_q_path[self.body_q_path_start[b]..self.body_q_path_start[b + 1]]
    }

    /// Whether joint `i` moves link `l` (lies on its path to the root).
    #[inline]
    pub fn moves_link(&self, i: usize, l: usize) -> bool {
        self.links[l]
            .parent_joint
            .is_some_and(|p| self.is_ancestor_or_self(i, p))
    }

    /// Total mass \[kg\].
    pub fn total_mass_kg(&self) -> f64 {
        self.mass_kg
    }
}
