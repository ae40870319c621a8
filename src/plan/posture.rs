//! A posture of the task's body, evaluated: holding torques (standing on both feet where the
//! body has a floating pelvis), the half-joints' relative loads, the hands' and feet's errors,
//! the centre of pressure and the clearances to obstacles and to the body itself — and their
//! first derivatives for the optimiser.

use super::stepping::yaw_rate;
use super::task::{GAZE_CONE_HALF_ANGLE_DEG, Head, Task};
use crate::body::stance::{
    GroundReaction, SOLE_CORNERS, cop_jacobian, foot_loads, ground_reaction, seat_load,
    settle_internal_force,
};
use crate::body::statics::{
    apply_loads, forward_kinematics, holding_torque_derivative, mass_moments,
};
use crate::body::{JointKind, PointLoad, StaticsData};
use crate::workstation::{Clearance, Workstation};
use nalgebra::{DMatrix, Isometry3, Matrix2xX, Matrix3, Matrix3xX, Vector2, Vector3};

/// A body capsule: link, segment end points in the link frame, radius.
#[derive(Debug, Clone, Copy)]
pub struct BodyCapsule {
    pub link: usize,
    pub a: Vector3<f64>,
    pub b: Vector3<f64>,
    pub radius_m: f64,
}

/// A body box (e.g. a foot).
#[derive(Debug, Clone, Copy)]
pub struct BodyBox {
    pub link: usize,
    pub link_from_box: Isometry3<f64>,
    pub half_extents_m: Vector3<f64>,
}

/// A clearance of the body, with what it is between.
#[derive(Debug, Clone, Copy)]
pub struct Contact {
    /// Signed distance \[m\] (negative: penetration).
    pub distance_m: f64,
    /// Link and world witness point on the body, and the unit normal from it toward the other side.
    pub link: usize,
    pub point_m: Vector3<f64>,
    pub normal: Vector3<f64>,
    /// The other side: an obstacle, or a body link (self-collision) with its witness point.
    pub other: Other,
}

/// What a body part is close to.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Other {
    Obstacle(usize),
    Body {
        link: usize,
        point_m: Vector3<f64>,
    },
    /// A held object of the phase (the body other than the arms keeps clear of it).
    HeldObject,
}

impl Other {
    /// Which other side this is, whatever the witness point (kind, index).
    pub fn id(&self) -> (u8, usize) {
        match *self {
            Other::Obstacle(i) => (0, i),
            Other::Body { link, .. } => (1, link),
            Other::HeldObject => (2, 0),
        }
    }
}

/// The task's body and scene as the optimiser sees them (fixed for a task).
#[derive(Debug, Clone)]
pub struct Scene {
    pub capsules: Vec<BodyCapsule>,
    pub boxes: Vec<BodyBox>,
    /// Pairs of capsule indices checked for self-collision.
    pub self_pairs: Vec<(usize, usize)>,
    /// Links that stand on the floor (exempt from the floor obstacle).
    pub feet_links: Vec<usize>,
    /// Actuated joints' q indices (the torque rows of the QP), in order.
    pub actuated: Vec<usize>,
    /// Row of each q index among the actuated joints.
    pub actuated_row: Vec<Option<usize>>,
    /// Links of the arms (they hold the object, so they may touch it: [`super::held`]).
    pub arm_link: Vec<bool>,
}

