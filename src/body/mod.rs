//! The body: a URDF kinematic tree ([`BodyModel`], immutable), its statics workspace
//! ([`StaticsData`]), standing on two feet ([`stance`]), half-joint strength, and the generated
//! default worker.
//!
//! Frames and signs: see [`statics`]. Half-joint ids are `JOINT+` (the muscle group that
//! produces positive torque about the joint) and `JOINT-`.

pub mod head;
pub mod heading;
pub mod model;
pub mod report;
pub mod seat;
pub mod stance;
pub mod statics;
pub mod strength;
pub mod worker;

pub use model::{BodyError, BodyModel, Capsule, Joint, JointKind, Link, LinkBox};
pub use report::{StaticsReport, statics_report};
pub use stance::{Foot, GroundReaction, Stance, ground_reaction};
pub use statics::{
    GRAVITY_M_S2, PointLoad, StaticsData, apply_loads, forward_kinematics,
    holding_torque_derivative, holding_torques, mass_moments,
};
pub use strength::{Direction, HalfJoint, StrengthError, StrengthTable, resolve_half_joints};
pub use worker::{Sex, Worker, WorkerError, worker_urdf};
