//! The Revised NIOSH Lifting Equation (RNLE): recommended weight limit (RWL), lifting index
//! (LI) and, for jobs made of several lifting tasks, the Composite Lifting Index (CLI).
//!
//! Sources:
//! * Waters TR, Putz-Anderson V, Garg A, Fine LJ (1993). Revised NIOSH equation for the design
//!   and evaluation of manual lifting tasks. *Ergonomics* 36(7):749–776.
//! * Waters TR, Putz-Anderson V, Garg A (1994). *Applications Manual for the Revised NIOSH
//!   Lifting Equation*. DHHS (NIOSH) Publication No. 94-110 (revised September 2021, which
//!   corrects typographical errors and keeps "the formulas, multipliers and limitations"
//!   of 1994). Page numbers below ("p. N") are the manual's printed pages.
//!
//! ```text
//! RWL = LC · HM · VM · DM · AM · FM · CM            LI = load / RWL
//! metric:    LC = 23 kg, HM = 25/H, VM = 1 − 0.003·|V − 75|, DM = 0.82 + 4.5/D   (cm)
//! customary: LC = 51 lb, HM = 10/H, VM = 1 − 0.0075·|V − 30|, DM = 0.82 + 1.8/D  (in)
//! both:      AM = 1 − 0.0032·A (deg), FM from Table 5, CM from Table 7
//! ```
//!
//! Inputs are SI (metres, kilograms, lifts per minute, degrees). By default the metric form of
//! the equation is evaluated ([`EquationForm::Metric`]); the manual's U.S.-customary form
//! ([`EquationForm::UsCustomary`]) is available because the two published constant sets are not
//! exact conversions of each other (51 lb = 23.13 kg, 10 in = 25.4 cm, 30 in = 76.2 cm) and the
//! manual's worked examples are all in the customary form.
//!
//! Out-of-range values are handled exactly as the manual prescribes (pp. 8–15), never refused:
//! * H below 25 cm (10 in) is set to 25 cm, so HM = 1; H above 63 cm (25 in) gives HM = 0.
//! * V above 175 cm (70 in, the upper limit of vertical reach) gives VM = 0.
//! * D below 25 cm (10 in) is set to 25 cm, so DM = 1; D above 175 cm (70 in) gives DM = 0.
//! * A above 135° gives AM = 0.
//! * F below 0.2 lifts/min is set to 0.2; F above the highest frequency of its Table 5 column
//!   that still has a non-zero multiplier gives FM = 0 ("Lifting above the maximum frequency
//!   results in a RWL of 0.0", p. 14).
//!
//! Every such substitution is listed in the result as an [`Adjustment`]. Only values that are
//! not physically meaningful are refused with a [`NioshError`]: non-finite numbers, negative
//! loads, distances or frequencies, V below the floor, |A| > 180°, a work duration of zero or
//! of more than 8 h ("No weight limits are provided for more than eight hours of work", p. 14).
//!
//! FM between two rows of Table 5 is interpolated linearly: "when the measured frequency is not
//! a whole number, the appropriate multiplier must be interpolated between the frequency values
//! in the table for the two values that are closest to the actual frequency" (p. 7; the manual's
//! Example 7 interpolates between 2 and 3 lifts/min). FM uses V at the **origin** of the lift
//! (p. 15), CM uses V at the point being evaluated (worksheet of Example 4, p. 46).
//!
//! The manual applies the equation only to two-handed, smooth lifting or lowering while
//! standing, for at most 8 h, with little carrying, holding, pushing or pulling, stable objects,
//! good foot–floor friction and a moderate environment (pp. 5–6). The caller is responsible for
//! those conditions; this module only evaluates the equation.

use serde::{Deserialize, Serialize};

/// Load constant of the metric form \[kg\]: the RWL under ideal conditions.
pub const LOAD_CONSTANT_KG: f64 = 23.0;
/// Load constant of the U.S.-customary form \[lb\].
pub const LOAD_CONSTANT_LB: f64 = 51.0;
/// Kilograms per avoirdupois pound (exact).
pub const KG_PER_LB: f64 = 0.453_592_37;
/// Metres per inch (exact).
pub const M_PER_IN: f64 = 0.0254;

/// Margin for comparing converted lengths and angles with the manual's limits, so that e.g.
/// 0.63 m is treated as exactly 63 cm despite floating-point conversion.
const LIMIT_EPS: f64 = 1e-9;

/// Frequencies \[lifts/min\] of the rows of Table 5 (p. 15); the first row is "≤ 0.2".
const FM_FREQ_PER_MIN: [f64; 17] = [
    0.2, 0.5, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0, 12.0, 13.0, 14.0, 15.0,
];

/// Table 5, Frequency Multiplier (p. 15). Columns: ≤1 h V<75 cm, ≤1 h V≥75 cm, ≤2 h V<75 cm,
/// ≤2 h V≥75 cm, ≤8 h V<75 cm, ≤8 h V≥75 cm. Frequencies above 15 lifts/min: 0.00.
const FM_TABLE: [[f64; 6]; 17] = [
    [1.00, 1.00, 0.95, 0.95, 0.85, 0.85],
    [0.97, 0.97, 0.92, 0.92, 0.81, 0.81],
    [0.94, 0.94, 0.88, 0.88, 0.75, 0.75],
    [0.91, 0.91, 0.84, 0.84, 0.65, 0.65],
    [0.88, 0.88, 0.79, 0.79, 0.55, 0.55],
    [0.84, 0.84, 0.72, 0.72, 0.45, 0.45],
    [0.80, 0.80, 0.60, 0.60, 0.35, 0.35],
    [0.75, 0.75, 0.50, 0.50, 0.27, 0.27],
    [0.70, 0.70, 0.42, 0.42, 0.22, 0.22],
    [0.60, 0.60, 0.35, 0.35, 0.18, 0.18],
    [0.52, 0.52, 0.30, 0.30, 0.00, 0.15],
    [0.45, 0.45, 0.26, 0.26, 0.00, 0.13],
    [0.41, 0.41, 0.00, 0.23, 0.00, 0.00],
    [0.37, 0.37, 0.00, 0.21, 0.00, 0.00],
    [0.00, 0.34, 0.00, 0.00, 0.00, 0.00],
    [0.00, 0.31, 0.00, 0.00, 0.00, 0.00],
    [0.00, 0.28, 0.00, 0.00, 0.00, 0.00],
];

/// Errors for inputs that the lifting equation cannot evaluate. Values that the manual handles
/// by a rule (e.g. H > 63 cm ⇒ HM = 0) are not errors; see the module documentation.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum NioshError {
    /// A number is NaN or infinite.
    #[error("{field} must be a finite number, got {value}")]
    NotFinite {
        /// Input field, e.g. `origin.h_m`.
        field: String,
        /// The value given.
        value: f64,
    },
    /// A load, distance, height or frequency is negative.
    #[error("{field} must be at least 0 {unit} ({meaning}), got {value}")]
    Negative {
        /// Input field, e.g. `destination.v_m`.
        field: String,
        /// Unit of the field.
        unit: &'static str,
        /// What the field measures.
        meaning: &'static str,
        /// The value given.
        value: f64,
    },
    /// An asymmetry angle outside −180…180°.
    #[error(
        "{field} must be between -180 and 180 deg (angle between the asymmetry line and the \
         mid-sagittal line; its sign is ignored), got {value}"
    )]
    AsymmetryOutOfRange {
        /// Input field, e.g. `origin.asymmetry_deg`.
        field: String,
        /// The value given.
        value: f64,
    },
    /// A work duration that has no NIOSH category.
    #[error(
        "duration_h must be more than 0 and at most 8 h (NIOSH gives no weight limits beyond \
         8 h of lifting), got {0}"
    )]
    DurationOutOfRange(f64),
    /// The maximum load is smaller than the average load.
    #[error("max_load_kg must be at least load_kg ({load_kg} kg), got {max_load_kg}")]
    MaxLoadBelowLoad {
        /// Average load given \[kg\].
        load_kg: f64,
        /// Maximum load given \[kg\].
        max_load_kg: f64,
    },
    /// [`composite`] was called without lifts.
    #[error("lifts must contain at least one lift for the composite lifting index, got none")]
    NoLifts,
    /// The lifts of a composite job have different work-duration categories.
    #[error(
        "lifts[{index}].duration is {found:?} but lifts[0].duration is {expected:?}: the \
         composite lifting index uses one work-duration category for the whole job"
    )]
    MixedDurations {
        /// Index of the first lift that differs.
        index: usize,
        /// Duration of lift 0.
        expected: WorkDuration,
        /// Duration of lift `index`.
        found: WorkDuration,
    },
    /// The lifts of a composite job use different forms of the equation.
    #[error(
        "lifts[{index}].form is {found:?} but lifts[0].form is {expected:?}: all lifts of a \
         job must use the same form of the equation"
    )]
    MixedForms {
        /// Index of the first lift that differs.
        index: usize,
        /// Form of lift 0.
        expected: EquationForm,
        /// Form of lift `index`.
        found: EquationForm,
    },
    /// An error in one lift of a composite job.
    #[error("lifts[{index}] ({name}): {source}")]
    InLift {
        /// Index of the lift in the input slice.
        index: usize,
        /// Name of the lift.
        name: String,
        /// The error in that lift.
        source: Box<NioshError>,
    },
}

