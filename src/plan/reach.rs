//! When "out of reach" is proven: a hand can never be farther from the point its body stands on
//! (a foot's frame on its stance, or the last frame fixed in the world on the way from a fixed
//! base to the hand, e.g. the shoulder of a fixed arm) than the kinematic chain between them is
//! long. The chain is made of rigid pieces joined at the joints, so the distance between two
//! link frames is at most the sum of the joint offsets on the tree path between them (the
//! triangle inequality, at any posture), plus the largest travel of any prismatic joint on the
//! path. A target beyond that bound is out of reach whatever the optimiser does; a target within
//! it that the optimiser did not reach (with the feet in place and the balance kept) is only
//! "not reached": no search can prove that no balanced, collision-free posture reaches it.
//! Where the planner places the feet, the anchor is anywhere a foot's frame can stand: at its
//! height, within its sole's reach of the standing area.

use super::task::Task;
use crate::body::{BodyModel, JointKind, StaticsData, forward_kinematics};
use nalgebra::Vector3;

/// A target the hand provably cannot bring its grip point to, for an obstacle next to it.
#[derive(Debug, Clone, PartialEq)]
pub struct HandBlocked {
    pub obstacle: String,
    /// The target's distance from the obstacle \[m\].
    pub distance_m: f64,
    /// How far the hand's own collision shape reaches beyond its grip point all round \[m\].
    pub hand_m: f64,
    /// The clearance the task asks between the body and obstacles \[m\].
    pub clearance_m: f64,
}

impl HandBlocked {
    /// How much nearer the obstacle the target is than the grip point can come \[m\]: the
    /// distance to move the target away from it (or to take off the clearance).
    pub fn shortfall_m(&self) -> f64 {
        self.hand_m + self.clearance_m - self.distance_m
    }

    pub fn words(&self) -> String {
        // whole millimetres, at least 1, never below the shortfall (a micron of rounding aside)
        let move_mm = (1000.0 * self.shortfall_m() - 1e-6).ceil().max(1.0);
        format!(
            "it lies {:.0} mm too near '{}': {:.0} mm from it, where the hand's shape reaches {:.0} mm beyond its grip point all round and the task asks {:.0} mm of clearance (objective.clearance_m), so the grip point comes no nearer than {:.0} mm; move the target {:.0} mm away from '{}' (where the grip point would be), or lower the clearance",
            move_mm,
            self.obstacle,
            1000.0 * self.distance_m,
            1000.0 * self.hand_m,
            1000.0 * self.clearance_m,
            1000.0 * (self.hand_m + self.clearance_m),
            move_mm,
            self.obstacle,
        )
    }
}

