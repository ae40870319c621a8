//! Muscle fatigue models, per muscle group (half-joint), in normalised form.
//!
//! Conventions (used across the crate):
//! * relative load `f = F_load / MVC` (or `τ / MVC_τ` for a joint torque), dimensionless in [0, 1];
//! * capacity `c = F_cem / MVC` in (0, 1], 1 when rested;
//! * fatigue index `U` in minutes (Ma et al. 2009, Eq. 1), 0 when rested;
//! * time in seconds (`dt_s`); rates quoted per minute carry `_per_min` and are converted in
//!   [`units`] only.

pub mod dual;
pub mod fit;
pub mod held_load;
pub mod ma;
pub mod met_models;
pub mod params;
pub mod schedule;
pub mod stats;
pub mod three_compartment;
pub mod units;

pub use held_load::{HeldLoad, MetReport, met_report};
pub use ma::{
    CurvePoint, FatigueError, MaParams, MaState, PreparedHold, Recovery, hold_all, met_min,
    step_exact,
};
pub use three_compartment::{Region, ThreeCompartment, ThreeCompartmentState};

/// A fatigue model behind one interface: hold a relative load for a while, read capacity and U.
pub trait FatigueModel {
    type State: Copy;
    /// State of a rested muscle group.
    fn fresh(&self) -> Self::State;
    /// Holds relative load `f` for `dt_s` seconds; `false` if the state no longer fits in doubles
    /// (a group held far past exhaustion).
    fn hold(&self, state: &mut Self::State, f: f64, dt_s: f64) -> bool;
    /// Capacity in (0, 1].
    fn capacity(&self, state: &Self::State) -> f64;
    /// Fatigue index U \[min\].
    fn fatigue_u_min(&self, state: &Self::State) -> f64;
    /// Endurance time \[s\] of a rested muscle group holding `f`; `None` if unlimited.
    fn endurance_time_s(&self, f: f64) -> Option<f64>;
}

impl FatigueModel for MaParams {
    type State = MaState;
    fn fresh(&self) -> MaState {
        MaState::FRESH
    }
    fn hold(&self, state: &mut MaState, f: f64, dt_s: f64) -> bool {
        MaParams::hold(self, state, f, dt_s)
    }
    fn capacity(&self, state: &MaState) -> f64 {
        state.capacity
    }
    fn fatigue_u_min(&self, state: &MaState) -> f64 {
        state.fatigue_u_min
    }
    fn endurance_time_s(&self, f: f64) -> Option<f64> {
        self.time_to_exhaustion_s(1.0, f)
    }
}

impl FatigueModel for ThreeCompartment {
    type State = ThreeCompartmentState;
    fn fresh(&self) -> ThreeCompartmentState {
        ThreeCompartmentState::FRESH
    }
    fn hold(&self, state: &mut ThreeCompartmentState, f: f64, dt_s: f64) -> bool {
        ThreeCompartment::hold(self, state, f, dt_s);
        state.fatigue_u_min.is_finite()
    }
    fn capacity(&self, state: &ThreeCompartmentState) -> f64 {
        state.capacity()
    }
    fn fatigue_u_min(&self, state: &ThreeCompartmentState) -> f64 {
        state.fatigue_u_min
    }
    fn endurance_time_s(&self, f: f64) -> Option<f64> {
        ThreeCompartment::endurance_time_s(self, f)
    }
}