/// Hand-to-object coupling classification (Table 6, p. 17; when in doubt, the manual says to
/// choose the more stressful class).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Coupling {
    /// Optimal container with optimal handles or hand-hold cut-outs, or an easily gripped
    /// loose part.
    Good,
    /// Optimal container without optimal handles but fingers can be flexed about 90° under it,
    /// or a loose part gripped with the fingers flexed about 90°.
    Fair,
    /// Less than optimal container, bulky or hard-to-handle loose object, or fingers cannot be
    /// flexed 90° under the object.
    Poor,
}

impl Coupling {
    /// Coupling multiplier, Table 7 (p. 18): Good 1.00; Fair 0.95 when V < 75 cm (30 in),
    /// 1.00 otherwise; Poor 0.90.
    fn multiplier(self, v_below_threshold: bool) -> f64 {
        match self {
            Coupling::Good => 1.0,
            Coupling::Fair if v_below_threshold => 0.95,
            Coupling::Fair => 1.0,
            Coupling::Poor => 0.90,
        }
    }
}

/// Work-duration category of continuous lifting (pp. 13–14), the column group of Table 5.
///
/// The manual defines the categories by the pattern of work time (WT) and recovery time (RT,
/// light work after lifting): short is ≤ 1 h followed by RT ≥ 1.0 × WT; moderate is > 1 h and
/// ≤ 2 h followed by RT ≥ 0.3 × WT; long is > 2 h and ≤ 8 h with standard rest allowances. If
/// the required recovery does not follow, the lifting sessions are added together. The caller
/// applies those recovery rules; [`WorkDuration::from_hours`] classifies the resulting time.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum WorkDuration {
    /// Short duration: at most 1 h.
    UpTo1h,
    /// Moderate duration: more than 1 h, at most 2 h.
    UpTo2h,
    /// Long duration: more than 2 h, at most 8 h.
    UpTo8h,
}

impl WorkDuration {
    /// Category for `duration_h` hours of continuous lifting (recovery rules already applied):
    /// ≤ 1 h short, ≤ 2 h moderate, ≤ 8 h long (Table 5 headings "≤1 Hour", ">1 but ≤2 Hours",
    /// ">2 but ≤8 Hours"). Refuses non-finite values, values ≤ 0 and values above 8 h.
    pub fn from_hours(duration_h: f64) -> Result<Self, NioshError> {
        if !duration_h.is_finite() {
            return Err(NioshError::NotFinite {
                field: "duration_h".into(),
                value: duration_h,
            });
        }
        if duration_h <= 0.0 || duration_h > 8.0 + LIMIT_EPS {
            Err(NioshError::DurationOutOfRange(duration_h))
        } else if duration_h <= 1.0 + LIMIT_EPS {
            Ok(WorkDuration::UpTo1h)
        } else if duration_h <= 2.0 + LIMIT_EPS {
            Ok(WorkDuration::UpTo2h)
        } else {
            Ok(WorkDuration::UpTo8h)
        }
    }

    /// First column of this duration's group in [`FM_TABLE`].
    fn column(self) -> usize {
        match self {
            WorkDuration::UpTo1h => 0,
            WorkDuration::UpTo2h => 2,
            WorkDuration::UpTo8h => 4,
        }
    }
}

/// Which of the manual's two published forms of the equation to evaluate (p. 7).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum EquationForm {
    /// Metric form: LC = 23 kg, lengths in cm, V threshold for FM and CM 75 cm. The default.
    #[default]
    Metric,
    /// U.S.-customary form: LC = 51 lb, lengths in inches, V threshold 30 in. Inputs stay SI and
    /// are converted exactly; the RWL is converted back to kg. Use it to reproduce the manual's
    /// worksheets, which are all customary.
    UsCustomary,
}

/// The constants of one form of the equation, in that form's length unit.
struct FormConstants {
    lc: f64,
    kg_per_mass_unit: f64,
    len_per_m: f64,
    h_num: f64,
    h_max: f64,
    v_opt: f64,
    v_coef: f64,
    v_max: f64,
    d_num: f64,
    d_min: f64,
    d_max: f64,
    v_threshold: f64,
}

impl EquationForm {
    fn constants(self) -> FormConstants {
        match self {
            EquationForm::Metric => FormConstants {
                lc: LOAD_CONSTANT_KG,
                kg_per_mass_unit: 1.0,
                len_per_m: 100.0,
                h_num: 25.0,
                h_max: 63.0,
                v_opt: 75.0,
                v_coef: 0.003,
                v_max: 175.0,
                d_num: 4.5,
                d_min: 25.0,
                d_max: 175.0,
                v_threshold: 75.0,
            },
            EquationForm::UsCustomary => FormConstants {
                lc: LOAD_CONSTANT_LB,
                kg_per_mass_unit: KG_PER_LB,
                len_per_m: 1.0 / M_PER_IN,
                h_num: 10.0,
                h_max: 25.0,
                v_opt: 30.0,
                v_coef: 0.0075,
                v_max: 70.0,
                d_num: 1.8,
                d_min: 10.0,
                d_max: 70.0,
                v_threshold: 30.0,
            },
        }
    }
}

/// Where the hands are at one end of a lift.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LiftGeometry {
    /// Horizontal location H \[m\]: horizontal distance from the mid-point between the inner
    /// ankle bones to the point on the floor directly below the mid-point of the hand grasps
    /// (the large middle knuckles) (p. 7).
    pub h_m: f64,
    /// Vertical location V \[m\]: height of the mid-point between the hand grasps above the
    /// floor (p. 9).
    pub v_m: f64,
    /// Asymmetry angle A \[deg\]: angle between the asymmetry line (ankle mid-point to the point
    /// below the hands) and the mid-sagittal line of the worker's neutral posture (p. 12). The
    /// sign (left or right) is ignored.
    pub asymmetry_deg: f64,
}

/// One lifting (or lowering) task. Lowering is assessed like lifting, with origin and
/// destination as the start and end of the lowering (p. 6 and p. 10).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Lift {
    /// Name of the task, copied to the result.
    pub name: String,
    /// Average weight of the object, container included \[kg\] (p. 2); used for RWL-based LI
    /// and for the single-task lifting index STLI.
    pub load_kg: f64,
    /// Maximum weight of the object \[kg\], used for the frequency-independent lifting index
    /// FILI (p. 27). `None` means the weight does not vary: `load_kg`.
    pub max_load_kg: Option<f64>,
    /// Hands at the start of the lift.
    pub origin: LiftGeometry,
    /// Hands at the end of the lift. Its V always sets the travel distance D; its H, V and A
    /// set a destination RWL only when `control_at_destination` is true.
    pub destination: LiftGeometry,
    /// Lifting frequency F \[lifts/min\], averaged over a 15-minute sample (p. 13).
    pub freq_per_min: f64,
    /// Work-duration category.
    pub duration: WorkDuration,
    /// Hand-to-object coupling.
    pub coupling: Coupling,
    /// Significant control at the destination: the worker re-grasps, momentarily holds, or
    /// carefully positions or guides the load there (p. 2). Then the RWL is computed at both
    /// ends and the lower governs (p. 21, p. 26).
    pub control_at_destination: bool,
    /// Form of the equation to evaluate.
    pub form: EquationForm,
}

/// End of a lift.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Point {
    /// Start of the lift.
    Origin,
    /// End of the lift.
    Destination,
}

/// A substitution that the manual's rules made to an input (module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(tag = "rule", rename_all = "snake_case")]
pub enum Adjustment {
    /// H was below 25 cm (10 in) and was set to 25 cm (10 in): HM = 1.
    HorizontalRaisedToMinimum {
        /// Where.
        at: Point,
    },
    /// H was above 63 cm (25 in): HM = 0.
    HorizontalBeyondMaximum {
        /// Where.
        at: Point,
    },
    /// V was above 175 cm (70 in): VM = 0.
    VerticalBeyondMaximum {
        /// Where.
        at: Point,
    },
    /// A was above 135°: AM = 0.
    AsymmetryBeyondMaximum {
        /// Where.
        at: Point,
    },
    /// D was below 25 cm (10 in) and was set to 25 cm (10 in): DM = 1.
    DistanceRaisedToMinimum,
    /// D was above 175 cm (70 in): DM = 0.
    DistanceBeyondMaximum,
    /// F was below 0.2 lifts/min and was set to 0.2.
    FrequencyRaisedToMinimum,
    /// F was above the highest frequency of its Table 5 column with a non-zero FM: FM = 0.
    FrequencyBeyondMaximum,
}

