//! Acceptable posture zones as constraints: the planner keeps each phase's trunk, upper arms and
//! head within the zones ISO 11226:2000 (static postures) and EN 1005-4:2005+A1:2008 (postures in
//! movement) accept, and minimises fatigue inside them.
//!
//! Each zone is one row `g(q) ≤ 0` per phase ([`Zone`]), measured as the shift verdict measures
//! it ([`crate::assess::angles`]): the trunk's long axis against the vertical in the body's
//! sagittal plane (forward positive) and out of it (side bending), the thorax's twist against the
//! pelvis and its turn against the feet, each upper arm's angle against straight down, the head's long axis against the
//! vertical, the neck's flexion and side bending (head against trunk; both in the head's own
//! planes, [`crate::body::head`]) and its twist joint, and each wrist's flexion and deviation
//! joints. The wrists' rows keep near-ties apart: without them a bent and a straight wrist can
//! reach a target for about the same fatigue, and which one a plan takes depended on the
//! search's path (shelf's 'place high board', 1 % apart). The limits ([`ZoneLimits::for_hold`]):
//!
//! | zone | limit | source |
//! |---|---|---|
//! | trunk inclination | 20° for a hold of 4 min or more, 60° for 1 min or less, linear in between (the holding-time line read the other way); 60° for movements | ISO 11226 Fig. 2; EN 1005-4 (beyond 60° not acceptable) |
//! | trunk leaning back | 5° | ISO 11226 (backward inclination without support not acceptable); 5°: [`ISO_BACKWARD_TOLERANCE_DEG`], ASSUMPTION |
//! | trunk side bending, axial rotation | 10° each way | ISO 11226; EN 1005-4 |
//! | trunk turned against the feet | 10° each way | ISO 11226; EN 1005-4 (see below) |
//! | upper-arm elevation | 20° for 3 min or more, 60° for 1 min or less, linear in between; 60° for movements | ISO 11226 Fig. 3; EN 1005-4 |
//! | head inclination | 25° for a hold of 8 min or more, 85° for 1 min or less, linear in between; 85° for movements; 5° back | ISO 11226 |
//! | neck flexion | 25° | ISO 11226 |
//! | neck side bending | 10° each way | ISO 11226; EN 1005-4 |
//! | neck twist | 45° each way ([`NECK_TWIST_DEG`], ASSUMPTION) | see the constant |
//! | wrist flexion, extension | 15° each way ([`WRIST_FLEXION_DEG`]) | RULA; REBA |
//! | wrist radial, ulnar deviation | 10° each way ([`WRIST_DEVIATION_DEG`], ASSUMPTION) | RULA |
//!
//! A phase's hold is the run of consecutive phases of the same work it belongs to
//! ([`Task::holds`]); a hold of 4 s or less is a movement (EN 1005-4). ASSUMPTION: the planner
//! keeps out of EN 1005-4's conditionally acceptable zones (a twist beyond 10° done less than
//! twice a minute) as well as its unacceptable ones, and applies the head's limits to movements
//! too: where the layout allows, a posture no standard questions costs nothing to choose.
//!
//! **The trunk's turn against the feet** is its twist against the pelvis plus the pelvis's turn
//! against the feet (the hips' rotation on planted feet: the pelvis's heading taken from its hip
//! axis, which a stoop leaves level, against the feet's mean heading, as
//! [`crate::assess::angles`] measures it; with the heading from the pelvis's forward axis, which
//! a stoop shortens, the pallet's stooped phases did not converge and the shelf's total moved
//! 1.4 % with the QP's precision). The standards' trunk rotation is the upper body's twist
//! out of the posture the feet set: NIOSH measures asymmetry from the mid-sagittal plane of "the
//! neutral body position", the feet's (Waters et al. 1993), and an observer scoring RULA or REBA
//! sees the shoulders turned against the feet whether the lumbar spine or the hips turn. Without
//! this row the pelvis turned up to 38° against the feet while the lumbar twist stayed within its
//! 10° (shelf: the trunk faced 44° left of a board 22° to the right, the head turned 45° back to
//! it), since the hips' rotators hold almost no gravity moment. So the plan keeps both: the lumbar
//! twist and the whole turn within 10° (ASSUMPTION: the standards' trunk-rotation limit applied to
//! the turn against the feet). A body without the worker's foot links turns against nothing
//! (the row is its lumbar twist).
//!
//! **The trunk's inclination and side bending** are measured against the same heading
//! ([`crate::body::heading::pelvis_forward`]). Against the pelvis's x axis on the floor, they
//! turned with the pelvis's list by about `atan(sin list · tan tilt)` and the inclination jumped by
//! its whole value as the pelvis tilted through 90°: the optimiser, drawn to the jump (the zone's
//! penalty falls across it), stalled there on the pallet's grasp (a line-search stop with an
//! optimality residual of 0.18).
//!
//! **Elastic.** A target can force a posture outside a zone (a shelf above the head forces the
//! arm up). So each row has its own slack with a linear penalty [`ZONE_PENALTY_PER_RAD`] in the
//! objective (an ℓ1 exact penalty, the elastic mode of SNOPT): inside the zones nothing changes,
//! and where the layout forces an excess, the plan makes the smallest one it can, each zone's
//! separately, and reports it ([`Excess`]).

