//! Named fatigue parameter sets: k per body region and the recovery form, with sources and the
//! ranges the uncertainty analysis varies. The sets ship in `data/fatigue_sets.yaml`
//! (documented in `docs/fatigue-parameters.md`).

use super::ma::{FatigueError, MaParams, Recovery};
use crate::body::Sex;
use serde::{Deserialize, Serialize};

/// The shipped sets.
pub const SETS_YAML: &str = include_str!("../../data/fatigue_sets.yaml");

/// k of one region \[1/min\] with its range.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RegionK {
    pub k: f64,
    pub k_low: f64,
    pub k_high: f64,
}

/// The recovery of a set, with ranges.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "form", rename_all = "snake_case", deny_unknown_fields)]
pub enum RecoverySpec {
    None,
    Perfusion {
        rest_per_min: f64,
        rest_low: f64,
        rest_high: f64,
        limit_fmvc: f64,
        limit_low: f64,
        limit_high: f64,
    },
    /// Two deficits ([`Recovery::Routed`]): the slow deficit's rate and the limit load with their
    /// ranges (the uncertainty analysis varies them as the perfusion form's), the fast deficit's
    /// rate and its largest share of new fatigue at their values.
    Routed {
        rest_per_min: f64,
        rest_low: f64,
        rest_high: f64,
        limit_fmvc: f64,
        limit_low: f64,
        limit_high: f64,
        fast_rest_per_min: f64,
        fast_share_max: f64,
    },
}

impl RecoverySpec {
    /// The recovery at the set's values.
    pub fn recovery(&self) -> Recovery {
        match *self {
            RecoverySpec::None => Recovery::None,
            RecoverySpec::Perfusion {
                rest_per_min,
                limit_fmvc,
                ..
            } => Recovery::Perfusion {
                rest_per_min,
                limit_fmvc,
            },
            RecoverySpec::Routed {
                rest_per_min,
                limit_fmvc,
                fast_rest_per_min,
                fast_share_max,
                ..
            } => Recovery::Routed {
                slow_rest_per_min: rest_per_min,
                fast_rest_per_min,
                limit_fmvc,
                fast_share_max,
            },
        }
    }

    /// `(rest, rest_low, rest_high, limit, limit_low, limit_high)` of the perfusion-limited forms.
    pub fn ranges(&self) -> Option<(f64, f64, f64, f64, f64, f64)> {
        match *self {
            RecoverySpec::None => None,
            RecoverySpec::Perfusion {
                rest_per_min,
                rest_low,
                rest_high,
                limit_fmvc,
                limit_low,
                limit_high,
            }
            | RecoverySpec::Routed {
                rest_per_min,
                rest_low,
                rest_high,
                limit_fmvc,
                limit_low,
                limit_high,
                ..
            } => Some((
                rest_per_min,
                rest_low,
                rest_high,
                limit_fmvc,
                limit_low,
                limit_high,
            )),
        }
    }
}

/// One named set.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParameterSet {
    pub name: String,
    pub description: String,
    pub recovery: RecoverySpec,
    /// Where this set's recovery values come from, when not the shipped sets' common sources.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub recovery_source: Option<String>,
    pub k_source: String,
    pub regions: std::collections::BTreeMap<String, RegionK>,
    /// Region values that differ for women / men.
    #[serde(default)]
    pub female: std::collections::BTreeMap<String, RegionK>,
    #[serde(default)]
    pub male: std::collections::BTreeMap<String, RegionK>,
    /// Regions missing from `regions` take the `general` region's k. Off by default: a set read
    /// from a file must then list every region ([`super::fit::REGIONS`]).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub unlisted_regions_use_general: bool,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct SetsFile {
    default_set: String,
    sets: Vec<ParameterSet>,
    recovery_sources: std::collections::BTreeMap<String, String>,
}

/// All shipped sets.
#[derive(Debug, Clone, PartialEq)]
pub struct ParameterSets {
    pub default_set: String,
    pub sets: Vec<ParameterSet>,
    pub recovery_sources: std::collections::BTreeMap<String, String>,
}

