//! Tests of the OpenSim reader and mapping. Data files are in `tests/data/opensim/`
//! (written by hand to the format), the shipped mapping in `data/opensim/`.

use super::*;
use std::io::{BufReader, Cursor, Read};

const SMALL_MOT: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/data/opensim/rajagopal_small.mot"
));
const RADIANS_STO: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/data/opensim/small_radians.sto"
));
const LEGACY_MOT: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/data/opensim/legacy_simm.mot"
));
const RAJAGOPAL_YAML: &str = include_str!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/data/opensim/rajagopal2016.mapping.yaml"
));

/// The worker's joints in q order (docs/body.md).
const WORKER: [&str; 38] = [
    "pelvis_tx",
    "pelvis_ty",
    "pelvis_tz",
    "pelvis_rotation",
    "pelvis_list",
    "pelvis_tilt",
    "lumbar_flexion",
    "lumbar_lateral_bending",
    "lumbar_axial_rotation",
    "neck_flexion",
    "neck_lateral_bending",
    "neck_axial_rotation",
    "r_shoulder_flexion",
    "r_shoulder_abduction",
    "r_shoulder_rotation",
    "r_elbow_flexion",
    "r_forearm_pronation",
    "r_wrist_flexion",
    "r_wrist_deviation",
    "l_shoulder_flexion",
    "l_shoulder_abduction",
    "l_shoulder_rotation",
    "l_elbow_flexion",
    "l_forearm_pronation",
    "l_wrist_flexion",
    "l_wrist_deviation",
    "r_hip_flexion",
    "r_hip_abduction",
    "r_hip_rotation",
    "r_knee_flexion",
    "r_ankle_dorsiflexion",
    "r_ankle_inversion",
    "l_hip_flexion",
    "l_hip_abduction",
    "l_hip_rotation",
    "l_knee_flexion",
    "l_ankle_dorsiflexion",
    "l_ankle_inversion",
];

fn reader(text: &str, origin: &str) -> Result<StorageReader<Cursor<Vec<u8>>>, OpenSimError> {
    StorageReader::new(Cursor::new(text.as_bytes().to_vec()), origin)
}

fn reader_bytes(
    bytes: &[u8],
    origin: &str,
) -> Result<StorageReader<Cursor<Vec<u8>>>, OpenSimError> {
    StorageReader::new(Cursor::new(bytes.to_vec()), origin)
}