/// Closest points of segments p1–q1 and p2–q2 (Ericson, Real-Time Collision Detection, 5.1.9).
fn segment_closest(
    p1: &Vector3<f64>,
    q1: &Vector3<f64>,
    p2: &Vector3<f64>,
    q2: &Vector3<f64>,
) -> (Vector3<f64>, Vector3<f64>) {
    let d1 = q1 - p1;
    let d2 = q2 - p2;
    let r = p1 - p2;
    let (a, e, f) = (d1.dot(&d1), d2.dot(&d2), d2.dot(&r));
    let eps = 1e-14;
    let (s, t) = if a <= eps && e <= eps {
        (0.0, 0.0)
    } else if a <= eps {
        (0.0, (f / e).clamp(0.0, 1.0))
    } else {
        let c = d1.dot(&r);
        if e <= eps {
            ((-c / a).clamp(0.0, 1.0), 0.0)
        } else {
            let b = d1.dot(&d2);
            let denom = a * e - b * b;
            let mut s = if denom > eps {
                ((b * f - c * e) / denom).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let mut t = (b * s + f) / e;
            if t < 0.0 {
                t = 0.0;
                s = (-c / a).clamp(0.0, 1.0);
            } else if t > 1.0 {
                t = 1.0;
                s = ((b - c) / a).clamp(0.0, 1.0);
            }
            (s, t)
        }
    };
    (p1 + d1 * s, p2 + d2 * t)
}

impl Scene {
    /// The scene of a task: every capsule and box of the body, the self-collision pairs (capsules
    /// on links that are not parent and child of each other and do not overlap by more than
    /// [`SELF_OVERLAP_M`] at the zero posture — pairs that do are joined by design), the feet.
    pub fn new(task: &Task) -> Self {
        let m = &task.model;
        let mut capsules = Vec::new();
        let mut boxes = Vec::new();
        for (l, link) in m.links.iter().enumerate() {
            for c in &link.capsules {
                capsules.push(BodyCapsule {
                    link: l,
                    a: c.a.coords,
                    b: c.b.coords,
                    radius_m: c.radius_m,
                });
            }
            for b in &link.boxes {
                boxes.push(BodyBox {
                    link: l,
                    link_from_box: b.link_from_box,
                    half_extents_m: b.half_extents_m,
                });
            }
        }
        let feet_links = task
            .stance
            .as_ref()
            .map(|s| s.feet.iter().map(|f| f.link).collect())
            .unwrap_or_default();
        // Self-collision pairs: apart at q = 0, on different rigid bodies that are not
        // parent and child.
        let mut data = StaticsData::new(m, 0);
        forward_kinematics(m, &mut data, &vec![0.0; m.nq()]);
        let world = |c: &BodyCapsule| {
            (
                data.link_point(m, c.link, &c.a),
                data.link_point(m, c.link, &c.b),
            )
        };
        let parent_body = |b: usize| {
            if b == 0 {
                None
            } else {
                Some(m.q_parent_body[b - 1])
            }
        };
        let mut self_pairs = Vec::new();
        let mut body_has_capsule = vec![false; m.bodies.len()];
        for c in &capsules {
            body_has_capsule[m.link_in_body[c.link].body] = true;
        }
        for i in 0..capsules.len() {
            for j in i + 1..capsules.len() {
                let (bi, bj) = (
                    m.link_in_body[capsules[i].link].body,
                    m.link_in_body[capsules[j].link].body,
                );
                if bi == bj {
                    continue;
                }
                // walk up massless/capsule-less bodies to the nearest one with a capsule
                let mut adjacent = false;
                for (x, y) in [(bi, bj), (bj, bi)] {
                    let mut p = parent_body(x);
                    while let Some(pb) = p {
                        if pb == y {
                            adjacent = true;
                            break;
                        }
                        if body_has_capsule[pb] {
                            break;
                        }
                        p = parent_body(pb);
                    }
                }
                if adjacent {
                    continue;
                }
                let (a1, b1) = world(&capsules[i]);
                let (a2, b2) = world(&capsules[j]);
                let (p1, p2) = segment_closest(&a1, &b1, &a2, &b2);
                let d = (p1 - p2).norm() - capsules[i].radius_m - capsules[j].radius_m;
                if d > -SELF_OVERLAP_M {
                    self_pairs.push((i, j));
                }
            }
        }
        let mut actuated_row = vec![None; m.nq()];
        let mut actuated = Vec::new();
        for q in 0..m.nq() {
            if !task.unactuated.contains(&q) {
                actuated_row[q] = Some(actuated.len());
                actuated.push(q);
            }
        }
        let arms = super::held::arm_bodies(task);
        let arm_link = (0..m.links.len())
            .map(|l| arms.contains(&m.link_in_body[l].body))
            .collect();
        Scene {
            capsules,
            boxes,
            self_pairs,
            feet_links,
            actuated,
            actuated_row,
            arm_link,
        }
    }
}

/// Capsules overlapping more than this \[m\] at the zero posture are parts joined by design.
pub const SELF_OVERLAP_M: f64 = 0.02;

/// Reusable buffers for evaluating postures of one task.
#[derive(Debug, Clone)]
pub struct PostureWork {
    pub data: StaticsData,
    /// Hand loads (right, left) of the last evaluation.
    pub hands: [PointLoad; 2],
    n_hands: usize,
    pub ground: Option<GroundReaction>,
    loads: Vec<PointLoad>,
    pub jac: Matrix3xX<f64>,
    /// Scratch of the feet's internal wrench (3×nq).
    settle_g: Matrix3xX<f64>,
    pub jac2: Matrix3xX<f64>,
    /// Scratch of [`PostureWork::ground_rows`] (3×nq each, and nq).
    jac3: Matrix3xX<f64>,
    jac4: Matrix3xX<f64>,
    row: Vec<f64>,
    pub cop_jac: Matrix2xX<f64>,
    /// ∂τ/∂q of the last [`PostureWork::linearise`].
    pub dtau_dq: DMatrix<f64>,
    tau_plus: Vec<f64>,
    q_scratch: Vec<f64>,
    pub contacts: Vec<Contact>,
    scratch: Vec<Clearance>,
    /// Whether each joint has muscles.
    actuated: Vec<bool>,
}

/// What a row of [`PostureWork::geometry_rows`] keeps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Row {
    Gaze,
    Balance,
    Placement,
    Seat,
}