/// When hand `h`'s target is provably too near an obstacle: a capsule of radius r on the grip's
/// rigid body whose axis passes d < r from the grip point holds the ball of radius r − d about
/// that point, at any posture; so if an obstacle is nearer the target than that margin plus the
/// task's clearance, no posture with the grip point on the target keeps the clearance.
pub fn hand_blocked(task: &Task, h: usize, target_m: &Vector3<f64>) -> Option<HandBlocked> {
    let m = &task.model;
    let grip = task.hand_links[h].as_ref()?.0;
    let mut data = StaticsData::new(m, 0);
    forward_kinematics(m, &mut data, &vec![0.0; m.nq()]);
    let o = Vector3::zeros();
    let g = data.link_point(m, grip, &o);
    let body = m.link_in_body[grip].body;
    let hand_m = m
        .links
        .iter()
        .enumerate()
        .filter(|(l, _)| m.link_in_body[*l].body == body)
        .flat_map(|(l, link)| link.capsules.iter().map(move |c| (l, c)))
        .map(|(l, c)| {
            let (a, b) = (
                data.link_point(m, l, &c.a.coords),
                data.link_point(m, l, &c.b.coords),
            );
            let ab = b - a;
            let t = if ab.norm_squared() > 0.0 {
                ((g - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            c.radius_m - (a + t * ab - g).norm()
        })
        .fold(0.0, f64::max);
    let mut near = Vec::new();
    task.workstation
        .clearances(target_m, target_m, 0.0, f64::INFINITY, &mut near);
    let closest = near
        .iter()
        .min_by(|a, b| a.distance_m.total_cmp(&b.distance_m))?;
    let clearance_m = task.objective.clearance_m;
    (closest.distance_m >= 0.0 && closest.distance_m < hand_m + clearance_m - 1e-9).then(|| {
        HandBlocked {
            obstacle: task.workstation.obstacles[closest.obstacle]
                .spec
                .name
                .clone(),
            distance_m: closest.distance_m,
            hand_m,
            clearance_m,
        }
    })
}

/// Upper bound on the distance between the frames of links `a` and `b` at any posture \[m\].
pub fn chain_length_m(m: &BodyModel, a: usize, b: usize) -> f64 {
    let ancestors = |mut l: usize| {
        let mut v = vec![l];
        while let Some(j) = m.links[l].parent_joint {
            l = m.joints[j].parent_link;
            v.push(l);
        }
        v
    };
    let (pa, pb) = (ancestors(a), ancestors(b));
    let Some(&common) = pa.iter().find(|l| pb.contains(l)) else {
        return f64::INFINITY;
    };
    let up_to_common = |path: &[usize]| -> f64 {
        path.iter()
            .take_while(|&&l| l != common)
            .filter_map(|&l| m.links[l].parent_joint)
            .map(|j| {
                let joint = &m.joints[j];
                let travel = if joint.kind == JointKind::Prismatic {
                    joint.lower_rad.abs().max(joint.upper_rad.abs())
                } else {
                    0.0
                };
                joint.parent_from_joint.translation.vector.norm() + travel
            })
            .sum()
    };
    up_to_common(&pa) + up_to_common(&pb)
}

/// How far \[m\] `target_m` lies beyond every posture's reach of hand `h` (the hand's link
/// frame), when it provably does: `Some(excess)` when it is farther from a foot's stance frame
/// (standing bodies: either foot) or from the fixed base than the chain between them is long.
pub fn beyond_reach_m(task: &Task, h: usize, target_m: &Vector3<f64>) -> Option<f64> {
    let m = &task.model;
    let hand = task.hand_links[h].as_ref()?.0;
    let anchors: Vec<(usize, Vector3<f64>)> = match &task.stance {
        Some(st) if st.placement.is_some() => {
            // placed feet: the foot's frame stands at its nominal height, its sole inside the
            // standing area, so its origin lies within the sole's reach r of the area
            let area = &st.placement.as_ref()?.area_m;
            let excess = (0..2)
                .map(|i| {
                    let f = &st.feet[i];
                    let r = crate::body::stance::SOLE_CORNERS
                        .iter()
                        .map(|(sx, sy)| {
                            (f.sole_center_in_link_m.xy()
                                + nalgebra::Vector2::new(sx * f.half_length_m, sy * f.half_width_m))
                            .norm()
                        })
                        .fold(0.0, f64::max);
                    let z0 = st.world_from_foot[i].translation.vector.z;
                    let flat = (distance_to_polygon(area, &target_m.xy()) - r).max(0.0);
                    (flat * flat + (target_m.z - z0).powi(2)).sqrt()
                        - chain_length_m(m, f.link, hand)
                })
                .fold(f64::NEG_INFINITY, f64::max);
            return (excess > 0.0).then_some(excess);
        }
        Some(st) => (0..2)
            .map(|i| (st.feet[i].link, st.world_from_foot[i].translation.vector))
            .collect(),
        None => {
            // The root's frame does not move with q, nor does the frame below it through fixed
            // joints, nor the child frame of the first revolute joint below those (it turns
            // about its own origin): the farthest such frame on the way to the hand anchors
            // the tightest chain.
            let mut path = vec![hand];
            while let Some(j) = m.links[*path.last()?].parent_joint {
                path.push(m.joints[j].parent_link);
            }
            path.reverse();
            let mut anchor = path[0];
            for &l in &path[1..] {
                let j = &m.joints[m.links[l].parent_joint?];
                match j.kind {
                    JointKind::Fixed => anchor = l,
                    JointKind::Revolute | JointKind::Continuous => {
                        anchor = l;
                        break;
                    }
                    _ => break,
                }
            }
            let mut d = StaticsData::new(m, 0);
            forward_kinematics(m, &mut d, &vec![0.0; m.nq()]);
            vec![(anchor, d.link_point(m, anchor, &Vector3::zeros()))]
        }
    };
    let excess = anchors
        .iter()
        .map(|(link, at)| (target_m - at).norm() - chain_length_m(m, *link, hand))
        .fold(f64::NEG_INFINITY, f64::max);
    (excess > 0.0).then_some(excess)
}

/// Distance \[m\] from `p` to the convex polygon `v` (counter-clockwise), 0 inside.
fn distance_to_polygon(v: &[nalgebra::Vector2<f64>], p: &nalgebra::Vector2<f64>) -> f64 {
    let n = v.len();
    let inside = (0..n).all(|i| {
        let (a, b) = (v[i], v[(i + 1) % n]);
        (b - a).perp(&(p - a)) >= 0.0
    });
    if inside {
        return 0.0;
    }
    (0..n)
        .map(|i| {
            let (a, b) = (v[i], v[(i + 1) % n]);
            let ab = b - a;
            let t = ((p - a).dot(&ab) / ab.norm_squared().max(1e-300)).clamp(0.0, 1.0);
            (a + ab * t - p).norm()
        })
        .fold(f64::INFINITY, f64::min)
}