/// Reads all rows, returning the first error.
fn read_all(text: &str, origin: &str) -> Result<Vec<(f64, Vec<f64>)>, OpenSimError> {
    let mut r = reader(text, origin)?;
    let mut rows = Vec::new();
    let mut row = Vec::new();
    while let Some(t) = r.next_row(&mut row)? {
        rows.push((t, row.clone()));
    }
    Ok(rows)
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

fn rajagopal() -> Mapping {
    Mapping::from_yaml_str(RAJAGOPAL_YAML, "rajagopal2016.mapping.yaml")
        .expect("shipped mapping parses")
}

fn idx(joint: &str) -> usize {
    WORKER
        .iter()
        .position(|j| *j == joint)
        .expect("worker joint")
}

// ---------------------------------------------------------------------------
// Reader
// ---------------------------------------------------------------------------

#[test]
fn header_of_hand_written_mot() {
    let r = reader(SMALL_MOT, "rajagopal_small.mot").unwrap();
    let h = r.header();
    assert_eq!(h.name.as_deref(), Some("Coordinates"));
    assert_eq!(h.version, 1);
    assert!(h.in_degrees);
    assert_eq!(h.in_degrees_source, InDegreesSource::Declared { line: 5 });
    assert_eq!(h.declared_rows, Some(6));
    assert_eq!(h.declared_columns, Some(40));
    assert_eq!(h.columns.len(), 39);
    assert_eq!(h.columns[0], "pelvis_tilt");
    assert_eq!(h.columns[38], "wrist_dev_l");
    assert_eq!(h.labels_line, 11);
    assert_eq!(h.description.len(), 2);
    assert!(h.description[0].starts_with("Units are S.I. units"));
}

#[test]
fn reader_yields_rows_with_degrees_converted_only_in_angle_columns() {
    let mut r = reader(SMALL_MOT, "rajagopal_small.mot").unwrap();
    let bound = rajagopal()
        .bind(r.header(), "rajagopal_small.mot", &WORKER)
        .unwrap();
    r.set_angle_columns(bound.angle_columns()).unwrap();
    let col = |name: &str| r.header().column_index(name).unwrap();
    let (knee, pelvis_ty, pelvis_tx, mtp, pro_sup_r) = (
        col("knee_angle_r"),
        col("pelvis_ty"),
        col("pelvis_tx"),
        col("mtp_angle_r"),
        col("pro_sup_r"),
    );
    let mut row = Vec::new();
    let mut times = Vec::new();
    let mut rows = Vec::new();
    while let Some(t) = r.next_row(&mut row).unwrap() {
        assert_eq!(row.len(), 39);
        times.push(t);
        rows.push(row.clone());
    }
    assert_eq!(times, vec![0.0, 0.01, 0.02, 0.03, 0.04, 0.05]);
    assert_eq!(r.rows_read(), 6);
    // Degrees -> radians in rotational columns.
    assert!(close(rows[1][knee], 30.0_f64.to_radians(), 1e-15));
    assert!(close(
        rows[0][pro_sup_r],
        std::f64::consts::FRAC_PI_2,
        1e-15
    ));
    // Translations stay in metres.
    assert_eq!(rows[0][pelvis_ty], 0.94);
    assert_eq!(rows[3][pelvis_tx], 1.5);
    // mtp_angle_r is ignored by the mapping, hence not declared an angle:
    // returned as written.
    assert_eq!(rows[1][mtp], 15.0);
    // End of data is sticky.
    assert_eq!(r.next_row(&mut row).unwrap(), None);
    assert_eq!(r.next_row(&mut row).unwrap(), None);
}

#[test]
fn reader_without_angle_columns_returns_values_as_written() {
    let rows = read_all(SMALL_MOT, "rajagopal_small.mot").unwrap();
    assert_eq!(rows.len(), 6);
    assert_eq!(rows[1].1[10], 30.0); // knee_angle_r, column 11 of the file
}

#[test]
fn sto_in_radians_is_not_converted() {
    let r = reader(RADIANS_STO, "small_radians.sto").unwrap();
    assert!(!r.header().in_degrees);
    assert_eq!(
        r.header().in_degrees_source,
        InDegreesSource::Declared { line: 5 }
    );
    let yaml = "joints:\n  - {joint: r_elbow_flexion, from: elbow_flex_r, sign: 1}\n  - {joint: r_forearm_pronation, from: pro_sup_r, sign: 1, offset_deg: -90}\n  - {joint: pelvis_tz, from: pelvis_ty, sign: 1, offset_m: -0.94, kind: translation}\n";
    let m = Mapping::from_yaml_str(yaml, "test.yaml").unwrap();
    let mut motion = MappedMotion::new(r, &m, &WORKER).unwrap();
    let mut q = vec![f64::NAN; WORKER.len()];
    let expected = [
        (0.0, 0.0, 0.0, 0.0),
        (0.5, 0.5, 1.0 - std::f64::consts::FRAC_PI_2, 0.01),
        (1.0, 1.0, 0.5 - std::f64::consts::FRAC_PI_2, 0.02),
        (1.5, 1.5, -std::f64::consts::FRAC_PI_2, 0.03),
    ];
    for (t, elbow, pron, tz) in expected {
        assert_eq!(motion.next_frame(&mut q).unwrap(), Some(t));
        assert!(close(q[idx("r_elbow_flexion")], elbow, 1e-12));
        assert!(close(q[idx("r_forearm_pronation")], pron, 1e-12));
        assert!(close(q[idx("pelvis_tz")], tz, 1e-12));
        assert_eq!(q[idx("r_knee_flexion")], 0.0);
    }
    assert_eq!(motion.next_frame(&mut q).unwrap(), None);
    assert_eq!(motion.frames_read(), 4);
}

#[test]
fn legacy_simm_mot_header_defaults_to_degrees() {
    let mut r = reader(LEGACY_MOT, "legacy_simm.mot").unwrap();
    let h = r.header().clone();
    assert_eq!(h.version, 0);
    assert_eq!(h.name.as_deref(), Some("first trial"));
    assert!(h.in_degrees);
    assert_eq!(h.in_degrees_source, InDegreesSource::LegacyMotionDefault);
    assert_eq!(h.declared_rows, Some(3));
    assert_eq!(h.declared_columns, Some(4));
    assert!(
        h.metadata
            .iter()
            .any(|(k, v)| k == "range" && v == "0.400000 0.433333")
    );
    assert_eq!(h.columns, vec!["knee_angle_r", "pelvis_ty", "elbow_flex_r"]);
    r.set_angle_columns(&[true, false, true]).unwrap();
    let mut row = Vec::new();
    assert_eq!(r.next_row(&mut row).unwrap(), Some(0.4));
    assert!(close(row[0], (-55.0_f64).to_radians(), 1e-15));
    assert_eq!(row[1], 1.045);
    assert!(close(row[2], 10.0_f64.to_radians(), 1e-15));
    assert_eq!(r.next_row(&mut row).unwrap(), Some(0.41666667));
    assert_eq!(r.next_row(&mut row).unwrap(), Some(0.43333333));
    assert_eq!(r.next_row(&mut row).unwrap(), None);
}

#[test]
fn legacy_header_in_sto_defaults_to_radians() {
    let r = reader(LEGACY_MOT, "legacy_simm.sto").unwrap();
    assert!(!r.header().in_degrees);
    assert_eq!(
        r.header().in_degrees_source,
        InDegreesSource::DefaultRadians
    );
}

#[test]
fn version0_angles_line_is_honoured() {
    let text = "Coordinates\nnRows=1\nnColumns=2\n\nUnits are S.I. units (second, meters, Newtons, ...)\nAngles are in degrees.\n\nendheader\ntime\tknee_angle_r\n0.0\t90\n";
    let r = reader(text, "kin_q.sto").unwrap();
    assert!(r.header().in_degrees);
    assert_eq!(
        r.header().in_degrees_source,
        InDegreesSource::AnglesLine { line: 6 }
    );
    // Version 1 ignores it, as OpenSim does.
    let text1 = text.replace("Coordinates\n", "Coordinates\nversion=1\n");
    let r = reader(&text1, "kin_q.sto").unwrap();
    assert!(!r.header().in_degrees);
}

#[test]
fn explicit_in_degrees_no_wins_over_legacy_mot_default() {
    let text = "x\nnRows=1\nnColumns=2\ninDegrees=no\nendheader\ntime a\n0 1\n";
    let r = reader(text, "x.mot").unwrap();
    assert!(!r.header().in_degrees);
}

#[test]
fn version2_header_with_datatype_double_is_read() {
    let text = "DataType=double\nversion=3\nOpenSimVersion=4.5\ninDegrees=yes\nendheader\ntime\tknee_angle_r\n0\t10\n0.1\t20\n";
    let mut r = reader(text, "solution.sto").unwrap();
    assert_eq!(r.header().version, 3);
    assert_eq!(r.header().data_type.as_deref(), Some("double"));
    assert!(
        r.header()
            .metadata
            .iter()
            .any(|(k, v)| k == "OpenSimVersion" && v == "4.5")
    );
    r.set_angle_columns(&[true]).unwrap();
    let mut row = Vec::new();
    assert_eq!(r.next_row(&mut row).unwrap(), Some(0.0));
    assert!(close(row[0], 10.0_f64.to_radians(), 1e-15));
}

#[test]
fn crlf_bom_padding_blank_lines_and_missing_final_newline() {
    let text = "\u{feff}trial\r\nversion=1\r\nnRows=2\r\nnColumns=3\r\ninDegrees=no\r\n\t endheader \t\r\n\r\n  time \t a b \t c  \r\n   0.0\t 1 \t 2\r\n\r\n   \t\r\n 1e-1 3 4";
    let mut r = reader(text, "x.sto").unwrap();
    assert_eq!(r.header().name.as_deref(), Some("trial"));
    // The label line has tabs: labels are split on tabs, so "a b" is one label.
    assert_eq!(r.header().columns, vec!["a b", "c"]);
    let mut row = Vec::new();
    assert_eq!(r.next_row(&mut row).unwrap(), Some(0.0));
    assert_eq!(row, vec![1.0, 2.0]);
    assert_eq!(r.next_row(&mut row).unwrap(), Some(0.1));
    assert_eq!(row, vec![3.0, 4.0]);
    assert_eq!(r.next_row(&mut row).unwrap(), None);
    assert_eq!(r.line_number(), 12);
}

// ---------------------------------------------------------------------------
// Reader errors: each names its line
// ---------------------------------------------------------------------------

/// The small file with line `n` (1-based) replaced.
fn with_line(n: usize, new: &str) -> String {
    let mut lines: Vec<&str> = SMALL_MOT.lines().collect();
    lines[n - 1] = new;
    lines.join("\n") + "\n"
}

fn row_line(values: &[&str]) -> String {
    values.join("\t")
}

fn zero_row(time: &str) -> Vec<String> {
    let mut v = vec![time.to_string()];
    v.extend(std::iter::repeat_n("0".to_string(), 39));
    v
}

#[test]
fn error_bad_number_names_line_and_column() {
    let mut v = zero_row("0.03");
    v[10] = "3O.5".to_string(); // letter O; knee_angle_r is file column 11
    let text = with_line(15, &v.join("\t"));
    let err = read_all(&text, "walk.mot").unwrap_err();
    match &err {
        OpenSimError::BadNumber {
            line, column, text, ..
        } => {
            assert_eq!(*line, 15);
            assert_eq!(column, "knee_angle_r");
            assert_eq!(text, "3O.5");
        }
        other => panic!("unexpected {other:?}"),
    }
    let msg = err.to_string();
    assert!(msg.contains("walk.mot line 15"), "{msg}");
    assert!(msg.contains("knee_angle_r"), "{msg}");
}

#[test]
fn error_short_row_names_counts() {
    let mut v = zero_row("0.03");
    v.pop();
    let text = with_line(15, &v.join("\t"));
    let err = read_all(&text, "walk.mot").unwrap_err();
    assert!(matches!(
        err,
        OpenSimError::RowLength {
            line: 15,
            found: 39,
            expected: 40,
            ..
        }
    ));
    assert!(
        err.to_string()
            .contains("row with 39 values where the header has 40 columns")
    );
}

#[test]
fn error_long_row() {
    let mut v = zero_row("0.03");
    v.push("7".to_string());
    let text = with_line(15, &v.join("\t"));
    let err = read_all(&text, "walk.mot").unwrap_err();
    assert!(matches!(
        err,
        OpenSimError::RowLength {
            line: 15,
            found: 41,
            ..
        }
    ));
}

#[test]
fn error_missing_endheader() {
    // endheader removed: the label line is reached inside the header.
    let text = with_line(10, "");
    let err = reader(&text, "walk.mot").unwrap_err();
    assert!(
        matches!(err, OpenSimError::MissingEndHeader { line: 11, .. }),
        "{err:?}"
    );
    assert!(err.to_string().contains("missing 'endheader'"));
    // A data row reached inside the header.
    let err = reader("name\nnRows=1\n0.0\t1.0\t2.0\n", "x.sto").unwrap_err();
    assert!(
        matches!(err, OpenSimError::MissingEndHeader { line: 3, .. }),
        "{err:?}"
    );
    // End of input inside the header.
    let err = reader("name\nnRows=1\n\n", "x.sto").unwrap_err();
    assert!(
        matches!(err, OpenSimError::MissingEndHeader { line: 3, .. }),
        "{err:?}"
    );
    // Empty input.
    let err = reader("", "x.sto").unwrap_err();
    assert!(
        matches!(err, OpenSimError::MissingEndHeader { line: 1, .. }),
        "{err:?}"
    );
    assert!(err.to_string().contains("the input is empty"));
    // A free-text header line starting with "time" is not taken for labels.
    let r = reader("x\ntime is in seconds\nendheader\ntime a\n0 1\n", "x.sto").unwrap();
    assert_eq!(r.header().description, vec!["time is in seconds"]);
}

#[test]
fn error_time_not_increasing() {
    let text = with_line(
        16,
        &row_line(
            &zero_row("0.02")
                .iter()
                .map(String::as_str)
                .collect::<Vec<_>>(),
        ),
    );
    let err = read_all(&text, "walk.mot").unwrap_err();
    match err {
        OpenSimError::TimeNotIncreasing {
            line,
            time_s,
            previous_s,
            previous_line,
            ..
        } => {
            assert_eq!((line, previous_line), (16, 15));
            assert_eq!((time_s, previous_s), (0.02, 0.03));
        }
        other => panic!("unexpected {other:?}"),
    }
    // Equal times are refused too.
    let err = read_all("x\nendheader\ntime a\n0 1\n0 2\n", "x.sto").unwrap_err();
    assert!(matches!(
        err,
        OpenSimError::TimeNotIncreasing { line: 5, .. }
    ));
}

#[test]
fn error_nan_and_infinity() {
    for bad in ["NaN", "nan", "inf", "-inf", "infinity", "1e999"] {
        let mut v = zero_row("0.03");
        v[5] = bad.to_string();
        let text = with_line(15, &v.join("\t"));
        let err = read_all(&text, "walk.mot").unwrap_err();
        match &err {
            OpenSimError::NonFiniteNumber { line, column, .. } => {
                assert_eq!(*line, 15, "{bad}");
                assert_eq!(column, "pelvis_ty");
            }
            other => panic!("{bad}: unexpected {other:?}"),
        }
    }
    let err = read_all("x\nendheader\ntime a\nnan 1\n", "x.sto").unwrap_err();
    assert!(
        matches!(err, OpenSimError::NonFiniteNumber { line: 4, ref column, .. } if column == "time")
    );
}

#[test]
fn error_over_long_line() {
    let opts = ReaderOptions {
        max_line_bytes: 64,
        ..ReaderOptions::default()
    };
    let long = format!("x\nendheader\ntime a\n0 1\n1 {}\n2 3\n", "1".repeat(100));
    let mut r = StorageReader::with_options(Cursor::new(long.into_bytes()), "x.sto", opts).unwrap();
    let mut row = Vec::new();
    assert_eq!(r.next_row(&mut row).unwrap(), Some(0.0));
    let err = r.next_row(&mut row).unwrap_err();
    assert!(
        matches!(
            err,
            OpenSimError::LineTooLong {
                line: 5,
                max_bytes: 64,
                ..
            }
        ),
        "{err:?}"
    );
    // The reader stops after an error.
    let again = r.next_row(&mut row).unwrap_err();
    assert!(
        matches!(again, OpenSimError::Stopped { line: 5, .. }),
        "{again:?}"
    );
    // Default cap: 1 MiB, also in the header. A line of exactly the cap passes.
    let at_cap = format!(
        "{}\nendheader\ntime a\n0 1\n",
        "n".repeat(DEFAULT_MAX_LINE_BYTES)
    );
    assert!(reader(&at_cap, "x.sto").is_ok());
    let over = format!(
        "{}\nendheader\ntime a\n0 1\n",
        "n".repeat(DEFAULT_MAX_LINE_BYTES + 1)
    );
    let err = reader(&over, "x.sto").unwrap_err();
    assert!(
        matches!(err, OpenSimError::LineTooLong { line: 1, .. }),
        "{err:?}"
    );
    // A line with no newline at all, longer than the cap, does not get buffered whole.
    let endless = std::io::repeat(b'7').take(10 * DEFAULT_MAX_LINE_BYTES as u64);
    let err = StorageReader::new(BufReader::new(endless), "x.sto").unwrap_err();
    assert!(matches!(err, OpenSimError::LineTooLong { line: 1, .. }));
}

#[test]
fn error_non_utf8() {
    let mut bytes = SMALL_MOT.as_bytes().to_vec();
    // Corrupt a byte in line 14 (row t=0.02).
    let start: usize = SMALL_MOT.lines().take(13).map(|l| l.len() + 1).sum();
    bytes[start + 2] = 0xFF;
    let mut r = reader_bytes(&bytes, "walk.mot").unwrap();
    let mut row = Vec::new();
    assert!(r.next_row(&mut row).unwrap().is_some());
    assert!(r.next_row(&mut row).unwrap().is_some());
    let err = r.next_row(&mut row).unwrap_err();
    assert!(
        matches!(
            err,
            OpenSimError::NotUtf8 {
                line: 14,
                column: 3,
                ..
            }
        ),
        "{err:?}"
    );
    assert!(err.to_string().contains("line 14"));
    // In the header.
    let err = reader_bytes(b"Coord\xC3\x28\nendheader\n", "x.sto").unwrap_err();
    assert!(
        matches!(
            err,
            OpenSimError::NotUtf8 {
                line: 1,
                column: 6,
                ..
            }
        ),
        "{err:?}"
    );
}

#[test]
fn error_unknown_in_degrees_value() {
    let text = with_line(5, "inDegrees=maybe");
    let err = reader(&text, "walk.mot").unwrap_err();
    assert!(
        matches!(err, OpenSimError::BadHeaderValue { line: 5, ref key, ref value, .. } if key == "inDegrees" && value == "maybe")
    );
    assert!(err.to_string().contains("expected yes or no"));
    // Case-insensitive yes/no and y/n are fine.
    for ok in ["inDegrees=YES", "inDegrees=y", "inDegrees = No"] {
        assert!(reader(&with_line(5, ok), "walk.mot").is_ok(), "{ok}");
    }
}

#[test]
fn error_bad_counts_in_header() {
    let err = reader(&with_line(3, "nRows=six"), "walk.mot").unwrap_err();
    assert!(matches!(err, OpenSimError::BadHeaderValue { line: 3, .. }));
    let err = reader(&with_line(4, "nColumns=41"), "walk.mot").unwrap_err();
    assert!(matches!(
        err,
        OpenSimError::ColumnCountMismatch {
            line: 11,
            declared: 41,
            declared_at: 4,
            found: 40,
            ..
        }
    ));
    let err = reader(&with_line(2, "version=one"), "walk.mot").unwrap_err();
    assert!(matches!(err, OpenSimError::BadHeaderValue { line: 2, .. }));
}

#[test]
fn error_truncated_file_rows_fewer_than_declared() {
    let truncated: String = SMALL_MOT
        .lines()
        .take(15)
        .map(|l| format!("{l}\n"))
        .collect();
    let err = read_all(&truncated, "walk.mot").unwrap_err();
    assert!(
        matches!(
            err,
            OpenSimError::RowCountMismatch {
                line: 15,
                declared: 6,
                found: 4,
                declared_at: 3,
                ..
            }
        ),
        "{err:?}"
    );
    // Switched off, the rows present are read.
    let opts = ReaderOptions {
        check_declared_counts: false,
        ..ReaderOptions::default()
    };
    let mut r =
        StorageReader::with_options(Cursor::new(truncated.into_bytes()), "walk.mot", opts).unwrap();
    let mut row = Vec::new();
    let mut n = 0;
    while r.next_row(&mut row).unwrap().is_some() {
        n += 1;
    }
    assert_eq!(n, 4);
}

#[test]
fn error_label_line_problems() {
    let err = reader("x\nendheader\nTime a\n", "x.sto").unwrap_err();
    assert!(
        matches!(err, OpenSimError::FirstColumnNotTime { line: 3, ref found, .. } if found == "Time")
    );
    // Duplicate labels are read (OpenSim's Storage reads them) ...
    let text = "x\nendheader\ntime\tknee_angle_r\tb\tknee_angle_r\tc\n0\t1\t2\t3\t4\n";
    let mut r = reader(text, "x.sto").unwrap();
    let mut row = Vec::new();
    assert_eq!(r.next_row(&mut row).unwrap(), Some(0.0));
    assert_eq!(row, vec![1.0, 2.0, 3.0, 4.0]);
    // ... mapping a column that is not duplicated is fine ...
    let yaml = "joints:\n  - {joint: r_knee_flexion, from: c, sign: 1}\n";
    let m = Mapping::from_yaml_str(yaml, "m.yaml").unwrap();
    assert!(m.bind(r.header(), "x.sto", &WORKER).is_ok());
    // ... but using a duplicated one is refused, naming both columns.
    let yaml = "joints:\n  - {joint: r_knee_flexion, from: knee_angle_r, sign: 1}\n";
    let m = Mapping::from_yaml_str(yaml, "m.yaml").unwrap();
    let err = m.bind(r.header(), "x.sto", &WORKER).unwrap_err();
    assert!(
        matches!(
            err,
            OpenSimError::DuplicateColumn {
                line: 3,
                first: 2,
                second: 4,
                ..
            }
        ),
        "{err:?}"
    );
    assert!(err.to_string().contains("x.sto line 3"), "{err}");
    let err = reader("x\nendheader\n\n\n", "x.sto").unwrap_err();
    assert!(
        matches!(err, OpenSimError::MissingColumnLabels { line: 4, .. }),
        "{err:?}"
    );
}

#[test]
fn error_unsupported_data_type() {
    let err = reader(
        "DataType=Vec3\nversion=3\nendheader\ntime\tm1\n0\t1,2,3\n",
        "markers.sto",
    )
    .unwrap_err();
    assert!(
        matches!(err, OpenSimError::UnsupportedDataType { line: 1, ref data_type, .. } if data_type == "Vec3")
    );
}

#[test]
fn error_header_too_long() {
    let opts = ReaderOptions {
        max_header_lines: 3,
        ..ReaderOptions::default()
    };
    let text = "a\nb\nc\nd\nendheader\ntime x\n";
    let err = StorageReader::with_options(Cursor::new(text.as_bytes().to_vec()), "x.sto", opts)
        .unwrap_err();
    assert!(matches!(
        err,
        OpenSimError::HeaderTooLong {
            line: 4,
            max_lines: 3,
            ..
        }
    ));
    let opts = ReaderOptions {
        max_header_bytes: 10,
        ..ReaderOptions::default()
    };
    let text = "abcd\nefgh\nijkl\nendheader\ntime x\n";
    let err = StorageReader::with_options(Cursor::new(text.as_bytes().to_vec()), "x.sto", opts)
        .unwrap_err();
    assert!(
        matches!(
            err,
            OpenSimError::HeaderTooLong {
                line: 3,
                max_bytes: 10,
                ..
            }
        ),
        "{err:?}"
    );
}

/// A reader whose underlying input fails.
struct Failing;
impl Read for Failing {
    fn read(&mut self, _: &mut [u8]) -> std::io::Result<usize> {
        Err(std::io::Error::other("disk on fire"))
    }
}

#[test]
fn error_io_names_line() {
    let input = Cursor::new(b"x\nendheader\ntime a\n0 1\n".to_vec()).chain(Failing);
    let mut r = StorageReader::new(BufReader::new(input), "x.sto").unwrap();
    let mut row = Vec::new();
    assert_eq!(r.next_row(&mut row).unwrap(), Some(0.0));
    let err = r.next_row(&mut row).unwrap_err();
    assert!(matches!(err, OpenSimError::Io { line: 5, .. }), "{err:?}");
}

// ---------------------------------------------------------------------------
// Streaming
// ---------------------------------------------------------------------------

/// Generates an OpenSim file of `n_rows` rows on the fly: it holds one line
/// at a time, so nothing but the reader under test could hold all rows.
struct Generated {
    n_rows: u64,
    next: u64,
    stage: u8,
    line: Vec<u8>,
    pos: usize,
    bytes_out: u64,
}

impl Generated {
    fn new(n_rows: u64) -> Self {
        Generated {
            n_rows,
            next: 0,
            stage: 0,
            line: Vec::new(),
            pos: 0,
            bytes_out: 0,
        }
    }
    fn refill(&mut self) {
        use std::io::Write;
        self.line.clear();
        self.pos = 0;
        match self.stage {
            0 => {
                let _ = write!(
                    self.line,
                    "generated\nversion=1\nnRows={}\nnColumns=4\ninDegrees=yes\nendheader\ntime\tknee_angle_r\tpelvis_ty\tarm_flex_r\n",
                    self.n_rows
                );
                self.stage = 1;
            }
            _ if self.next < self.n_rows => {
                let i = self.next;
                let _ = writeln!(
                    self.line,
                    "{:.3}\t{}\t0.94\t{}.5",
                    i as f64 * 0.001,
                    i % 90,
                    i % 7
                );
                self.next += 1;
            }
            _ => {}
        }
    }
}

impl Read for Generated {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let available = self.fill_buf()?;
        let n = available.len().min(buf.len());
        buf[..n].copy_from_slice(&available[..n]);
        self.consume(n);
        Ok(n)
    }
}

