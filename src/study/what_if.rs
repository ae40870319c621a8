//! What would change the plan: workstation changes, each planned again by posture-opt with the
//! same options, so that the report can say in numbers what the change would do ("raising the
//! pallet 10 cm lowers …").
//!
//! **The work moved.** The phase that matters most, re-planned with its hands' target moved
//! toward the worker's elbow height — the height the ergonomics literature recommends for
//! handling. The phase: the one with the highest L5/S1 compression when a phase exceeds NIOSH's
//! action limit, else the one whose posture the targets force farthest beyond the acceptable
//! zones (ISO 11226 / EN 1005-4, summed excess), else the one where the group whose capacity
//! falls lowest holds its highest load. The move: toward elbow height, by at most
//! [`MAX_MOVE_M`]; no such what-if when the target is already within [`NEAR_ELBOW_M`] of it. A
//! standing worker's elbow height is 0.630 × stature (Drillis & Contini 1966); a seated
//! worker's is where the plan's seated rest posture (upper arms hanging) puts the elbow — the
//! seat's height plus the worker's sitting elbow height, which no fraction of stature gives.
//!
//! **The worker free to step.** When the task fixes the feet of a standing worker, the task
//! planned again with the feet placed by the planner within a standing area around the task's
//! stance, [`STANDING_AREA_HALF_SIDE_M`] each way: real workers pivot or step rather than twist
//! (HUMOSIM's stepping studies, SAE 2006-01-2364 and 2007-01-2478), and with the feet fixed
//! the work to the side is reached by turning the trunk and the head.
//!
//! The comparison gives the zones' summed excess first.

use crate::assess::meaning::time_words as duration;
use crate::assess::{Assessment, assess};
use crate::plan::{Plan, PlanError, PlanOptions, Task, plan_task_with};
use nalgebra::Vector3;
use serde::Serialize;

/// Largest move of the target \[m\].
pub const MAX_MOVE_M: f64 = 0.10;

/// Largest horizontal move of the work toward the normal working area \[m\]: ASSUMPTION, about
/// a forearm's length — enough to bring a bin from the edge of the maximum reach into the normal
/// area (Barnes 1963: about 0.35–0.40 m from the elbow to the edge of the maximum area), not a
/// new workstation.
pub const MAX_CLOSER_M: f64 = 0.30;

/// A target this close to elbow height \[m\] is left where it is.
pub const NEAR_ELBOW_M: f64 = 0.05;

/// Standing elbow height as a fraction of stature (Drillis & Contini 1966).
pub const ELBOW_HEIGHT_PER_STATURE: f64 = 0.630;

/// Half the side of the square standing area of the stepping what-if, centred on the task's
/// stance \[m\]: ASSUMPTION, a square about a metre across (as the stance table of
/// docs/results.md plans every shipped task), one short step in any direction from the stance; no
/// standard gives the floor a worker at a station may use, so a workstation with less floor
/// declares its own area (`stance.area_m`).
pub const STANDING_AREA_HALF_SIDE_M: f64 = 0.5;

/// A change the report's verdict recommends lowers fatigue per hour by at least this fraction:
/// ASSUMPTION, a change an ergonomist would act on, twenty times the 0.5 % the plan's total may
/// move with solver noise (the stability tests' bound); smaller gains stay among the findings.
pub const ADVISE_FRACTION: f64 = 0.10;

/// Largest move of what the worker looks at (a screen, a dial) \[m\]: ASSUMPTION, about the
/// travel of a monitor arm or of a screen moved on its desk, not a new workstation.
pub const MAX_GAZE_MOVE_M: f64 = 0.30;

/// A move of what the worker looks at smaller than this is not planned \[m\]: ASSUMPTION, as
/// [`NEAR_ELBOW_M`] for the hands' work (less is within what the eyes take without the head).
pub const MIN_GAZE_MOVE_M: f64 = 0.05;

/// A change the report's verdict recommends for its postures brings their excess beyond the
/// standards' acceptable zones (summed over the cycle's phases) down by at least this much
/// \[deg\] without raising fatigue per hour: ASSUMPTION, about what an observer sees (the 10° the
/// trunk's and neck's asymmetry zones allow). An ergonomist's trial had an arm 125° overhead:
/// lowering the work 100 mm took its excess 88° → 50° for 7 % less fatigue, stepping 88° → 85°
/// for 16 % less, and the verdict recommended stepping.
pub const ADVISE_POSTURE_DEG: f64 = 10.0;

/// The figures of one plan that the what-if compares.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Figures {
    /// NIOSH's lifting index that decides the task (the composite index with several lifts);
    /// `None` without declared lifts or when it is not defined.
    pub lifting_index: Option<f64>,
    /// Why the lifting index is not defined, when a lift lies outside the equation's limits.
    pub lifting_outside_limits: Option<String>,
    /// Total U per hour of simulated work \[min/h\].
    pub u_per_hour_min: f64,
    pub lowest_capacity: f64,
    pub back_compression_max_n: Option<f64>,
    pub capable_women: f64,
    /// When a muscle group gives out \[s from the start of the task\]; `None` when none does.
    /// A plan stops there, so its figures per hour and its lowest capacity are of that
    /// shortened run.
    pub exhaustion_s: Option<f64>,
    /// Steps per cycle (the phases' steps from the state before each).
    pub steps_per_cycle: u32,
    /// The worst phase's RULA grand score.
    pub rula_max: Option<i32>,
    /// The postures' excess beyond ISO 11226 / EN 1005-4's acceptable zones, summed over the
    /// cycle's phases and zones \[deg\] (`phases[].outside_zones`).
    pub zone_excess_deg: f64,
}

/// `+12 %` from `a` to `b` ("from 0" when `a` is not positive).
pub fn relative_change(a: f64, b: f64) -> String {
    if a > 0.0 {
        let x = 100.0 * (b / a - 1.0);
        if x.abs() < 1.0 {
            format!("{x:+.1} %")
        } else {
            format!("{x:+.0} %")
        }
    } else {
        "from 0".into()
    }
}

/// A change of the deciding lifting index in words ("NIOSH lifting index not defined (outside
/// the equation's limits) → 0.93"), and whether it is for the worse: a higher risk class
/// ([`crate::assess::lifting::risk_key`]) or, both defined, a higher index as reported (two
/// decimals). `None` when neither
/// side declares a lift.
pub fn lifting_change(
    before: Option<&Result<f64, String>>,
    after: Option<&Result<f64, String>>,
) -> Option<LiftingChange> {
    use crate::assess::lifting::{index_words, reported, risk_key};
    if before.is_none() && after.is_none() {
        return None;
    }
    // as NIOSH reports the index: a change in its third decimal is no change
    let worse = match (before, after) {
        (Some(Ok(b)), Some(Ok(a))) => reported(*a) > reported(*b),
        _ => risk_key(after).0 > risk_key(before).0,
    };
    Some(LiftingChange {
        words: format!(
            "NIOSH lifting index {} → {}",
            index_words(before),
            index_words(after)
        ),
        worse,
    })
}

