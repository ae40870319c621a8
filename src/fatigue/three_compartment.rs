//! The three-compartment (3CC) fatigue model of Xia & Frey-Law (2008), a second model behind the
//! same [`FatigueModel`](super::FatigueModel) interface, for comparison with Ma et al.
//!
//! Motor-unit fractions: active `MA`, resting `MR`, fatigued `MF`, with `MA + MR + MF = 1`:
//!
//! * `dMA/dt = C − F·MA`, `dMR/dt = −C + R·MF`, `dMF/dt = F·MA − R·MF`;
//! * controller toward target load `TL` (= relative load f):
//!   `C = LD·(TL − MA)` if `MA < TL` and `MR > TL − MA`; `C = LD·MR` if `MA < TL` otherwise;
//!   `C = LR·(TL − MA)` if `MA ≥ TL`;
//! * during rest (`TL = 0`) the recovery rate becomes `r·R` (Looft et al. 2018).
//!
//! Capacity is the residual capacity `MA + MR = 1 − MF`. F and R per joint: Frey-Law, Looft &
//! Heitsman (2012), J Biomech 45:1803, Table 1 (see `docs/fatigue-parameters.md`).
//! The controller is discontinuous, so there is no closed form for arbitrary loads: [`ThreeCompartment::hold`]
//! integrates with classic RK4 at a fixed sub-step of at most [`ThreeCompartment::MAX_SUBSTEP_S`]
//! (stable and accurate for LD = LR = 10 s⁻¹; checked against the sustained-load closed form in
//! the tests). The fatigue index `U` is accumulated with Ma's definition, `dU/dt = f / c²`.

use super::units::s_to_min;

/// 3CC parameters; rates in 1/s as published.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ThreeCompartment {
    /// Fatigue rate F [1/s].
    pub f_per_s: f64,
    /// Recovery rate R [1/s].
    pub r_per_s: f64,
    /// Development gain LD [1/s] (Xia & Frey-Law: 10).
    pub ld_per_s: f64,
    /// Relaxation gain LR [1/s] (Xia & Frey-Law: 10).
    pub lr_per_s: f64,
    /// Rest recovery multiplier r (Looft et al. 2018): R becomes r·R while TL = 0.
    pub rest_multiplier: f64,
}

/// Motor-unit fractions and the accumulated fatigue index.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ThreeCompartmentState {
    pub ma: f64,
    pub mr: f64,
    pub mf: f64,
    pub fatigue_u_min: f64,
}

impl ThreeCompartmentState {
    pub const FRESH: Self = ThreeCompartmentState {
        ma: 0.0,
        mr: 1.0,
        mf: 0.0,
        fatigue_u_min: 0.0,
    };
    /// Residual capacity `MA + MR`.
    pub fn capacity(&self) -> f64 {
        self.ma + self.mr
    }
}

/// Frey-Law et al. (2012) joint regions with fitted F and R [1/s].
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Region {
    Ankle,
    Knee,
    Trunk,
    Shoulder,
    Elbow,
    Grip,
    General,
}

impl Region {
    pub const ALL: [Region; 7] = [
        Region::Ankle,
        Region::Knee,
        Region::Trunk,
        Region::Shoulder,
        Region::Elbow,
        Region::Grip,
        Region::General,
    ];
    pub fn name(self) -> &'static str {
        match self {
            Region::Ankle => "ankle",
            Region::Knee => "knee",
            Region::Trunk => "trunk",
            Region::Shoulder => "shoulder",
            Region::Elbow => "elbow",
            Region::Grip => "grip",
            Region::General => "general",
        }
    }
    /// (F, R) in 1/s, Frey-Law, Looft & Heitsman (2012), J Biomech 45:1803.
    pub fn frey_law_2012_f_r_per_s(self) -> (f64, f64) {
        match self {
            Region::Ankle => (0.00589, 0.00058),
            Region::Knee => (0.01500, 0.00149),
            Region::Trunk => (0.00755, 0.00075),
            Region::Shoulder => (0.01820, 0.00168),
            Region::Elbow => (0.00912, 0.00094),
            Region::Grip => (0.00980, 0.00064),
            Region::General => (0.00970, 0.00091),
        }
    }
    /// Rest recovery multiplier r (Looft, Herkert & Frey-Law 2018; Looft & Frey-Law 2020):
    /// 15 for ankle, knee, elbow and shoulder, 30 for the hand. Trunk and general: 15, an
    /// assumption (not fitted in those papers).
    pub fn rest_multiplier(self) -> f64 {
        match self {
            Region::Grip => 30.0,
            _ => 15.0,
        }
    }
}