use super::task::Task;
use crate::body::worker::{LEFT_FOOT_LINK, RIGHT_FOOT_LINK};
use crate::body::{BodyModel, StaticsData, forward_kinematics};
use nalgebra::Vector3;

/// Backward trunk lean and head extension smaller than this are not judged \[deg\] (ASSUMPTION:
/// less is not visible to an observer).
pub const ISO_BACKWARD_TOLERANCE_DEG: f64 = 5.0;

/// Wrist flexion or extension beyond this is scored as bent \[deg\]: RULA (McAtamney & Corlett
/// 1993, Appl Ergon 24:91) scores the wrist 3 of 3 beyond 15° either way, REBA (Hignett &
/// McAtamney 2000, Appl Ergon 31:201) 2 of 2; ISO 11226:2000 calls extreme wrist positions not
/// acceptable without giving an angle.
pub const WRIST_FLEXION_DEG: f64 = 15.0;

/// Radial or ulnar deviation beyond this is scored as deviated \[deg\]: RULA adds a point for a
/// wrist "bent from the midline", REBA for one "deviated or twisted"; neither gives an angle, so
/// 10° is an ASSUMPTION (what an observer would not see), the threshold posture-opt's RULA and
/// REBA scoring uses.
pub const WRIST_DEVIATION_DEG: f64 = 10.0;

/// Side bending of the head against the trunk beyond this is not acceptable \[deg\]: ISO 11226:2000
/// and EN 1005-4 (neutral zone ±10°, as applied e.g. by Occup Med 2020, doi:10.1186/s12995-020-00286-9,
/// Table 2); RULA and REBA add a point for a side-bent neck.
pub const NECK_SIDE_BEND_DEG: f64 = 10.0;

/// Axial rotation of the head against the trunk beyond this is held to be too much \[deg\].
/// ASSUMPTION: 45°, about half the active cervical rotation range (70–90° each way in clinical
/// norms); secondary summaries of ISO 11226 give this figure as its limit for the head's axial
/// rotation, which we could not check against the standard's text. RULA and REBA add a point for
/// a twisted neck without an angle. It matters once the worker looks at the work: looking to
/// the side is a neck twist unless the feet or the trunk turn.
pub const NECK_TWIST_DEG: f64 = 45.0;

/// The upper arm of a free hand (one with no target in the phase) is kept within this angle of
/// hanging straight down \[deg\]. The task format says a free hand hangs, unloaded; without this
/// limit the plans swung the free arm 25–60° back and out as a counterweight (shelf's 'pick from
/// cart': the left upper arm 32° behind the trunk and 22° out, 60° from the vertical, at the
/// standards' movement limit), since spreading the load over more muscle groups lowers the sum of
/// their fatigue; no ergonomist would plan that (secondary summaries of ISO 11226:2000 list
/// upper-arm retroflexion among the arm positions it does not accept; we could not check the
/// standard's text). ASSUMPTION: 10°, as the trunk's side bending and
/// twist, what an observer would not see; a planner limit, not a standard's: it is not reported
/// as a zone excess (the standards' 20° from ISO 11226 Fig. 3 is).
pub const FREE_ARM_DEG: f64 = 10.0;

/// Number of zone rows per phase.
pub const ZONE_ROWS: usize = 25;

