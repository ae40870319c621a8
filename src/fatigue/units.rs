//! The one place where minutes meet seconds.
//!
//! Everything inside posture-opt runs in SI seconds. The paper's fatigue rate `k` and our recovery
//! rate `R` are quoted per minute, and its fatigue index `U` is in minutes (Ma et al. 2009,
//! Table 1); those quantities carry `_per_min` / `_min` in their names and are converted here.

/// Seconds in one minute.
pub const SECONDS_PER_MINUTE: f64 = 60.0;

/// Converts a duration in seconds to minutes.
#[inline]
pub fn s_to_min(t_s: f64) -> f64 {
    t_s / SECONDS_PER_MINUTE
}

/// Converts a duration in minutes to seconds.
#[inline]
pub fn min_to_s(t_min: f64) -> f64 {
    t_min * SECONDS_PER_MINUTE
}