/// See [`lifting_change`].
#[derive(Debug, Clone, PartialEq)]
pub struct LiftingChange {
    pub words: String,
    pub worse: bool,
}

impl Figures {
    /// Whether a muscle group gives out within the task.
    pub fn exhausted(&self) -> bool {
        self.exhaustion_s.is_some()
    }

    /// The deciding lifting index, or why it is not defined; `None` without declared lifts.
    pub fn lifting(&self) -> Option<Result<f64, String>> {
        crate::assess::lifting::from_fields(self.lifting_index, &self.lifting_outside_limits)
    }

    /// The lifting index's risk class ([`crate::assess::lifting::risk_key`]).
    fn lifting_class(&self) -> u8 {
        crate::assess::lifting::risk_key(self.lifting().as_ref()).0
    }

    /// What changes from these figures to `after`, in words, one item per figure.
    pub fn changes_to(&self, after: &Figures) -> Vec<String> {
        let mut v = Vec::new();
        // a plan that gives out stops there: its figures per hour and its lowest capacity are of
        // that shortened run, so whether and when a group gives out is said first
        match (self.exhaustion_s, after.exhaustion_s) {
            (Some(_), None) => v.push(
                "whether a muscle group gives out: yes → no (as planned one does and the plan stops there: its figures after this are of that shortened run)"
                    .into(),
            ),
            (Some(a), Some(b)) => v.push(format!(
                "when a muscle group gives out: after {} → after {} (one gives out in both plans, and each stops there: the figures after this are of two shortened runs of different lengths, not comparable as rates)",
                duration(a),
                duration(b)
            )),
            _ => {}
        }
        if let Some(l) = lifting_change(self.lifting().as_ref(), after.lifting().as_ref()) {
            v.push(l.words);
        }
        if self.zone_excess_deg > 0.0 || after.zone_excess_deg > 0.0 {
            v.push(format!(
                "postures beyond the acceptable zones (ISO 11226 / EN 1005-4) by {:.0}° → {:.0}° (summed over phases)",
                self.zone_excess_deg, after.zone_excess_deg
            ));
        }
        if let (Some(a), Some(b)) = (self.rula_max, after.rula_max)
            && a != b
        {
            v.push(format!("worst RULA {a} → {b}"));
        }
        v.push(format!(
            "fatigue per hour {:.1} → {:.1} min/h ({})",
            self.u_per_hour_min,
            after.u_per_hour_min,
            relative_change(self.u_per_hour_min, after.u_per_hour_min)
        ));
        if let (Some(a), Some(b)) = (self.back_compression_max_n, after.back_compression_max_n) {
            v.push(format!("highest L5/S1 compression {a:.0} → {b:.0} N"));
        }
        v.push(format!(
            "lowest capacity {:.0} % → {:.0} %",
            100.0 * self.lowest_capacity,
            100.0 * after.lowest_capacity
        ));
        v.push(format!(
            "women strong enough {:.0} % → {:.0} %",
            100.0 * self.capable_women,
            100.0 * after.capable_women
        ));
        if self.steps_per_cycle > 0 || after.steps_per_cycle > 0 {
            v.push(format!(
                "steps per cycle {} → {}",
                self.steps_per_cycle, after.steps_per_cycle
            ));
        }
        if let (None, Some(b)) = (self.exhaustion_s, after.exhaustion_s) {
            v.push(format!(
                "but a muscle group then gives out within the task, after {}",
                duration(b)
            ));
        }
        v
    }
}

/// A workstation change.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Change {
    /// A phase's work (and every phase doing the same work) moved toward elbow height.
    MoveWork {
        phase: String,
        /// Vertical move of the phase's hand targets (and held object) \[m\], + up.
        dz_m: f64,
        elbow_height_m: f64,
        /// The worker sits: the elbow height is the seated one.
        seated: bool,
        /// The box the work rests on (a shelf board, a bench), moved with it and with the
        /// other work on it, then the boxes standing on it (a bin on the bench); empty: none.
        surfaces: Vec<String>,
    },
    /// A phase's work (and every phase doing the same work) moved horizontally toward the
    /// normal working area in front of the worker.
    BringWorkCloser {
        phase: String,
        /// Horizontal move of the phase's hand targets (and held object) \[m\], world x and y.
        dx_m: f64,
        dy_m: f64,
        /// The work's horizontal distance from the normal working area's centre before the
        /// move \[m\].
        beyond_m: f64,
        /// The box the work rests on (a bin, a cart), moved with it where the work would
        /// otherwise leave it, then the boxes standing on it; empty: none.
        surfaces: Vec<String>,
        /// The move stops short of the normal working area so that a moved box keeps
        /// [`FEET_ROOM_M`] from the fixed feet.
        short_of_feet: bool,
    },
    /// What a phase looks at (its `gaze_m`, and every phase looking at the same point) moved up
    /// or down to where the normal line of sight meets it.
    MoveGaze {
        phase: String,
        /// Vertical move of the gaze point \[m\], + up.
        dz_m: f64,
    },
    /// The feet, fixed in the task, placed by the planner within a square standing area
    /// centred on the task's stance.
    StandingArea {
        /// Half the square's side \[m\].
        half_side_m: f64,
    },
}

/// A workstation change and what it does.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WhatIf {
    pub change: Change,
    pub before: Figures,
    pub after: Figures,
    /// What makes the changed task impossible as planned (then the change is not advised).
    pub problems: Vec<String>,
    /// The changed plan's phases whose solve stopped short of convergence: its figures are
    /// those of the plan the optimiser stopped at (a finished plan may do better).
    pub not_converged: Vec<String>,
}

impl WhatIf {
    /// Whether the change keeps every muscle group from giving out where the plan has one give
    /// out within the task.
    pub fn ends_exhaustion(&self) -> bool {
        self.before.exhausted() && !self.after.exhausted()
    }

    /// Whether the change brings NIOSH's lifting index into a lower risk class (defined where
    /// it was not, at most 3 where it was above, at most 1 where it was above).
    pub fn lowers_lifting_risk(&self) -> bool {
        self.after.lifting_class() < self.before.lifting_class()
    }

    /// Whether the change brings the postures' excess beyond the acceptable zones down by at
    /// least [`ADVISE_POSTURE_DEG`] without raising fatigue per hour.
    pub fn eases_postures(&self) -> bool {
        self.after.zone_excess_deg <= self.before.zone_excess_deg - ADVISE_POSTURE_DEG
            && self.after.u_per_hour_min <= self.before.u_per_hour_min
    }

