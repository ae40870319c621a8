//! Agreement statistics of the paper's static validation.

/// Pearson's correlation r between two equally long series (paper Eq. 9).
/// Returns NaN when a series has zero variance or the lengths differ.
///
/// ```
/// let r = posture_opt::fatigue::stats::pearson_r(&[1.0, 2.0, 3.0], &[2.0, 4.0, 7.0]);
/// // by hand: Σdxdy = 5, Σdx² = 2, Σdy² = 114/9, r = 5 / sqrt(2·114/9)
/// assert!((r - 5.0 / (2.0f64 * 114.0 / 9.0).sqrt()).abs() < 1e-15);
/// ```
pub fn pearson_r(a: &[f64], b: &[f64]) -> f64 {
    if a.len() != b.len() || a.is_empty() {
        return f64::NAN;
    }
    let n = a.len() as f64;
    let ma = a.iter().sum::<f64>() / n;
    let mb = b.iter().sum::<f64>() / n;
    let (mut sab, mut saa, mut sbb) = (0.0, 0.0, 0.0);
    for (x, y) in a.iter().zip(b) {
        let (dx, dy) = (x - ma, y - mb);
        sab += dx * dy;
        saa += dx * dx;
        sbb += dy * dy;
    }
    sab / (saa * sbb).sqrt()
}

/// One-way intraclass correlation of two "raters" (paper Eq. 10 with p = 2):
/// `ICC = (MS_between − MS_within) / (MS_between + (p − 1) MS_within)`, where `MS_between` is the
/// mean square between targets (the n %MVC levels, df = n − 1) and `MS_within` the mean square
/// within each target (between the two models, df = n (p − 1)).
///
/// ```
/// // by hand: target means 1.5, 3, 6, grand mean 3.5; MSB = 2·(4 + 0.25 + 6.25)/2 = 10.5,
/// // MSW = (0.5 + 0 + 2)/3 = 5/6; ICC = (10.5 − 5/6)/(10.5 + 5/6) = 29/34
/// let icc = posture_opt::fatigue::stats::icc_oneway(&[1.0, 3.0, 5.0], &[2.0, 3.0, 7.0]);
/// assert!((icc - 29.0 / 34.0).abs() < 1e-12);
/// ```
pub fn icc_oneway(a: &[f64], b: &[f64]) -> f64 {
    if a.len() != b.len() || a.len() < 2 {
        return f64::NAN;
    }
    let n = a.len() as f64;
    let p = 2.0;
    let grand = (a.iter().sum::<f64>() + b.iter().sum::<f64>()) / (n * p);
    let (mut ssb, mut ssw) = (0.0, 0.0);
    for (x, y) in a.iter().zip(b) {
        let m = 0.5 * (x + y);
        ssb += p * (m - grand) * (m - grand);
        ssw += (x - m) * (x - m) + (y - m) * (y - m);
    }
    let msb = ssb / (n - 1.0);
    let msw = ssw / (n * (p - 1.0));
    (msb - msw) / (msb + (p - 1.0) * msw)
}