impl BufRead for Generated {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        if self.pos >= self.line.len() {
            self.refill();
        }
        Ok(&self.line[self.pos..])
    }
    fn consume(&mut self, amt: usize) {
        self.pos += amt;
        self.bytes_out += amt as u64;
    }
}

#[test]
fn streams_two_million_rows_in_bounded_memory() {
    const N: u64 = 2_000_000;
    let mut r = StorageReader::new(Generated::new(N), "generated.mot").unwrap();
    r.set_angle_columns(&[true, false, true]).unwrap();
    let mut row = Vec::with_capacity(3);
    let capacity = row.capacity();
    let mut count = 0u64;
    let mut last_time = -1.0;
    let mut knee_sum = 0.0;
    while let Some(t) = r.next_row(&mut row).unwrap() {
        assert!(t > last_time);
        last_time = t;
        knee_sum += row[0];
        count += 1;
    }
    assert_eq!(count, N);
    assert_eq!(r.rows_read() as u64, N);
    assert!(close(last_time, (N - 1) as f64 * 0.001, 1e-9));
    // Sum of (i mod 90) degrees over the rows, converted.
    let full_cycles = N / 90;
    let expected_deg =
        full_cycles as f64 * (89.0 * 90.0 / 2.0) + (0..N % 90).map(|k| k as f64).sum::<f64>();
    assert!(close(
        knee_sum,
        expected_deg.to_radians(),
        1e-6 * expected_deg
    ));
    // Bounded memory by construction: the row buffer never grew, the line
    // buffer is one line, and the generator never held more than one line
    // while tens of megabytes went through.
    assert_eq!(row.capacity(), capacity);
    assert!(r.lines.buf.capacity() < 4096, "{}", r.lines.buf.capacity());
    assert!(
        r.lines.inner.bytes_out > 30_000_000,
        "{}",
        r.lines.inner.bytes_out
    );
    assert!(r.lines.inner.line.capacity() < 4096);
}