    /// Whether the report's verdict recommends the change: it can be done as planned, every
    /// phase of its plan converged, no group gives out after it, NIOSH's lifting index does not
    /// rise, and it ends an exhaustion ([`Self::ends_exhaustion`], whatever fatigue per hour
    /// does: a plan that gives out stops early, so its figure per hour is not comparable),
    /// brings the lifting index into a lower risk class ([`Self::lowers_lifting_risk`]), eases
    /// the postures beyond the acceptable zones ([`Self::eases_postures`]) or lowers fatigue per
    /// hour by at least [`ADVISE_FRACTION`]. A change after which a group still
    /// gives out is not advised, however much later: the job stays one the worker cannot keep
    /// up, and the rates of two runs cut short at different times do not compare.
    pub fn advised(&self) -> bool {
        let lowers = self.before.u_per_hour_min > 0.0
            && self.after.u_per_hour_min <= (1.0 - ADVISE_FRACTION) * self.before.u_per_hour_min;
        let lifting_worse = lifting_change(
            self.before.lifting().as_ref(),
            self.after.lifting().as_ref(),
        )
        .is_some_and(|l| l.worse);
        self.problems.is_empty()
            && self.not_converged.is_empty()
            && !self.after.exhausted()
            && !lifting_worse
            && (self.ends_exhaustion()
                || self.lowers_lifting_risk()
                || self.eases_postures()
                || lowers)
    }
}

/// The change the report's verdict recommends: the first advised one of the ranked what-ifs.
pub fn advice(v: &[WhatIf]) -> Option<&WhatIf> {
    v.iter().find(|w| w.advised())
}

/// The plan's phases whose solve did not converge.
fn not_converged(plan: &Plan) -> Vec<String> {
    plan.summary
        .phases
        .iter()
        .filter(|p| !p.converged)
        .map(|p| p.phase.clone())
        .collect()
}

fn figures(plan: &Plan, a: &Assessment) -> Figures {
    let s = &plan.summary;
    let lifting = a.lifting_index();
    Figures {
        lifting_index: lifting.clone().and_then(Result::ok),
        lifting_outside_limits: lifting.and_then(Result::err),
        u_per_hour_min: if s.duration_s > 0.0 {
            s.total_u / (s.duration_s / 3600.0)
        } else {
            0.0
        },
        lowest_capacity: s.lowest_capacity,
        back_compression_max_n: a.back_compression_max_n,
        capable_women: a.capable_women,
        exhaustion_s: s.exhaustion.as_ref().map(|e| e.t_s),
        steps_per_cycle: s.steps_per_cycle(),
        zone_excess_deg: zone_excess_deg(plan),
        rula_max: a.rula_max,
    }
}

/// The plan's excess beyond the acceptable zones \[deg\], summed over phases and zones.
fn zone_excess_deg(plan: &Plan) -> f64 {
    // a fold from +0 (an empty f64 sum is −0, printed "-0°")
    (0..plan.summary.phases.len())
        .map(|p| phase_zone_excess_deg(plan, p))
        .fold(0.0, |a, x| a + x)
}

/// Phase `p`'s excess beyond the acceptable zones \[deg\], summed over zones.
fn phase_zone_excess_deg(plan: &Plan, p: usize) -> f64 {
    plan.summary.phases.get(p).map_or(0.0, |x| {
        x.outside_zones
            .iter()
            .map(|z| z.angle_deg - z.limit_deg)
            .fold(0.0, |a, x| a + x)
    })
}

/// The phase a what-if moves (see the module documentation).
pub fn phase_to_move(task: &Task, plan: &Plan, a: &Assessment) -> Option<usize> {
    use crate::assess::low_back::CompressionVerdict;
    let back = |p: usize| a.phases.get(p).and_then(|x| x.low_back.as_ref());
    let compression = |p: usize| back(p).map_or(0.0, |b| b.compression_n);
    let n = task.phases.len();
    // (each search takes the first of equal phases: `rev` before `max_by`, which keeps the last)
    if let Some(p) = (0..n)
        .rev()
        .filter(|&p| {
            back(p).is_some_and(|b| b.compression_verdict != CompressionVerdict::WithinActionLimit)
        })
        .max_by(|&x, &y| compression(x).total_cmp(&compression(y)))
    {
        return Some(p);
    }
    // a posture the targets force beyond the acceptable zones: the largest excess
    let excess = |p: usize| phase_zone_excess_deg(plan, p);
    if plan.summary.zones
        && let Some(p) = (0..n)
            .rev()
            .filter(|&p| excess(p) > 0.0)
            .max_by(|&x, &y| excess(x).total_cmp(&excess(y)))
    {
        return Some(p);
    }
    let h = plan.half_joint(&plan.summary.lowest_capacity_half_joint)?;
    let load = |p: usize| {
        plan.postures
            .iter()
            .filter(|r| r.phase == task.phases[p].name)
            .filter_map(|r| r.load.get(h).copied())
            .fold(0.0, f64::max)
    };
    (0..n)
        .rev()
        .filter(|&p| load(p) > 0.0)
        .max_by(|&x, &y| load(x).total_cmp(&load(y)))
}

/// Moves phase `p`'s targets toward elbow height (with the shelf or bench they rest on and the
/// other work there, [`work_moved`]), plans the changed task with `opts` (without baselines) and
/// compares. `None` when the phase has no target or sits near elbow height.
pub fn what_if(
    task: &Task,
    plan: &Plan,
    a: &Assessment,
    opts: PlanOptions,
    floor: f64,
) -> Result<Option<WhatIf>, PlanError> {
    let Some(p) = phase_to_move(task, plan, a) else {
        return Ok(None);
    };
    let ph = &task.phases[p];
    let heights: Vec<f64> = ph.targets_m.iter().flatten().map(|t| t.z).collect();
    if heights.is_empty() {
        return Ok(None);
    }
    let z = heights.iter().sum::<f64>() / heights.len() as f64;
    let seated = task.stance.as_ref().is_some_and(|s| s.seat.is_some());
    let elbow = match seated_elbow_height_m(task, plan) {
        Some(z) if seated => z,
        _ => ELBOW_HEIGHT_PER_STATURE * task.worker.stature_m,
    };
    if (elbow - z).abs() < NEAR_ELBOW_M {
        return Ok(None);
    }
    let dz = (elbow - z).clamp(-MAX_MOVE_M, MAX_MOVE_M);
    let Some((changed, surfaces)) = work_moved(task, p, Vector3::new(0.0, 0.0, dz), Surface::Moves)
    else {
        return Ok(None);
    };
    let change = Change::MoveWork {
        phase: ph.name.clone(),
        dz_m: dz,
        elbow_height_m: elbow,
        seated,
        surfaces,
    };
    plan_changed(change, &changed, plan, a, opts, floor).map(Some)
}

