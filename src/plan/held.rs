//! The held object against the worker's own body.
//!
//! A two-handed phase's object sits where the task puts it (`object.center_m`, an axis-aligned
//! box). The arms hold it, so they may touch it; any other part of the body (trunk, head, legs,
//! pelvis) that reaches into it deeper than resting contact ([`OBJECT_CONTACT_TOL_M`]) is a
//! collision of that phase, reported like an object inside an obstacle: the phase's
//! `min_clearance_m` becomes the (negative) depth and `closest` says "held object ↔ trunk".
//!
//! The arms are the rigid bodies on the path from one hand to the root that are not on the
//! other hand's path (for the generated worker: hands, forearms, upper arms, shoulders).
//!
//! The planner keeps the rest of the body clear of the object as of any obstacle
//! ([`objects`]: the phase's objects are obstacles of its solve, at the task's clearance), so a
//! collision reported here is one the optimiser could not avoid.

use super::posture::Scene;
use super::task::{Phase, Task};
use crate::body::{StaticsData, forward_kinematics};
use crate::workstation::{ObstacleSpec, ShapeSpec, Workstation};
use std::collections::HashSet;

pub use super::planner::OBJECT_CONTACT_TOL_M;

/// Rigid bodies of the arms: on one hand's path to the root but not on the other's.
pub(crate) fn arm_bodies(t: &Task) -> HashSet<usize> {
    let m = &t.model;
    let path = |link: usize| {
        let mut b = m.link_in_body[link].body;
        let mut v = vec![b];
        while b > 0 {
            b = m.q_parent_body[b - 1];
            v.push(b);
        }
        v.into_iter().collect::<HashSet<usize>>()
    };
    let paths: Vec<HashSet<usize>> = t
        .hand_links
        .iter()
        .flatten()
        .map(|(l, _)| path(*l))
        .collect();
    match paths.as_slice() {
        [a, b] => a.symmetric_difference(b).copied().collect(),
        [a] => a.clone(),
        _ => HashSet::new(),
    }
}

/// The held object of a phase as an obstacle: an axis-aligned box at its place.
fn object_spec(o: &super::task::HeldObject) -> ObstacleSpec {
    ObstacleSpec {
        name: "held object".into(),
        shape: ShapeSpec::Box { size_m: o.size_m },
        position_m: o.center_m,
        rpy_rad: [0.0; 3],
    }
}

/// The held objects of phases `members` (one posture serves them all) as obstacles, each
/// distinct object once; `None` when no phase holds one.
pub(crate) fn objects(t: &Task, members: &[usize]) -> Option<Workstation> {
    let mut specs: Vec<ObstacleSpec> = Vec::new();
    for o in members.iter().filter_map(|&p| t.phases[p].object.as_ref()) {
        let s = object_spec(o);
        if !specs.contains(&s) {
            specs.push(s);
        }
    }
    if specs.is_empty() {
        return None;
    }
    // the task's loader checked every object's size and place
    Workstation::new(specs).ok()
}

/// The deepest overlap of phase `ph`'s held object with the body (arms excepted) in posture
/// `q_rad`, when deeper than resting contact: (signed distance \[m\], the link's name).
pub fn object_body_overlap(t: &Task, ph: &Phase, q_rad: &[f64]) -> Option<(f64, String)> {
    overlap(t, &Scene::new(t), &arm_bodies(t), ph, q_rad)
}

pub(crate) fn overlap(
    t: &Task,
    scene: &Scene,
    arms: &HashSet<usize>,
    ph: &Phase,
    q_rad: &[f64],
) -> Option<(f64, String)> {
    let o = ph.object?;
    if q_rad.len() != t.model.nq() {
        return None;
    }
    let ws = Workstation::new(vec![object_spec(&o)]).ok()?;
    let m = &t.model;
    let mut data = StaticsData::new(m, 0);
    forward_kinematics(m, &mut data, q_rad);
    let mut out = Vec::new();
    let mut deepest: Option<(f64, usize)> = None;
    for c in &scene.capsules {
        if arms.contains(&m.link_in_body[c.link].body) {
            continue;
        }
        let a = data.link_point(m, c.link, &c.a);
        let b = data.link_point(m, c.link, &c.b);
        out.clear();
        ws.clearances(&a, &b, c.radius_m, 0.0, &mut out);
        for cl in &out {
            if cl.distance_m < -OBJECT_CONTACT_TOL_M
                && deepest.is_none_or(|(d, _)| cl.distance_m < d)
            {
                deepest = Some((cl.distance_m, c.link));
            }
        }
    }
    deepest.map(|(d, l)| (d, super::planner::link_words(&m.links[l].name)))
}