// ---------------------------------------------------------------------------
// Mapping
// ---------------------------------------------------------------------------

#[test]
fn shipped_rajagopal_mapping_parses() {
    let m = rajagopal();
    assert!(m.model().unwrap().contains("Rajagopal"));
    assert_eq!(m.joints().len(), 32);
    assert_eq!(m.rotation_groups().len(), 1);
    assert_eq!(m.ignored().len(), 4);
    // Every worker joint except the neck is fed.
    let r = reader(SMALL_MOT, "rajagopal_small.mot").unwrap();
    let b = m.bind(r.header(), "rajagopal_small.mot", &WORKER).unwrap();
    assert_eq!(
        b.unmapped_worker_joints(),
        [
            "neck_flexion",
            "neck_lateral_bending",
            "neck_axial_rotation"
        ]
    );
    let ignored: Vec<(&str, bool)> = b
        .ignored_columns()
        .iter()
        .map(|c| (c.name.as_str(), c.declared))
        .collect();
    assert_eq!(
        ignored,
        vec![
            ("knee_angle_r_beta", true),
            ("mtp_angle_r", true),
            ("knee_angle_l_beta", true),
            ("mtp_angle_l", true)
        ]
    );
    let report = b.report();
    assert!(report.contains("held at 0: neck_flexion, neck_lateral_bending, neck_axial_rotation"));
    assert!(report.contains("ignored by the mapping: knee_angle_r_beta, mtp_angle_r"));
}