/// Where each hand's normal working area is centred, in the plan's rest posture (upper arms
/// hanging): in front of the elbow, horizontally, by the elbow's distance from the grip — the
/// arc the hand sweeps with the elbow at the side (Barnes 1963, Motion and time study: the
/// "normal area" of each hand; Squires 1956). `None` for a body without the elbow and hand links.
fn normal_area_m(task: &Task, plan: &Plan, h: usize) -> Option<Vector3<f64>> {
    let m = &task.model;
    let find = |name: &str| m.links.iter().position(|l| l.name == name);
    let elbow = find(["r_forearm", "l_forearm"][h])?;
    let pelvis = find("pelvis")?;
    let (grip, _) = task.hand_links[h].clone()?;
    let q = &plan.summary.rest_posture_rad;
    if q.len() != m.nq() {
        return None;
    }
    let mut data = crate::body::StaticsData::new(m, 0);
    crate::body::forward_kinematics(m, &mut data, q);
    let e = data.link_point(m, elbow, &Vector3::zeros());
    let g = data.link_point(m, grip, &Vector3::zeros());
    let (r, _) = data.link_pose(m, pelvis);
    let forward = Vector3::new(r[(0, 0)], r[(1, 0)], 0.0).try_normalize(1e-9)?;
    Some(e + forward * (g - e).norm())
}

/// Largest height of a hand target above the top of the box it works on \[m\]: ASSUMPTION, the
/// height of a tall box or tote grasped at its top (a target higher above a surface is work in
/// the air, not on it).
pub const SUPPORT_GAP_M: f64 = 0.30;

/// How far in front of (or beside) a box's outline a hand target still works on the box \[m\]:
/// ASSUMPTION, a hand setting a box down at a shelf's front edge holds it a few centimetres
/// short of the edge (the shipped shelves' targets lie 5 cm in front of their boards).
pub const SUPPORT_EDGE_M: f64 = 0.10;

/// Whether `local` (a point in a box's frame) lies over the box's outline, seen from above,
/// within `edge_m` of it.
fn over_outline(local: &nalgebra::Point3<f64>, size_m: &[f64; 3], edge_m: f64) -> bool {
    local.x.abs() <= 0.5 * size_m[0] + edge_m && local.y.abs() <= 0.5 * size_m[1] + edge_m
}

