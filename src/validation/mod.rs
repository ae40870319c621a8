//! The paper's validations, reproduced: static (§3, Table 2) and dynamic (§4), plus the
//! Frey-Law & Avin (2010) endurance curves and the three-compartment model as extra anchors, and
//! the planning model itself (with recovery) against endurance, intermittent and recovery data.
//! Results are plain data (serde) for the CLI's tables, JSON and SVG figures.

pub mod dynamic;
pub mod plots;
pub mod recovery;
pub mod report;
pub mod static_table;

pub use dynamic::{DynamicValidation, dynamic_validation};
pub use recovery::{RecoveryValidation, recovery_validation};
pub use static_table::{StaticValidation, static_validation};