/// Expected worker q (degrees for angles, metres for translations) for the
/// six rows of tests/data/rajagopal_small.mot, worked out by hand with the
/// signs documented in rajagopal2016.mapping.yaml. Joints not listed are 0.
fn expected_rows() -> Vec<Vec<(&'static str, f64)>> {
    let d = [-0.056276, 0.0, -0.07849]; // reference point (worker axes)
    let rad = f64::to_radians;
    // Row 4: OpenSim pelvis_tilt +10 deg (posterior) -> worker tilt -10 deg
    // about +y: R = Ry(-10 deg). (R - I) d in x and z:
    let (s, c) = rad(-10.0).sin_cos();
    let r4_dx = c * d[0] + s * d[2] - d[0];
    let r4_dz = -s * d[0] + c * d[2] - d[2];
    // Row 5: OpenSim pelvis_list +5 deg (top to the right) -> worker list
    // -5 deg about -x = Rx(+5 deg): (R - I) d in y and z.
    let (s, c) = rad(5.0).sin_cos();
    let r5_dy = -s * d[2];
    let r5_dz = (c - 1.0) * d[2];
    // Row 6: pelvis_rotation -20 deg about +z both: Rz(-20 deg).
    let (s, c) = rad(-20.0).sin_cos();
    let r6_dx = (c - 1.0) * d[0];
    let r6_dy = s * d[0];
    vec![
        vec![],
        vec![
            ("r_hip_flexion", 20.0),
            ("r_hip_abduction", -10.0),
            ("r_hip_rotation", 5.0),
            ("r_knee_flexion", 30.0),
            ("r_ankle_dorsiflexion", 10.0),
            ("l_hip_flexion", -10.0),
            ("l_hip_abduction", 5.0),
            ("l_hip_rotation", -4.0),
            ("l_knee_flexion", 45.0),
            ("l_ankle_dorsiflexion", -15.0),
            ("l_ankle_inversion", 5.0),
        ],
        vec![
            ("lumbar_flexion", 20.0),
            ("lumbar_lateral_bending", -10.0),
            ("lumbar_axial_rotation", 15.0),
            ("r_shoulder_flexion", 40.0),
            ("r_shoulder_abduction", 25.0),
            ("r_shoulder_rotation", 10.0),
            ("r_elbow_flexion", 90.0),
            ("r_forearm_pronation", -90.0),
            ("r_wrist_deviation", -10.0),
            ("l_shoulder_flexion", -15.0),
            ("l_shoulder_abduction", 30.0),
            ("l_shoulder_rotation", -5.0),
            ("l_elbow_flexion", 45.0),
            ("l_wrist_flexion", 20.0),
            ("l_wrist_deviation", 8.0),
        ],
        vec![
            ("pelvis_tilt", -10.0),
            ("pelvis_tx", 1.5 + r4_dx),
            ("pelvis_ty", -0.2),
            ("pelvis_tz", 0.90 - 0.94 + r4_dz),
        ],
        vec![
            ("pelvis_list", -5.0),
            ("pelvis_tx", 1.6),
            ("pelvis_ty", r5_dy),
            ("pelvis_tz", r5_dz),
        ],
        vec![
            ("pelvis_rotation", -20.0),
            ("pelvis_tx", r6_dx),
            ("pelvis_ty", r6_dy),
        ],
    ]
}