/// The box obstacle that work at `point` rests on: the one whose top lies under the point (the
/// point over its outline, [`over_outline`]) by at most [`SUPPORT_GAP_M`], the nearest below.
/// Only upright boxes (no roll or pitch) count.
fn support_of(task: &Task, point: &Vector3<f64>) -> Option<usize> {
    use crate::workstation::ShapeSpec;
    task.workstation
        .obstacles
        .iter()
        .enumerate()
        .filter_map(|(i, o)| {
            let ShapeSpec::Box { size_m } = o.spec.shape else {
                return None;
            };
            let [roll, pitch, _] = o.spec.rpy_rad;
            if roll.abs() > 1e-9 || pitch.abs() > 1e-9 {
                return None;
            }
            let local = o
                .world_from_obstacle()
                .inverse_transform_point(&(*point).into());
            let gap = local.z - 0.5 * size_m[2];
            (over_outline(&local, &size_m, SUPPORT_EDGE_M) && (0.0..=SUPPORT_GAP_M).contains(&gap))
                .then_some((i, gap))
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(i, _)| i)
}

/// When the box the work rests on moves with it.
#[derive(Clone, Copy, PartialEq)]
enum Surface {
    /// Always: the work moves up or down, and the shelf or bench with it.
    Moves,
    /// Only when the moved work would leave its outline (a bin or a cart brought closer); work
    /// moved across a bench stays on the bench.
    MovesIfLeft,
}

/// The task with phase `p`'s work moved by `step`: its hands' targets and held object, and those
/// of every phase doing the same work (they share one place); and, as `surface` says, the box
/// that work rests on ([`support_of`]) with every phase's work on it, so that no work floats
/// above or sinks into its surface, and the boxes standing on it ([`stands_on`]). Returns the
/// changed task and the moved boxes' names, the support first; `None` when a moved box would
/// leave the coordinates a task accepts.
fn work_moved(
    task: &Task,
    p: usize,
    step: Vector3<f64>,
    surface: Surface,
) -> Option<(Task, Vec<String>)> {
    let mut changed = task.clone();
    let ph = &task.phases[p];
    let support = ph.targets_m.iter().flatten().find_map(|t| {
        let i = support_of(task, t)?;
        let o = &task.workstation.obstacles[i];
        let stays_on = || {
            let moved = o
                .world_from_obstacle()
                .inverse_transform_point(&(t + step).into());
            let crate::workstation::ShapeSpec::Box { size_m } = o.spec.shape else {
                return false;
            };
            // still over it (a part slid across a bench), not merely at its edge
            over_outline(&moved, &size_m, 0.0)
        };
        (surface == Surface::Moves || !stays_on()).then_some(i)
    });
    // raised or lowered, a box moves with what it stands on (a bin on a bench: the bench moves)
    let support = support.map(|mut i| {
        if surface == Surface::Moves {
            // (each box once: thin boxes side by side could each count as standing on the other)
            let boxes = &task.workstation.obstacles;
            let mut seen = vec![i];
            while let Some(b) =
                (0..boxes.len()).find(|&b| !seen.contains(&b) && stands_on(&boxes[i], &boxes[b]))
            {
                seen.push(b);
                i = b;
            }
        }
        i
    });
    // the support and every box standing on it (a bin on the bench), and on those in turn
    let mut moved: Vec<usize> = support.into_iter().collect();
    let mut k = 0;
    while k < moved.len() {
        let below = &task.workstation.obstacles[moved[k]];
        for (j, o) in task.workstation.obstacles.iter().enumerate() {
            if !moved.contains(&j) && stands_on(o, below) {
                moved.push(j);
            }
        }
        k += 1;
    }
    let moves = |q: &crate::plan::task::Phase| {
        q.same_work(ph)
            || q.targets_m
                .iter()
                .flatten()
                .any(|t| support_of(task, t).is_some_and(|i| moved.contains(&i)))
    };
    for (q, orig) in changed.phases.iter_mut().zip(&task.phases) {
        if moves(orig) {
            for t in q.targets_m.iter_mut().flatten() {
                *t += step;
            }
            if let Some(o) = q.object.as_mut() {
                for (c, d) in o.center_m.iter_mut().zip(step.iter()) {
                    *c += d;
                }
            }
        }
    }
    for &i in &moved {
        let mut spec = task.workstation.obstacles[i].spec.clone();
        for (c, d) in spec.position_m.iter_mut().zip(step.iter()) {
            *c += d;
        }
        changed.workstation.obstacles[i] = crate::workstation::Obstacle::new(spec).ok()?;
    }
    Some((
        changed,
        moved
            .iter()
            .map(|&i| task.workstation.obstacles[i].spec.name.clone())
            .collect(),
    ))
}

/// Whether upright box `o` stands on upright box `below`: its bottom within 1 cm of the other's
/// top, its centre over the other's outline.
fn stands_on(o: &crate::workstation::Obstacle, below: &crate::workstation::Obstacle) -> bool {
    use crate::workstation::ShapeSpec;
    let (ShapeSpec::Box { size_m: a }, ShapeSpec::Box { size_m: b }) =
        (&o.spec.shape, &below.spec.shape)
    else {
        return false;
    };
    let upright = |x: &crate::workstation::Obstacle| {
        x.spec.rpy_rad[0].abs() <= 1e-9 && x.spec.rpy_rad[1].abs() <= 1e-9
    };
    let centre = nalgebra::Point3::from(o.spec.position_m);
    let local = below.world_from_obstacle().inverse_transform_point(&centre);
    upright(o)
        && upright(below)
        && ((o.spec.position_m[2] - 0.5 * a[2]) - (below.spec.position_m[2] + 0.5 * b[2])).abs()
            <= 0.01
        && local.x.abs() <= 0.5 * b[0]
        && local.y.abs() <= 0.5 * b[1]
}

/// The horizontal move from phase `p`'s work (its hand targets' mean) to the centre of its
/// hands' normal working areas ([`normal_area_m`]); `None` for a phase without targets or a body
/// without those links.
fn toward_normal_area(task: &Task, plan: &Plan, p: usize) -> Option<Vector3<f64>> {
    let ph = &task.phases[p];
    let hands: Vec<usize> = (0..2).filter(|&h| ph.targets_m[h].is_some()).collect();
    if hands.is_empty() {
        return None;
    }
    let mut d = Vector3::zeros();
    for &h in &hands {
        d += normal_area_m(task, plan, h)? - ph.targets_m[h]?;
    }
    d /= hands.len() as f64;
    d.z = 0.0;
    Some(d)
}

/// Moves the work that lies farthest from the normal working area in front of the worker
/// (horizontally, [`toward_normal_area`]; every phase doing the same work with it) to within
/// [`NEAR_ELBOW_M`] of that area's centre, by at most [`MAX_CLOSER_M`], plans the changed task
/// with `opts` (without baselines) and compares. `None` when every phase's work lies within
/// [`NEAR_ELBOW_M`] of it. The bin or cart the work rests on moves with it only where the work
/// would otherwise leave it ([`work_moved`]), and a moved box that reaches below the knee stops
/// [`FEET_ROOM_M`] short of fixed feet (the move shortened; no what-if when less than
/// [`NEAR_ELBOW_M`] is left); other obstacles stay (a change that then collides is not advised).
pub fn bring_work_closer(
    task: &Task,
    plan: &Plan,
    a: &Assessment,
    opts: PlanOptions,
    floor: f64,
) -> Result<Option<WhatIf>, PlanError> {
    // (the first of equal phases: `max_by` keeps the last)
    let farthest = (0..task.phases.len())
        .rev()
        .filter_map(|p| toward_normal_area(task, plan, p).map(|d| (p, d)))
        .max_by(|x, y| x.1.norm().total_cmp(&y.1.norm()));
    let Some((p, d)) = farthest else {
        return Ok(None);
    };
    let beyond_m = d.norm();
    if beyond_m < NEAR_ELBOW_M {
        return Ok(None);
    }
    let full = d * ((beyond_m - NEAR_ELBOW_M).min(MAX_CLOSER_M) / beyond_m);
    let moved = |s: f64| work_moved(task, p, s * full, Surface::MovesIfLeft);
    let Some((mut changed, mut surfaces)) = moved(1.0) else {
        return Ok(None);
    };
    // a box on the floor moved with the work stops short of fixed feet (the cart brought under
    // the toes left no posture to plan: every phase collided at the foot)
    let mut fraction = 1.0;
    let knee_m = knee_height_m(task, plan);
    if !clear_of_fixed_feet(task, &changed, &surfaces, knee_m) {
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..24 {
            let mid = 0.5 * (lo + hi);
            match moved(mid) {
                Some((c, n)) if clear_of_fixed_feet(task, &c, &n, knee_m) => lo = mid,
                _ => hi = mid,
            }
        }
        if lo * full.norm() < NEAR_ELBOW_M {
            return Ok(None);
        }
        let Some((c, n)) = moved(lo) else {
            return Ok(None);
        };
        (changed, surfaces, fraction) = (c, n, lo);
    }
    let step = fraction * full;
    let change = Change::BringWorkCloser {
        phase: task.phases[p].name.clone(),
        dx_m: step.x,
        dy_m: step.y,
        beyond_m,
        surfaces,
        short_of_feet: fraction < 1.0,
    };
    plan_changed(change, &changed, plan, a, opts, floor).map(Some)
}

/// How far a box the closer what-if moves stays from the soles of fixed feet, seen from above
/// \[m\]: ASSUMPTION, room for the toes and a shoe's edge (the plan keeps the body's own clearance).
pub const FEET_ROOM_M: f64 = 0.05;

/// Whether every box named in `moved` (of `changed`) that reaches below `knee_m` keeps
/// [`FEET_ROOM_M`] from the soles of `task`'s fixed feet (their support polygon) seen from above
/// (a box higher up, a bin on a bench, passes over the feet and the shins); true for feet the
/// planner places and for a body without a stance.
fn clear_of_fixed_feet(task: &Task, changed: &Task, moved: &[String], knee_m: f64) -> bool {
    let Some(st) = task.stance.as_ref().filter(|st| st.placement.is_none()) else {
        return true;
    };
    changed
        .workstation
        .obstacles
        .iter()
        .filter(|o| moved.contains(&o.spec.name))
        .filter_map(footprint_m)
        .all(|(f, bottom_m)| {
            bottom_m >= knee_m || separation_m(&f, &st.support_polygon_m) >= FEET_ROOM_M
        })
}

/// The outline of an upright box seen from above (its four corners, world x-y) and its bottom's
/// height \[m\]; `None` for another shape or a tilted box.
fn footprint_m(o: &crate::workstation::Obstacle) -> Option<(Vec<nalgebra::Vector2<f64>>, f64)> {
    let crate::workstation::ShapeSpec::Box { size_m } = o.spec.shape else {
        return None;
    };
    let [roll, pitch, _] = o.spec.rpy_rad;
    if roll.abs() > 1e-9 || pitch.abs() > 1e-9 {
        return None;
    }
    let w = o.world_from_obstacle();
    let corners = [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)]
        .iter()
        .map(|&(sx, sy)| {
            let c = w * nalgebra::Point3::new(0.5 * sx * size_m[0], 0.5 * sy * size_m[1], 0.0);
            nalgebra::Vector2::new(c.x, c.y)
        })
        .collect();
    Some((corners, o.spec.position_m[2] - 0.5 * size_m[2]))
}

