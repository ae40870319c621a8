//! The crate's error type: one variant family per module, combined here.

use crate::fatigue::FatigueError;
use crate::validation::plots::PlotError;

/// Any error posture-opt reports.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A parameter or load given to the fatigue models is invalid (bad input).
    #[error(transparent)]
    Fatigue(#[from] FatigueError),
    /// A figure could not be written.
    #[error(transparent)]
    Plot(#[from] PlotError),
}

impl Error {
    /// True when the user's input is at fault (exit code 2), false for internal failures (1).
    pub fn is_bad_input(&self) -> bool {
        match self {
            Error::Fatigue(_) => true,
            Error::Plot(_) => true,
        }
    }
}