#[test]
fn rajagopal_mapping_produces_hand_worked_worker_angles() {
    let r = reader(SMALL_MOT, "rajagopal_small.mot").unwrap();
    let mut motion = MappedMotion::new(r, &rajagopal(), &WORKER).unwrap();
    let mut q = vec![f64::NAN; WORKER.len()];
    for (k, expected) in expected_rows().into_iter().enumerate() {
        let t = motion.next_frame(&mut q).unwrap().unwrap();
        assert!(close(t, k as f64 * 0.01, 1e-12));
        for (i, joint) in WORKER.iter().enumerate() {
            let want = match expected.iter().find(|(j, _)| j == joint) {
                Some((_, v)) if joint.starts_with("pelvis_t") && *joint != "pelvis_tilt" => *v,
                Some((_, v)) => v.to_radians(),
                None => 0.0,
            };
            assert!(
                close(q[i], want, 1e-12),
                "row {}: {joint} = {} expected {want}",
                k + 1,
                q[i]
            );
        }
    }
    assert_eq!(motion.next_frame(&mut q).unwrap(), None);
    // Sanity of the hand-computed lever arm of row 4 (posterior tilt moves the
    // hip-centre level point forward and down by about 1.4 cm and 0.9 cm).
    let rows = expected_rows();
    let tx = rows[3].iter().find(|(j, _)| *j == "pelvis_tx").unwrap().1;
    assert!(close(tx - 1.5, 0.014485, 1e-5), "{tx}");
}