/// The multipliers at one end of a lift, with the measured and the used task variables.
/// Lengths are reported in cm whatever the form of the equation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Multipliers {
    /// Measured horizontal location H \[cm\].
    pub h_cm: f64,
    /// H used in HM after the manual's minimum (25 cm, or 10 in = 25.4 cm) \[cm\].
    pub h_used_cm: f64,
    /// Measured vertical location V \[cm\].
    pub v_cm: f64,
    /// Measured vertical travel distance D = |V_destination − V_origin| \[cm\].
    pub d_cm: f64,
    /// D used in DM after the manual's minimum (25 cm, or 10 in) \[cm\].
    pub d_used_cm: f64,
    /// Asymmetry angle |A| \[deg\].
    pub asymmetry_deg: f64,
    /// Horizontal multiplier HM = 25/H (10/H in inches); 0 beyond 63 cm (25 in).
    pub hm: f64,
    /// Vertical multiplier VM = 1 − 0.003·|V − 75| (1 − 0.0075·|V − 30| in inches); 0 beyond
    /// 175 cm (70 in).
    pub vm: f64,
    /// Distance multiplier DM = 0.82 + 4.5/D (0.82 + 1.8/D in inches); 0 beyond 175 cm (70 in).
    pub dm: f64,
    /// Asymmetric multiplier AM = 1 − 0.0032·A; 0 beyond 135°.
    pub am: f64,
    /// Frequency multiplier from Table 5 (V at the origin, linear interpolation in F).
    pub fm: f64,
    /// Coupling multiplier from Table 7 (V at this end of the lift).
    pub cm: f64,
}

/// RWL and LI at one end of a lift.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PointResult {
    /// The multipliers and task variables.
    pub multipliers: Multipliers,
    /// Frequency-independent RWL, FIRWL = LC·HM·VM·DM·AM·CM (FM = 1) \[kg\] (p. 26).
    pub fi_rwl_kg: f64,
    /// Recommended weight limit RWL = FIRWL·FM \[kg\].
    pub rwl_kg: f64,
    /// Lifting index load / RWL; `None` when RWL = 0 (a multiplier is 0: the task is outside
    /// the equation's limits and no load is recommended).
    pub lifting_index: Option<f64>,
    /// Frequency-independent lifting index max load / FIRWL; `None` when FIRWL = 0.
    pub fi_lifting_index: Option<f64>,
}

impl Point {
    /// "origin" or "destination".
    pub fn words(self) -> &'static str {
        match self {
            Point::Origin => "origin",
            Point::Destination => "destination",
        }
    }
}

impl PointResult {
    /// Why the RWL is 0 at this end, one item per multiplier at 0, with the value that puts it
    /// there: "H 66.5 cm beyond 63 cm (HM = 0)". Empty when the RWL is positive.
    pub fn zero_reasons(&self) -> Vec<String> {
        let m = &self.multipliers;
        let mut v = Vec::new();
        if m.hm == 0.0 {
            v.push(format!("H {:.1} cm beyond 63 cm (HM = 0)", m.h_cm));
        }
        if m.vm == 0.0 {
            v.push(format!("V {:.1} cm beyond 175 cm (VM = 0)", m.v_cm));
        }
        if m.dm == 0.0 {
            v.push(format!("D {:.1} cm beyond 175 cm (DM = 0)", m.d_cm));
        }
        if m.am == 0.0 {
            v.push(format!(
                "asymmetry {:.0}° beyond 135° (AM = 0)",
                m.asymmetry_deg
            ));
        }
        if m.fm == 0.0 {
            v.push("the frequency beyond Table 5 for this duration and height (FM = 0)".into());
        }
        if m.cm == 0.0 {
            v.push("CM = 0".into());
        }
        v
    }
}

/// Assessment of one lift (single-task procedure, p. 26, and the per-task quantities of the
/// multi-task procedure, pp. 26–27).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LiftResult {
    /// Name of the task.
    pub name: String,
    /// Form of the equation evaluated.
    pub form: EquationForm,
    /// Average load \[kg\].
    pub load_kg: f64,
    /// Maximum load \[kg\] (equal to `load_kg` when not given).
    pub max_load_kg: f64,
    /// Measured frequency \[lifts/min\].
    pub freq_per_min: f64,
    /// Frequency used in Table 5 after the 0.2 lifts/min minimum \[lifts/min\].
    pub freq_used_per_min: f64,
    /// Work-duration category.
    pub duration: WorkDuration,
    /// Coupling classification.
    pub coupling: Coupling,
    /// Whether significant control at the destination was required.
    pub control_at_destination: bool,
    /// RWL and LI at the origin.
    pub origin: PointResult,
    /// RWL and LI at the destination, when control at the destination is required.
    pub destination: Option<PointResult>,
    /// The destination's H \[cm\] when control there is not declared (so the destination is not
    /// assessed) and H lies beyond the equation's 63 cm (HM would be 0): placing a load that far
    /// out usually needs control (Waters et al. 1994, p. 11: "significant control … at the
    /// destination"), so the report warns. `None` otherwise.
    pub uncontrolled_destination_h_cm: Option<f64>,
    /// End with the lower RWL, which governs the task (origin on a tie).
    pub governing: Point,
    /// RWL of the task: the lower of origin and destination \[kg\].
    pub rwl_kg: f64,
    /// LI of the task: load / `rwl_kg` (the larger LI); `None` when the RWL is 0.
    pub lifting_index: Option<f64>,
    /// Frequency-independent RWL at the governing end \[kg\].
    pub fi_rwl_kg: f64,
    /// Single-task RWL, STRWL = FIRWL·FM with the task's own frequency (= `rwl_kg`) \[kg\].
    pub st_rwl_kg: f64,
    /// Frequency-independent lifting index FILI = max load / FIRWL; `None` when FIRWL = 0.
    pub fi_li: Option<f64>,
    /// Single-task lifting index STLI = average load / STRWL; `None` when STRWL = 0.
    pub st_li: Option<f64>,
    /// Substitutions made by the manual's rules.
    pub adjustments: Vec<Adjustment>,
}

/// One term of the Composite Lifting Index, in the order of decreasing STLI.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CliTerm {
    /// New task number (1 = greatest STLI).
    pub rank: usize,
    /// Index of the lift in the input slice.
    pub lift_index: usize,
    /// Name of the lift.
    pub name: String,
    /// STLI of the task (the whole of term 1).
    pub st_li: Option<f64>,
    /// FILI of the task.
    pub fi_li: Option<f64>,
    /// Sum of the frequencies of tasks 1..=rank \[lifts/min\].
    pub cumulative_freq_per_min: f64,
    /// FM for the cumulative frequency, FM(1,2,…,rank) (Table 5).
    pub fm_cumulative: f64,
    /// FM(1,2,…,rank−1); `None` for rank 1.
    pub fm_previous_cumulative: Option<f64>,
    /// Whether the V < 75 cm (30 in) column of Table 5 was used for `fm_cumulative`.
    pub fm_column_v_below_threshold: bool,
    /// Contribution to the CLI: STLI₁ for rank 1, FILI·(1/FM(1..rank) − 1/FM(1..rank−1))
    /// otherwise; `None` when undefined (an FM or FIRWL of 0).
    pub contribution: Option<f64>,
}

/// Composite Lifting Index of a job made of several lifting tasks (pp. 26–28).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CompositeResult {
    /// Per-task assessment, in input order.
    pub lifts: Vec<LiftResult>,
    /// Input indices in the order of decreasing STLI (ties: higher frequency first, p. 57;
    /// then input order).
    pub order: Vec<usize>,
    /// CLI terms in that order.
    pub terms: Vec<CliTerm>,
    /// CLI = STLI₁ + Σ ΔLI; `None` when a term is undefined (an FM or FIRWL of 0, i.e. no
    /// load is acceptable for the combination).
    pub cli: Option<f64>,
}