impl ThreeCompartment {
    /// Largest RK4 sub-step \[s\].
    pub const MAX_SUBSTEP_S: f64 = 0.02;

    /// Published parameters for a region, LD = LR = 10 s⁻¹.
    pub fn for_region(region: Region) -> Self {
        let (f, r) = region.frey_law_2012_f_r_per_s();
        ThreeCompartment {
            f_per_s: f,
            r_per_s: r,
            ld_per_s: 10.0,
            lr_per_s: 10.0,
            rest_multiplier: region.rest_multiplier(),
        }
    }

    #[inline]
    fn deriv(&self, s: &[f64; 3], tl: f64) -> [f64; 3] {
        let [ma, mr, mf] = *s;
        let c = if ma < tl {
            if mr > tl - ma {
                self.ld_per_s * (tl - ma)
            } else {
                self.ld_per_s * mr
            }
        } else {
            self.lr_per_s * (tl - ma)
        };
        let r = if tl > 0.0 {
            self.r_per_s
        } else {
            self.r_per_s * self.rest_multiplier
        };
        [
            c - self.f_per_s * ma,
            -c + r * mf,
            self.f_per_s * ma - r * mf,
        ]
    }

    /// Holds target load `f` for `dt_s` seconds (RK4, fixed sub-steps).
    pub fn hold(&self, st: &mut ThreeCompartmentState, f: f64, dt_s: f64) {
        if dt_s <= 0.0 {
            return;
        }
        let n = (dt_s / Self::MAX_SUBSTEP_S).ceil().max(1.0);
        let h = dt_s / n;
        let mut y = [st.ma, st.mr, st.mf];
        let mut u = st.fatigue_u_min;
        let du = |y: &[f64; 3]| {
            let c = (y[0] + y[1]).max(1e-12);
            f / (c * c)
        };
        for _ in 0..n as usize {
            let add = |a: &[f64; 3], k: &[f64; 3], s: f64| {
                [a[0] + s * k[0], a[1] + s * k[1], a[2] + s * k[2]]
            };
            let k1 = self.deriv(&y, f);
            let y2 = add(&y, &k1, h / 2.0);
            let k2 = self.deriv(&y2, f);
            let y3 = add(&y, &k2, h / 2.0);
            let k3 = self.deriv(&y3, f);
            let y4 = add(&y, &k3, h);
            let k4 = self.deriv(&y4, f);
            if f > 0.0 {
                u += s_to_min(h) / 6.0 * (du(&y) + 2.0 * du(&y2) + 2.0 * du(&y3) + du(&y4));
            }
            for i in 0..3 {
                y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
                y[i] = y[i].clamp(0.0, 1.0);
            }
        }
        st.ma = y[0];
        st.mr = y[1];
        st.mf = y[2];
        st.fatigue_u_min = if u.is_finite() { u } else { f64::MAX };
    }

    /// Sustained-load endurance time \[s\] (closed form, neglecting the ~0.1 s rise of MA):
    /// `ET = −ln(1 − R(1 − TL)/(F·TL)) / R`; `None` if the load can be held indefinitely.
    pub fn endurance_time_s(&self, f: f64) -> Option<f64> {
        if f <= 0.0 {
            return None;
        }
        if f >= 1.0 {
            return Some(0.0);
        }
        let x = self.r_per_s * (1.0 - f) / (self.f_per_s * f);
        if x >= 1.0 {
            None
        } else {
            Some(-(1.0 - x).ln() / self.r_per_s)
        }
    }
}