/// Most rows [`PostureWork::geometry_rows`] gives for `task`: the gaze row, the support hull's
/// edges (at most eight for the feet alone), the seat's edges for a seated body, and with placed
/// feet eight sole corners per edge of the standing area and six stance rows.
pub fn geometry_row_count(task: &Task) -> usize {
    let gaze = usize::from(task.head.is_some());
    gaze + match &task.stance {
        None => 0,
        Some(st) => {
            8.max(st.edges().count())
                + st.seat.as_ref().map_or(0, |s| s.edges().count())
                + st.placement
                    .as_ref()
                    .map_or(0, |p| 8 * p.area_edges().count() + 6)
        }
    }
}

/// Finite-difference step for ∂τ/∂q on standing bodies \[rad or m\].
const FD_STEP: f64 = 1e-6;

impl PostureWork {
    pub fn new(task: &Task) -> Self {
        let nq = task.model.nq();
        let zero = PointLoad::force_at(0, Vector3::zeros());
        PostureWork {
            data: StaticsData::new(&task.model, 5),
            hands: [zero; 2],
            n_hands: 0,
            ground: None,
            loads: Vec::with_capacity(5),
            jac: Matrix3xX::zeros(nq),
            settle_g: Matrix3xX::zeros(nq),
            jac2: Matrix3xX::zeros(nq),
            jac3: Matrix3xX::zeros(nq),
            jac4: Matrix3xX::zeros(nq),
            row: vec![0.0; nq],
            cop_jac: Matrix2xX::zeros(nq),
            dtau_dq: DMatrix::zeros(nq, nq),
            tau_plus: vec![0.0; nq],
            q_scratch: vec![0.0; nq],
            contacts: Vec::with_capacity(64),
            scratch: Vec::with_capacity(16),
            actuated: (0..nq).map(|k| !task.unactuated.contains(&k)).collect(),
        }
    }

    /// Statics of posture `q` with forces `hand_force_n` (right, left) on the hands: torques in
    /// `self.data`, the floor's reaction in `self.ground` for a standing body.
    pub fn statics(&mut self, task: &Task, q: &[f64], hand_force_n: &[Vector3<f64>; 2]) {
        let m = &task.model;
        forward_kinematics(m, &mut self.data, q);
        mass_moments(m, &mut self.data);
        self.n_hands = 0;
        for h in 0..2 {
            if let Some((link, _)) = &task.hand_links[h]
                && hand_force_n[h] != Vector3::zeros()
            {
                self.hands[self.n_hands] = PointLoad::force_at(*link, hand_force_n[h]);
                self.n_hands += 1;
            }
        }
        self.loads.clear();
        self.loads.extend_from_slice(&self.hands[..self.n_hands]);
        self.ground = None;
        let mut ground = None;
        if let Some(st) = &task.stance {
            let g = ground_reaction(
                m,
                &self.data,
                st,
                &self.hands[..self.n_hands],
                &task.gravity_m_s2,
            );
            let feet = foot_loads(m, &self.data, st, &g);
            self.loads.extend_from_slice(&feet);
            self.loads.extend(seat_load(m, &self.data, st, &g));
            ground = Some(g);
        }
        apply_loads(m, &mut self.data, &self.loads, &task.gravity_m_s2);
        if let (Some(st), Some(mut g)) = (&task.stance, ground) {
            settle_internal_force(
                m,
                &mut self.data,
                st,
                &mut g,
                &self.actuated,
                &mut self.settle_g,
            );
            ground = Some(g);
        }
        self.ground = ground;
    }