/// Assesses one lift: multipliers, RWL and LI at the origin (and at the destination when
/// control is required there), FIRWL, STRWL, FILI and STLI.
pub fn assess_lift(l: &Lift) -> Result<LiftResult, NioshError> {
    validate(l)?;
    let k = l.form.constants();
    let mut adjustments = Vec::new();
    let max_load_kg = l.max_load_kg.unwrap_or(l.load_kg);

    // Frequency multiplier: V at the origin (p. 15).
    let v_origin = l.origin.v_m * k.len_per_m;
    let origin_low = v_origin < k.v_threshold - LIMIT_EPS;
    let freq_used = if l.freq_per_min < FM_FREQ_PER_MIN[0] {
        adjustments.push(Adjustment::FrequencyRaisedToMinimum);
        FM_FREQ_PER_MIN[0]
    } else {
        l.freq_per_min
    };
    let fm = frequency_multiplier(freq_used, l.duration, origin_low);
    if fm == 0.0 {
        adjustments.push(Adjustment::FrequencyBeyondMaximum);
    }

    // Vertical travel distance D, common to both ends.
    let d = (l.destination.v_m - l.origin.v_m).abs() * k.len_per_m;
    let (dm, d_used) = if d > k.d_max + LIMIT_EPS {
        adjustments.push(Adjustment::DistanceBeyondMaximum);
        (0.0, d)
    } else if d < k.d_min {
        adjustments.push(Adjustment::DistanceRaisedToMinimum);
        (1.0, k.d_min)
    } else {
        (0.82 + k.d_num / d, d)
    };
    let d_cm = d / k.len_per_m * 100.0;
    let d_used_cm = d_used / k.len_per_m * 100.0;

    let mut point = |g: &LiftGeometry, at: Point| -> PointResult {
        let h = g.h_m * k.len_per_m;
        let v = g.v_m * k.len_per_m;
        let a = g.asymmetry_deg.abs();
        let (hm, h_used) = if h > k.h_max + LIMIT_EPS {
            adjustments.push(Adjustment::HorizontalBeyondMaximum { at });
            (0.0, h)
        } else if h < k.h_num {
            adjustments.push(Adjustment::HorizontalRaisedToMinimum { at });
            (1.0, k.h_num)
        } else {
            (k.h_num / h, h)
        };
        let vm = if v > k.v_max + LIMIT_EPS {
            adjustments.push(Adjustment::VerticalBeyondMaximum { at });
            0.0
        } else {
            1.0 - k.v_coef * (v - k.v_opt).abs()
        };
        let am = if a > 135.0 + LIMIT_EPS {
            adjustments.push(Adjustment::AsymmetryBeyondMaximum { at });
            0.0
        } else {
            1.0 - 0.0032 * a
        };
        let cm = l.coupling.multiplier(v < k.v_threshold - LIMIT_EPS);
        let fi_rwl_kg = k.lc * hm * vm * dm * am * cm * k.kg_per_mass_unit;
        let rwl_kg = fi_rwl_kg * fm;
        PointResult {
            multipliers: Multipliers {
                h_cm: g.h_m * 100.0,
                h_used_cm: h_used / k.len_per_m * 100.0,
                v_cm: g.v_m * 100.0,
                d_cm,
                d_used_cm,
                asymmetry_deg: a,
                hm,
                vm,
                dm,
                am,
                fm,
                cm,
            },
            fi_rwl_kg,
            rwl_kg,
            lifting_index: ratio(l.load_kg, rwl_kg),
            fi_lifting_index: ratio(max_load_kg, fi_rwl_kg),
        }
    };

    let origin = point(&l.origin, Point::Origin);
    let destination = if l.control_at_destination {
        Some(point(&l.destination, Point::Destination))
    } else {
        None
    };
    let uncontrolled_destination_h_cm = (!l.control_at_destination
        && l.destination.h_m * k.len_per_m > k.h_max + LIMIT_EPS)
        .then_some(l.destination.h_m * 100.0);
    let (governing, gov) = match destination {
        Some(dest) if dest.rwl_kg < origin.rwl_kg => (Point::Destination, dest),
        _ => (Point::Origin, origin),
    };

    Ok(LiftResult {
        name: l.name.clone(),
        form: l.form,
        load_kg: l.load_kg,
        max_load_kg,
        freq_per_min: l.freq_per_min,
        freq_used_per_min: freq_used,
        duration: l.duration,
        coupling: l.coupling,
        control_at_destination: l.control_at_destination,
        origin,
        destination,
        uncontrolled_destination_h_cm,
        governing,
        rwl_kg: gov.rwl_kg,
        lifting_index: gov.lifting_index,
        fi_rwl_kg: gov.fi_rwl_kg,
        st_rwl_kg: gov.rwl_kg,
        fi_li: gov.fi_lifting_index,
        st_li: gov.lifting_index,
        adjustments,
    })
}

/// Composite Lifting Index of a multi-task job (pp. 26–28):
///
/// 1. FIRWL, STRWL, FILI (maximum load / FIRWL) and STLI (average load / STRWL) of every task,
///    at the governing end when control at the destination is required (the manual does not say
///    which end feeds FILI and STLI then; the lower RWL is used, as for the single-task LI).
/// 2. Tasks renumbered by decreasing STLI; equal STLI: higher frequency first (p. 57); then
///    input order.
/// 3. CLI = STLI₁ + Σₖ FILIₖ·(1/FM(1,…,k) − 1/FM(1,…,k−1)), where FM(1,…,k) comes from
///    Table 5 with the **sum** of the frequencies of tasks 1…k (the 0.2 lifts/min minimum is
///    applied to the sum) and the job's duration (p. 28).
///
/// All lifts must share the work duration and the form of the equation. The manual does not
/// say which V selects the Table 5 column for a combined frequency when the tasks differ; this
/// implementation uses the V < 75 cm (30 in) column when the origin of any task 1…k is below
/// it, which never gives a smaller CLI than the other choice.
pub fn composite(lifts: &[Lift]) -> Result<CompositeResult, NioshError> {
    let first = lifts.first().ok_or(NioshError::NoLifts)?;
    for (index, l) in lifts.iter().enumerate().skip(1) {
        if l.duration != first.duration {
            return Err(NioshError::MixedDurations {
                index,
                expected: first.duration,
                found: l.duration,
            });
        }
        if l.form != first.form {
            return Err(NioshError::MixedForms {
                index,
                expected: first.form,
                found: l.form,
            });
        }
    }
    let results = lifts
        .iter()
        .enumerate()
        .map(|(index, l)| {
            assess_lift(l).map_err(|e| NioshError::InLift {
                index,
                name: l.name.clone(),
                source: Box::new(e),
            })
        })
        .collect::<Result<Vec<_>, _>>()?;

    let mut order: Vec<usize> = (0..lifts.len()).collect();
    order.sort_by(|&a, &b| {
        let sa = results[a].st_li.unwrap_or(f64::INFINITY);
        let sb = results[b].st_li.unwrap_or(f64::INFINITY);
        sb.total_cmp(&sa)
            .then(lifts[b].freq_per_min.total_cmp(&lifts[a].freq_per_min))
            .then(a.cmp(&b))
    });

    let k = first.form.constants();
    let duration = first.duration;
    let mut terms = Vec::with_capacity(order.len());
    let mut cumulative_freq = 0.0;
    let mut any_low = false;
    let mut previous_fm: Option<f64> = None;
    for (pos, &i) in order.iter().enumerate() {
        let l = &lifts[i];
        let r = &results[i];
        cumulative_freq += l.freq_per_min;
        any_low |= l.origin.v_m * k.len_per_m < k.v_threshold - LIMIT_EPS;
        let fm_cum =
            frequency_multiplier(cumulative_freq.max(FM_FREQ_PER_MIN[0]), duration, any_low);
        let contribution = match previous_fm {
            None => r.st_li,
            Some(prev) => match r.fi_li {
                Some(fili) if fm_cum > 0.0 && prev > 0.0 => {
                    Some(fili * (1.0 / fm_cum - 1.0 / prev))
                }
                _ => None,
            },
        };
        terms.push(CliTerm {
            rank: pos + 1,
            lift_index: i,
            name: l.name.clone(),
            st_li: r.st_li,
            fi_li: r.fi_li,
            cumulative_freq_per_min: cumulative_freq,
            fm_cumulative: fm_cum,
            fm_previous_cumulative: previous_fm,
            fm_column_v_below_threshold: any_low,
            contribution,
        });
        previous_fm = Some(fm_cum);
    }
    let cli = terms
        .iter()
        .try_fold(0.0, |acc, t| t.contribution.map(|c| acc + c));
    Ok(CompositeResult {
        lifts: results,
        order,
        terms,
        cli,
    })
}

/// `num / den`, or `None` when `den` is not positive.
fn ratio(num: f64, den: f64) -> Option<f64> {
    (den > 0.0).then(|| num / den)
}

/// FM from Table 5 for `freq` (already ≥ 0.2) lifts/min: linear interpolation between the two
/// nearest rows; 0 above the highest frequency of the column whose FM is not 0.
fn frequency_multiplier(freq: f64, duration: WorkDuration, v_below_threshold: bool) -> f64 {
    let col = duration.column() + usize::from(!v_below_threshold);
    let last_nonzero = FM_TABLE.iter().rposition(|row| row[col] > 0.0).unwrap_or(0);
    if freq > FM_FREQ_PER_MIN[last_nonzero] + LIMIT_EPS {
        return 0.0;
    }
    if freq <= FM_FREQ_PER_MIN[0] {
        return FM_TABLE[0][col];
    }
    for i in 0..last_nonzero {
        let (f0, f1) = (FM_FREQ_PER_MIN[i], FM_FREQ_PER_MIN[i + 1]);
        if freq <= f1 {
            let t = (freq - f0) / (f1 - f0);
            return FM_TABLE[i][col] + t * (FM_TABLE[i + 1][col] - FM_TABLE[i][col]);
        }
    }
    FM_TABLE[last_nonzero][col]
}

/// Refuses the inputs the equation cannot evaluate (module documentation).
fn validate(l: &Lift) -> Result<(), NioshError> {
    non_negative("load_kg", l.load_kg, "kg", "object weight")?;
    if let Some(max) = l.max_load_kg {
        non_negative("max_load_kg", max, "kg", "maximum object weight")?;
        if max < l.load_kg {
            return Err(NioshError::MaxLoadBelowLoad {
                load_kg: l.load_kg,
                max_load_kg: max,
            });
        }
    }
    non_negative(
        "freq_per_min",
        l.freq_per_min,
        "lifts/min",
        "lifting frequency",
    )?;
    for (name, g) in [("origin", &l.origin), ("destination", &l.destination)] {
        non_negative(
            &format!("{name}.h_m"),
            g.h_m,
            "m",
            "horizontal distance of the hands from the mid-point between the inner ankle bones",
        )?;
        non_negative(
            &format!("{name}.v_m"),
            g.v_m,
            "m",
            "height of the hands above the floor",
        )?;
        let field = format!("{name}.asymmetry_deg");
        finite(&field, g.asymmetry_deg)?;
        if g.asymmetry_deg.abs() > 180.0 {
            return Err(NioshError::AsymmetryOutOfRange {
                field,
                value: g.asymmetry_deg,
            });
        }
    }
    Ok(())
}