#[test]
fn pelvis_group_matches_signs_for_single_axes_and_is_exact_for_combined() {
    let m = rajagopal();
    let g = &m.rotation_groups()[0];
    let from = [g.from[0].1, g.from[1].1, g.from[2].1];
    let to = [g.to[0].1, g.to[1].1, g.to[2].1];
    let rad = f64::to_radians;
    // Combined OpenSim pelvis angles (tilt, list, rotation), including large
    // ones typical of lifting (forward bend with twist) and a gimbal case.
    let cases = [
        [-40.0, 8.0, 30.0],
        [-70.0, -15.0, -45.0],
        [20.0, 10.0, 170.0],
        [0.0, 90.0, 30.0],
        [5.0, 0.0, 0.0],
    ];
    for c in cases {
        let angles = [rad(c[0]), rad(c[1]), rad(c[2])];
        let r = compose(from, angles);
        let p = decompose(&r, to);
        let back = compose(to, p);
        for i in 0..3 {
            for j in 0..3 {
                assert!(close(r[i][j], back[i][j], 1e-12), "{c:?}");
            }
        }
    }
    // A single non-zero OpenSim angle gives exactly the per-axis sign.
    let one = |k: usize, v: f64| {
        let mut a = [0.0; 3];
        a[k] = rad(v);
        decompose(&compose(from, a), to)
    };
    assert!(close(one(0, 25.0)[2], rad(-25.0), 1e-12)); // tilt -> -tilt
    assert!(close(one(1, 12.0)[1], rad(-12.0), 1e-12)); // list -> -list
    assert!(close(one(2, -33.0)[0], rad(-33.0), 1e-12)); // rotation -> rotation
    // Combined large angles differ from per-axis signs: a 40 deg forward bend
    // with a 30 deg pelvis turn gives a worker pelvis_list of about 20 deg
    // (OpenSim's pelvis_rotation is about the tilted pelvis axis).
    let p = decompose(&compose(from, [rad(-40.0), 0.0, rad(30.0)]), to);
    assert!(
        p[1].to_degrees().abs() > 15.0,
        "{:?}",
        p.map(f64::to_degrees)
    );
}

#[test]
fn mapping_names_missing_coordinate_and_joint() {
    let text = "x\nendheader\ntime\tknee_angle_r\n0\t1\n";
    let r = reader(text, "walk.mot").unwrap();
    let err = rajagopal()
        .bind(r.header(), "walk.mot", &WORKER)
        .unwrap_err();
    match &err {
        OpenSimError::MissingCoordinate {
            joint,
            coordinate,
            recording,
            line,
            mapping,
        } => {
            assert_eq!(joint, "pelvis_tx");
            assert_eq!(coordinate, "pelvis_tx");
            assert_eq!(recording, "walk.mot");
            assert_eq!(mapping, "rajagopal2016.mapping.yaml");
            assert!(*line > 20);
        }
        other => panic!("unexpected {other:?}"),
    }
    let yaml = "joints:\n  - {joint: r_knee_flexion, from: knee_angle_r, sign: 1}\n  - {joint: l_knee_flexion, from: knee_angle_l, sign: 1}\n";
    let m = Mapping::from_yaml_str(yaml, "m.yaml").unwrap();
    let err = m.bind(r.header(), "walk.mot", &WORKER).unwrap_err();
    let msg = err.to_string();
    assert!(msg.contains("m.yaml line 3"), "{msg}");
    assert!(
        msg.contains("l_knee_flexion") && msg.contains("knee_angle_l") && msg.contains("walk.mot"),
        "{msg}"
    );
}