/// Penalty of one radian beyond a zone, in the objective's units (its fatigue term is the
/// logarithm of the total fatigue index, so 10 makes a degree beyond a zone cost as much as
/// about 19 % more fatigue). ASSUMPTION: large enough that no fatigue saving the shipped tasks
/// offer buys a posture outside a zone the layout allows (measured: docs/results.md), small
/// enough to keep the QP well scaled.
pub const ZONE_PENALTY_PER_RAD: f64 = 10.0;

/// A static hold is longer than this \[s\] (ISO 11226, EN 1005-4).
pub const STATIC_HOLD_S: f64 = 4.0;

/// A zone acceptable held up to a maximum holding time that falls linearly with the angle, from
/// `from_min` minutes at `from_deg` to `to_min` at `to_deg` (beyond `to_deg` not acceptable held;
/// ISO 11226:2000 step 2, as secondary sources reproduce its figures: the original figures were
/// not available to check here).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HoldingTime {
    pub from_deg: f64,
    pub to_deg: f64,
    pub from_min: f64,
    pub to_min: f64,
}

impl HoldingTime {
    /// The maximum acceptable holding time \[s\] at `angle_deg` (the longest below the line's
    /// start, the shortest beyond its end).
    pub fn max_hold_s(&self, angle_deg: f64) -> f64 {
        let x = ((angle_deg - self.from_deg) / (self.to_deg - self.from_deg)).clamp(0.0, 1.0);
        60.0 * (self.from_min + x * (self.to_min - self.from_min))
    }

    /// The largest angle \[deg\] that may be held for `hold_s` (the line read the other way:
    /// `to_deg` up to the shortest time, `from_deg` from the longest).
    pub fn largest_angle_deg(&self, hold_s: f64) -> f64 {
        let t_min = hold_s / 60.0;
        let x = ((self.from_min - t_min) / (self.from_min - self.to_min)).clamp(0.0, 1.0);
        self.from_deg + (self.to_deg - self.from_deg) * x
    }
}

/// ISO 11226 Figure 2 (trunk inclination): 4 min at 20° to 1 min at 60°.
pub const TRUNK_HOLD: HoldingTime = HoldingTime {
    from_deg: 20.0,
    to_deg: 60.0,
    from_min: 4.0,
    to_min: 1.0,
};

/// ISO 11226 Figure 3 (upper-arm elevation): 3 min at 20° to 1 min at 60°.
pub const ARM_HOLD: HoldingTime = HoldingTime {
    from_deg: 20.0,
    to_deg: 60.0,
    from_min: 3.0,
    to_min: 1.0,
};

/// ISO 11226 (head inclination, step 2): 8 min at 25° to 1 min at 85° (reproduced as 25° 8 min,
/// 45° 5 min 40 s, 65° 3 min 20 s, 85° 1 min in ergonomiesite.be's summary of NBN ISO 11226).
pub const HEAD_HOLD: HoldingTime = HoldingTime {
    from_deg: 25.0,
    to_deg: 85.0,
    from_min: 8.0,
    to_min: 1.0,
};

/// One zone row.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Zone {
    TrunkInclination,
    TrunkBack,
    TrunkSideLeft,
    TrunkSideRight,
    TwistLeft,
    TwistRight,
    RightUpperArm,
    LeftUpperArm,
    HeadInclination,
    HeadBack,
    NeckFlexion,
    NeckSideLeft,
    NeckSideRight,
    NeckTwistLeft,
    NeckTwistRight,
    RightWristFlexed,
    RightWristExtended,
    RightWristRadial,
    RightWristUlnar,
    LeftWristFlexed,
    LeftWristExtended,
    LeftWristRadial,
    LeftWristUlnar,
    TurnLeft,
    TurnRight,
}

impl Zone {
    pub const ALL: [Zone; ZONE_ROWS] = [
        Zone::TrunkInclination,
        Zone::TrunkBack,
        Zone::TrunkSideLeft,
        Zone::TrunkSideRight,
        Zone::TwistLeft,
        Zone::TwistRight,
        Zone::RightUpperArm,
        Zone::LeftUpperArm,
        Zone::HeadInclination,
        Zone::HeadBack,
        Zone::NeckFlexion,
        Zone::NeckSideLeft,
        Zone::NeckSideRight,
        Zone::NeckTwistLeft,
        Zone::NeckTwistRight,
        Zone::RightWristFlexed,
        Zone::RightWristExtended,
        Zone::RightWristRadial,
        Zone::RightWristUlnar,
        Zone::LeftWristFlexed,
        Zone::LeftWristExtended,
        Zone::LeftWristRadial,
        Zone::LeftWristUlnar,
        Zone::TurnLeft,
        Zone::TurnRight,
    ];