    /// Relative loads of every half-joint after [`PostureWork::statics`].
    pub fn half_joint_loads(&self, task: &Task, q: &[f64], f: &mut [f64]) {
        for (i, h) in task.half_joints.iter().enumerate() {
            f[i] = h.load(self.data.tau_nm[h.q_index], q);
        }
    }

    /// World position of hand `h`'s frame after the statics.
    pub fn hand_position(&self, task: &Task, h: usize) -> Option<Vector3<f64>> {
        task.hand_links[h]
            .as_ref()
            .map(|(l, _)| self.data.link_point(&task.model, *l, &Vector3::zeros()))
    }

    /// ∂τ/∂q at `q` into `self.dtau_dq`: analytic for a fixed base, central differences through
    /// the feet's load split for a standing body (step 1e-6; the split rule is only piecewise
    /// smooth). Leaves the statics of `q` in `self.data`.
    pub fn linearise(&mut self, task: &Task, q: &[f64], hand_force_n: &[Vector3<f64>; 2]) {
        let nq = task.model.nq();
        if task.stance.is_none() {
            self.statics(task, q, hand_force_n);
            holding_torque_derivative(&task.model, &mut self.data);
            self.dtau_dq.copy_from(&self.data.dtau_dq);
            return;
        }
        self.q_scratch.copy_from_slice(q);
        for k in 0..nq {
            let h = FD_STEP;
            self.q_scratch[k] = q[k] + h;
            let mut qs = std::mem::take(&mut self.q_scratch);
            self.statics(task, &qs, hand_force_n);
            for r in 0..nq {
                self.tau_plus[r] = self.data.tau_nm[r];
            }
            qs[k] = q[k] - h;
            self.statics(task, &qs, hand_force_n);
            for r in 0..nq {
                self.dtau_dq[(r, k)] = (self.tau_plus[r] - self.data.tau_nm[r]) / (2.0 * h);
            }
            qs[k] = q[k];
            self.q_scratch = qs;
        }
        self.statics(task, q, hand_force_n);
    }

    /// d(centre of pressure)/dq into `self.cop_jac` after the statics (standing bodies).
    pub fn centre_of_pressure_jacobian(&mut self, task: &Task) {
        cop_jacobian(
            &task.model,
            &self.data,
            &self.hands[..self.n_hands],
            &task.gravity_m_s2,
            &mut self.jac,
            &mut self.cop_jac,
        );
    }

    /// The gaze row's value `cos θ_max − s·d̂` after the forward kinematics, with the eye point,
    /// the line of sight `s` and the unit direction `d̂` to `target`.
    pub fn gaze(
        &self,
        task: &Task,
        head: &Head,
        target: &Vector3<f64>,
    ) -> (f64, Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        let (rot, _) = self.data.link_pose(&task.model, head.link);
        let eye = self
            .data
            .link_point(&task.model, head.link, &head.eye_in_link_m);
        let s = rot * head.sight_in_link;
        let d = (target - eye).normalize();
        let cos_max = GAZE_CONE_HALF_ANGLE_DEG.to_radians().cos();
        (cos_max - s.dot(&d), eye, s, d)
    }

    /// Position and orientation errors of foot `i` against its stance pose: (target − actual
    /// position, rotation vector taking the actual orientation to the target), world axes.
    ///
    /// When the planner places the feet, the target is the nominal pose moved over the floor to
    /// where the foot stands now (its position and yaw): only the height and the tilts are
    /// errors, and the other three components are zero.
    pub fn foot_error(&self, task: &Task, i: usize) -> (Vector3<f64>, Vector3<f64>) {
        let st = task.stance.as_ref().expect("a standing body");
        let (rot, pos) = self.data.link_pose(&task.model, st.feet[i].link);
        let nominal = &st.world_from_foot[i];
        let target_rot = nominal.rotation.to_rotation_matrix().into_inner();
        if st.placement.is_some() {
            let yaw = |r: &Matrix3<f64>| r[(1, 0)].atan2(r[(0, 0)]);
            let turn = nalgebra::Rotation3::from_axis_angle(
                &Vector3::z_axis(),
                yaw(&rot) - yaw(&target_rot),
            );
            let r_err = turn.matrix() * target_rot * rot.transpose();
            let dr = rotation_vector(&r_err);
            let dz = nominal.translation.vector.z - pos.z;
            return (Vector3::new(0.0, 0.0, dz), Vector3::new(dr.x, dr.y, 0.0));
        }
        let dp = nominal.translation.vector - pos;
        let r_err = target_rot * rot.transpose();
        (dp, rotation_vector(&r_err))
    }

