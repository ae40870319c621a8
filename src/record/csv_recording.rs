//! Recordings as CSV, read line by line in bounded memory.
//!
//! **Format** (header first): `t_s` (or `time`), then one column per joint of the body (radians,
//! or degrees with `degrees`; joints without a column stay at 0), then the hand loads: the right
//! hand's `load_kg` or `force_x_n, force_y_n, force_z_n` (force the environment applies on the
//! hand, world frame, N), the left hand's `left_load_kg` or `left_force_x_n, …`. Without load
//! columns the hands carry the constant loads given to the reader. Times must increase strictly;
//! empty cells, non-numbers and non-finite numbers are refused with their line and column; a line
//! longer than [`MAX_LINE_BYTES`] or not UTF-8 is refused with its number.

use super::{RecordingError, Sample};
use crate::body::BodyModel;
use nalgebra::Vector3;
use std::io::BufRead;

/// Longest line accepted \[bytes\].
pub const MAX_LINE_BYTES: usize = 1 << 20;

/// Reads one line (without its end) into `buf`, at most `max` bytes: `Ok(false)` at the end of
/// the input. Errors name the line: too long, not UTF-8, or the reader's own error.
pub fn read_line_bounded(
    reader: &mut impl BufRead,
    buf: &mut String,
    bytes: &mut Vec<u8>,
    max: usize,
    source: &str,
    line: usize,
) -> Result<bool, RecordingError> {
    bytes.clear();
    buf.clear();
    let n = std::io::Read::take(&mut *reader, max as u64 + 1)
        .read_until(b'\n', bytes)
        .map_err(|e| RecordingError::Line {
            source_name: source.into(),
            line,
            problem: format!("cannot read: {e}"),
        })?;
    if n == 0 {
        return Ok(false);
    }
    if bytes.len() > max && bytes.last() != Some(&b'\n') {
        return Err(RecordingError::Line {
            source_name: source.into(),
            line,
            problem: format!("longer than {max} bytes"),
        });
    }
    while matches!(bytes.last(), Some(b'\n' | b'\r')) {
        bytes.pop();
    }
    match std::str::from_utf8(bytes) {
        Ok(s) => buf.push_str(s),
        Err(e) => {
            return Err(RecordingError::Line {
                source_name: source.into(),
                line,
                problem: format!(
                    "not UTF-8 text (invalid byte at position {})",
                    e.valid_up_to() + 1
                ),
            });
        }
    }
    Ok(true)
}

/// The fields of one CSV line, quoting as RFC 4180 (the csv crate): `"a,b"` is one field and
/// `""` inside quotes is a quote. A quoted field may not span lines.
pub fn split_fields(text: &str) -> Result<Vec<String>, String> {
    if text.bytes().filter(|&b| b == b'"').count() % 2 == 1 {
        return Err("a quoted field is not closed on its line".into());
    }
    let mut r = ::csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .from_reader(text.as_bytes());
    let mut rec = ::csv::StringRecord::new();
    let got = r
        .read_record(&mut rec)
        .map_err(|e| format!("not CSV: {e}"))?;
    if !got {
        return Ok(vec![String::new()]);
    }
    Ok(rec.iter().map(str::to_string).collect())
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Joint(usize),
    LoadKg(usize),
    Force(usize, usize),
}

/// How the columns of a CSV recording map onto the body.
#[derive(Debug, Clone)]
pub struct Columns {
    names: Vec<String>,
    kinds: Vec<Kind>,
    /// Whether each hand's load comes from the file.
    pub hand_from_file: [bool; 2],
}