fn finite(field: &str, value: f64) -> Result<(), NioshError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(NioshError::NotFinite {
            field: field.into(),
            value,
        })
    }
}

fn non_negative(
    field: &str,
    value: f64,
    unit: &'static str,
    meaning: &'static str,
) -> Result<(), NioshError> {
    finite(field, value)?;
    if value < 0.0 {
        Err(NioshError::Negative {
            field: field.into(),
            unit,
            meaning,
            value,
        })
    } else {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;

    /// Rounds half away from zero to `decimals`, as the manual's tables and worksheets do
    /// (p. 29); the small offset keeps values such as 0.925 from rounding down through
    /// binary representation.
    fn round(x: f64, decimals: i32) -> f64 {
        let p = 10f64.powi(decimals);
        ((x * p) + 1e-9_f64.copysign(x)).round() / p
    }

    fn inch(x: f64) -> f64 {
        x * M_PER_IN
    }

    fn geometry(h_m: f64, v_m: f64, asymmetry_deg: f64) -> LiftGeometry {
        LiftGeometry {
            h_m,
            v_m,
            asymmetry_deg,
        }
    }

    /// A metric lift with everything ideal unless changed by the caller.
    fn ideal_metric() -> Lift {
        Lift {
            name: "test".into(),
            load_kg: 10.0,
            max_load_kg: None,
            origin: geometry(0.25, 0.75, 0.0),
            destination: geometry(0.25, 1.00, 0.0),
            freq_per_min: 0.2,
            duration: WorkDuration::UpTo1h,
            coupling: Coupling::Good,
            control_at_destination: false,
            form: EquationForm::Metric,
        }
    }

    /// Origin multipliers of a metric lift with H, V (origin), V (destination) in cm, A in deg.
    fn metric_multipliers(h_cm: f64, v_cm: f64, v_dest_cm: f64, a_deg: f64) -> Multipliers {
        let mut l = ideal_metric();
        l.origin = geometry(h_cm / 100.0, v_cm / 100.0, a_deg);
        l.destination = geometry(0.25, v_dest_cm / 100.0, 0.0);
        assess_lift(&l).unwrap().origin.multipliers
    }

    /// Origin multipliers of a customary-form lift, lengths in inches.
    fn us_multipliers(h_in: f64, v_in: f64, v_dest_in: f64) -> Multipliers {
        let mut l = ideal_metric();
        l.form = EquationForm::UsCustomary;
        l.origin = geometry(inch(h_in), inch(v_in), 0.0);
        l.destination = geometry(inch(10.0), inch(v_dest_in), 0.0);
        assess_lift(&l).unwrap().origin.multipliers
    }

    /// RWL the way the manual's worksheets compute it: the product of the multipliers rounded
    /// to two decimals, rounded to one decimal (p. 29). In the form's mass unit.
    fn worksheet_rwl(p: &PointResult, lc: f64) -> f64 {
        let m = &p.multipliers;
        round(
            lc * round(m.hm, 2)
                * round(m.vm, 2)
                * round(m.dm, 2)
                * round(m.am, 2)
                * round(m.fm, 2)
                * round(m.cm, 2),
            1,
        )
    }

    // ----- Tables 1–4 of the manual (pp. 8–13), reprinted in the Lifting Analysis Worksheet.
    // The manual says the formulas govern (p. 7); every printed row equals the formula rounded
    // to two decimals except the three misprints checked separately below.

    #[test]
    fn table_1_horizontal_multiplier_metric() {
        let rows = [
            (25.0, 1.00),
            (28.0, 0.89),
            (30.0, 0.83),
            (32.0, 0.78),
            (34.0, 0.74),
            (36.0, 0.69),
            (38.0, 0.66),
            (40.0, 0.63),
            (42.0, 0.60),
            (44.0, 0.57),
            (46.0, 0.54),
            (48.0, 0.52),
            (50.0, 0.50),
            (52.0, 0.48),
            (54.0, 0.46),
            (56.0, 0.45),
            (58.0, 0.43),
            (60.0, 0.42),
            (63.0, 0.40),
        ];
        for (h, hm) in rows {
            assert_eq!(
                round(metric_multipliers(h, 75.0, 100.0, 0.0).hm, 2),
                hm,
                "H = {h} cm"
            );
        }
        // "≤ 25 cm: 1.00" and "> 63 cm: .00".
        assert_eq!(metric_multipliers(10.0, 75.0, 100.0, 0.0).hm, 1.0);
        assert_eq!(metric_multipliers(63.5, 75.0, 100.0, 0.0).hm, 0.0);
    }

    #[test]
    fn table_1_horizontal_multiplier_customary() {
        let rows = [
            (10.0, 1.00),
            (11.0, 0.91),
            (12.0, 0.83),
            (13.0, 0.77),
            (14.0, 0.71),
            (15.0, 0.67),
            (16.0, 0.63),
            (17.0, 0.59),
            (18.0, 0.56),
            (19.0, 0.53),
            (20.0, 0.50),
            (21.0, 0.48),
            (24.0, 0.42),
            (25.0, 0.40),
        ];
        for (h, hm) in rows {
            assert_eq!(round(us_multipliers(h, 30.0, 40.0).hm, 2), hm, "H = {h} in");
        }
        // Printed .46 and .44 at 22 and 23 in are misprints: 10/22 = .4545, 10/23 = .4348.
        assert_eq!(round(us_multipliers(22.0, 30.0, 40.0).hm, 2), 0.45);
        assert_eq!(round(us_multipliers(23.0, 30.0, 40.0).hm, 2), 0.43);
        assert_eq!(us_multipliers(25.5, 30.0, 40.0).hm, 0.0);
    }

    #[test]
    fn table_2_vertical_multiplier_metric() {
        let rows = [
            (0.0, 0.78),
            (10.0, 0.81),
            (20.0, 0.84),
            (30.0, 0.87),
            (40.0, 0.90),
            (50.0, 0.93),
            (60.0, 0.96),
            (70.0, 0.99),
            (80.0, 0.99),
            (90.0, 0.96),
            (100.0, 0.93),
            (110.0, 0.90),
            (120.0, 0.87),
            (130.0, 0.84),
            (140.0, 0.81),
            (150.0, 0.78),
            (160.0, 0.75),
            (170.0, 0.72),
            (175.0, 0.70),
        ];
        for (v, vm) in rows {
            assert_eq!(
                round(metric_multipliers(25.0, v, 100.0, 0.0).vm, 2),
                vm,
                "V = {v} cm"
            );
        }
        assert_eq!(metric_multipliers(25.0, 176.0, 100.0, 0.0).vm, 0.0);
    }

    #[test]
    fn table_2_vertical_multiplier_customary() {
        let rows = [
            (0.0, 0.78),
            (5.0, 0.81),
            (10.0, 0.85),
            (15.0, 0.89),
            (20.0, 0.93),
            (25.0, 0.96),
            (30.0, 1.00),
            (35.0, 0.96),
            (40.0, 0.93),
            (45.0, 0.89),
            (50.0, 0.85),
            (55.0, 0.81),
            (60.0, 0.78),
            (65.0, 0.74),
            (70.0, 0.70),
        ];
        for (v, vm) in rows {
            assert_eq!(round(us_multipliers(10.0, v, 40.0).vm, 2), vm, "V = {v} in");
        }
        assert_eq!(us_multipliers(10.0, 70.5, 40.0).vm, 0.0);
    }

    #[test]
    fn table_3_distance_multiplier_metric() {
        // D = V_destination − V_origin with V_origin = 0 cm.
        let rows = [
            (25.0, 1.00),
            (40.0, 0.93),
            (55.0, 0.90),
            (70.0, 0.88),
            (85.0, 0.87),
            (100.0, 0.87),
            (115.0, 0.86),
            (145.0, 0.85),
            (160.0, 0.85),
            (175.0, 0.85),
        ];
        for (d, dm) in rows {
            assert_eq!(
                round(metric_multipliers(25.0, 0.0, d, 0.0).dm, 2),
                dm,
                "D = {d} cm"
            );
        }
        // Printed .86 at 130 cm is a misprint: .82 + 4.5/130 = .8546.
        assert_eq!(round(metric_multipliers(25.0, 0.0, 130.0, 0.0).dm, 2), 0.85);
        // "< 25 cm: 1.00".
        assert_eq!(metric_multipliers(25.0, 0.0, 10.0, 0.0).dm, 1.0);
    }

    #[test]
    fn table_3_distance_multiplier_customary() {
        let rows = [
            (10.0, 1.00),
            (15.0, 0.94),
            (20.0, 0.91),
            (25.0, 0.89),
            (30.0, 0.88),
            (35.0, 0.87),
            (40.0, 0.87),
            (45.0, 0.86),
            (50.0, 0.86),
            (55.0, 0.85),
            (60.0, 0.85),
            (70.0, 0.85),
        ];
        for (d, dm) in rows {
            assert_eq!(round(us_multipliers(10.0, 0.0, d).dm, 2), dm, "D = {d} in");
        }
    }

    #[test]
    fn distance_beyond_maximum_gives_zero() {
        // D > 175 cm needs V > 175 cm at one end (where VM is 0 as well).
        let m = metric_multipliers(25.0, 0.0, 180.0, 0.0);
        assert_eq!(m.dm, 0.0);
    }

    #[test]
    fn table_4_asymmetric_multiplier() {
        let rows = [
            (0.0, 1.00),
            (15.0, 0.95),
            (30.0, 0.90),
            (45.0, 0.86),
            (60.0, 0.81),
            (75.0, 0.76),
            (90.0, 0.71),
            (105.0, 0.66),
            (120.0, 0.62),
            (135.0, 0.57),
        ];
        for (a, am) in rows {
            assert_eq!(
                round(metric_multipliers(25.0, 75.0, 100.0, a).am, 2),
                am,
                "A = {a}°"
            );
            // The side of the twist does not matter.
            assert_eq!(
                metric_multipliers(25.0, 75.0, 100.0, -a).am,
                metric_multipliers(25.0, 75.0, 100.0, a).am
            );
        }
        assert_eq!(metric_multipliers(25.0, 75.0, 100.0, 136.0).am, 0.0);
    }

    // ----- Table 5 (p. 15) and Table 7 (p. 18).

    #[test]
    fn table_5_frequency_multiplier_cells() {
        use WorkDuration::*;
        // (F, duration, V below 75 cm, published FM)
        let cells = [
            (0.2, UpTo1h, true, 1.00),
            (0.2, UpTo2h, false, 0.95),
            (0.2, UpTo8h, true, 0.85),
            (0.5, UpTo8h, false, 0.81),
            (1.0, UpTo2h, true, 0.88),
            (3.0, UpTo1h, true, 0.88),
            (4.0, UpTo8h, false, 0.45),
            (5.0, UpTo1h, false, 0.80),
            (8.0, UpTo8h, true, 0.18),
            (9.0, UpTo8h, true, 0.00),
            (9.0, UpTo8h, false, 0.15),
            (10.0, UpTo2h, true, 0.26),
            (11.0, UpTo2h, true, 0.00),
            (12.0, UpTo2h, false, 0.21),
            (12.0, UpTo1h, true, 0.37),
            (13.0, UpTo1h, true, 0.00),
            (15.0, UpTo1h, false, 0.28),
            (15.5, UpTo1h, false, 0.00),
        ];
        for (f, dur, low, fm) in cells {
            assert_abs_diff_eq!(frequency_multiplier(f, dur, low), fm, epsilon = 1e-12);
        }
    }

    #[test]
    fn table_5_interpolates_linearly_between_rows() {
        // p. 7: "the appropriate multiplier must be interpolated between the frequency values
        // in the table for the two values that are closest to the actual frequency".
        // F = 2.4, ≤ 1 h: .91 + 0.4 × (.88 − .91) = .898.
        assert_abs_diff_eq!(
            frequency_multiplier(2.4, WorkDuration::UpTo1h, true),
            0.898,
            epsilon = 1e-12
        );
        // F = 0.35, ≤ 8 h: .85 + 0.5 × (.81 − .85) = .83.
        assert_abs_diff_eq!(
            frequency_multiplier(0.35, WorkDuration::UpTo8h, false),
            0.83,
            epsilon = 1e-12
        );
    }

    #[test]
    fn table_5_zero_beyond_the_columns_maximum_frequency() {
        // Last non-zero rows: ≤1 h V<75: 12; ≤2 h V<75: 10; ≤8 h V<75: 8; ≤8 h V≥75: 10.
        assert_eq!(frequency_multiplier(12.5, WorkDuration::UpTo1h, true), 0.0);
        assert_eq!(frequency_multiplier(10.01, WorkDuration::UpTo2h, true), 0.0);
        assert_eq!(frequency_multiplier(8.5, WorkDuration::UpTo8h, true), 0.0);
        assert_eq!(frequency_multiplier(10.2, WorkDuration::UpTo8h, false), 0.0);
    }

    #[test]
    fn frequency_below_minimum_uses_0_2() {
        let mut l = ideal_metric();
        l.freq_per_min = 0.05;
        let r = assess_lift(&l).unwrap();
        assert_eq!(r.freq_used_per_min, 0.2);
        assert_eq!(r.origin.multipliers.fm, 1.0);
        assert!(
            r.adjustments
                .contains(&Adjustment::FrequencyRaisedToMinimum)
        );
    }

    #[test]
    fn table_7_coupling_multiplier() {
        assert_eq!(Coupling::Good.multiplier(true), 1.00);
        assert_eq!(Coupling::Good.multiplier(false), 1.00);
        assert_eq!(Coupling::Fair.multiplier(true), 0.95);
        assert_eq!(Coupling::Fair.multiplier(false), 1.00);
        assert_eq!(Coupling::Poor.multiplier(true), 0.90);
        assert_eq!(Coupling::Poor.multiplier(false), 0.90);
        // The V threshold is 75 cm: 74.9 cm is "V < 75", 75 cm is "V ≥ 75".
        let mut l = ideal_metric();
        l.coupling = Coupling::Fair;
        l.origin.v_m = 0.749;
        assert_eq!(assess_lift(&l).unwrap().origin.multipliers.cm, 0.95);
        l.origin.v_m = 0.75;
        assert_eq!(assess_lift(&l).unwrap().origin.multipliers.cm, 1.0);
    }

    #[test]
    fn work_duration_from_hours() {
        assert_eq!(WorkDuration::from_hours(0.75), Ok(WorkDuration::UpTo1h));
        assert_eq!(WorkDuration::from_hours(1.0), Ok(WorkDuration::UpTo1h));
        // p. 14: 30 min lifting + 10 min light work + 45 min lifting is 75 min (moderate).
        assert_eq!(WorkDuration::from_hours(1.25), Ok(WorkDuration::UpTo2h));
        assert_eq!(WorkDuration::from_hours(2.0), Ok(WorkDuration::UpTo2h));
        assert_eq!(WorkDuration::from_hours(2.01), Ok(WorkDuration::UpTo8h));
        assert_eq!(WorkDuration::from_hours(8.0), Ok(WorkDuration::UpTo8h));
        assert_eq!(
            WorkDuration::from_hours(8.5),
            Err(NioshError::DurationOutOfRange(8.5))
        );
        assert!(WorkDuration::from_hours(0.0).is_err());
        assert!(WorkDuration::from_hours(f64::NAN).is_err());
    }

    // ----- Worked examples of the Applications Manual.

    /// Example 5, "Dish-Washing Machine Unloading" (Applications Manual pp. 47–50, worksheet
    /// Figure 16). Job analysis as published: origin H = 20 in, V = 44 in, A = 30°;
    /// destination H = 20 in, V = 7 in, A = 30°; trays 20 lb; coupling Good; significant
    /// control at the destination; 5 lifts/min for 45 min to 1 h, FM = .80. Published: RWL
    /// 14.4 lb at the origin and 13.3 lb at the destination; LI 20/14.4 = 1.4 and 1.5;
    /// smallest multipliers .50 (HM), .80 (FM), .83 (VM, destination), .90 (AM).
    /// Tolerance: the manual rounds multipliers to 2 decimals and RWL/LI to 1 (p. 29).
    #[test]
    fn manual_example_5_dish_washing_machine_unloading() {
        let l = Lift {
            name: "Example 5: dish-washing machine unloading".into(),
            load_kg: 20.0 * KG_PER_LB,
            max_load_kg: None,
            origin: geometry(inch(20.0), inch(44.0), 30.0),
            destination: geometry(inch(20.0), inch(7.0), 30.0),
            freq_per_min: 5.0,
            duration: WorkDuration::UpTo1h,
            coupling: Coupling::Good,
            control_at_destination: true,
            form: EquationForm::UsCustomary,
        };
        let r = assess_lift(&l).unwrap();
        let o = r.origin;
        let d = r.destination.unwrap();
        // Published multipliers.
        assert_eq!(round(o.multipliers.hm, 2), 0.50);
        assert_eq!(round(o.multipliers.fm, 2), 0.80);
        assert_eq!(round(o.multipliers.am, 2), 0.90);
        assert_eq!(round(d.multipliers.vm, 2), 0.83);
        assert_eq!(round(o.multipliers.cm, 2), 1.00);
        // Worksheet RWLs (products of the rounded multipliers).
        assert_eq!(worksheet_rwl(&o, LOAD_CONSTANT_LB), 14.4);
        assert_eq!(worksheet_rwl(&d, LOAD_CONSTANT_LB), 13.3);
        // Full precision: 14.34 and 13.26 lb, within one rounding step of the worksheet.
        assert_abs_diff_eq!(o.rwl_kg / KG_PER_LB, 14.4, epsilon = 0.1);
        assert_abs_diff_eq!(d.rwl_kg / KG_PER_LB, 13.3, epsilon = 0.05);
        // Published LIs.
        assert_eq!(round(o.lifting_index.unwrap(), 1), 1.4);
        assert_eq!(round(d.lifting_index.unwrap(), 1), 1.5);
        assert_eq!(r.governing, Point::Destination);
        assert_eq!(round(r.lifting_index.unwrap(), 1), 1.5);
    }

    /// Example 4, "Package Inspection" (Applications Manual pp. 44–46, worksheet Figure 14),
    /// PARTIAL transcription (see niosh.md): L = 26 lb; origin V = 22 in with HM = 1.0 (H ≤ 10
    /// in), AM = 1.0; destination V = 59 in; D = 37 in; coupling Fair (CM .95 at the origin,
    /// 1.0 at the destination); FM = .88. Published worksheet RWL: 51 × 1.0 × .94 × .87 × 1.0 ×
    /// .88 × .95 = 34.9 lb at the origin and 15.2 lb at the destination. NOT verified from the
    /// manual itself: F and duration (3 lifts/min for ≤ 1 h is one cell of Table 5 that gives
    /// .88) and destination H = 20 in, A = 0° (inferred: it is the geometry that reproduces
    /// both the 15.2 lb worksheet value and the 15.3 lb full-precision value).
    #[test]
    fn manual_example_4_package_inspection_partial() {
        let l = Lift {
            name: "Example 4: package inspection".into(),
            load_kg: 26.0 * KG_PER_LB,
            max_load_kg: None,
            origin: geometry(inch(10.0), inch(22.0), 0.0),
            destination: geometry(inch(20.0), inch(59.0), 0.0),
            freq_per_min: 3.0,
            duration: WorkDuration::UpTo1h,
            coupling: Coupling::Fair,
            control_at_destination: true,
            form: EquationForm::UsCustomary,
        };
        let r = assess_lift(&l).unwrap();
        let o = r.origin;
        let d = r.destination.unwrap();
        let m = o.multipliers;
        assert_eq!(
            [m.hm, m.vm, m.dm, m.am, m.fm, m.cm].map(|x| round(x, 2)),
            [1.0, 0.94, 0.87, 1.0, 0.88, 0.95]
        );
        assert_eq!(round(d.multipliers.cm, 2), 1.0);
        assert_eq!(worksheet_rwl(&o, LOAD_CONSTANT_LB), 34.9);
        assert_eq!(worksheet_rwl(&d, LOAD_CONSTANT_LB), 15.2);
        assert_eq!(round(o.rwl_kg / KG_PER_LB, 1), 34.8);
        assert_eq!(round(d.rwl_kg / KG_PER_LB, 1), 15.3);
    }

    // ----- Hand-worked values.

    /// Metric, by hand: H = 40 cm → HM = 25/40 = .625; V = 30 cm → VM = 1 − .003·45 = .865;
    /// destination V = 100 cm → D = 70 cm → DM = .82 + 4.5/70 = .884286; A = 30° → AM = .904;
    /// F = 1/min, ≤ 2 h, V < 75 → FM = .88; Fair, V < 75 → CM = .95.
    /// FIRWL = 23 × .625 × .865 × .884286 × .904 × .95 = 9.44297 kg; RWL = × .88 = 8.30981 kg;
    /// LI = 10/8.30981 = 1.20340; FILI (max 12 kg) = 12/9.44297 = 1.27079.
    #[test]
    fn hand_worked_metric_lift() {
        let l = Lift {
            name: "hand".into(),
            load_kg: 10.0,
            max_load_kg: Some(12.0),
            origin: geometry(0.40, 0.30, 30.0),
            destination: geometry(0.40, 1.00, 0.0),
            freq_per_min: 1.0,
            duration: WorkDuration::UpTo2h,
            coupling: Coupling::Fair,
            control_at_destination: false,
            form: EquationForm::Metric,
        };
        let r = assess_lift(&l).unwrap();
        let m = r.origin.multipliers;
        assert_abs_diff_eq!(m.hm, 0.625, epsilon = 1e-12);
        assert_abs_diff_eq!(m.vm, 0.865, epsilon = 1e-12);
        assert_abs_diff_eq!(m.dm, 0.82 + 4.5 / 70.0, epsilon = 1e-12);
        assert_abs_diff_eq!(m.am, 0.904, epsilon = 1e-12);
        assert_abs_diff_eq!(m.fm, 0.88, epsilon = 1e-12);
        assert_abs_diff_eq!(m.cm, 0.95, epsilon = 1e-12);
        assert_abs_diff_eq!(r.fi_rwl_kg, 9.44297, epsilon = 1e-5);
        assert_abs_diff_eq!(r.rwl_kg, 8.30981, epsilon = 1e-5);
        assert_abs_diff_eq!(r.st_rwl_kg, r.rwl_kg, epsilon = 0.0);
        assert_abs_diff_eq!(r.lifting_index.unwrap(), 1.20340, epsilon = 1e-5);
        assert_abs_diff_eq!(r.fi_li.unwrap(), 1.27079, epsilon = 1e-5);
        assert!(r.destination.is_none());
        assert_eq!(r.governing, Point::Origin);
        assert!(r.adjustments.is_empty());
    }

    #[test]
    fn ideal_lift_gives_the_load_constant() {
        let r = assess_lift(&ideal_metric()).unwrap();
        assert_abs_diff_eq!(r.rwl_kg, LOAD_CONSTANT_KG, epsilon = 1e-12);
        let mut us = ideal_metric();
        us.form = EquationForm::UsCustomary;
        us.origin = geometry(inch(10.0), inch(30.0), 0.0);
        us.destination = geometry(inch(10.0), inch(40.0), 0.0);
        let r = assess_lift(&us).unwrap();
        assert_abs_diff_eq!(r.rwl_kg / KG_PER_LB, LOAD_CONSTANT_LB, epsilon = 1e-9);
    }

    #[test]
    fn metric_and_customary_forms_agree_within_a_few_percent() {
        // Same physical task in both forms: the constant sets differ by up to ~2 % (p. 7).
        let mut l = ideal_metric();
        l.origin = geometry(0.45, 0.20, 45.0);
        l.destination = geometry(0.35, 1.30, 0.0);
        l.freq_per_min = 2.0;
        l.duration = WorkDuration::UpTo8h;
        l.control_at_destination = true;
        let metric = assess_lift(&l).unwrap();
        l.form = EquationForm::UsCustomary;
        let us = assess_lift(&l).unwrap();
        assert!((metric.rwl_kg / us.rwl_kg - 1.0).abs() < 0.04);
    }

    #[test]
    fn out_of_range_geometry_follows_the_manual() {
        // H < 25 cm → 25 cm (HM = 1).
        let mut l = ideal_metric();
        l.origin.h_m = 0.10;
        let r = assess_lift(&l).unwrap();
        assert_eq!(r.origin.multipliers.hm, 1.0);
        assert_eq!(r.origin.multipliers.h_used_cm, 25.0);
        assert!(
            r.adjustments
                .contains(&Adjustment::HorizontalRaisedToMinimum { at: Point::Origin })
        );
        // H = 63 cm exactly is inside the range; above it HM = 0, RWL = 0, LI undefined.
        l.origin.h_m = 0.63;
        assert_abs_diff_eq!(
            assess_lift(&l).unwrap().origin.multipliers.hm,
            25.0 / 63.0,
            epsilon = 1e-12
        );
        l.origin.h_m = 0.64;
        let r = assess_lift(&l).unwrap();
        assert_eq!(r.rwl_kg, 0.0);
        assert_eq!(r.lifting_index, None);
        assert_eq!(r.fi_li, None);
        assert!(
            r.adjustments
                .contains(&Adjustment::HorizontalBeyondMaximum { at: Point::Origin })
        );
        // V above reach → VM = 0; A > 135° → AM = 0; D < 25 cm → DM = 1.
        let mut l = ideal_metric();
        l.destination.v_m = 0.80;
        l.origin.asymmetry_deg = 140.0;
        let r = assess_lift(&l).unwrap();
        assert_eq!(r.origin.multipliers.am, 0.0);
        assert_eq!(r.origin.multipliers.dm, 1.0);
        assert_eq!(r.origin.multipliers.d_used_cm, 25.0);
        assert!(r.adjustments.contains(&Adjustment::DistanceRaisedToMinimum));
        let mut l = ideal_metric();
        l.origin.v_m = 1.80;
        l.destination.v_m = 1.70;
        assert_eq!(assess_lift(&l).unwrap().origin.multipliers.vm, 0.0);
        // F above the column's maximum → FM = 0.
        let mut l = ideal_metric();
        l.freq_per_min = 16.0;
        let r = assess_lift(&l).unwrap();
        assert_eq!(r.origin.multipliers.fm, 0.0);
        assert_eq!(r.rwl_kg, 0.0);
        assert!(r.adjustments.contains(&Adjustment::FrequencyBeyondMaximum));
        assert!(r.fi_li.is_some());
    }

    #[test]
    fn lowering_uses_the_same_distance() {
        let mut up = ideal_metric();
        up.origin.v_m = 0.20;
        up.destination.v_m = 1.20;
        let mut down = up.clone();
        std::mem::swap(&mut down.origin, &mut down.destination);
        let a = assess_lift(&up).unwrap().origin.multipliers.dm;
        let b = assess_lift(&down).unwrap().origin.multipliers.dm;
        assert_eq!(a, b);
    }

    #[test]
    fn fm_uses_origin_v_and_cm_uses_each_end() {
        // Origin V = 30 cm, destination V = 120 cm, F = 11/min, ≤ 2 h: the V < 75 column gives
        // FM = 0, the V ≥ 75 column .23. FM follows the origin (0 at both ends, p. 15); CM
        // follows each end (Fair: .95 below 75 cm, 1.0 above).
        let mut l = ideal_metric();
        l.origin.v_m = 0.30;
        l.destination.v_m = 1.20;
        l.freq_per_min = 11.0;
        l.duration = WorkDuration::UpTo2h;
        l.coupling = Coupling::Fair;
        l.control_at_destination = true;
        let r = assess_lift(&l).unwrap();
        assert_eq!(r.origin.multipliers.fm, 0.0);
        assert_eq!(r.destination.unwrap().multipliers.fm, 0.0);
        assert_eq!(r.origin.multipliers.cm, 0.95);
        assert_eq!(r.destination.unwrap().multipliers.cm, 1.0);
    }

    #[test]
    fn invalid_inputs_are_refused_with_the_field_named() {
        let mut l = ideal_metric();
        l.load_kg = -1.0;
        let e = assess_lift(&l).unwrap_err();
        assert_eq!(
            e.to_string(),
            "load_kg must be at least 0 kg (object weight), got -1"
        );
        let mut l = ideal_metric();
        l.origin.h_m = f64::NAN;
        assert_eq!(
            assess_lift(&l).unwrap_err().to_string(),
            "origin.h_m must be a finite number, got NaN"
        );
        let mut l = ideal_metric();
        l.destination.v_m = -0.1;
        assert!(
            assess_lift(&l)
                .unwrap_err()
                .to_string()
                .starts_with("destination.v_m must be at least 0 m")
        );
        let mut l = ideal_metric();
        l.origin.asymmetry_deg = 200.0;
        assert!(matches!(
            assess_lift(&l),
            Err(NioshError::AsymmetryOutOfRange { .. })
        ));
        let mut l = ideal_metric();
        l.freq_per_min = f64::INFINITY;
        assert!(assess_lift(&l).is_err());
        let mut l = ideal_metric();
        l.max_load_kg = Some(5.0);
        assert_eq!(
            assess_lift(&l),
            Err(NioshError::MaxLoadBelowLoad {
                load_kg: 10.0,
                max_load_kg: 5.0
            })
        );
    }

    // ----- Composite Lifting Index.

    /// Three tasks, ≤ 1 h, worked by hand (the manual's own multi-task worksheets could not be
    /// transcribed; see niosh.md):
    /// * A: 10 kg, H 25, V 75 → 100 cm, Good, F = 1: FIRWL = 23, FM = .94, STRWL = 21.62,
    ///   FILI = 10/23 = .434783, STLI = 10/21.62 = .462535.
    /// * B: 15 kg, H 50 cm (HM .5), same V, F = 2: FIRWL = 11.5, FM = .91, STRWL = 10.465,
    ///   FILI = 1.304348, STLI = 1.433349.
    /// * C: 8 kg, H 25, V 50 → 75 cm (VM .925), Fair (CM .95, V < 75), F = 3: FIRWL =
    ///   20.21125, FM = .88, FILI = .395819, STLI = 8/17.7859 = .449797.
    ///
    /// Order by STLI: B, A, C. CLI = STLI_B + FILI_A·(1/FM(3) − 1/FM(2)) + FILI_C·(1/FM(6) −
    /// 1/FM(3)), with FM(3) = .88 (V ≥ 75 column: B and A start at 75 cm) and FM(6) = .75
    /// (V < 75 column since C starts at 50 cm): 1.433349 + .016288 + .077964 = 1.527601.
    #[test]
    fn composite_lifting_index_hand_worked() {
        let base = ideal_metric();
        let a = Lift {
            name: "A".into(),
            freq_per_min: 1.0,
            ..base.clone()
        };
        let b = Lift {
            name: "B".into(),
            load_kg: 15.0,
            origin: geometry(0.50, 0.75, 0.0),
            freq_per_min: 2.0,
            ..base.clone()
        };
        let c = Lift {
            name: "C".into(),
            load_kg: 8.0,
            origin: geometry(0.25, 0.50, 0.0),
            destination: geometry(0.25, 0.75, 0.0),
            coupling: Coupling::Fair,
            freq_per_min: 3.0,
            ..base
        };
        let r = composite(&[a, b, c]).unwrap();
        assert_eq!(r.order, vec![1, 0, 2]);
        let fili_a = 10.0 / 23.0;
        let fili_c = 8.0 / (23.0 * 0.925 * 0.95);
        let stli_b = 15.0 / (11.5 * 0.91);
        let expected =
            stli_b + fili_a * (1.0 / 0.88 - 1.0 / 0.91) + fili_c * (1.0 / 0.75 - 1.0 / 0.88);
        assert_abs_diff_eq!(expected, 1.527601, epsilon = 1e-6);
        assert_abs_diff_eq!(r.cli.unwrap(), expected, epsilon = 1e-12);
        assert_eq!(r.terms[1].cumulative_freq_per_min, 3.0);
        assert_eq!(r.terms[1].fm_cumulative, 0.88);
        assert!(!r.terms[1].fm_column_v_below_threshold);
        assert_eq!(r.terms[2].cumulative_freq_per_min, 6.0);
        assert_eq!(r.terms[2].fm_cumulative, 0.75);
        assert_eq!(r.terms[2].fm_previous_cumulative, Some(0.88));
        assert!(r.terms[2].fm_column_v_below_threshold);
        assert_abs_diff_eq!(r.terms[0].contribution.unwrap(), stli_b, epsilon = 1e-12);
    }

    #[test]
    fn composite_of_one_task_is_its_stli() {
        let mut l = ideal_metric();
        l.freq_per_min = 4.0;
        let single = assess_lift(&l).unwrap();
        let r = composite(std::slice::from_ref(&l)).unwrap();
        assert_eq!(r.cli, single.st_li);
    }

    #[test]
    fn composite_ties_put_the_higher_frequency_first() {
        // F = 0.1 and 0.2 both use FM(0.2) = 1, so the STLIs are exactly equal (p. 57).
        let mut slow = ideal_metric();
        slow.name = "slow".into();
        slow.freq_per_min = 0.1;
        let mut fast = slow.clone();
        fast.name = "fast".into();
        fast.freq_per_min = 0.2;
        let r = composite(&[slow, fast]).unwrap();
        assert_eq!(r.order, vec![1, 0]);
    }

    #[test]
    fn composite_is_undefined_when_the_combined_frequency_is_too_high() {
        let mut a = ideal_metric();
        a.freq_per_min = 10.0;
        let b = a.clone();
        // 20 lifts/min exceeds Table 5: FM(1,2) = 0.
        let r = composite(&[a, b]).unwrap();
        assert_eq!(r.terms[1].fm_cumulative, 0.0);
        assert_eq!(r.cli, None);
    }

    #[test]
    fn composite_refuses_mixed_jobs_and_bad_lifts() {
        assert_eq!(composite(&[]), Err(NioshError::NoLifts));
        let a = ideal_metric();
        let mut b = a.clone();
        b.duration = WorkDuration::UpTo8h;
        assert!(matches!(
            composite(&[a.clone(), b]),
            Err(NioshError::MixedDurations { index: 1, .. })
        ));
        let mut c = a.clone();
        c.form = EquationForm::UsCustomary;
        assert!(matches!(
            composite(&[a.clone(), c]),
            Err(NioshError::MixedForms { index: 1, .. })
        ));
        let mut d = a.clone();
        d.name = "bad".into();
        d.load_kg = -2.0;
        let e = composite(&[a, d]).unwrap_err();
        assert!(e.to_string().starts_with("lifts[1] (bad): load_kg must be"));
    }

    /// Every extreme value in every numeric input either gives an error or a result without
    /// panicking; the RWL and the multipliers stay finite.
    #[test]
    fn never_panics_on_extreme_inputs() {
        let extremes = [
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            -1e308,
            -1.0,
            -0.0,
            0.0,
            1e-300,
            0.2,
            0.75,
            1.0,
            63.0,
            180.0,
            1e308,
        ];
        for form in [EquationForm::Metric, EquationForm::UsCustomary] {
            for which in 0..9 {
                for &x in &extremes {
                    let mut l = ideal_metric();
                    l.form = form;
                    l.control_at_destination = true;
                    match which {
                        0 => l.load_kg = x,
                        1 => l.max_load_kg = Some(x),
                        2 => l.freq_per_min = x,
                        3 => l.origin.h_m = x,
                        4 => l.origin.v_m = x,
                        5 => l.origin.asymmetry_deg = x,
                        6 => l.destination.h_m = x,
                        7 => l.destination.v_m = x,
                        _ => l.destination.asymmetry_deg = x,
                    }
                    if let Ok(r) = assess_lift(&l) {
                        let m = r.origin.multipliers;
                        for v in [r.rwl_kg, r.fi_rwl_kg, m.hm, m.vm, m.dm, m.am, m.fm, m.cm] {
                            assert!(v.is_finite(), "input {which} = {x}: {r:?}");
                        }
                    }
                    let _ = composite(&[l.clone(), l]);
                }
            }
        }
    }

    #[test]
    fn results_serialize() {
        fn is_serialize<T: Serialize>() {}
        is_serialize::<LiftResult>();
        is_serialize::<CompositeResult>();
    }
}