    /// The geometric rows, each `g(q) ≤ 0` with its gradient in q, after the statics of `q`:
    ///
    /// * balance: the centre of pressure at least the task's margin inside every edge of the
    ///   support hull of the feet where they stand now; an edge moves with its two sole corners,
    ///   so with `r = a − p`, `t` the edge's unit direction, `L` its length and `n` its outward
    ///   normal, `∇(n·r) = u·(J_b − J_a) + n·(J_a − J_p)`, `u = (I − t tᵀ)(−r_y, r_x)/L`;
    /// * when the planner places the feet: every sole corner inside every edge of the standing
    ///   area, then the stance's width (both bounds), stagger (both signs) and relative yaw (both
    ///   bounds, as the arc at the soles' mean half-length, in metres like the other rows);
    /// * when the body sits: the pelvis point resting on the seat inside every edge of the seat's
    ///   outline;
    /// * when the body has a head and the phase a gaze point: the gaze point within the eyes'
    ///   cone, `cos θ_max − s·d̂ ≤ 0` (per metre), `s` the line of sight and `d̂` the unit
    ///   direction from the eyes to the point.
    ///
    /// The number of rows is at most [`geometry_row_count`].
    pub fn geometry_rows(
        &mut self,
        task: &Task,
        gaze_m: Option<&Vector3<f64>>,
        mut each: impl FnMut(Row, f64, &[f64]),
    ) {
        if let (Some(head), Some(target)) = (&task.head, gaze_m) {
            let (g, eye, s, d) = self.gaze(task, head, target);
            let m = &task.model;
            self.data.point_jacobian(m, head.link, &eye, &mut self.jac);
            self.data.angular_jacobian(m, head.link, &mut self.jac2);
            let dist = (target - eye).norm().max(1e-9);
            for k in 0..m.nq() {
                let w = Vector3::new(self.jac2[(0, k)], self.jac2[(1, k)], self.jac2[(2, k)]);
                let je = Vector3::new(self.jac[(0, k)], self.jac[(1, k)], self.jac[(2, k)]);
                // d(s·d̂) = (ω × s)·d̂ + s·(I − d̂d̂ᵀ)(−J_eye)/|d|
                let dd = -(je - d * d.dot(&je)) / dist;
                self.row[k] = -(w.cross(&s).dot(&d) + s.dot(&dd));
            }
            each(Row::Gaze, g, &self.row);
        }
        let (Some(st), Some(g)) = (&task.stance, self.ground) else {
            return;
        };
        let m = &task.model;
        let n = m.nq();
        self.centre_of_pressure_jacobian(task);
        let corner = |data: &StaticsData, id: usize| {
            let f = &st.feet[id / 4];
            let (sx, sy) = SOLE_CORNERS[id % 4];
            let off = Vector3::new(sx * f.half_length_m, sy * f.half_width_m, 0.0);
            data.link_point(m, f.link, &(f.sole_center_in_link_m + off))
        };
        let p = g.cop_total_m;
        let margin = task.objective.balance_margin_m;
        if let Some(seat) = &st.seat {
            let c = self.data.link_point(m, seat.link, &seat.contact_in_link_m);
            self.data.point_jacobian(m, seat.link, &c, &mut self.jac);
            for (nrm, d) in seat.edges() {
                for k in 0..n {
                    self.row[k] = nrm.x * self.jac[(0, k)] + nrm.y * self.jac[(1, k)];
                }
                each(Row::Seat, nrm.dot(&c.xy()) - d, &self.row);
            }
        }
        let Some(pl) = &st.placement else {
            // fixed feet: the nominal stance's polygon, which does not move
            for (nrm, d) in st.edges() {
                for k in 0..n {
                    self.row[k] = nrm.x * self.cop_jac[(0, k)] + nrm.y * self.cop_jac[(1, k)];
                }
                each(Row::Balance, margin - (d - nrm.dot(&p)), &self.row);
            }
            return;
        };
        for (ia, ib, nrm, _) in g.support.edges() {
            let (a3, b3) = (corner(&self.data, ia), corner(&self.data, ib));
            let (a, b) = (a3.xy(), b3.xy());
            let l = (b - a).norm();
            let t = (b - a) / l;
            let r = a - p;
            let rot = Vector2::new(-r.y, r.x);
            let u = (rot - t * t.dot(&rot)) / l;
            self.data
                .point_jacobian(m, st.feet[ia / 4].link, &a3, &mut self.jac);
            self.data
                .point_jacobian(m, st.feet[ib / 4].link, &b3, &mut self.jac2);
            for k in 0..n {
                let ja = Vector2::new(self.jac[(0, k)], self.jac[(1, k)]);
                let jb = Vector2::new(self.jac2[(0, k)], self.jac2[(1, k)]);
                let jp = Vector2::new(self.cop_jac[(0, k)], self.cop_jac[(1, k)]);
                self.row[k] = -(u.dot(&(jb - ja)) + nrm.dot(&(ja - jp)));
            }
            each(Row::Balance, margin - nrm.dot(&r), &self.row);
        }
        for id in 0..8 {
            let c3 = corner(&self.data, id);
            self.data
                .point_jacobian(m, st.feet[id / 4].link, &c3, &mut self.jac);
            for (nrm, d) in pl.area_edges() {
                for k in 0..n {
                    self.row[k] = nrm.x * self.jac[(0, k)] + nrm.y * self.jac[(1, k)];
                }
                each(Row::Placement, nrm.dot(&c3.xy()) - d, &self.row);
            }
        }
        let geo = g.feet.geometry();
        let centre = |data: &StaticsData, i: usize| {
            data.link_point(m, st.feet[i].link, &st.feet[i].sole_center_in_link_m)
        };
        let (cl, cr) = (centre(&self.data, 0), centre(&self.data, 1));
        self.data
            .point_jacobian(m, st.feet[0].link, &cl, &mut self.jac);
        self.data
            .point_jacobian(m, st.feet[1].link, &cr, &mut self.jac2);
        self.data
            .angular_jacobian(m, st.feet[0].link, &mut self.jac3);
        self.data
            .angular_jacobian(m, st.feet[1].link, &mut self.jac4);
        let x_axis =
            |data: &StaticsData, i: usize| data.link_pose(m, st.feet[i].link).0 * Vector3::x();
        let (xl, xr) = (x_axis(&self.data, 0), x_axis(&self.data, 1));
        let (sh, ch) = geo.heading_rad.sin_cos();
        let (x_h, y_h) = (Vector2::new(ch, sh), Vector2::new(-sh, ch));
        let arm = 0.5 * (st.feet[0].half_length_m + st.feet[1].half_length_m);
        // d(width), d(stagger), d(relative yaw) per coordinate, then the six rows
        for (which, (value, sign)) in [
            (0, (pl.width_range_m.0 - geo.width_m, -1.0)),
            (0, (geo.width_m - pl.width_range_m.1, 1.0)),
            (1, (geo.stagger_m - pl.stagger_max_m, 1.0)),
            (1, (-geo.stagger_m - pl.stagger_max_m, -1.0)),
            (
                2,
                (
                    arm * (pl.relative_yaw_range_rad.0 - geo.relative_yaw_rad),
                    -arm,
                ),
            ),
            (
                2,
                (
                    arm * (geo.relative_yaw_rad - pl.relative_yaw_range_rad.1),
                    arm,
                ),
            ),
        ] {
            for k in 0..n {
                let dd = Vector2::new(
                    self.jac[(0, k)] - self.jac2[(0, k)],
                    self.jac[(1, k)] - self.jac2[(1, k)],
                );
                let w = |j: &Matrix3xX<f64>| Vector3::new(j[(0, k)], j[(1, k)], j[(2, k)]);
                let (dl, dr) = (yaw_rate(&xl, &w(&self.jac3)), yaw_rate(&xr, &w(&self.jac4)));
                let dh = 0.5 * (dl + dr);
                let d = match which {
                    0 => dd.dot(&y_h) - geo.stagger_m * dh,
                    1 => dd.dot(&x_h) + geo.width_m * dh,
                    _ => dl - dr,
                };
                self.row[k] = sign * d;
            }
            each(Row::Placement, value, &self.row);
        }
    }

