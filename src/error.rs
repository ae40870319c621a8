//! The crate's error type: one variant family per module, combined here.

use crate::body::{BodyError, StrengthError, WorkerError};
use crate::fatigue::FatigueError;
use crate::validation::plots::PlotError;

/// Any error posture-opt reports.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    #[error(transparent)]
    Fatigue(#[from] FatigueError),
    #[error(transparent)]
    Body(#[from] BodyError),
    #[error(transparent)]
    Strength(#[from] StrengthError),
    #[error(transparent)]
    Worker(#[from] WorkerError),
    #[error(transparent)]
    Plot(#[from] PlotError),
}

impl Error {
    /// True when the user's input is at fault (exit code 2), false for internal failures (1).
    /// Every current variant is about input the user gave (parameters, files, output paths).
    pub fn is_bad_input(&self) -> bool {
        matches!(
            self,
            Error::Fatigue(_)
                | Error::Body(_)
                | Error::Strength(_)
                | Error::Worker(_)
                | Error::Plot(_)
        )
    }
}
