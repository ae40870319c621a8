//! The body: a URDF kinematic tree ([`BodyModel`], immutable), its statics workspace
//! ([`StaticsData`]), half-joint strength, and the generated default worker.
//!
//! Frames and signs: see [`statics`]. Half-joint ids are `JOINT+` (the muscle group that
//! produces positive torque about the joint axis) and `JOINT-`.

pub mod model;
pub mod report;
pub mod statics;
pub mod strength;
pub mod worker;

pub use model::{BodyError, BodyModel, Capsule, Joint, JointKind, Link};
pub use report::{statics_report, StaticsReport};
pub use statics::{
    forward_kinematics, holding_torque_derivative, holding_torques, StaticsData, GRAVITY_M_S2,
};
pub use strength::{resolve_half_joints, Direction, HalfJoint, StrengthError, StrengthTable};
pub use worker::{worker_urdf, Sex, Worker, WorkerError};