    /// Clearances of the body (capsules and boxes) from the obstacles, from the phase's held
    /// objects (`held`, the arms excepted) and from itself, below `within_m`, into
    /// `self.contacts`; returns the smallest.
    pub fn clearances(
        &mut self,
        task: &Task,
        scene: &Scene,
        within_m: f64,
        held: Option<&Workstation>,
    ) -> f64 {
        let m = &task.model;
        self.contacts.clear();
        let mut min_d = f64::INFINITY;
        for c in &scene.capsules {
            let a = self.data.link_point(m, c.link, &c.a);
            let b = self.data.link_point(m, c.link, &c.b);
            self.scratch.clear();
            task.workstation
                .clearances(&a, &b, c.radius_m, within_m, &mut self.scratch);
            let obstacles = self.scratch.len();
            if let Some(h) = held.filter(|_| !scene.arm_link[c.link]) {
                h.clearances(&a, &b, c.radius_m, within_m, &mut self.scratch);
            }
            for (i, cl) in self.scratch.iter().enumerate() {
                min_d = min_d.min(cl.distance_m);
                self.contacts.push(Contact {
                    distance_m: cl.distance_m,
                    link: c.link,
                    point_m: cl.point_m,
                    normal: cl.normal,
                    other: if i < obstacles {
                        Other::Obstacle(cl.obstacle)
                    } else {
                        Other::HeldObject
                    },
                });
            }
        }
        for bx in &scene.boxes {
            let (rot, pos) = self.data.link_pose(m, bx.link);
            let link_pose = Isometry3::from_parts(
                nalgebra::Translation3::from(pos),
                nalgebra::UnitQuaternion::from_matrix(&rot),
            );
            let world_from_box = link_pose * bx.link_from_box;
            let foot = scene.feet_links.contains(&bx.link);
            for (i, o) in task.workstation.obstacles.iter().enumerate() {
                if foot && o.is_floor() {
                    continue;
                }
                if let Some(cl) = o.box_clearance(i, &world_from_box, &bx.half_extents_m, within_m)
                {
                    min_d = min_d.min(cl.distance_m);
                    self.contacts.push(Contact {
                        distance_m: cl.distance_m,
                        link: bx.link,
                        point_m: cl.point_m,
                        normal: cl.normal,
                        other: Other::Obstacle(i),
                    });
                }
            }
        }
        for &(i, j) in &scene.self_pairs {
            let (ci, cj) = (&scene.capsules[i], &scene.capsules[j]);
            let (a1, b1) = (
                self.data.link_point(m, ci.link, &ci.a),
                self.data.link_point(m, ci.link, &ci.b),
            );
            let (a2, b2) = (
                self.data.link_point(m, cj.link, &cj.a),
                self.data.link_point(m, cj.link, &cj.b),
            );
            let (p1, p2) = segment_closest(&a1, &b1, &a2, &b2);
            let d_axes = (p2 - p1).norm();
            let d = d_axes - ci.radius_m - cj.radius_m;
            if d <= within_m {
                let n = if d_axes > 1e-12 {
                    (p2 - p1) / d_axes
                } else {
                    Vector3::z()
                };
                min_d = min_d.min(d);
                self.contacts.push(Contact {
                    distance_m: d,
                    link: ci.link,
                    point_m: p1 + n * ci.radius_m,
                    normal: n,
                    other: Other::Body {
                        link: cj.link,
                        point_m: p2 - n * cj.radius_m,
                    },
                });
            }
        }
        min_d
    }