#[test]
fn mapping_errors_are_located() {
    let bind_err = |yaml: &str| {
        let r = reader(
            "x\nendheader\ntime\tknee_angle_r\tpelvis_ty\n0\t1\t1\n",
            "w.mot",
        )
        .unwrap();
        Mapping::from_yaml_str(yaml, "m.yaml").and_then(|m| m.bind(r.header(), "w.mot", &WORKER))
    };
    let cases: [(&str, u64, &str); 10] = [
        (
            "joints:\n  - {joint: r_knee_flex, from: knee_angle_r, sign: 1}\n",
            2,
            "not a joint of the worker",
        ),
        (
            "joints:\n  - {joint: r_knee_flexion, from: knee_angle_r, sign: 2}\n",
            2,
            "sign must be 1 or -1",
        ),
        (
            "joints:\n  - {joint: r_knee_flexion, from: knee_angle_r, sign: 1, offset_m: 0.1}\n",
            2,
            "offset_m is for translations",
        ),
        (
            "joints:\n  - {joint: pelvis_tz, from: pelvis_ty, sign: 1, offset_deg: 1, kind: translation}\n",
            2,
            "offset_deg is for rotations",
        ),
        (
            "joints:\n  - {joint: r_knee_flexion, from: knee_angle_r, sign: 1}\n  - {joint: r_knee_flexion, from: pelvis_ty, sign: 1}\n",
            3,
            "fed twice",
        ),
        (
            "joints:\n  - {joint: r_knee_flexion, from: knee_angle_r, sign: 1}\n  - {joint: l_knee_flexion, from: knee_angle_r, sign: 1, kind: translation}\n",
            3,
            "declared",
        ),
        (
            "joints:\n  - {joint: r_knee_flexion, from: knee_angle_r, sign: 1}\nignore:\n  - knee_angle_r\n",
            4,
            "also used",
        ),
        (
            "rotation_groups:\n  - name: p\n    from: [{coordinate: a, axis: [1,0,0]}, {coordinate: b, axis: [0,1,0]}, {coordinate: c, axis: [0,0,1]}]\n    to: [{joint: pelvis_tilt, axis: [1,0,0]}, {joint: pelvis_list, axis: [1,1,0]}, {joint: pelvis_rotation, axis: [0,0,1]}]\n",
            2,
            "not perpendicular",
        ),
        (
            "rotation_groups:\n  - name: p\n    from: [{coordinate: a, axis: [0,0,0]}, {coordinate: b, axis: [0,1,0]}, {coordinate: c, axis: [0,0,1]}]\n    to: [{joint: pelvis_tilt, axis: [1,0,0]}, {joint: pelvis_list, axis: [0,1,0]}, {joint: pelvis_rotation, axis: [0,0,1]}]\n",
            2,
            "zero",
        ),
        (
            "joints:\n  - {joint: r_knee_flexion, from: knee_angle_r, sign: 1, offset_deg: .nan}\n",
            2,
            "not finite",
        ),
    ];
    for (yaml, line, words) in cases {
        let err = bind_err(yaml).unwrap_err();
        assert_eq!(err.line(), Some(line), "{yaml}: {err}");
        assert!(err.to_string().contains(words), "{yaml}: {err}");
    }
    // YAML syntax and schema errors carry the parser's line and column.
    for (yaml, needle) in [
        (
            "joints:\n  - {joint: r_knee_flexion, from: knee_angle_r, sing: 1}\n",
            "line 2",
        ),
        (
            "joints:\n  - {joint: r_knee_flexion, from: knee_angle_r}\n",
            "sign",
        ),
        ("joints: [\n", "line"),
        (
            "joints:\n  - {joint: r_knee_flexion, from: knee_angle_r, sign: 1, kind: spiral}\n",
            "line 2",
        ),
    ] {
        let err = bind_err(yaml).unwrap_err();
        assert!(
            matches!(err, OpenSimError::MappingSyntax { .. }),
            "{yaml}: {err:?}"
        );
        assert!(err.to_string().contains(needle), "{yaml}: {err}");
    }
}

#[test]
fn apply_checks_lengths_instead_of_panicking() {
    let r = reader(SMALL_MOT, "rajagopal_small.mot").unwrap();
    let b = rajagopal().bind(r.header(), "x", &WORKER).unwrap();
    let mut q = vec![0.0; WORKER.len()];
    assert!(matches!(
        b.apply(&[0.0; 3], &mut q),
        Err(OpenSimError::LengthMismatch {
            expected: 39,
            found: 3,
            ..
        })
    ));
    assert!(matches!(
        b.apply(&[0.0; 39], &mut q[..5]),
        Err(OpenSimError::LengthMismatch {
            expected: 38,
            found: 5,
            ..
        })
    ));
    let mut r = reader(SMALL_MOT, "x").unwrap();
    assert!(r.set_angle_columns(&[true]).is_err());
}

#[test]
fn worker_list_with_duplicates_is_refused() {
    let r = reader(SMALL_MOT, "x").unwrap();
    let err = rajagopal()
        .bind(r.header(), "x", &["a", "b", "a"])
        .unwrap_err();
    assert!(err.to_string().contains("twice"));
}

// ---------------------------------------------------------------------------
// No panics on any input
// ---------------------------------------------------------------------------

#[test]
fn garbage_input_never_panics() {
    // Deterministic pseudo-random mutations of the hand-written file plus
    // random byte soup, each read to the end or to its first error.
    let mut seed: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    };
    let alphabet = b"0123456789.-+eE \t\r\nnaNiIfytime=endheader\xff\xc3";
    let m = rajagopal();
    for case in 0..400 {
        let mut bytes = SMALL_MOT.as_bytes().to_vec();
        if case % 4 == 3 {
            bytes = (0..(next() % 600))
                .map(|_| alphabet[(next() % alphabet.len() as u64) as usize])
                .collect();
        } else {
            for _ in 0..(1 + next() % 6) {
                let pos = (next() % bytes.len() as u64) as usize;
                match next() % 3 {
                    0 => bytes[pos] = alphabet[(next() % alphabet.len() as u64) as usize],
                    1 => {
                        bytes.remove(pos);
                    }
                    _ => bytes.insert(pos, alphabet[(next() % alphabet.len() as u64) as usize]),
                }
            }
        }
        let opts = ReaderOptions {
            max_line_bytes: 512,
            ..ReaderOptions::default()
        };
        if let Ok(r) = StorageReader::with_options(Cursor::new(bytes), "fuzz.mot", opts) {
            let mut q = vec![0.0; WORKER.len()];
            match MappedMotion::new(r, &m, &WORKER) {
                Ok(mut motion) => {
                    while let Ok(Some(_)) = motion.next_frame(&mut q) {
                        assert!(q.iter().all(|v| v.is_finite()));
                    }
                }
                Err(e) => {
                    let _ = e.to_string();
                }
            }
        }
    }
}