    /// What the zone limits, in words ("trunk twisted to the left").
    pub fn words(self) -> &'static str {
        match self {
            Zone::TrunkInclination => "trunk inclined forward from the vertical",
            Zone::TrunkBack => "trunk leaning back",
            Zone::TrunkSideLeft => "trunk bent to the left",
            Zone::TrunkSideRight => "trunk bent to the right",
            Zone::TwistLeft => "trunk twisted to the left",
            Zone::TwistRight => "trunk twisted to the right",
            Zone::RightUpperArm => "right upper arm raised from the vertical",
            Zone::LeftUpperArm => "left upper arm raised from the vertical",
            Zone::HeadInclination => "head inclined forward from the vertical",
            Zone::HeadBack => "head tilted back",
            Zone::NeckFlexion => "neck flexed against the trunk",
            Zone::NeckSideLeft => "head bent to the left against the trunk",
            Zone::NeckSideRight => "head bent to the right against the trunk",
            Zone::NeckTwistLeft => "head turned to the left against the trunk",
            Zone::NeckTwistRight => "head turned to the right against the trunk",
            Zone::RightWristFlexed => "right wrist flexed",
            Zone::RightWristExtended => "right wrist extended",
            Zone::RightWristRadial => "right wrist bent toward the thumb (radial deviation)",
            Zone::RightWristUlnar => "right wrist bent toward the little finger (ulnar deviation)",
            Zone::LeftWristFlexed => "left wrist flexed",
            Zone::LeftWristExtended => "left wrist extended",
            Zone::LeftWristRadial => "left wrist bent toward the thumb (radial deviation)",
            Zone::LeftWristUlnar => "left wrist bent toward the little finger (ulnar deviation)",
            Zone::TurnLeft => "trunk turned to the left of the feet",
            Zone::TurnRight => "trunk turned to the right of the feet",
        }
    }

    /// The standard the limit comes from.
    pub fn source(self, movement: bool) -> &'static str {
        match (self, movement) {
            // ISO 11226's static limits, which the planner keeps in movements too
            (Zone::HeadInclination | Zone::HeadBack | Zone::NeckFlexion, false) => "ISO 11226",
            (Zone::HeadInclination | Zone::HeadBack | Zone::NeckFlexion, true) => {
                "ISO 11226's static limit, kept in movements too"
            }
            (Zone::NeckSideLeft | Zone::NeckSideRight, _) => "ISO 11226; EN 1005-4",
            (Zone::NeckTwistLeft | Zone::NeckTwistRight, _) => "ASSUMPTION (45°)",
            (
                Zone::RightWristFlexed
                | Zone::RightWristExtended
                | Zone::LeftWristFlexed
                | Zone::LeftWristExtended,
                _,
            ) => "RULA; REBA",
            (
                Zone::RightWristRadial
                | Zone::RightWristUlnar
                | Zone::LeftWristRadial
                | Zone::LeftWristUlnar,
                _,
            ) => "RULA",
            (_, true) => "EN 1005-4",
            (_, false) => "ISO 11226",
        }
    }
}

/// The largest angle of each zone \[rad\] for one phase.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ZoneLimits {
    pub max_rad: [f64; ZONE_ROWS],
    /// Whether the limits are those of a movement (a hold of at most 4 s).
    pub movement: bool,
}

impl ZoneLimits {
    /// The limits for a posture held `hold_s` seconds without a break.
    pub fn for_hold(hold_s: f64) -> Self {
        let movement = hold_s <= STATIC_HOLD_S;
        let (trunk, arm) = if movement {
            (60.0, 60.0)
        } else {
            (
                TRUNK_HOLD.largest_angle_deg(hold_s),
                ARM_HOLD.largest_angle_deg(hold_s),
            )
        };
        let head = HEAD_HOLD.largest_angle_deg(hold_s);
        let back = ISO_BACKWARD_TOLERANCE_DEG;
        let (w, d) = (WRIST_FLEXION_DEG, WRIST_DEVIATION_DEG);
        let (ns, nt) = (NECK_SIDE_BEND_DEG, NECK_TWIST_DEG);
        let deg = [
            trunk, back, 10.0, 10.0, 10.0, 10.0, arm, arm, head, back, 25.0, ns, ns, nt, nt, w, w,
            d, d, w, w, d, d, 10.0, 10.0,
        ];
        ZoneLimits {
            max_rad: deg.map(f64::to_radians),
            movement,
        }
    }

