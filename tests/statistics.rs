//! r and ICC against values worked out by hand.

use posture_opt::fatigue::stats::{icc_oneway, pearson_r};

#[test]
fn pearson_by_hand() {
    // a = (0, 1, 2, 3), b = (1, 3, 2, 6): means 1.5, 3; dx = (−1.5, −.5, .5, 1.5), dy = (−2, 0, −1, 3)
    // Σdxdy = 3 + 0 − .5 + 4.5 = 7; Σdx² = 5; Σdy² = 14 → r = 7/√70
    let r = pearson_r(&[0.0, 1.0, 2.0, 3.0], &[1.0, 3.0, 2.0, 6.0]);
    assert!((r - 7.0 / 70f64.sqrt()).abs() < 1e-15);
    assert!((pearson_r(&[1.0, 2.0, 3.0], &[-2.0, -4.0, -6.0]) + 1.0).abs() < 1e-15);
    assert!(pearson_r(&[1.0, 1.0], &[1.0, 2.0]).is_nan());
}

#[test]
fn icc_by_hand() {
    // identical raters: MS_within = 0 → ICC = 1
    assert!((icc_oneway(&[1.0, 4.0, 9.0], &[1.0, 4.0, 9.0]) - 1.0).abs() < 1e-15);
    // targets (2, 4), (6, 6): means 3, 6, grand 4.5; SSB = 2·(2.25 + 2.25) = 9, MSB = 9/1;
    // SSW = 1 + 1 + 0 + 0 = 2, MSW = 2/2 = 1 → ICC = (9 − 1)/(9 + 1) = 0.8
    assert!((icc_oneway(&[2.0, 6.0], &[4.0, 6.0]) - 0.8).abs() < 1e-15);
    // a constant offset lowers ICC but not r
    let a = [1.0, 2.0, 3.0, 4.0];
    let b = [3.0, 4.0, 5.0, 6.0];
    assert!((pearson_r(&a, &b) - 1.0).abs() < 1e-15);
    // means 2,3,4,5 grand 3.5: SSB = 2·(2.25+.25+.25+2.25) = 10, MSB = 10/3; SSW = 4·2 = 8, MSW = 8/4 = 2
    assert!((icc_oneway(&a, &b) - (10.0 / 3.0 - 2.0) / (10.0 / 3.0 + 2.0)).abs() < 1e-15);
}