impl Columns {
    /// Parses the header line against the model.
    pub fn parse(header: &str, model: &BodyModel, source: &str) -> Result<Self, RecordingError> {
        let bad = |problem: String| RecordingError::Header {
            source_name: source.into(),
            problem,
        };
        let names: Vec<String> = split_fields(header)
            .map_err(bad)?
            .iter()
            .map(|s| s.trim().to_string())
            .collect();
        match names.first().map(String::as_str) {
            Some("t_s" | "time") => {}
            other => {
                return Err(bad(format!(
                    "the first column must be t_s (or time), got '{}'",
                    other.unwrap_or_default()
                )));
            }
        }
        let mut kinds = Vec::with_capacity(names.len() - 1);
        for (i, n) in names.iter().enumerate().skip(1) {
            let k = match n.as_str() {
                "load_kg" => Kind::LoadKg(0),
                "left_load_kg" => Kind::LoadKg(1),
                "force_x_n" => Kind::Force(0, 0),
                "force_y_n" => Kind::Force(0, 1),
                "force_z_n" => Kind::Force(0, 2),
                "left_force_x_n" => Kind::Force(1, 0),
                "left_force_y_n" => Kind::Force(1, 1),
                "left_force_z_n" => Kind::Force(1, 2),
                _ => Kind::Joint(model.q_index(n).map_err(|_| {
                    let joints = (0..model.nq()).map(|k| model.q_joint(k).name.as_str());
                    bad(format!(
                        "column {} '{n}' is not a moving joint of the body, nor a load column (load_kg, force_x_n, left_load_kg, left_force_x_n, ...){}",
                        i + 1,
                        crate::schema::did_you_mean(n, joints)
                    ))
                })?),
            };
            if kinds.contains(&k) {
                return Err(bad(format!("column {} '{n}' appears twice", i + 1)));
            }
            kinds.push(k);
        }
        let mut hand_from_file = [false; 2];
        for (h, name) in [(0, "right"), (1, "left")] {
            let forces = kinds
                .iter()
                .filter(|k| matches!(k, Kind::Force(x, _) if *x == h))
                .count();
            let load = kinds.contains(&Kind::LoadKg(h));
            if forces != 0 && forces != 3 {
                return Err(bad(format!(
                    "the {name} hand's force needs all three columns (x, y, z)"
                )));
            }
            if forces == 3 && load {
                return Err(bad(format!(
                    "give the {name} hand's load in kg or as a force, not both"
                )));
            }
            hand_from_file[h] = load || forces == 3;
        }
        Ok(Columns {
            names,
            kinds,
            hand_from_file,
        })
    }

    /// Parses one data line (`line` is its 1-based number) into `out`; angles in degrees when
    /// `degrees`. Joints without a column and hands without load columns are left as they are.
    pub fn parse_sample(
        &self,
        text: &str,
        line: usize,
        degrees: bool,
        gravity: &Vector3<f64>,
        source: &str,
        out: &mut Sample,
    ) -> Result<(), RecordingError> {
        let cell = |column: usize, problem: String| RecordingError::Cell {
            source_name: source.into(),
            line,
            column,
            name: self.names.get(column - 1).cloned().unwrap_or_default(),
            problem,
        };
        // the common case (no quotes) without the csv parser; quoted cells through it
        let quoted;
        let mut fields: Box<dyn Iterator<Item = &str>> = if text.contains('"') {
            quoted = split_fields(text).map_err(|problem| RecordingError::Line {
                source_name: source.into(),
                line,
                problem,
            })?;
            Box::new(quoted.iter().map(String::as_str))
        } else {
            Box::new(text.split(','))
        };
        let mut num = |column: usize| -> Result<f64, RecordingError> {
            let raw = fields
                .next()
                .ok_or_else(|| cell(column, "missing value (too few columns)".into()))?
                .trim();
            if raw.is_empty() {
                return Err(cell(column, "missing value".into()));
            }
            let v: f64 = raw
                .parse()
                .map_err(|_| cell(column, format!("'{raw}' is not a number")))?;
            if !v.is_finite() {
                return Err(cell(column, format!("'{raw}' is not finite")));
            }
            Ok(v)
        };
        out.t_s = num(1)?;
        for h in 0..2 {
            if self.hand_from_file[h] {
                out.hand_force_n[h] = Vector3::zeros();
            }
        }
        for (i, kind) in self.kinds.iter().enumerate() {
            let v = num(i + 2)?;
            match *kind {
                Kind::Joint(k) => out.q_rad[k] = if degrees { v.to_radians() } else { v },
                Kind::LoadKg(h) => {
                    if !(0.0..=crate::plan::task::MAX_LOAD_KG).contains(&v) {
                        return Err(cell(
                            i + 2,
                            format!(
                                "a load must be 0..{} kg, got {v}",
                                crate::plan::task::MAX_LOAD_KG
                            ),
                        ));
                    }
                    out.hand_force_n[h] = gravity * v;
                }
                Kind::Force(h, a) => {
                    if v.abs() > crate::plan::task::MAX_HAND_FORCE_N {
                        return Err(cell(
                            i + 2,
                            format!(
                                "a hand force must be within ±{} N, got {v}",
                                crate::plan::task::MAX_HAND_FORCE_N
                            ),
                        ));
                    }
                    out.hand_force_n[h][a] = v;
                }
            }
        }
        if fields.next().is_some() {
            return Err(RecordingError::Line {
                source_name: source.into(),
                line,
                problem: format!("more values than the {} header columns", self.names.len()),
            });
        }
        Ok(())
    }

    /// The joint (q index) of every data column that holds one, with the column number.
    pub fn joint_columns(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.kinds.iter().enumerate().filter_map(|(i, k)| match k {
            Kind::Joint(q) => Some((i + 2, *q)),
            _ => None,
        })
    }

    /// Name of column `column` (1-based).
    pub fn name(&self, column: usize) -> &str {
        self.names.get(column - 1).map_or("", String::as_str)
    }
}
