//! The body: a URDF kinematic tree ([`BodyModel`], immutable), its statics workspace
//! ([`StaticsData`]), standing on two feet ([`stance`]), half-joint strength, and the generated
//! default worker.
//!
//! Frames and signs: see [`statics`]. Half-joint ids are `JOINT+` (the muscle group that
//! produces positive torque about the joint) and `JOINT-`.

pub mod model;
pub mod report;
pub mod stance;
pub mod statics;
pub mod strength;
pub mod worker;

pub use model::{BodyError, BodyModel, Capsule, Joint, JointKind, Link, LinkBox};
pub use report::{statics_report, StaticsReport};
pub use stance::{ground_reaction, Foot, GroundReaction, Stance};
pub use statics::{
    apply_loads, forward_kinematics, holding_torque_derivative, holding_torques, mass_moments,
    PointLoad, StaticsData, GRAVITY_M_S2,
};
pub use strength::{resolve_half_joints, Direction, HalfJoint, StrengthError, StrengthTable};
pub use worker::{worker_urdf, Sex, Worker, WorkerError};