    /// Gradient of a contact's distance with respect to q, into `out` (length nq).
    pub fn contact_gradient(&mut self, task: &Task, c: &Contact, out: &mut [f64]) {
        let m = &task.model;
        self.data
            .point_jacobian(m, c.link, &c.point_m, &mut self.jac);
        // d = n·(p_other − p_body) − …: moving the body point along n closes the gap.
        for (k, o) in out.iter_mut().enumerate() {
            *o = -c.normal.dot(&self.jac.column(k).into_owned());
        }
        if let Other::Body { link, point_m } = c.other {
            self.data.point_jacobian(m, link, &point_m, &mut self.jac2);
            for (k, o) in out.iter_mut().enumerate() {
                *o += c.normal.dot(&self.jac2.column(k).into_owned());
            }
        }
    }

    /// Positional Jacobian of hand `h`'s frame origin into `self.jac`.
    pub fn hand_jacobian(&mut self, task: &Task, h: usize) {
        if let Some((l, _)) = &task.hand_links[h] {
            let p = self.data.link_point(&task.model, *l, &Vector3::zeros());
            self.data.point_jacobian(&task.model, *l, &p, &mut self.jac);
        }
    }

    /// The seat's height minus that of the pelvis point resting on it (a seated body).
    pub fn seat_error(&self, task: &Task) -> Option<f64> {
        let seat = task.stance.as_ref()?.seat.as_ref()?;
        let c = self
            .data
            .link_point(&task.model, seat.link, &seat.contact_in_link_m);
        Some(seat.height_m - c.z)
    }