/// The height of the knee (the origin of the link `r_shank`) in the plan's rest posture \[m\];
/// infinite for a body without that link (every moved box then counts).
fn knee_height_m(task: &Task, plan: &Plan) -> f64 {
    let m = &task.model;
    let q = &plan.summary.rest_posture_rad;
    match m.links.iter().position(|l| l.name == "r_shank") {
        Some(knee) if q.len() == m.nq() => {
            let mut data = crate::body::StaticsData::new(m, 0);
            crate::body::forward_kinematics(m, &mut data, q);
            data.link_point(m, knee, &Vector3::zeros()).z
        }
        _ => f64::INFINITY,
    }
}

/// A lower bound on the distance between two convex polygons \[m\]: their largest separation
/// along the normals of their edges (separating axes); ≤ 0 when they overlap.
fn separation_m(a: &[nalgebra::Vector2<f64>], b: &[nalgebra::Vector2<f64>]) -> f64 {
    let normals = |p: &[nalgebra::Vector2<f64>]| -> Vec<nalgebra::Vector2<f64>> {
        (0..p.len())
            .filter_map(|i| {
                let e = p[(i + 1) % p.len()] - p[i];
                nalgebra::Vector2::new(e.y, -e.x).try_normalize(1e-12)
            })
            .collect()
    };
    let span = |p: &[nalgebra::Vector2<f64>], n: &nalgebra::Vector2<f64>| {
        p.iter()
            .map(|v| v.dot(n))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x), hi.max(x))
            })
    };
    normals(a)
        .iter()
        .chain(normals(b).iter())
        .map(|n| {
            let ((a0, a1), (b0, b1)) = (span(a, n), span(b, n));
            (b0 - a1).max(a0 - b1)
        })
        .fold(f64::NEG_INFINITY, f64::max)
}

/// The height of the right elbow (the origin of the link `r_forearm`) in the plan's rest posture
/// \[m\]: for a seated worker, the seated elbow height with the upper arms hanging. `None`
/// for a body without that link.
pub fn seated_elbow_height_m(task: &Task, plan: &Plan) -> Option<f64> {
    let m = &task.model;
    let link = m.links.iter().position(|l| l.name == "r_forearm")?;
    let q = &plan.summary.rest_posture_rad;
    if q.len() != m.nq() {
        return None;
    }
    let mut data = crate::body::StaticsData::new(m, 0);
    crate::body::forward_kinematics(m, &mut data, q);
    Some(data.link_point(m, link, &Vector3::zeros()).z)
}

/// The head's inclination beyond ISO 11226's zone \[deg\]: tilted back beyond
/// [`crate::plan::zones::ISO_BACKWARD_TOLERANCE_DEG`] or inclined forward beyond 25° (0
/// within).
fn head_beyond_deg(a: &Assessment, p: usize) -> f64 {
    a.phases
        .get(p)
        .and_then(|pa| pa.angles.as_ref())
        .map_or(0.0, |x| {
            use crate::plan::zones::{HEAD_HOLD, ISO_BACKWARD_TOLERANCE_DEG};
            let back = -x.head_inclination_deg - ISO_BACKWARD_TOLERANCE_DEG;
            back.max(x.head_inclination_deg - HEAD_HOLD.from_deg)
                .max(0.0)
        })
}

/// Moves what the worker looks at where the head is tilted back or bowed beyond ISO 11226's
/// zone (the phase with the largest excess among those that give a `gaze_m`: a screen, a dial, a
/// part held in a fixture) up or down to where the normal line of sight from the planned eyes
/// meets it ([`crate::plan::task::LINE_OF_SIGHT_BELOW_DEG`] below the horizontal, MIL-STD-1472),
/// by at most [`MAX_GAZE_MOVE_M`], plans the changed task with `opts` (without baselines) and
/// compares. `None` when no such phase, no head, or a move under [`MIN_GAZE_MOVE_M`]. An
/// ergonomist's trial had a screen above eye level tilt the head back while the report only
/// offered to move the hands' work.
pub fn move_gaze(
    task: &Task,
    plan: &Plan,
    a: &Assessment,
    opts: PlanOptions,
    floor: f64,
) -> Result<Option<WhatIf>, PlanError> {
    use crate::plan::task::Gaze;
    let Some(head) = task.head else {
        return Ok(None);
    };
    let worst = (0..task.phases.len().min(plan.summary.phases.len()))
        .rev()
        .filter(|&p| matches!(task.phases[p].gaze, Gaze::Point(_)))
        .map(|p| (p, head_beyond_deg(a, p)))
        .filter(|(_, d)| *d > 0.0)
        .max_by(|x, y| x.1.total_cmp(&y.1));
    let Some((p, _)) = worst else {
        return Ok(None);
    };
    let Gaze::Point(point) = task.phases[p].gaze else {
        return Ok(None);
    };
    let m = &task.model;
    let q = &plan.summary.phases[p].q_rad;
    if q.len() != m.nq() {
        return Ok(None);
    }
    let mut data = crate::body::StaticsData::new(m, 0);
    crate::body::forward_kinematics(m, &mut data, q);
    let eye = data.link_point(m, head.link, &head.eye_in_link_m);
    let d = (point - eye).xy().norm();
    let below = crate::plan::task::LINE_OF_SIGHT_BELOW_DEG
        .to_radians()
        .tan();
    let dz = (eye.z - d * below - point.z).clamp(-MAX_GAZE_MOVE_M, MAX_GAZE_MOVE_M);
    if dz.abs() < MIN_GAZE_MOVE_M {
        return Ok(None);
    }
    let mut changed = task.clone();
    for ph in &mut changed.phases {
        if ph.gaze == Gaze::Point(point) {
            ph.gaze = Gaze::Point(point + Vector3::new(0.0, 0.0, dz));
        }
    }
    let change = Change::MoveGaze {
        phase: task.phases[p].name.clone(),
        dz_m: dz,
    };
    plan_changed(change, &changed, plan, a, opts, floor).map(Some)
}

