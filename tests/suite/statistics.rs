//! The agreement statistics of the paper's static validation (Ma et al. 2009, Eq. 9 and 10),
//! against values worked out by hand and against their defining properties.

use posture_opt::fatigue::stats::{icc_oneway, pearson_r};
use proptest::prelude::*;

#[test]
fn pearson_by_hand() {
    // a = (0, 1, 2, 3), b = (1, 3, 2, 6): means 1.5, 3; dx = (−1.5, −.5, .5, 1.5), dy = (−2, 0, −1, 3)
    // Σdxdy = 3 + 0 − .5 + 4.5 = 7; Σdx² = 5; Σdy² = 14 → r = 7/√70
    let r = pearson_r(&[0.0, 1.0, 2.0, 3.0], &[1.0, 3.0, 2.0, 6.0]);
    assert!((r - 7.0 / 70f64.sqrt()).abs() < 1e-15);
    assert!((pearson_r(&[1.0, 2.0, 3.0], &[-2.0, -4.0, -6.0]) + 1.0).abs() < 1e-15);
    // uncorrelated by construction: dx = (−1, 0, 1), dy = (1, −2, 1)
    assert!(pearson_r(&[1.0, 2.0, 3.0], &[2.0, -1.0, 2.0]).abs() < 1e-15);
    // undefined: a constant series, unequal lengths, nothing
    assert!(pearson_r(&[1.0, 1.0], &[1.0, 2.0]).is_nan());
    assert!(pearson_r(&[1.0, 2.0], &[1.0, 2.0, 3.0]).is_nan());
    assert!(pearson_r(&[], &[]).is_nan());
}

#[test]
fn icc_by_hand() {
    // identical raters: MS_within = 0 → ICC = 1
    assert!((icc_oneway(&[1.0, 4.0, 9.0], &[1.0, 4.0, 9.0]) - 1.0).abs() < 1e-15);
    // targets (2, 4), (6, 6): means 3, 6, grand 4.5; SSB = 2·(2.25 + 2.25) = 9, MSB = 9/1;
    // SSW = 1 + 1 + 0 + 0 = 2, MSW = 2/2 = 1 → ICC = (9 − 1)/(9 + 1) = 0.8
    assert!((icc_oneway(&[2.0, 6.0], &[4.0, 6.0]) - 0.8).abs() < 1e-15);
    // a constant offset lowers ICC but not r:
    // means 2, 3, 4, 5, grand 3.5: SSB = 2·(2.25 + .25 + .25 + 2.25) = 10, MSB = 10/3; SSW = 4·2 = 8, MSW = 2
    let a = [1.0, 2.0, 3.0, 4.0];
    let b = [3.0, 4.0, 5.0, 6.0];
    assert!((pearson_r(&a, &b) - 1.0).abs() < 1e-15);
    assert!((icc_oneway(&a, &b) - (10.0 / 3.0 - 2.0) / (10.0 / 3.0 + 2.0)).abs() < 1e-15);
    // raters disagreeing more than targets differ: (1, 3), (3, 1): means 2, 2 → MSB = 0,
    // SSW = 4·1 = 4, MSW = 2 → ICC = −1
    assert!((icc_oneway(&[1.0, 3.0], &[3.0, 1.0]) + 1.0).abs() < 1e-15);
    // undefined with fewer than two targets or unequal lengths
    assert!(icc_oneway(&[1.0], &[2.0]).is_nan());
    assert!(icc_oneway(&[1.0, 2.0], &[1.0]).is_nan());
}

fn series() -> impl Strategy<Value = (Vec<f64>, Vec<f64>)> {
    (3usize..40).prop_flat_map(|n| {
        (
            proptest::collection::vec(-100.0f64..100.0, n),
            proptest::collection::vec(-100.0f64..100.0, n),
        )
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, failure_persistence: None, ..ProptestConfig::default() })]

    /// r is symmetric, within [−1, 1], unchanged by a positive affine map of either series and
    /// negated by a negative one.
    #[test]
    fn pearson_properties((a, b) in series(), s in 0.1f64..10.0, t in -50.0f64..50.0) {
        let r = pearson_r(&a, &b);
        prop_assume!(r.is_finite());
        prop_assert!((-1.0 - 1e-12..=1.0 + 1e-12).contains(&r));
        prop_assert!((r - pearson_r(&b, &a)).abs() < 1e-12);
        let scaled: Vec<f64> = b.iter().map(|x| s * x + t).collect();
        prop_assert!((r - pearson_r(&a, &scaled)).abs() < 1e-10);
        let flipped: Vec<f64> = b.iter().map(|x| -s * x + t).collect();
        prop_assert!((r + pearson_r(&a, &flipped)).abs() < 1e-10);
        let line: Vec<f64> = a.iter().map(|x| s * x + t).collect();
        prop_assume!(pearson_r(&a, &a).is_finite());
        prop_assert!((pearson_r(&a, &line) - 1.0).abs() < 1e-10);
    }

    /// ICC is symmetric in the two raters, at most 1, 1 for identical raters, unchanged by one
    /// affine map applied to both; with a constant offset δ between them, by hand
    /// `ICC = (2 s² − δ²/2)/(2 s² + δ²/2)`, s² the sample variance of the targets.
    #[test]
    fn icc_properties((a, b) in series(), s in 0.1f64..10.0, t in -50.0f64..50.0, delta in -20.0f64..20.0) {
        let i = icc_oneway(&a, &b);
        prop_assert!(i <= 1.0 + 1e-12);
        prop_assert!((i - icc_oneway(&b, &a)).abs() < 1e-12);
        let map = |v: &[f64]| v.iter().map(|x| s * x + t).collect::<Vec<f64>>();
        prop_assert!((i - icc_oneway(&map(&a), &map(&b))).abs() < 1e-9);
        prop_assert!((icc_oneway(&a, &a) - 1.0).abs() < 1e-12);
        let n = a.len() as f64;
        let mean = a.iter().sum::<f64>() / n;
        let s2 = a.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / (n - 1.0);
        let shifted: Vec<f64> = a.iter().map(|x| x + delta).collect();
        let by_hand = (2.0 * s2 - delta * delta / 2.0) / (2.0 * s2 + delta * delta / 2.0);
        prop_assert!((icc_oneway(&a, &shifted) - by_hand).abs() < 1e-9);
    }
}