    /// The Jacobian of the pelvis point resting on the seat into `self.jac`; false when the body
    /// does not sit.
    pub fn seat_jacobian(&mut self, task: &Task) -> bool {
        let Some(seat) = task.stance.as_ref().and_then(|st| st.seat.as_ref()) else {
            return false;
        };
        let c = self
            .data
            .link_point(&task.model, seat.link, &seat.contact_in_link_m);
        self.data
            .point_jacobian(&task.model, seat.link, &c, &mut self.jac);
        true
    }

    /// Foot `i`'s positional (into `self.jac`) and angular (into `self.jac2`) Jacobians of its
    /// link frame.
    pub fn foot_jacobians(&mut self, task: &Task, i: usize) {
        let st = task.stance.as_ref().expect("a standing body");
        let l = st.feet[i].link;
        let (_, p) = self.data.link_pose(&task.model, l);
        self.data.point_jacobian(&task.model, l, &p, &mut self.jac);
        self.data.angular_jacobian(&task.model, l, &mut self.jac2);
        if st.placement.is_some() {
            // placed feet: only the height and the tilts are held (see `foot_error`)
            self.jac.row_mut(0).fill(0.0);
            self.jac.row_mut(1).fill(0.0);
            self.jac2.row_mut(2).fill(0.0);
        }
    }
}

/// The rotation vector (axis × angle) of a rotation matrix, robust to round-off (atan2 of the
/// skew part's norm and the trace, never acos of a value past 1).
pub fn rotation_vector(r: &Matrix3<f64>) -> Vector3<f64> {
    let v = 0.5
        * Vector3::new(
            r[(2, 1)] - r[(1, 2)],
            r[(0, 2)] - r[(2, 0)],
            r[(1, 0)] - r[(0, 1)],
        );
    let s = v.norm();
    let c = 0.5 * (r.trace() - 1.0);
    let theta = s.atan2(c);
    if s > 1e-12 { v * (theta / s) } else { v }
}

/// The trunk's orientation in the world at the last statics (for reports): the rotation of the
/// first link after the lumbar joints, if the body is the generated worker.
pub fn link_rotation(task: &Task, work: &PostureWork, link: &str) -> Option<Matrix3<f64>> {
    let l = task.model.frame_link(link).ok()?;
    Some(work.data.link_pose(&task.model, l).0)
}

/// Whether joint `k` is prismatic (its steps are in metres).
pub fn is_prismatic(task: &Task, k: usize) -> bool {
    task.model.q_joint(k).kind == JointKind::Prismatic
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closest_points_of_crossing_and_parallel_segments() {
        let (p, q) = segment_closest(
            &Vector3::new(-1.0, 0.0, 0.0),
            &Vector3::new(1.0, 0.0, 0.0),
            &Vector3::new(0.0, -1.0, 2.0),
            &Vector3::new(0.0, 1.0, 2.0),
        );
        assert!(
            (p - Vector3::zeros()).norm() < 1e-12
                && (q - Vector3::new(0.0, 0.0, 2.0)).norm() < 1e-12
        );
        let (p, q) = segment_closest(
            &Vector3::new(0.0, 0.0, 0.0),
            &Vector3::new(1.0, 0.0, 0.0),
            &Vector3::new(2.0, 1.0, 0.0),
            &Vector3::new(3.0, 1.0, 0.0),
        );
        assert!((p - Vector3::new(1.0, 0.0, 0.0)).norm() < 1e-12);
        assert!((q - Vector3::new(2.0, 1.0, 0.0)).norm() < 1e-12);
    }
}