/// Plans the changed task with `opts` (without baselines) and compares it with `plan`.
fn plan_changed(
    change: Change,
    changed: &Task,
    plan: &Plan,
    a: &Assessment,
    opts: PlanOptions,
    floor: f64,
) -> Result<WhatIf, PlanError> {
    let opts = PlanOptions {
        baselines: false,
        ..opts
    };
    let plan2 = plan_task_with(changed, opts)?;
    let a2 = assess(changed, &plan2, floor);
    Ok(WhatIf {
        change,
        before: figures(plan, a),
        after: figures(&plan2, &a2),
        problems: plan2.problems(),
        not_converged: not_converged(&plan2),
    })
}

/// The task planned again with the worker free to step and turn within a square standing area
/// of half-side [`STANDING_AREA_HALF_SIDE_M`] centred on its stance, with `opts` (without
/// baselines), and compared. `None` unless the task fixes the feet of a standing worker (a
/// seated worker, a task that gives its own standing area, a body without feet), or when the
/// area cannot hold the task's stance.
pub fn with_standing_area(
    task: &Task,
    plan: &Plan,
    a: &Assessment,
    opts: PlanOptions,
    floor: f64,
) -> Result<Option<WhatIf>, PlanError> {
    let standing = task
        .stance
        .as_ref()
        .is_some_and(|s| s.placement.is_none() && s.seat.is_none());
    if !standing {
        return Ok(None);
    }
    let mut file = task.source.clone();
    let h = STANDING_AREA_HALF_SIDE_M;
    let stance = file.stance.get_or_insert_with(Default::default);
    let x0 = stance.forward_m;
    stance.area_m = Some(vec![[x0 - h, -h], [x0 + h, -h], [x0 + h, h], [x0 - h, h]]);
    // the area holds every stance the task format accepts but the widest: then no what-if
    let Ok(changed) = Task::from_task_file(file, &task.path) else {
        return Ok(None);
    };
    let change = Change::StandingArea { half_side_m: h };
    plan_changed(change, &changed, plan, a, opts, floor).map(Some)
}

/// Every what-if of the plan: the work moved ([`what_if`]) and the worker free to step
/// ([`with_standing_area`]), those that apply: those that can be done as planned first, and
/// among them the one that lowers fatigue per hour most.
pub fn what_ifs(
    task: &Task,
    plan: &Plan,
    a: &Assessment,
    opts: PlanOptions,
    floor: f64,
) -> Result<Vec<WhatIf>, PlanError> {
    let mut v: Vec<WhatIf> = [
        what_if(task, plan, a, opts, floor)?,
        bring_work_closer(task, plan, a, opts, floor)?,
        move_gaze(task, plan, a, opts, floor)?,
        with_standing_area(task, plan, a, opts, floor)?,
    ]
    .into_iter()
    .flatten()
    .collect();
    rank(&mut v);
    Ok(v)
}