impl ParameterSets {
    /// The shipped sets (`data/fatigue_sets.yaml`).
    pub fn shipped() -> Self {
        let f: SetsFile =
            serde_saphyr::from_str(SETS_YAML).expect("the shipped parameter sets parse");
        ParameterSets {
            default_set: f.default_set,
            sets: f.sets,
            recovery_sources: f.recovery_sources,
        }
    }

    /// A set by name.
    pub fn get(&self, name: &str) -> Option<&ParameterSet> {
        self.sets.iter().find(|s| s.name == name)
    }

    /// Names of all sets.
    pub fn names(&self) -> Vec<&str> {
        self.sets.iter().map(|s| s.name.as_str()).collect()
    }
}

impl ParameterSet {
    /// Reads and checks a parameter set written as YAML (e.g. by `posture-opt fit`): every
    /// region known, every k and its range within the model's limits (low ≤ value ≤ high), the
    /// recovery's values within theirs. `origin` names the text in messages.
    pub fn from_yaml_str(text: &str, origin: &str) -> Result<Self, String> {
        use super::ma::{K_MAX_PER_MIN, K_MIN_PER_MIN, R_MAX_PER_MIN};
        let set: ParameterSet =
            serde_saphyr::from_str(text).map_err(|e| format!("{origin}: {e}"))?;
        let known = super::fit::REGIONS;
        let k_ok = |v: f64| v.is_finite() && (K_MIN_PER_MIN..=K_MAX_PER_MIN).contains(&v);
        for (scope, map) in [
            ("regions", &set.regions),
            ("female", &set.female),
            ("male", &set.male),
        ] {
            for (name, r) in map {
                if !known.contains(&name.as_str()) {
                    return Err(format!(
                        "{origin}: {scope}.{name} is not a body region ({}){}",
                        known.join(", "),
                        crate::schema::did_you_mean(name, known.iter().copied())
                    ));
                }
                if !(k_ok(r.k)
                    && k_ok(r.k_low)
                    && k_ok(r.k_high)
                    && r.k_low <= r.k
                    && r.k <= r.k_high)
                {
                    return Err(format!(
                        "{origin}: {scope}.{name}: need {K_MIN_PER_MIN} <= k_low <= k <= k_high <= {K_MAX_PER_MIN} 1/min, got {} <= {} <= {}",
                        r.k_low, r.k, r.k_high
                    ));
                }
            }
        }
        let missing: Vec<&str> = known
            .iter()
            .copied()
            .filter(|r| !set.regions.contains_key(*r))
            .collect();
        if !missing.is_empty() {
            if !set.unlisted_regions_use_general {
                return Err(format!(
                    "{origin}: regions: missing {} (a set lists every region: {}); or write `unlisted_regions_use_general: true` to give them the general region's k",
                    missing.join(", "),
                    known.join(", ")
                ));
            }
            if missing.contains(&"general") {
                return Err(format!(
                    "{origin}: regions: unlisted_regions_use_general needs the region general, which is missing"
                ));
            }
        }
        if let Some((rest_per_min, rest_low, rest_high, limit_fmvc, limit_low, limit_high)) =
            set.recovery.ranges()
        {
            let r_ok = |v: f64| v.is_finite() && (0.0..=R_MAX_PER_MIN).contains(&v);
            let l_ok = |v: f64| v.is_finite() && (0.01..=1.0).contains(&v);
            if !(r_ok(rest_per_min)
                && r_ok(rest_low)
                && r_ok(rest_high)
                && rest_low <= rest_per_min
                && rest_per_min <= rest_high)
            {
                return Err(format!(
                    "{origin}: recovery: need 0 <= rest_low <= rest_per_min <= rest_high <= {R_MAX_PER_MIN} 1/min"
                ));
            }
            if !(l_ok(limit_fmvc)
                && l_ok(limit_low)
                && l_ok(limit_high)
                && limit_low <= limit_fmvc
                && limit_fmvc <= limit_high)
            {
                return Err(format!(
                    "{origin}: recovery: need 0.01 <= limit_low <= limit_fmvc <= limit_high <= 1"
                ));
            }
        }
        if matches!(set.recovery, RecoverySpec::Routed { .. }) {
            // every variant the uncertainty analysis takes must be a valid routed recovery too
            for rest in [Bound::Low, Bound::Value, Bound::High] {
                for limit in [Bound::Low, Bound::Value, Bound::High] {
                    MaParams::with_recovery(1.0, set.recovery_at(rest, limit))
                        .map_err(|e| format!("{origin}: recovery: {e}"))?;
                }
            }
        }
        Ok(set)
    }
}