    /// The same with the upper arm of each free hand (right, left) held within [`FREE_ARM_DEG`]
    /// of hanging straight down.
    pub fn with_free_arms_hanging(&self, free: [bool; 2]) -> Self {
        let mut z = *self;
        for (zone, free) in [Zone::RightUpperArm, Zone::LeftUpperArm]
            .into_iter()
            .zip(free)
        {
            let i = zone as usize;
            if free {
                z.max_rad[i] = z.max_rad[i].min(FREE_ARM_DEG.to_radians());
            }
        }
        z
    }

    /// The tighter of two phases' limits (phases sharing one posture).
    pub fn tighter(&self, other: &ZoneLimits) -> Self {
        let mut max_rad = self.max_rad;
        for (a, b) in max_rad.iter_mut().zip(other.max_rad) {
            *a = a.min(b);
        }
        ZoneLimits {
            max_rad,
            movement: self.movement && other.movement,
        }
    }
}

/// A zone a planned posture goes beyond.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Excess {
    pub zone: Zone,
    pub angle_deg: f64,
    pub limit_deg: f64,
}

/// The links the zones are measured on (the generated worker's).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Frames {
    pelvis: usize,
    trunk: usize,
    head: usize,
    upper: [usize; 2],
    fore: [usize; 2],
    /// q indices of each wrist's flexion and deviation joints (right, left).
    wrist: [[usize; 2]; 2],
    /// q index of the neck's twist joint.
    neck_twist: usize,
    /// The feet's links (right, left), where the body has them.
    feet: [Option<usize>; 2],
}

impl Frames {
    fn angles_rad(&self, model: &BodyModel, data: &StaticsData, q: &[f64]) -> [f64; ZONE_ROWS] {
        let f = self;
        let (r_pelvis, _) = data.link_pose(model, f.pelvis);
        let (r_trunk, _) = data.link_pose(model, f.trunk);
        let (r_head, _) = data.link_pose(model, f.head);
        let fwd = crate::body::heading::pelvis_forward(&r_pelvis);
        let left = Vector3::z().cross(&fwd);
        let a = r_trunk * Vector3::z();
        let trunk = a.dot(&fwd).atan2(a.z);
        let side = a.dot(&left).clamp(-1.0, 1.0).asin();
        let rel = nalgebra::UnitQuaternion::from_matrix(&(r_pelvis.transpose() * r_trunk));
        let twist = crate::body::stance::wrap_pi(2.0 * rel.k.atan2(rel.w));
        // the pelvis's heading against the feet's mean heading (0 without the feet's links)
        let feet = f.feet.iter().flatten().map(|&l| data.link_pose(model, l).0);
        let pelvis_turn = crate::body::heading::pelvis_turn_rad(&r_pelvis, feet);
        let turn = twist + pelvis_turn;
        let h = crate::body::head::HeadAngles::measure(&r_trunk, &r_head);
        let (head, neck, neck_side) = (h.inclination_rad, h.neck_flexion_rad, h.neck_side_bend_rad);
        let nt = q[f.neck_twist];
        let o = Vector3::zeros();
        let arm = |i: usize| {
            let s = data.link_point(model, f.upper[i], &o);
            let e = data.link_point(model, f.fore[i], &o);
            (-(e - s).normalize().z).clamp(-1.0, 1.0).acos()
        };
        let [[rf, rd], [lf, ld]] = f.wrist;
        [
            trunk,
            -trunk,
            side,
            -side,
            twist,
            -twist,
            arm(0),
            arm(1),
            head,
            -head,
            neck,
            neck_side,
            -neck_side,
            nt,
            -nt,
            q[rf],
            -q[rf],
            q[rd],
            -q[rd],
            q[lf],
            -q[lf],
            q[ld],
            -q[ld],
            turn,
            -turn,
        ]
    }