/// Orders what-ifs for the report: those that can be done as planned first, then those after
/// which no group gives out, then by NIOSH's lifting index after the change (its risk class,
/// then the index above 1, as `compare` ranks layouts), then by the postures' excess beyond the
/// acceptable zones after the change (to the whole degree; `compare` too ranks the standards'
/// postures before fatigue), then by fatigue per hour after the change, lowest first (where a
/// group gives out after each, by when it does, latest first).
fn rank(v: &mut [WhatIf]) {
    let li = |w: &WhatIf| crate::assess::lifting::risk_key(w.after.lifting().as_ref());
    v.sort_by(|x, y| {
        (!x.problems.is_empty())
            .cmp(&!y.problems.is_empty())
            .then(x.after.exhausted().cmp(&y.after.exhausted()))
            // after both a group gives out: the later the better (their rates do not compare)
            .then(
                y.after
                    .exhaustion_s
                    .unwrap_or(0.0)
                    .total_cmp(&x.after.exhaustion_s.unwrap_or(0.0)),
            )
            .then(li(x).0.cmp(&li(y).0))
            .then(li(x).1.total_cmp(&li(y).1))
            .then(
                x.after
                    .zone_excess_deg
                    .round()
                    .total_cmp(&y.after.zone_excess_deg.round()),
            )
            .then(x.after.u_per_hour_min.total_cmp(&y.after.u_per_hour_min))
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    fn figures(u_per_hour_min: f64) -> Figures {
        Figures {
            lifting_index: None,
            lifting_outside_limits: None,
            u_per_hour_min,
            lowest_capacity: 0.5,
            back_compression_max_n: None,
            capable_women: 0.5,
            exhaustion_s: None,
            steps_per_cycle: 0,
            zone_excess_deg: 0.0,
            rula_max: None,
        }
    }

    fn what_if(dz_m: f64, after_u: f64, problem: bool) -> WhatIf {
        WhatIf {
            change: Change::MoveWork {
                phase: format!("{dz_m}"),
                dz_m,
                elbow_height_m: 1.1,
                seated: false,
                surfaces: vec![],
            },
            before: figures(100.0),
            after: figures(after_u),
            problems: if problem {
                vec!["collision".into()]
            } else {
                vec![]
            },
            not_converged: vec![],
        }
    }

    /// A change that cannot be done as planned comes last however low its fatigue, one after
    /// which a group gives out comes after those after which none does; the others by fatigue
    /// per hour after the change.
    #[test]
    fn doable_changes_first_then_no_exhaustion_then_the_least_fatigue() {
        let mut exhausting = what_if(0.4, 40.0, false);
        exhausting.after.exhaustion_s = Some(60.0);
        // gives out later, at a higher rate over its longer run: ranked before
        let mut later = what_if(0.45, 45.0, false);
        later.after.exhaustion_s = Some(90.0);
        let mut v = vec![
            what_if(0.1, 50.0, true),
            exhausting,
            what_if(0.2, 90.0, false),
            later,
            what_if(0.3, 60.0, false),
        ];
        rank(&mut v);
        let order: Vec<f64> = v.iter().map(|w| w.after.u_per_hour_min).collect();
        assert_eq!(order, [60.0, 90.0, 45.0, 40.0, 50.0]);
    }

    /// A change after which no group gives out, where the plan has one give out, says so before
    /// the figures per hour (those of the plan that gives out are of a shortened run); the other
    /// way round it says so after them, with when; where a group gives out in both, when it does
    /// in each comes first, and the rates are said not to compare; nothing when none gives out.
    #[test]
    fn ending_an_exhaustion_is_said_first() {
        let (mut before, after) = (figures(130.0), figures(120.0));
        before.exhaustion_s = Some(63.0);
        let v = before.changes_to(&after);
        assert!(
            v[0].starts_with("whether a muscle group gives out: yes → no"),
            "{v:?}"
        );
        let v = after.changes_to(&before);
        assert!(
            v.last()
                .unwrap()
                .contains("gives out within the task, after 63 s"),
            "{v:?}"
        );
        assert!(!v.iter().any(|s| s.contains("yes → no")));
        let mut later = figures(143.4);
        later.exhaustion_s = Some(300.0);
        let v = before.changes_to(&later);
        assert!(
            v[0].starts_with("when a muscle group gives out: after 63 s → after 5 min")
                && v[0].contains("not comparable as rates"),
            "{v:?}"
        );
        assert_eq!(v.iter().filter(|s| s.contains("gives out")).count(), 1);
        let v = figures(130.0).changes_to(&figures(120.0));
        assert!(
            !v.iter()
                .any(|s| s.contains("gives out") || s.contains("exhausted"))
        );
    }

    /// Postures beyond the acceptable zones rank before fatigue, and a change that brings their
    /// excess down by 10° or more without more fatigue is advised although fatigue falls less
    /// than a tenth (the trial's overhead arm: lowering the work 88° → 50° for 7 % less fatigue,
    /// stepping 88° → 85° for 16 % less: lowering is recommended).
    #[test]
    fn easing_postures_beyond_the_zones_ranks_first_and_is_advised() {
        let mut lower = what_if(-0.1, 93.0, false);
        let mut step = what_if(0.0, 84.0, false);
        for (w, after_deg) in [(&mut lower, 50.0), (&mut step, 85.0)] {
            w.before.zone_excess_deg = 88.0;
            w.after.zone_excess_deg = after_deg;
        }
        assert!(lower.eases_postures() && lower.advised());
        assert!(!step.eases_postures() && step.advised());
        let mut v = vec![step, lower];
        rank(&mut v);
        assert_eq!(advice(&v).map(|w| w.after.u_per_hour_min), Some(93.0));
        // 9° less is not enough; 10° less with more fatigue is not advised
        let mut w = what_if(0.2, 99.0, false);
        (w.before.zone_excess_deg, w.after.zone_excess_deg) = (20.0, 11.0);
        assert!(!w.eases_postures() && !w.advised());
        let mut w = what_if(0.3, 101.0, false);
        (w.before.zone_excess_deg, w.after.zone_excess_deg) = (20.0, 10.0);
        assert!(!w.eases_postures() && !w.advised());
        w.after.u_per_hour_min = 100.0;
        assert!(w.eases_postures() && w.advised());
    }

    /// The verdict recommends the first ranked change that is doable, finished, exhausts no
    /// group and lowers fatigue per hour by at least a tenth; none when no change does.
    #[test]
    fn advice_is_the_first_change_that_lowers_fatigue_a_tenth_cleanly() {
        let mut v = vec![
            what_if(0.1, 50.0, true),
            what_if(0.2, 91.0, false),
            what_if(0.3, 85.0, false),
        ];
        rank(&mut v);
        assert_eq!(advice(&v).map(|w| w.after.u_per_hour_min), Some(85.0));
        // 9 % lower is not enough, and the one that collides is never advised
        v.retain(|w| w.after.u_per_hour_min != 85.0);
        assert!(advice(&v).is_none());
        // exactly a tenth lower is
        let at_bound = what_if(0.4, 90.0, false);
        assert!(at_bound.advised());
        // unfinished, or exhausting a group the plan did not: not advised
        let mut w = what_if(0.5, 60.0, false);
        w.not_converged = vec!["lift".into()];
        assert!(!w.advised());
        let mut w = what_if(0.6, 60.0, false);
        w.after.exhaustion_s = Some(100.0);
        assert!(!w.advised());
        // a group gives out both before and after: not advised, however much lower the rate
        // over the shortened runs or later the exhaustion
        w.before.exhaustion_s = Some(50.0);
        assert!(!w.advised());
        // a change that ends an exhaustion is advised even when fatigue per hour rises (the
        // plan that gives out stops early); unless it collides or did not finish
        let mut w = what_if(0.7, 130.0, false);
        w.before.exhaustion_s = Some(63.0);
        assert!(w.ends_exhaustion() && w.advised());
        w.not_converged = vec!["lift".into()];
        assert!(!w.advised());
        // no fatigue before: nothing to lower
        let mut w = what_if(0.8, 0.0, false);
        w.before.u_per_hour_min = 0.0;
        assert!(!w.advised());
    }

    /// NIOSH's lifting index in the what-ifs: a change that brings the index into a lower risk
    /// class is advised although fatigue per hour barely moves, one that raises the index is
    /// never advised however much it lowers fatigue, and among changes that can be done the
    /// lower index ranks first (as `compare` ranks layouts); the change is said in words.
    #[test]
    fn the_lifting_index_decides_before_fatigue() {
        let outside = Some("'lift' at the destination: H 66.5 cm beyond 63 cm (HM = 0)".into());
        // from not defined to 0.93, fatigue per hour 1 % lower
        let mut defined = what_if(0.1, 99.0, false);
        defined.before.lifting_outside_limits = outside.clone();
        defined.after.lifting_index = Some(0.93);
        assert!(defined.lowers_lifting_risk() && defined.advised());
        assert_eq!(
            defined.before.changes_to(&defined.after)[0],
            "NIOSH lifting index not defined (outside the equation's limits) → 0.93"
        );
        // fatigue per hour 40 % lower, but the index rises from 0.93 to 1.2: not advised
        let mut higher = what_if(0.2, 60.0, false);
        higher.before.lifting_index = Some(0.93);
        higher.after.lifting_index = Some(1.2);
        assert!(!higher.advised());
        // a change in the index's third decimal is no change (NIOSH reports two)
        let (b, a) = (Ok(1.009045), Ok(1.009166));
        assert!(!lifting_change(Some(&b), Some(&a)).unwrap().worse);
        assert!(lifting_change(Some(&b), Some(&Ok(1.02))).unwrap().worse);
        // both within the same class: fatigue decides whether it is advised
        let mut same = what_if(0.3, 60.0, false);
        same.before.lifting_index = Some(1.4);
        same.after.lifting_index = Some(1.3);
        assert!(same.advised() && !same.lowers_lifting_risk());
        // ranking: the index after the change before fatigue per hour
        let mut still_outside = what_if(0.4, 40.0, false);
        still_outside.before.lifting_outside_limits = outside.clone();
        still_outside.after.lifting_outside_limits = outside;
        let mut v = vec![still_outside, higher, same, defined];
        rank(&mut v);
        let order: Vec<f64> = v.iter().map(|w| w.after.u_per_hour_min).collect();
        assert_eq!(order, [99.0, 60.0, 60.0, 40.0]);
        assert_eq!(v[1].after.lifting_index, Some(1.2));
        assert_eq!(v[2].after.lifting_index, Some(1.3));
    }
}