/// Where a parameter at one end of its range is taken, for the uncertainty analysis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Bound {
    Low,
    Value,
    High,
}

impl ParameterSet {
    /// k \[1/min\] for a region and sex at a bound of its range; "general" for unknown regions.
    pub fn k(&self, region: &str, sex: Sex, bound: Bound) -> f64 {
        let by_sex = match sex {
            Sex::Female => &self.female,
            Sex::Male => &self.male,
        };
        let r = by_sex
            .get(region)
            .or_else(|| self.regions.get(region))
            .or_else(|| self.regions.get("general"))
            .copied()
            .unwrap_or(RegionK {
                k: 1.0,
                k_low: 1.0,
                k_high: 1.0,
            });
        match bound {
            Bound::Low => r.k_low,
            Bound::Value => r.k,
            Bound::High => r.k_high,
        }
    }

    /// The recovery at bounds of its two parameters (rest rate, limit load).
    pub fn recovery_at(&self, rest: Bound, limit: Bound) -> Recovery {
        let Some((rest_per_min, rest_low, rest_high, limit_fmvc, limit_low, limit_high)) =
            self.recovery.ranges()
        else {
            return Recovery::None;
        };
        let rest_per_min = match rest {
            Bound::Low => rest_low,
            Bound::Value => rest_per_min,
            Bound::High => rest_high,
        };
        let limit_fmvc = match limit {
            Bound::Low => limit_low,
            Bound::Value => limit_fmvc,
            Bound::High => limit_high,
        };
        match self.recovery {
            RecoverySpec::Routed {
                fast_rest_per_min,
                fast_share_max,
                ..
            } => Recovery::Routed {
                slow_rest_per_min: rest_per_min,
                fast_rest_per_min,
                limit_fmvc,
                fast_share_max,
            },
            _ => Recovery::Perfusion {
                rest_per_min,
                limit_fmvc,
            },
        }
    }

    /// Parameters of a muscle group of `region` for a worker of `sex`, at the set's values.
    pub fn params(&self, region: &str, sex: Sex) -> Result<MaParams, FatigueError> {
        MaParams::with_recovery(self.k(region, sex, Bound::Value), self.recovery.recovery())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shipped_sets_parse_and_have_every_region() {
        let s = ParameterSets::shipped();
        assert!(s.get(&s.default_set).is_some());
        for set in &s.sets {
            for region in [
                "general", "trunk", "neck", "shoulder", "elbow", "grip", "hip", "knee", "ankle",
            ] {
                let k = set.k(region, Sex::Male, Bound::Value);
                assert!(k > 0.0 && set.k(region, Sex::Male, Bound::Low) <= k);
                assert!(
                    set.k(region, Sex::Female, Bound::High)
                        >= set.k(region, Sex::Female, Bound::Value)
                );
            }
        }
        let d = s.get("default-2026").unwrap();
        assert_eq!(d.k("elbow", Sex::Female, Bound::Value), 0.7376);
        assert_eq!(d.k("elbow", Sex::Male, Bound::Value), 1.0315);
        assert_eq!(d.k("shoulder", Sex::Female, Bound::Value), 1.3967);
    }
}