    /// The rows `g ≤ 0` (radians beyond each limit, to first order) at the posture whose forward
    /// kinematics `data` holds. The arms' rows are `(cos L − cos θ)/sin L`, smooth where the arm
    /// hangs straight down.
    fn rows(
        &self,
        model: &BodyModel,
        data: &StaticsData,
        q: &[f64],
        limits: &ZoneLimits,
        out: &mut [f64; ZONE_ROWS],
    ) {
        let f = self;
        let ang = self.angles_rad(model, data, q);
        let o = Vector3::zeros();
        for (i, z) in Zone::ALL.iter().enumerate() {
            let lim = limits.max_rad[i];
            out[i] = match z {
                Zone::RightUpperArm | Zone::LeftUpperArm => {
                    let side = usize::from(*z == Zone::LeftUpperArm);
                    let s = data.link_point(model, f.upper[side], &o);
                    let e = data.link_point(model, f.fore[side], &o);
                    let c = -(e - s).normalize().z;
                    (lim.cos() - c) / lim.sin().max(1e-6)
                }
                _ => ang[i] - lim,
            };
        }
    }
}

/// Evaluates the zone rows of a posture and their gradients (central differences of the forward
/// kinematics over the joints that move the measured links), without allocating.
#[derive(Debug, Clone)]
pub struct ZoneWork {
    frames: Frames,
    data: StaticsData,
    q: Vec<f64>,
    /// q indices of the joints that move a measured link.
    moving: Vec<usize>,
}

/// Central-difference step \[rad or m\].
const FD_STEP: f64 = 1e-6;

impl ZoneWork {
    /// `None` for a body that is not the generated worker (no pelvis, trunk, head and arms).
    pub fn new(model: &BodyModel) -> Option<Self> {
        let link = |n: &str| model.frame_link(n).ok();
        let frames = Frames {
            pelvis: link("pelvis")?,
            trunk: link("trunk")?,
            head: link("head")?,
            upper: [link("r_upper_arm")?, link("l_upper_arm")?],
            fore: [link("r_forearm")?, link("l_forearm")?],
            wrist: [
                [
                    model.q_index("r_wrist_flexion").ok()?,
                    model.q_index("r_wrist_deviation").ok()?,
                ],
                [
                    model.q_index("l_wrist_flexion").ok()?,
                    model.q_index("l_wrist_deviation").ok()?,
                ],
            ],
            neck_twist: model.q_index("neck_axial_rotation").ok()?,
            feet: [link(RIGHT_FOOT_LINK), link(LEFT_FOOT_LINK)],
        };
        let links = [
            frames.pelvis,
            frames.trunk,
            frames.head,
            frames.upper[0],
            frames.upper[1],
            frames.fore[0],
            frames.fore[1],
        ]
        .into_iter()
        .chain(frames.feet.into_iter().flatten())
        .collect::<Vec<_>>();
        let moving = (0..model.nq())
            .filter(|&k| {
                let j = model.joint_of_q[k];
                links.iter().any(|&l| model.moves_link(j, l))
            })
            .collect();
        Some(ZoneWork {
            frames,
            data: StaticsData::new(model, 0),
            q: vec![0.0; model.nq()],
            moving,
        })
    }

    /// The angles \[rad\] of each zone (the value its limit bounds) at the posture whose forward
    /// kinematics `data` holds.
    pub fn angles_rad(&self, model: &BodyModel, data: &StaticsData, q: &[f64]) -> [f64; ZONE_ROWS] {
        self.frames.angles_rad(model, data, q)
    }

    /// The rows `g ≤ 0` (radians beyond each limit, to first order) at the posture whose forward
    /// kinematics `data` holds. The arms' rows are `(cos L − cos θ)/sin L`, smooth where the arm
    /// hangs straight down.
    pub fn rows(
        &self,
        model: &BodyModel,
        data: &StaticsData,
        q: &[f64],
        limits: &ZoneLimits,
        out: &mut [f64; ZONE_ROWS],
    ) {
        self.frames.rows(model, data, q, limits, out)
    }

    /// The rows at `q` and their gradients: `grad[i][k] = ∂g_i/∂q_k` (zero for joints that move
    /// no measured link).
    pub fn rows_and_gradients(
        &mut self,
        model: &BodyModel,
        q: &[f64],
        limits: &ZoneLimits,
        g: &mut [f64; ZONE_ROWS],
        grad: &mut [Vec<f64>; ZONE_ROWS],
    ) {
        self.q.copy_from_slice(q);
        forward_kinematics(model, &mut self.data, &self.q);
        self.frames.rows(model, &self.data, q, limits, g);
        for row in grad.iter_mut() {
            row.iter_mut().for_each(|v| *v = 0.0);
        }
        let (mut plus, mut minus) = ([0.0; ZONE_ROWS], [0.0; ZONE_ROWS]);
        for idx in 0..self.moving.len() {
            let k = self.moving[idx];
            self.q[k] = q[k] + FD_STEP;
            forward_kinematics(model, &mut self.data, &self.q);
            self.frames
                .rows(model, &self.data, &self.q, limits, &mut plus);
            self.q[k] = q[k] - FD_STEP;
            forward_kinematics(model, &mut self.data, &self.q);
            self.frames
                .rows(model, &self.data, &self.q, limits, &mut minus);
            self.q[k] = q[k];
            for i in 0..ZONE_ROWS {
                grad[i][k] = (plus[i] - minus[i]) / (2.0 * FD_STEP);
            }
        }
        // the wrist rows are ± a joint angle (the wrists move no measured link; the neck's twist
        // moves the head, so the loop above has its rows)
        let first = Zone::ALL
            .iter()
            .position(|z| *z == Zone::RightWristFlexed)
            .unwrap_or(ZONE_ROWS);
        for (side, joints) in self.frames.wrist.iter().enumerate() {
            for (j, &k) in joints.iter().enumerate() {
                let i = first + 4 * side + 2 * j;
                grad[i][k] = 1.0;
                grad[i + 1][k] = -1.0;
            }
        }
    }

    /// The sum of the rows' violations \[rad\] at `q` (its own forward kinematics).
    pub fn violation_rad(&mut self, model: &BodyModel, q: &[f64], limits: &ZoneLimits) -> f64 {
        self.q.copy_from_slice(q);
        forward_kinematics(model, &mut self.data, &self.q);
        let mut g = [0.0; ZONE_ROWS];
        self.frames.rows(model, &self.data, q, limits, &mut g);
        g.iter().map(|v| v.max(0.0)).sum()
    }

    /// The zones posture `q` goes beyond by more than `tolerance_deg` (its own forward
    /// kinematics).
    pub fn excesses_at(
        &mut self,
        model: &BodyModel,
        q: &[f64],
        limits: &ZoneLimits,
        tolerance_deg: f64,
    ) -> Vec<Excess> {
        self.q.copy_from_slice(q);
        forward_kinematics(model, &mut self.data, &self.q);
        self.excesses(model, &self.data, q, limits, tolerance_deg)
    }

    /// The zones the posture whose forward kinematics `data` holds goes beyond by more than
    /// `tolerance_deg`.
    pub fn excesses(
        &self,
        model: &BodyModel,
        data: &StaticsData,
        q: &[f64],
        limits: &ZoneLimits,
        tolerance_deg: f64,
    ) -> Vec<Excess> {
        let ang = self.angles_rad(model, data, q);
        Zone::ALL
            .iter()
            .enumerate()
            .filter(|&(i, _)| (ang[i] - limits.max_rad[i]).to_degrees() > tolerance_deg)
            .map(|(i, &zone)| Excess {
                zone,
                angle_deg: ang[i].to_degrees(),
                limit_deg: limits.max_rad[i].to_degrees(),
            })
            .collect()
    }
}

/// Each phase's zone limits from its hold ([`Task::holds`]): the standards' limits, which the
/// plan reports excesses against.
pub fn phase_limits(task: &Task) -> Vec<ZoneLimits> {
    task.holds()
        .iter()
        .map(|&(hold_s, _)| ZoneLimits::for_hold(hold_s))
        .collect()
}

/// Each phase's limits as the planner keeps them: the standards' ([`phase_limits`]) with the
/// upper arm of a free hand (no target in the phase) held within [`FREE_ARM_DEG`] of hanging.
pub fn planning_limits(task: &Task) -> Vec<ZoneLimits> {
    phase_limits(task)
        .into_iter()
        .zip(&task.phases)
        .map(|(z, ph)| z.with_free_arms_hanging(ph.targets_m.each_ref().map(Option::is_none)))
        .collect()
}
