//! OpenSim motion (`.mot`) and storage (`.sto`) recordings, and their mapping
//! onto posture-opt's whole-body worker.
//!
//! Recorded work often comes out of OpenSim inverse kinematics, OpenCap or
//! Pose2Sim as `.mot`/`.sto` files of generalized coordinates. This module
//!
//! 1. streams such a file row by row ([`StorageReader`]) from any [`BufRead`],
//!    in bounded memory, with an error naming the line for every defect, and
//! 2. maps the OpenSim coordinates onto the worker's joints ([`Mapping`],
//!    [`BoundMapping`], [`MappedMotion`]) as described by a YAML mapping file.
//!
//! Inside, everything is SI: seconds, radians, metres.
//!
//! # The file format followed
//!
//! There is no separate written specification of the Storage format; it is
//! defined by OpenSim's readers, and this module follows them as found in
//! opensim-core (`OpenSim/Common/Storage.cpp`: `Storage::Storage(fileName)`,
//! `Storage::parseHeaders`, `Storage::parseColumnLabels`, `writeHeader`,
//! `writeSIMMHeader`; `OpenSim/Common/STOFileAdapter.{h,cpp}`,
//! `DelimFileAdapter.h` (`extendRead`) and `FileAdapter.cpp` (`tokenize`,
//! `getNextLine`); `TimeSeriesTable.h`), checked against the `.mot`/`.sto`
//! files in opensim-core's test resources:
//!
//! * **Header**: lines up to a line `endheader` (surrounding blanks and tabs
//!   allowed). Each header line is trimmed; blank lines are skipped. As in
//!   `Storage::parseHeaders`, the key is the text before the first blank, tab
//!   or `=`, and the value is what follows the run of blanks/tabs/`=`, so both
//!   `nRows=73` and the SIMM-style `datarows 73` are understood.
//!   * `name` — the table name; otherwise the first header line, when it is
//!     not a known key, is the name (OpenSim writes the name there).
//!   * `nRows`, `nr`, `datarows` — declared number of data rows.
//!   * `nColumns`, `nc`, `datacolumns` — declared number of columns,
//!     **including** the time column.
//!   * `version` — file version: absent (= 0, SIMM-era files), 1 (written by
//!     `Storage`), 2 or 3 (written by `STOFileAdapter`).
//!   * `inDegrees` — `yes`/`y` or `no`/`n` (case-insensitive). OpenSim treats
//!     any other text as "no"; this reader refuses it instead.
//!   * `Angles are in degrees.` / `Angles are in radians.` — version-0 way of
//!     saying the same, honoured only in version-0 headers (as OpenSim does).
//!   * `DataType` — written by `STOFileAdapter`; only `double` (plain
//!     numbers) can be read here. `Vec3`, `Quaternion`, … tables are refused.
//!   * `range`, `otherdata`, `units`, `OpenSimVersion`, `# comment` and any
//!     other line are kept as metadata or description and otherwise ignored.
//! * **Column labels**: the first non-blank line after `endheader`. The first
//!   label must be `time`. Labels are separated by tabs (STOFileAdapter) or,
//!   in lines without a tab, by blanks (legacy `strtok(" \t")`). Duplicate
//!   labels are allowed (OpenSim's `Storage` allows them; combined IK+GRF
//!   files have them) unless the mapping uses one.
//! * **Rows**: numbers separated by tabs and/or blanks (OpenSim writes
//!   right-aligned numbers padded with blanks; the legacy reader uses
//!   `operator>>`). Each row has exactly one value per label. Blank lines are
//!   skipped. Times must increase strictly (`TimeSeriesTable` enforces
//!   "Time column is not strictly increasing"). NaN and infinities are
//!   refused.
//! * **Degrees**: whether angles are in degrees is decided, in this order, by
//!   an `inDegrees` line, by an `Angles are in …` line in a version-0 header,
//!   then, for a version-0 `.mot` file, degrees (OpenSim: "Motion files from
//!   SIMM are in degrees"); otherwise radians. Only *rotational* coordinates
//!   are converted: OpenSim converts with the model, which knows each
//!   coordinate's motion type. Without the model, the mapping file declares
//!   each used coordinate's kind (`rotation` or `translation`), and only the
//!   columns declared rotational are converted ([`StorageReader::set_angle_columns`]).
//! * **Line endings**: `\n` or `\r\n`; a UTF-8 byte-order mark at the start is
//!   skipped. Text must be UTF-8 (OpenSim files are ASCII).
//!
//! Deliberate differences from OpenSim, all towards refusing doubtful input:
//! a version-0 `.mot` file with an explicit `inDegrees=no` is read in radians
//! (OpenSim forces degrees for every version-0 `.mot`); a header `nColumns`
//! that disagrees with the label count, and a row count that disagrees with
//! `nRows`, are errors (OpenSim warns, or stops reading after `nRows` rows);
//! both checks can be switched off with [`ReaderOptions::check_declared_counts`].
//! Blank lines inside the data are skipped (STOFileAdapter stops at the first
//! one). SIMM files without a `time` column (time rebuilt from `range`), which
//! OpenSim's own code marks as untested, are refused.
//!
//! Sources read: opensim-core commit `0435b081dc38`, opensim-models commit
//! `20a888b9655e` (Rajagopal model), Simbody `MobilizedBodyImpl.h`
//! (`FunctionBasedImpl`: rotation order of OpenSim's `CustomJoint`).
//!
//! # Mapping file
//!
//! See [`Mapping`], [`RotationGroup`] and the end-user page `opensim.md`;
//! `rajagopal2016.mapping.yaml` is the mapping for the Rajagopal et al. (2016)
//! full-body model, with the reason for every sign.
//!
//! # Usage
//!
//! ```rust,ignore
//! let file = std::fs::File::open("walk.mot")?;
//! let reader = StorageReader::new(std::io::BufReader::new(file), "walk.mot")?;
//! let mapping = Mapping::from_yaml_str(&std::fs::read_to_string(map_path)?, map_path)?;
//! let mut motion = MappedMotion::new(reader, &mapping, &worker_joint_names)?;
//! eprint!("{}", motion.mapping().report()); // joints held at 0, columns ignored
//! let mut q = vec![0.0; worker_joint_names.len()];
//! while let Some(time_s) = motion.next_frame(&mut q)? {
//!     // q: radians (revolute) / metres (prismatic), in worker joint order
//! }
//! ```

use std::fmt;
use std::io::{BufRead, ErrorKind};

use serde::Deserialize;
use serde_saphyr::Spanned;

/// Default cap on one line's length in bytes (1 MiB); longer lines are refused.
pub const DEFAULT_MAX_LINE_BYTES: usize = 1 << 20;

/// Default cap on the number of header lines before `endheader`.
pub const DEFAULT_MAX_HEADER_LINES: usize = 10_000;

/// Default cap on the total size of the header lines, in bytes (4 MiB).
pub const DEFAULT_MAX_HEADER_BYTES: usize = 4 << 20;

/// Largest mapping (YAML) text accepted, in bytes.
pub const MAX_MAPPING_BYTES: usize = 1 << 20;

// ---------------------------------------------------------------------------
// Errors
// ---------------------------------------------------------------------------

/// Everything that can go wrong reading a recording or a mapping file.
///
/// Every variant about input text names the input (`origin`) and the 1-based
/// line number where the problem is.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum OpenSimError {
    /// The underlying reader failed.
    #[error("{origin} line {line}: cannot read: {source}")]
    Io {
        /// Name of the input (file name) used in messages.
        origin: String,
        /// Line being read.
        line: u64,
        /// The I/O error.
        #[source]
        source: std::io::Error,
    },
    /// A line is longer than the configured cap.
    #[error(
        "{origin} line {line}: line is longer than {max_bytes} bytes; refused \
         (is this really an OpenSim .mot/.sto file?)"
    )]
    LineTooLong {
        /// Name of the input.
        origin: String,
        /// Line number.
        line: u64,
        /// The cap in bytes.
        max_bytes: usize,
    },
    /// A line is not valid UTF-8 text.
    #[error("{origin} line {line}: not UTF-8 text (invalid byte at column {column})")]
    NotUtf8 {
        /// Name of the input.
        origin: String,
        /// Line number.
        line: u64,
        /// 1-based byte column of the first invalid byte.
        column: usize,
    },
    /// The header has no `endheader` line.
    #[error("{origin} line {line}: missing 'endheader': {detail}")]
    MissingEndHeader {
        /// Name of the input.
        origin: String,
        /// Line where the absence was noticed.
        line: u64,
        /// What was found instead.
        detail: String,
    },
    /// The header goes on for more lines or bytes than allowed.
    #[error(
        "{origin} line {line}: header longer than {max_lines} lines or {max_bytes} bytes \
         without 'endheader'"
    )]
    HeaderTooLong {
        /// Name of the input.
        origin: String,
        /// Line number.
        line: u64,
        /// The cap on lines.
        max_lines: usize,
        /// The cap on bytes.
        max_bytes: usize,
    },
    /// A header value could not be understood (e.g. `inDegrees=maybe`).
    #[error("{origin} line {line}: {key}={value:?} is not valid: expected {expected}")]
    BadHeaderValue {
        /// Name of the input.
        origin: String,
        /// Line number.
        line: u64,
        /// Header key.
        key: String,
        /// The value found.
        value: String,
        /// What was expected.
        expected: &'static str,
    },
    /// The table holds vectors, quaternions, … instead of plain numbers.
    #[error(
        "{origin} line {line}: DataType={data_type} is not supported; only tables of \
         plain numbers (DataType=double) of generalized coordinates can be read"
    )]
    UnsupportedDataType {
        /// Name of the input.
        origin: String,
        /// Line number.
        line: u64,
        /// The declared data type.
        data_type: String,
    },
    /// The input ends after `endheader` without the column-label line.
    #[error("{origin} line {line}: input ends after 'endheader' without the column-label line")]
    MissingColumnLabels {
        /// Name of the input.
        origin: String,
        /// Last line number.
        line: u64,
    },
    /// The first column label is not `time`.
    #[error("{origin} line {line}: first column label is {found:?}; expected 'time'")]
    FirstColumnNotTime {
        /// Name of the input.
        origin: String,
        /// Line number.
        line: u64,
        /// The first label found.
        found: String,
    },
    /// A column the mapping uses appears twice in the recording (which one
    /// is meant is unknown). Duplicate columns the mapping does not use are
    /// allowed, as OpenSim's `Storage` allows them.
    #[error(
        "{origin} line {line}: column label {name:?} appears twice (columns {first} and \
         {second}); the mapping uses it, so which one is meant is unknown"
    )]
    DuplicateColumn {
        /// Name of the input.
        origin: String,
        /// Line number.
        line: u64,
        /// The label.
        name: String,
        /// 1-based column of its first occurrence (time is column 1).
        first: usize,
        /// 1-based column of its second occurrence.
        second: usize,
    },
    /// The label count disagrees with the header's `nColumns`.
    #[error(
        "{origin} line {line}: {found} column labels but the header (line {declared_at}) \
         declares nColumns={declared}"
    )]
    ColumnCountMismatch {
        /// Name of the input.
        origin: String,
        /// Line of the labels.
        line: u64,
        /// Declared number of columns (including time).
        declared: usize,
        /// Line where it was declared.
        declared_at: u64,
        /// Labels found (including time).
        found: usize,
    },
    /// A value is not a number.
    #[error("{origin} line {line}: bad number {text:?} in column {column:?}")]
    BadNumber {
        /// Name of the input.
        origin: String,
        /// Line number.
        line: u64,
        /// Column label.
        column: String,
        /// The text found.
        text: String,
    },
    /// A value is NaN or infinite.
    #[error(
        "{origin} line {line}: value {text:?} in column {column:?} is not finite; NaN and infinity are refused"
    )]
    NonFiniteNumber {
        /// Name of the input.
        origin: String,
        /// Line number.
        line: u64,
        /// Column label.
        column: String,
        /// The text found.
        text: String,
    },
    /// A row has the wrong number of values.
    #[error(
        "{origin} line {line}: row with {found} values where the header has {expected} columns"
    )]
    RowLength {
        /// Name of the input.
        origin: String,
        /// Line number.
        line: u64,
        /// Values found (including time).
        found: usize,
        /// Columns expected (including time).
        expected: usize,
    },
    /// Time does not increase strictly.
    #[error(
        "{origin} line {line}: time {time_s} s is not after the previous row's time \
         {previous_s} s (line {previous_line}); time must increase"
    )]
    TimeNotIncreasing {
        /// Name of the input.
        origin: String,
        /// Line number.
        line: u64,
        /// This row's time in seconds.
        time_s: f64,
        /// Previous row's time in seconds.
        previous_s: f64,
        /// Line of the previous row.
        previous_line: u64,
    },
    /// The number of rows disagrees with the header's `nRows`.
    #[error(
        "{origin} line {line}: input ends after {found} data rows but the header \
         (line {declared_at}) declares nRows={declared} (truncated file?)"
    )]
    RowCountMismatch {
        /// Name of the input.
        origin: String,
        /// Last line number.
        line: u64,
        /// Declared rows.
        declared: usize,
        /// Line where it was declared.
        declared_at: u64,
        /// Rows found.
        found: usize,
    },
    /// The reader was used again after it had reported an error.
    #[error("{origin} line {line}: reading stopped at an earlier error")]
    Stopped {
        /// Name of the input.
        origin: String,
        /// Line of the earlier error.
        line: u64,
    },
    /// The mapping file is not valid YAML of the expected shape.
    #[error("{origin}: {message}")]
    MappingSyntax {
        /// Name of the mapping file.
        origin: String,
        /// The parser's message, which names line and column.
        message: String,
    },
    /// The mapping file is well-formed YAML but says something impossible.
    #[error("{origin} line {line}: {detail}")]
    MappingInvalid {
        /// Name of the mapping file.
        origin: String,
        /// Line of the offending entry.
        line: u64,
        /// What is wrong.
        detail: String,
    },
    /// The mapping feeds a worker joint from a coordinate the recording lacks.
    #[error(
        "{mapping} line {line}: worker joint {joint:?} is fed from OpenSim coordinate \
         {coordinate:?}, but recording {recording} has no column {coordinate:?}"
    )]
    MissingCoordinate {
        /// Name of the mapping file.
        mapping: String,
        /// Line of the mapping entry.
        line: u64,
        /// Worker joint.
        joint: String,
        /// OpenSim coordinate.
        coordinate: String,
        /// Name of the recording.
        recording: String,
    },
    /// The mapping names a joint the worker does not have.
    #[error("{mapping} line {line}: {joint:?} is not a joint of the worker (its joints: {known})")]
    UnknownWorkerJoint {
        /// Name of the mapping file.
        mapping: String,
        /// Line of the mapping entry.
        line: u64,
        /// The unknown joint.
        joint: String,
        /// The worker's joints, comma-separated.
        known: String,
    },
    /// The worker joint list given to [`Mapping::bind`] names a joint twice
    /// (a programming error, reported instead of panicking).
    #[error("the worker joint list names {joint:?} twice")]
    DuplicateWorkerJoint {
        /// The joint named twice.
        joint: String,
    },
    /// A slice passed to the API has the wrong length (a programming error,
    /// reported instead of panicking).
    #[error("{what}: expected {expected} values, got {found}")]
    LengthMismatch {
        /// Which argument.
        what: &'static str,
        /// Expected length.
        expected: usize,
        /// Actual length.
        found: usize,
    },
}

impl OpenSimError {
    /// The 1-based line number the error refers to, if it refers to one.
    pub fn line(&self) -> Option<u64> {
        use OpenSimError as E;
        match self {
            E::Io { line, .. }
            | E::LineTooLong { line, .. }
            | E::NotUtf8 { line, .. }
            | E::MissingEndHeader { line, .. }
            | E::HeaderTooLong { line, .. }
            | E::BadHeaderValue { line, .. }
            | E::UnsupportedDataType { line, .. }
            | E::MissingColumnLabels { line, .. }
            | E::FirstColumnNotTime { line, .. }
            | E::DuplicateColumn { line, .. }
            | E::ColumnCountMismatch { line, .. }
            | E::BadNumber { line, .. }
            | E::NonFiniteNumber { line, .. }
            | E::RowLength { line, .. }
            | E::TimeNotIncreasing { line, .. }
            | E::RowCountMismatch { line, .. }
            | E::Stopped { line, .. }
            | E::MappingInvalid { line, .. }
            | E::MissingCoordinate { line, .. }
            | E::UnknownWorkerJoint { line, .. } => Some(*line),
            E::MappingSyntax { .. } | E::LengthMismatch { .. } | E::DuplicateWorkerJoint { .. } => {
                None
            }
        }
    }
}

// ---------------------------------------------------------------------------
// Header
// ---------------------------------------------------------------------------

/// Which kind of file the input is, as told by its extension. It matters only
/// for version-0 headers that do not say whether angles are in degrees.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StorageKind {
    /// A `.mot` motion file (version-0 ones default to degrees).
    Motion,
    /// A `.sto` storage file (defaults to radians).
    Storage,
    /// Unknown extension: treated like `.sto`.
    Unknown,
}

impl StorageKind {
    /// Kind from a file name's extension (case-insensitive `.mot` / `.sto`).
    pub fn from_file_name(name: &str) -> Self {
        let lower = name.to_ascii_lowercase();
        if lower.ends_with(".mot") {
            StorageKind::Motion
        } else if lower.ends_with(".sto") {
            StorageKind::Storage
        } else {
            StorageKind::Unknown
        }
    }
}

/// How the reader decided whether angles are in degrees.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InDegreesSource {
    /// An `inDegrees=` header line at this line.
    Declared {
        /// Line of the declaration.
        line: u64,
    },
    /// A version-0 `Angles are in degrees.`/`… radians.` line at this line.
    AnglesLine {
        /// Line of the statement.
        line: u64,
    },
    /// Nothing said; a version-0 `.mot` file, which OpenSim reads in degrees.
    LegacyMotionDefault,
    /// Nothing said; radians (OpenSim's default).
    DefaultRadians,
}

/// The parsed header and column labels of a storage file.
#[derive(Debug, Clone, PartialEq)]
pub struct StorageHeader {
    /// Table name (`name` line, or the first header line).
    pub name: Option<String>,
    /// File version (0 when the header has no `version` line).
    pub version: u32,
    /// Whether rotational values are in degrees.
    pub in_degrees: bool,
    /// How [`StorageHeader::in_degrees`] was decided.
    pub in_degrees_source: InDegreesSource,
    /// Column labels after `time`, in file order (data row `i` of
    /// [`StorageReader::next_row`] belongs to `columns[i]`).
    pub columns: Vec<String>,
    /// Declared number of data rows (`nRows`/`nr`/`datarows`), if any.
    pub declared_rows: Option<usize>,
    /// Declared number of columns including time (`nColumns`/`nc`/`datacolumns`).
    pub declared_columns: Option<usize>,
    /// Declared `DataType`, if any (only `double` is accepted).
    pub data_type: Option<String>,
    /// Other `key=value` / `key value` header lines, in order.
    pub metadata: Vec<(String, String)>,
    /// Free-text header lines (without a key), in order.
    pub description: Vec<String>,
    /// Line number of the column-label line.
    pub labels_line: u64,
}

impl StorageHeader {
    /// Index in [`StorageHeader::columns`] of the column with this label.
    pub fn column_index(&self, label: &str) -> Option<usize> {
        self.columns.iter().position(|c| c == label)
    }
}

/// Options for [`StorageReader::with_options`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ReaderOptions {
    /// Longest accepted line in bytes (without the line ending).
    pub max_line_bytes: usize,
    /// Most non-blank header lines accepted before `endheader`.
    pub max_header_lines: usize,
    /// Most bytes of non-blank header lines accepted before `endheader`.
    pub max_header_bytes: usize,
    /// File kind (only matters for version-0 headers without a degrees statement).
    pub kind: StorageKind,
    /// Refuse a file whose label count or row count disagrees with the
    /// header's `nColumns` / `nRows`.
    pub check_declared_counts: bool,
}

impl Default for ReaderOptions {
    fn default() -> Self {
        ReaderOptions {
            max_line_bytes: DEFAULT_MAX_LINE_BYTES,
            max_header_lines: DEFAULT_MAX_HEADER_LINES,
            max_header_bytes: DEFAULT_MAX_HEADER_BYTES,
            kind: StorageKind::Unknown,
            check_declared_counts: true,
        }
    }
}

// ---------------------------------------------------------------------------
// Line reading
// ---------------------------------------------------------------------------

/// Reads lines of at most `max` bytes into one reused buffer.
struct Lines<R> {
    inner: R,
    origin: String,
    /// The current line, validated UTF-8 (its allocation is reused).
    buf: String,
    line: u64,
    max: usize,
}

impl<R: BufRead> Lines<R> {
    /// Reads the next line (without its `\n` / `\r\n`) into `self.buf`.
    /// Returns `Ok(false)` at end of input.
    fn next_raw(&mut self) -> Result<bool, OpenSimError> {
        let mut bytes = std::mem::take(&mut self.buf).into_bytes();
        bytes.clear();
        let result = self.fill_line(&mut bytes);
        match result {
            Ok(true) => match String::from_utf8(bytes) {
                Ok(text) => {
                    self.buf = text;
                    Ok(true)
                }
                Err(e) => {
                    let column = e.utf8_error().valid_up_to() + 1;
                    let mut bytes = e.into_bytes();
                    bytes.clear();
                    self.buf = String::from_utf8(bytes).unwrap_or_default();
                    Err(OpenSimError::NotUtf8 {
                        origin: self.origin.clone(),
                        line: self.line,
                        column,
                    })
                }
            },
            other => {
                bytes.clear();
                self.buf = String::from_utf8(bytes).unwrap_or_default();
                other
            }
        }
    }

    /// Reads the next raw line into `bytes` (without UTF-8 check).
    fn fill_line(&mut self, bytes: &mut Vec<u8>) -> Result<bool, OpenSimError> {
        let mut got_any = false;
        loop {
            let available = match self.inner.fill_buf() {
                Ok(b) => b,
                Err(e) if e.kind() == ErrorKind::Interrupted => continue,
                Err(e) => {
                    return Err(OpenSimError::Io {
                        origin: self.origin.clone(),
                        line: self.line + 1,
                        source: e,
                    });
                }
            };
            if available.is_empty() {
                break;
            }
            got_any = true;
            let newline = available.iter().position(|&b| b == b'\n');
            let take = newline.unwrap_or(available.len());
            // `\r` of a `\r\n` ending may be the last byte kept: allow it beyond the cap.
            let allowed = self.max.saturating_add(1);
            if bytes.len().saturating_add(take) > allowed {
                self.line += 1;
                return Err(OpenSimError::LineTooLong {
                    origin: self.origin.clone(),
                    line: self.line,
                    max_bytes: self.max,
                });
            }
            bytes.extend_from_slice(&available[..take]);
            match newline {
                Some(i) => {
                    self.inner.consume(i + 1);
                    break;
                }
                None => {
                    let n = available.len();
                    self.inner.consume(n);
                }
            }
        }
        if !got_any {
            return Ok(false);
        }
        self.line += 1;
        if bytes.last() == Some(&b'\r') {
            bytes.pop();
        }
        if bytes.len() > self.max {
            return Err(OpenSimError::LineTooLong {
                origin: self.origin.clone(),
                line: self.line,
                max_bytes: self.max,
            });
        }
        if self.line == 1 && bytes.starts_with(&[0xEF, 0xBB, 0xBF]) {
            bytes.drain(..3);
        }
        Ok(true)
    }

    /// The current line as text (valid after `next_raw` returned `Ok(true)`).
    fn text(&self) -> &str {
        &self.buf
    }
}

// ---------------------------------------------------------------------------
// Reader
// ---------------------------------------------------------------------------

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum ReaderState {
    Data,
    Done,
    Failed(u64),
}

/// Streams the rows of an OpenSim `.mot`/`.sto` file from any [`BufRead`].
///
/// Memory use is bounded by one line (at most
/// [`ReaderOptions::max_line_bytes`]) plus the header, whatever the number of
/// rows. After an error the reader stops and every later call returns
/// [`OpenSimError::Stopped`].
pub struct StorageReader<R> {
    lines: Lines<R>,
    header: StorageHeader,
    angle_columns: Vec<bool>,
    check_counts: bool,
    declared_rows_line: u64,
    rows_read: usize,
    previous_time: Option<(f64, u64)>,
    state: ReaderState,
}

impl<R> fmt::Debug for StorageReader<R> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("StorageReader")
            .field("origin", &self.lines.origin)
            .field("line", &self.lines.line)
            .field("rows_read", &self.rows_read)
            .field("header", &self.header)
            .finish_non_exhaustive()
    }
}

/// Splits a header line into (key, rest) like `Storage::parseHeaders`.
fn split_key(line: &str) -> (&str, &str) {
    let is_sep = |c: char| c == ' ' || c == '\t' || c == '=';
    match line.find(is_sep) {
        Some(i) => (&line[..i], line[i..].trim_start_matches(is_sep)),
        None => (line, ""),
    }
}

fn parse_yes_no(value: &str) -> Option<bool> {
    match value.to_ascii_lowercase().as_str() {
        "yes" | "y" => Some(true),
        "no" | "n" => Some(false),
        _ => None,
    }
}

/// A tab-separated line starting with `time` (how OpenSim writes labels).
fn looks_like_labels(line: &str) -> bool {
    line.contains('\t')
        && !line.contains('=')
        && line
            .split('\t')
            .next()
            .is_some_and(|t| t.trim().eq_ignore_ascii_case("time"))
}

fn looks_like_data(line: &str) -> bool {
    let mut n = 0usize;
    for t in line.split_whitespace() {
        if t.parse::<f64>().is_err() {
            return false;
        }
        n += 1;
    }
    n >= 2
}

impl<R: BufRead> StorageReader<R> {
    /// Opens a recording: reads and checks its header and column labels.
    ///
    /// `origin` names the input in messages (normally the file name); its
    /// extension (`.mot`/`.sto`) sets [`ReaderOptions::kind`]. Other options
    /// are the defaults.
    pub fn new(reader: R, origin: &str) -> Result<Self, OpenSimError> {
        let options = ReaderOptions {
            kind: StorageKind::from_file_name(origin),
            ..ReaderOptions::default()
        };
        Self::with_options(reader, origin, options)
    }

    /// Opens a recording with explicit options.
    pub fn with_options(
        reader: R,
        origin: &str,
        options: ReaderOptions,
    ) -> Result<Self, OpenSimError> {
        let mut lines = Lines {
            inner: reader,
            origin: origin.to_string(),
            buf: String::new(),
            line: 0,
            max: options.max_line_bytes,
        };
        let origin_s = origin.to_string();

        let mut name: Option<String> = None;
        let mut version: Option<(u32, u64)> = None;
        let mut in_degrees: Option<(bool, u64)> = None;
        let mut angles_line: Option<(bool, u64)> = None;
        let mut declared_rows: Option<(usize, u64)> = None;
        let mut declared_columns: Option<(usize, u64)> = None;
        let mut data_type: Option<(String, u64)> = None;
        let mut metadata = Vec::new();
        let mut description = Vec::new();
        let mut first_line = true;
        let mut header_lines = 0usize;
        let mut header_bytes = 0usize;

        let bad = |line: u64, key: &str, value: &str, expected: &'static str| {
            OpenSimError::BadHeaderValue {
                origin: origin_s.clone(),
                line,
                key: key.to_string(),
                value: value.to_string(),
                expected,
            }
        };

        loop {
            if !lines.next_raw()? {
                let (line, detail) = if lines.line == 0 {
                    (1, "the input is empty")
                } else {
                    (lines.line, "the input ended before an 'endheader' line")
                };
                return Err(OpenSimError::MissingEndHeader {
                    origin: origin_s.clone(),
                    line,
                    detail: detail.to_string(),
                });
            }
            let ln = lines.line;
            let line = lines.text().trim_matches(|c| c == ' ' || c == '\t');
            if line.is_empty() {
                continue;
            }
            header_lines += 1;
            header_bytes = header_bytes.saturating_add(line.len());
            if header_lines > options.max_header_lines || header_bytes > options.max_header_bytes {
                return Err(OpenSimError::HeaderTooLong {
                    origin: origin_s.clone(),
                    line: ln,
                    max_lines: options.max_header_lines,
                    max_bytes: options.max_header_bytes,
                });
            }
            let (key, rest) = split_key(line);
            let rest = rest.trim();
            match key {
                "endheader" => break,
                "name" => name = Some(rest.to_string()),
                "nRows" | "nr" | "datarows" => {
                    let n = rest
                        .parse::<usize>()
                        .map_err(|_| bad(ln, key, rest, "a whole number of rows"))?;
                    declared_rows = Some((n, ln));
                }
                "nColumns" | "nc" | "datacolumns" => {
                    let n = rest
                        .parse::<usize>()
                        .map_err(|_| bad(ln, key, rest, "a whole number of columns"))?;
                    declared_columns = Some((n, ln));
                }
                "version" => {
                    let v = rest
                        .parse::<u32>()
                        .map_err(|_| bad(ln, key, rest, "a whole version number"))?;
                    version = Some((v, ln));
                }
                "inDegrees" => {
                    let v = parse_yes_no(rest).ok_or_else(|| bad(ln, key, rest, "yes or no"))?;
                    in_degrees = Some((v, ln));
                }
                "DataType" => data_type = Some((rest.to_string(), ln)),
                "Angles" if line == "Angles are in degrees." => angles_line = Some((true, ln)),
                "Angles" if line == "Angles are in radians." => angles_line = Some((false, ln)),
                _ => {
                    if looks_like_labels(line) {
                        return Err(OpenSimError::MissingEndHeader {
                            origin: origin_s.clone(),
                            line: ln,
                            detail: "this line looks like the column-label line ('time ...'), \
                                     but no 'endheader' line came before it"
                                .to_string(),
                        });
                    }
                    if looks_like_data(line) {
                        return Err(OpenSimError::MissingEndHeader {
                            origin: origin_s.clone(),
                            line: ln,
                            detail: "this line looks like a row of numbers, but no \
                                     'endheader' line came before it"
                                .to_string(),
                        });
                    }
                    if first_line {
                        name = Some(line.to_string());
                    } else if let Some((k, v)) = line.split_once('=') {
                        metadata.push((k.trim().to_string(), v.trim().to_string()));
                    } else if matches!(key, "range" | "otherdata" | "units" | "#") {
                        metadata.push((key.to_string(), rest.to_string()));
                    } else {
                        description.push(line.to_string());
                    }
                }
            }
            first_line = false;
        }

        let version_n = version.map_or(0, |v| v.0);
        if let Some((dt, ln)) = &data_type
            && dt != "double"
        {
            return Err(OpenSimError::UnsupportedDataType {
                origin: origin_s.clone(),
                line: *ln,
                data_type: dt.clone(),
            });
        }
        let (in_deg, source) = match (in_degrees, angles_line) {
            (Some((v, line)), _) => (v, InDegreesSource::Declared { line }),
            (None, Some((v, line))) if version_n == 0 => (v, InDegreesSource::AnglesLine { line }),
            _ if version_n == 0 && options.kind == StorageKind::Motion => {
                (true, InDegreesSource::LegacyMotionDefault)
            }
            _ => (false, InDegreesSource::DefaultRadians),
        };

        // Column labels: the first non-blank line after endheader.
        let labels_line;
        let labels: Vec<String> = loop {
            if !lines.next_raw()? {
                return Err(OpenSimError::MissingColumnLabels {
                    origin: origin_s.clone(),
                    line: lines.line,
                });
            }
            let text = lines.text();
            if text.trim().is_empty() {
                continue;
            }
            labels_line = lines.line;
            let v: Vec<String> = if text.contains('\t') {
                text.split('\t')
                    .map(str::trim)
                    .filter(|s| !s.is_empty())
                    .map(str::to_string)
                    .collect()
            } else {
                text.split_whitespace().map(str::to_string).collect()
            };
            break v;
        };
        let first = labels.first().map(String::as_str).unwrap_or("");
        if first != "time" {
            return Err(OpenSimError::FirstColumnNotTime {
                origin: origin_s.clone(),
                line: labels_line,
                found: first.to_string(),
            });
        }
        if options.check_declared_counts
            && let Some((n, at)) = declared_columns
            && n != labels.len()
        {
            return Err(OpenSimError::ColumnCountMismatch {
                origin: origin_s.clone(),
                line: labels_line,
                declared: n,
                declared_at: at,
                found: labels.len(),
            });
        }
        let columns: Vec<String> = labels.into_iter().skip(1).collect();
        let n_columns = columns.len();
        let header = StorageHeader {
            name,
            version: version_n,
            in_degrees: in_deg,
            in_degrees_source: source,
            columns,
            declared_rows: declared_rows.map(|d| d.0),
            declared_columns: declared_columns.map(|d| d.0),
            data_type: data_type.map(|d| d.0),
            metadata,
            description,
            labels_line,
        };
        Ok(StorageReader {
            lines,
            header,
            angle_columns: vec![false; n_columns],
            check_counts: options.check_declared_counts,
            declared_rows_line: declared_rows.map_or(0, |d| d.1),
            rows_read: 0,
            previous_time: None,
            state: ReaderState::Data,
        })
    }

    /// The header and column labels.
    pub fn header(&self) -> &StorageHeader {
        &self.header
    }

    /// The name of the input used in messages.
    pub fn origin(&self) -> &str {
        &self.lines.origin
    }

    /// Number of data rows returned so far.
    pub fn rows_read(&self) -> usize {
        self.rows_read
    }

    /// Number of the last line read (1-based; 0 before any).
    pub fn line_number(&self) -> u64 {
        self.lines.line
    }

    /// Declares which data columns hold angles (rotational coordinates).
    ///
    /// `is_angle[i]` belongs to `header().columns[i]`. When the file is in
    /// degrees, those columns are converted to radians by
    /// [`StorageReader::next_row`]; the others (translations in metres, and
    /// anything else) are returned as written. Before this is called no
    /// column is converted. [`BoundMapping::angle_columns`] gives the vector
    /// declared by a mapping file.
    pub fn set_angle_columns(&mut self, is_angle: &[bool]) -> Result<(), OpenSimError> {
        if is_angle.len() != self.header.columns.len() {
            return Err(OpenSimError::LengthMismatch {
                what: "StorageReader::set_angle_columns(is_angle)",
                expected: self.header.columns.len(),
                found: is_angle.len(),
            });
        }
        self.angle_columns.clear();
        self.angle_columns.extend_from_slice(is_angle);
        Ok(())
    }

    /// Reads the next data row.
    ///
    /// On success `out` is cleared and filled with one value per
    /// `header().columns` entry (angle columns converted to radians, see
    /// [`StorageReader::set_angle_columns`]) and the row's time in seconds is
    /// returned. Returns `Ok(None)` at the end of the data.
    pub fn next_row(&mut self, out: &mut Vec<f64>) -> Result<Option<f64>, OpenSimError> {
        match self.state {
            ReaderState::Data => {}
            ReaderState::Done => return Ok(None),
            ReaderState::Failed(line) => {
                return Err(OpenSimError::Stopped {
                    origin: self.lines.origin.clone(),
                    line,
                });
            }
        }
        match self.read_row(out) {
            Ok(Some(t)) => Ok(Some(t)),
            Ok(None) => {
                self.state = ReaderState::Done;
                Ok(None)
            }
            Err(e) => {
                self.state = ReaderState::Failed(e.line().unwrap_or(self.lines.line));
                out.clear();
                Err(e)
            }
        }
    }

    fn read_row(&mut self, out: &mut Vec<f64>) -> Result<Option<f64>, OpenSimError> {
        out.clear();
        loop {
            if !self.lines.next_raw()? {
                if self.check_counts
                    && let Some(declared) = self.header.declared_rows
                    && declared != self.rows_read
                {
                    return Err(OpenSimError::RowCountMismatch {
                        origin: self.lines.origin.clone(),
                        line: self.lines.line,
                        declared,
                        declared_at: self.declared_rows_line,
                        found: self.rows_read,
                    });
                }
                return Ok(None);
            }
            if !self.lines.text().trim().is_empty() {
                break;
            }
        }
        let line = self.lines.line;
        let expected = self.header.columns.len() + 1;
        let text = self.lines.text();
        let found = text.split_whitespace().count();
        if found != expected {
            return Err(OpenSimError::RowLength {
                origin: self.lines.origin.clone(),
                line,
                found,
                expected,
            });
        }
        let mut time = 0.0;
        for (i, token) in text.split_whitespace().enumerate() {
            let column = if i == 0 {
                "time"
            } else {
                self.header.columns.get(i - 1).map_or("", String::as_str)
            };
            let v: f64 = token.parse().map_err(|_| OpenSimError::BadNumber {
                origin: self.lines.origin.clone(),
                line,
                column: column.to_string(),
                text: token.to_string(),
            })?;
            if !v.is_finite() {
                return Err(OpenSimError::NonFiniteNumber {
                    origin: self.lines.origin.clone(),
                    line,
                    column: column.to_string(),
                    text: token.to_string(),
                });
            }
            if i == 0 {
                time = v;
            } else {
                let angle = self.angle_columns.get(i - 1).copied().unwrap_or(false);
                out.push(if angle && self.header.in_degrees {
                    v.to_radians()
                } else {
                    v
                });
            }
        }
        if let Some((previous_s, previous_line)) = self.previous_time
            && time <= previous_s
        {
            return Err(OpenSimError::TimeNotIncreasing {
                origin: self.lines.origin.clone(),
                line,
                time_s: time,
                previous_s,
                previous_line,
            });
        }
        self.previous_time = Some((time, line));
        self.rows_read += 1;
        Ok(Some(time))
    }
}

// ---------------------------------------------------------------------------
// Mapping
// ---------------------------------------------------------------------------

/// Whether an OpenSim coordinate is an angle or a length.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
pub enum CoordinateKind {
    /// Rotational coordinate: radians inside, degrees in `inDegrees=yes` files.
    #[serde(rename = "rotation", alias = "rotational")]
    Rotation,
    /// Translational coordinate: metres, never converted.
    #[serde(rename = "translation", alias = "translational")]
    Translation,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawEntry {
    joint: String,
    from: String,
    sign: f64,
    #[serde(default)]
    offset_deg: Option<f64>,
    #[serde(default)]
    offset_m: Option<f64>,
    #[serde(default)]
    kind: Option<CoordinateKind>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawAxisFrom {
    coordinate: String,
    axis: [f64; 3],
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawAxisTo {
    joint: String,
    axis: [f64; 3],
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawGroup {
    name: String,
    from: Vec<RawAxisFrom>,
    to: Vec<RawAxisTo>,
    #[serde(default)]
    reference_point_m: Option<[f64; 3]>,
    #[serde(default)]
    translation_joints: Option<Vec<String>>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMapping {
    #[serde(default)]
    model: Option<String>,
    #[serde(default)]
    joints: Vec<Spanned<RawEntry>>,
    #[serde(default)]
    ignore: Vec<Spanned<String>>,
    #[serde(default)]
    rotation_groups: Vec<Spanned<RawGroup>>,
}

/// One `joints:` entry: `q[joint] = sign * value(from) + offset`.
#[derive(Debug, Clone, PartialEq)]
pub struct JointMap {
    /// Worker joint fed.
    pub joint: String,
    /// OpenSim coordinate (column label) feeding it.
    pub from: String,
    /// +1 or -1.
    pub sign: f64,
    /// Offset added after the sign, in radians (rotation) or metres (translation).
    pub offset: f64,
    /// Kind of the coordinate (decides the degree conversion).
    pub kind: CoordinateKind,
    /// Line of the entry in the mapping file.
    pub line: u64,
}

/// A `rotation_groups:` entry: three OpenSim rotations composed in their
/// order, re-expressed as three worker rotations in the worker's order.
///
/// OpenSim's `CustomJoint` applies its rotations as a body-fixed sequence
/// `R = R(a1, q1) R(a2, q2) R(a3, q3)` (Simbody `MobilizedBody::FunctionBased`),
/// axes given at zero pose. When the worker chains the same three rotations
/// in another order (the pelvis: OpenSim tilt→list→rotation, worker
/// rotation→list→tilt) a per-joint sign is only right for small angles; the
/// group composes the OpenSim rotation matrix and decomposes it exactly into
/// the worker's sequence `R = R(b1, p1) R(b2, p2) R(b3, p3)`.
#[derive(Debug, Clone, PartialEq)]
pub struct RotationGroup {
    /// Name used in messages.
    pub name: String,
    /// OpenSim coordinates in application order, with each axis in the
    /// worker's world frame (x forward, y left, z up) at zero pose.
    pub from: Vec<(String, [f64; 3])>,
    /// Worker joints in their chain order, with each axis in the world frame
    /// at q = 0 (must be mutually orthogonal).
    pub to: Vec<(String, [f64; 3])>,
    /// Position of the worker body's origin relative to the OpenSim body's
    /// origin, in the body frame at zero pose (worker axes), metres. When
    /// set, `(R - I) * reference_point_m` is added to `translation_joints`,
    /// so that the worker's origin, not OpenSim's, follows the motion.
    pub reference_point_m: Option<[f64; 3]>,
    /// Worker prismatic joints along world x, y, z receiving the correction.
    pub translation_joints: Option<[String; 3]>,
    /// Line of the group in the mapping file.
    pub line: u64,
}

/// A mapping file: how OpenSim coordinates feed the worker's joints.
///
/// YAML shape (all angles in the file in degrees, lengths in metres):
///
/// ```yaml
/// model: Rajagopal et al. 2016 full-body model (Rajagopal2015.osim)
/// joints:
///   - {joint: r_knee_flexion, from: knee_angle_r, sign: 1, offset_deg: 0}
///   - {joint: lumbar_lateral_bending, from: lumbar_bending, sign: -1}
///   - {joint: pelvis_tz, from: pelvis_ty, sign: 1, offset_m: -0.94, kind: translation}
/// ignore: [mtp_angle_r, mtp_angle_l]     # used by nothing, on purpose
/// rotation_groups:                        # optional, see RotationGroup
///   - name: pelvis
///     from: [{coordinate: pelvis_tilt, axis: [0, -1, 0]}, ...]
///     to:   [{joint: pelvis_rotation, axis: [0, 0, 1]}, ...]
/// ```
///
/// `kind` is `rotation` (default) or `translation`; `offset_deg` is only
/// allowed for rotations and `offset_m` only for translations; `sign` is
/// required and must be 1 or -1. A worker joint may be fed once.
#[derive(Debug, Clone, PartialEq)]
pub struct Mapping {
    origin: String,
    model: Option<String>,
    joints: Vec<JointMap>,
    ignore: Vec<String>,
    groups: Vec<RotationGroup>,
}

fn normalized(v: [f64; 3]) -> Option<[f64; 3]> {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if v.iter().all(|x| x.is_finite()) && n.is_finite() && n > 1e-9 {
        Some([v[0] / n, v[1] / n, v[2] / n])
    } else {
        None
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

impl Mapping {
    /// Parses a mapping file. `origin` names it in messages.
    pub fn from_yaml_str(text: &str, origin: &str) -> Result<Self, OpenSimError> {
        let invalid = |line: u64, detail: String| OpenSimError::MappingInvalid {
            origin: origin.to_string(),
            line,
            detail,
        };
        if text.len() > MAX_MAPPING_BYTES {
            return Err(invalid(
                1,
                format!("mapping file is larger than {MAX_MAPPING_BYTES} bytes"),
            ));
        }
        let raw: RawMapping = serde_saphyr::from_str(text).map_err(|e| {
            let message = e.to_string();
            let message = message.strip_prefix("error: ").unwrap_or(&message);
            OpenSimError::MappingSyntax {
                origin: origin.to_string(),
                message: message.replace("<input>", origin),
            }
        })?;

        if raw.joints.is_empty() && raw.rotation_groups.is_empty() {
            return Err(invalid(
                1,
                "the mapping lists no joints and no rotation groups: nothing of the recording would be read; map at least one coordinate to a joint".into(),
            ));
        }
        let mut joints = Vec::with_capacity(raw.joints.len());
        for s in &raw.joints {
            let e = &s.value;
            let line = s.referenced.line();
            let kind = e.kind.unwrap_or(CoordinateKind::Rotation);
            if !(e.sign == 1.0 || e.sign == -1.0) {
                return Err(invalid(
                    line,
                    format!("joint {:?}: sign must be 1 or -1, not {}", e.joint, e.sign),
                ));
            }
            let offset = match (kind, e.offset_deg, e.offset_m) {
                (CoordinateKind::Rotation, Some(_), Some(_))
                | (CoordinateKind::Translation, Some(_), Some(_)) => {
                    return Err(invalid(
                        line,
                        format!("joint {:?}: give offset_deg or offset_m, not both", e.joint),
                    ));
                }
                (CoordinateKind::Rotation, None, Some(_)) => {
                    return Err(invalid(
                        line,
                        format!(
                            "joint {:?}: offset_m is for translations; this entry is a \
                             rotation (use offset_deg, or kind: translation)",
                            e.joint
                        ),
                    ));
                }
                (CoordinateKind::Translation, Some(_), None) => {
                    return Err(invalid(
                        line,
                        format!(
                            "joint {:?}: offset_deg is for rotations; this entry is a \
                             translation (use offset_m)",
                            e.joint
                        ),
                    ));
                }
                (CoordinateKind::Rotation, Some(d), None) => d.to_radians(),
                (CoordinateKind::Translation, None, Some(m)) => m,
                (_, None, None) => 0.0,
            };
            if !offset.is_finite() {
                return Err(invalid(
                    line,
                    format!("joint {:?}: offset is not finite", e.joint),
                ));
            }
            // an offset of more than a turn, or beyond the body model's largest offset, is a
            // typo (it would only surface as an absurd joint value at the first sample)
            let (limit, unit) = match kind {
                CoordinateKind::Rotation => (std::f64::consts::TAU, "360°"),
                CoordinateKind::Translation => (crate::body::model::MAX_OFFSET_M, "100 m"),
            };
            if offset.abs() > limit {
                return Err(invalid(
                    line,
                    format!(
                        "joint {:?}: offset must be within ±{unit}, got {}",
                        e.joint,
                        match kind {
                            CoordinateKind::Rotation => format!("{}°", offset.to_degrees()),
                            CoordinateKind::Translation => format!("{offset} m"),
                        }
                    ),
                ));
            }
            if let Some(prev) = joints.iter().find(|j: &&JointMap| j.joint == e.joint) {
                return Err(invalid(
                    line,
                    format!(
                        "worker joint {:?} is fed twice (also at line {})",
                        e.joint, prev.line
                    ),
                ));
            }
            if let Some(prev) = joints
                .iter()
                .find(|j: &&JointMap| j.from == e.from && j.kind != kind)
            {
                return Err(invalid(
                    line,
                    format!(
                        "coordinate {:?} is declared {:?} here but {:?} at line {}",
                        e.from, kind, prev.kind, prev.line
                    ),
                ));
            }
            joints.push(JointMap {
                joint: e.joint.clone(),
                from: e.from.clone(),
                sign: e.sign,
                offset,
                kind,
                line,
            });
        }

        let mut groups = Vec::with_capacity(raw.rotation_groups.len());
        for s in &raw.rotation_groups {
            let g = &s.value;
            let line = s.referenced.line();
            if g.from.len() != 3 || g.to.len() != 3 {
                return Err(invalid(
                    line,
                    format!(
                        "rotation group {:?}: needs exactly 3 'from' and 3 'to' axes",
                        g.name
                    ),
                ));
            }
            let mut from = Vec::with_capacity(3);
            for f in &g.from {
                let a = normalized(f.axis).ok_or_else(|| {
                    invalid(
                        line,
                        format!(
                            "rotation group {:?}: axis of {:?} is zero or not finite",
                            g.name, f.coordinate
                        ),
                    )
                })?;
                if let Some(j) = joints
                    .iter()
                    .find(|j| j.from == f.coordinate && j.kind != CoordinateKind::Rotation)
                {
                    return Err(invalid(
                        line,
                        format!(
                            "rotation group {:?}: coordinate {:?} is declared a \
                             translation at line {}",
                            g.name, f.coordinate, j.line
                        ),
                    ));
                }
                from.push((f.coordinate.clone(), a));
            }
            let mut to = Vec::with_capacity(3);
            for t in &g.to {
                let a = normalized(t.axis).ok_or_else(|| {
                    invalid(
                        line,
                        format!(
                            "rotation group {:?}: axis of {:?} is zero or not finite",
                            g.name, t.joint
                        ),
                    )
                })?;
                if let Some(j) = joints.iter().find(|j| j.joint == t.joint) {
                    return Err(invalid(
                        line,
                        format!(
                            "worker joint {:?} is fed by rotation group {:?} and by the \
                             entry at line {}",
                            t.joint, g.name, j.line
                        ),
                    ));
                }
                to.push((t.joint.clone(), a));
            }
            for i in 0..3 {
                for k in (i + 1)..3 {
                    if dot(to[i].1, to[k].1).abs() > 1e-6 {
                        return Err(invalid(
                            line,
                            format!(
                                "rotation group {:?}: worker axes of {:?} and {:?} are not \
                                 perpendicular",
                                g.name, to[i].0, to[k].0
                            ),
                        ));
                    }
                    if to[i].0 == to[k].0 {
                        return Err(invalid(
                            line,
                            format!(
                                "rotation group {:?}: joint {:?} named twice",
                                g.name, to[i].0
                            ),
                        ));
                    }
                }
            }
            if groups
                .iter()
                .flat_map(|h: &RotationGroup| h.to.iter())
                .any(|(n, _)| to.iter().any(|(m, _)| m == n))
            {
                return Err(invalid(
                    line,
                    format!(
                        "rotation group {:?} feeds a joint another group feeds",
                        g.name
                    ),
                ));
            }
            let translation_joints = match (&g.reference_point_m, &g.translation_joints) {
                (None, None) => None,
                (Some(p), Some(t)) => {
                    if !p
                        .iter()
                        .all(|x| x.is_finite() && x.abs() <= crate::body::model::MAX_OFFSET_M)
                    {
                        return Err(invalid(
                            line,
                            format!(
                                "rotation group {:?}: reference_point_m must be finite and within ±{} m, got {:?}",
                                g.name,
                                crate::body::model::MAX_OFFSET_M,
                                p
                            ),
                        ));
                    }
                    match t.as_slice() {
                        [a, b, c] => Some([a.clone(), b.clone(), c.clone()]),
                        _ => {
                            return Err(invalid(
                                line,
                                format!(
                                    "rotation group {:?}: translation_joints needs 3 joints \
                                     (along world x, y, z)",
                                    g.name
                                ),
                            ));
                        }
                    }
                }
                _ => {
                    return Err(invalid(
                        line,
                        format!(
                            "rotation group {:?}: give both reference_point_m and \
                             translation_joints, or neither",
                            g.name
                        ),
                    ));
                }
            };
            groups.push(RotationGroup {
                name: g.name.clone(),
                from,
                to,
                reference_point_m: g.reference_point_m,
                translation_joints,
                line,
            });
        }

        let mut ignore = Vec::with_capacity(raw.ignore.len());
        for s in &raw.ignore {
            let used = joints.iter().any(|j| j.from == s.value)
                || groups
                    .iter()
                    .any(|g| g.from.iter().any(|(c, _)| c == &s.value));
            if used {
                return Err(invalid(
                    s.referenced.line(),
                    format!(
                        "coordinate {:?} is listed under ignore but is also used",
                        s.value
                    ),
                ));
            }
            ignore.push(s.value.clone());
        }

        Ok(Mapping {
            origin: origin.to_string(),
            model: raw.model,
            joints,
            ignore,
            groups,
        })
    }

    /// The `model:` text of the file.
    pub fn model(&self) -> Option<&str> {
        self.model.as_deref()
    }

    /// The name the mapping was given in messages.
    pub fn origin(&self) -> &str {
        &self.origin
    }

    /// The `joints:` entries.
    pub fn joints(&self) -> &[JointMap] {
        &self.joints
    }

    /// The `rotation_groups:` entries.
    pub fn rotation_groups(&self) -> &[RotationGroup] {
        &self.groups
    }

    /// Coordinates listed under `ignore:`.
    pub fn ignored(&self) -> &[String] {
        &self.ignore
    }

    /// Binds the mapping to a recording's columns and to the worker's joint
    /// list (`worker_joints`, in the order of the worker's `q`).
    ///
    /// Errors when the mapping names a worker joint not in `worker_joints`,
    /// or a coordinate the recording lacks (naming both).
    pub fn bind(
        &self,
        header: &StorageHeader,
        recording: &str,
        worker_joints: &[&str],
    ) -> Result<BoundMapping, OpenSimError> {
        let known = || worker_joints.join(", ");
        for (i, a) in worker_joints.iter().enumerate() {
            if worker_joints[..i].contains(a) {
                return Err(OpenSimError::DuplicateWorkerJoint {
                    joint: (*a).to_string(),
                });
            }
        }
        let joint_index = |name: &str, line: u64| {
            worker_joints
                .iter()
                .position(|j| *j == name)
                .ok_or_else(|| OpenSimError::UnknownWorkerJoint {
                    mapping: self.origin.clone(),
                    line,
                    joint: name.to_string(),
                    known: known(),
                })
        };
        let column_index = |coordinate: &str, joint: &str, line: u64| {
            let first =
                header
                    .column_index(coordinate)
                    .ok_or_else(|| OpenSimError::MissingCoordinate {
                        mapping: self.origin.clone(),
                        line,
                        joint: joint.to_string(),
                        coordinate: coordinate.to_string(),
                        recording: recording.to_string(),
                    })?;
            if let Some(k) = header.columns[first + 1..]
                .iter()
                .position(|c| c == coordinate)
            {
                return Err(OpenSimError::DuplicateColumn {
                    origin: recording.to_string(),
                    line: header.labels_line,
                    name: coordinate.to_string(),
                    first: first + 2,
                    second: first + k + 3,
                });
            }
            Ok(first)
        };

        let mut fed = vec![false; worker_joints.len()];
        let mut used = vec![false; header.columns.len()];
        let mut angle = vec![false; header.columns.len()];

        let mut linear = Vec::with_capacity(self.joints.len());
        for j in &self.joints {
            let q = joint_index(&j.joint, j.line)?;
            let c = column_index(&j.from, &j.joint, j.line)?;
            fed[q] = true;
            used[c] = true;
            angle[c] = j.kind == CoordinateKind::Rotation;
            linear.push(BoundLinear {
                column: c,
                q,
                sign: j.sign,
                offset: j.offset,
            });
        }
        let mut groups = Vec::with_capacity(self.groups.len());
        for g in &self.groups {
            let mut from = [(0usize, [0.0; 3]); 3];
            let mut to = [(0usize, [0.0; 3]); 3];
            for (k, (coordinate, axis)) in g.from.iter().enumerate().take(3) {
                let joint = g.to.get(k).map_or("", |t| t.0.as_str());
                let c = column_index(coordinate, joint, g.line)?;
                used[c] = true;
                angle[c] = true;
                from[k] = (c, *axis);
            }
            for (k, (joint, axis)) in g.to.iter().enumerate().take(3) {
                let q = joint_index(joint, g.line)?;
                fed[q] = true;
                to[k] = (q, *axis);
            }
            let correction = match (&g.reference_point_m, &g.translation_joints) {
                (Some(p), Some(t)) => Some((
                    *p,
                    [
                        joint_index(&t[0], g.line)?,
                        joint_index(&t[1], g.line)?,
                        joint_index(&t[2], g.line)?,
                    ],
                )),
                _ => None,
            };
            groups.push(BoundGroup {
                from,
                to,
                correction,
            });
        }
        let unmapped = worker_joints
            .iter()
            .zip(&fed)
            .filter(|(_, f)| !**f)
            .map(|(j, _)| (*j).to_string())
            .collect();
        let ignored = header
            .columns
            .iter()
            .zip(&used)
            .filter(|(_, u)| !**u)
            .map(|(c, _)| IgnoredColumn {
                name: c.clone(),
                declared: self.ignore.contains(c),
            })
            .collect();
        Ok(BoundMapping {
            n_columns: header.columns.len(),
            n_joints: worker_joints.len(),
            linear,
            groups,
            angle,
            unmapped,
            ignored,
        })
    }
}

#[derive(Debug, Clone, PartialEq)]
struct BoundLinear {
    column: usize,
    q: usize,
    sign: f64,
    offset: f64,
}

type Vec3 = [f64; 3];
type Mat3 = [[f64; 3]; 3];

#[derive(Debug, Clone, PartialEq)]
struct BoundGroup {
    from: [(usize, Vec3); 3],
    to: [(usize, Vec3); 3],
    correction: Option<(Vec3, [usize; 3])>,
}

/// A recording column the mapping does not use.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct IgnoredColumn {
    /// Column label.
    pub name: String,
    /// True when the mapping lists it under `ignore:` (left out on purpose).
    pub declared: bool,
}

/// A [`Mapping`] bound to one recording's columns and the worker's joints.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundMapping {
    n_columns: usize,
    n_joints: usize,
    linear: Vec<BoundLinear>,
    groups: Vec<BoundGroup>,
    angle: Vec<bool>,
    unmapped: Vec<String>,
    ignored: Vec<IgnoredColumn>,
}

fn axis_angle(a: Vec3, t: f64) -> Mat3 {
    let (s, c) = t.sin_cos();
    let v = 1.0 - c;
    [
        [
            c + a[0] * a[0] * v,
            a[0] * a[1] * v - a[2] * s,
            a[0] * a[2] * v + a[1] * s,
        ],
        [
            a[1] * a[0] * v + a[2] * s,
            c + a[1] * a[1] * v,
            a[1] * a[2] * v - a[0] * s,
        ],
        [
            a[2] * a[0] * v - a[1] * s,
            a[2] * a[1] * v + a[0] * s,
            c + a[2] * a[2] * v,
        ],
    ]
}

fn mat_mul(a: &Mat3, b: &Mat3) -> Mat3 {
    let mut r = [[0.0; 3]; 3];
    for (i, row) in r.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
        }
    }
    r
}

fn transpose(a: &Mat3) -> Mat3 {
    let mut r = [[0.0; 3]; 3];
    for (i, row) in a.iter().enumerate() {
        for (j, x) in row.iter().enumerate() {
            r[j][i] = *x;
        }
    }
    r
}

fn det(a: &Mat3) -> f64 {
    a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
        - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
        + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
}

/// Composes `R = R(a1, q1) R(a2, q2) R(a3, q3)` (body-fixed sequence).
fn compose(axes: [Vec3; 3], angles: [f64; 3]) -> Mat3 {
    let r12 = mat_mul(
        &axis_angle(axes[0], angles[0]),
        &axis_angle(axes[1], angles[1]),
    );
    mat_mul(&r12, &axis_angle(axes[2], angles[2]))
}

/// Angles `p` with `R = R(b1, p1) R(b2, p2) R(b3, p3)` for mutually
/// orthogonal unit axes `b`; `p2` is in [-pi/2, pi/2].
fn decompose(r: &Mat3, axes: [Vec3; 3]) -> [f64; 3] {
    let mut p: Mat3 = [axes[0], axes[1], axes[2]];
    let flip = det(&p) < 0.0;
    if flip {
        p[2] = [-p[2][0], -p[2][1], -p[2][2]];
    }
    // P maps b_i to e_i, so P R Pt = Rx(p1) Ry(p2) Rz(+-p3).
    let m = mat_mul(&mat_mul(&p, r), &transpose(&p));
    let s2 = m[0][2].clamp(-1.0, 1.0);
    let a2 = s2.asin();
    let (a1, a3) = if s2.abs() < 1.0 - 1e-12 {
        ((-m[1][2]).atan2(m[2][2]), (-m[0][1]).atan2(m[0][0]))
    } else {
        (m[2][1].atan2(m[1][1]), 0.0)
    };
    [a1, a2, if flip { -a3 } else { a3 }]
}

impl BoundMapping {
    /// Maps one recording row (values in radians and metres, as returned by
    /// [`StorageReader::next_row`] after [`StorageReader::set_angle_columns`]
    /// with [`BoundMapping::angle_columns`]) onto the worker's `q`: radians
    /// for revolute joints, metres for prismatic ones, in the order of the
    /// worker joint list given to [`Mapping::bind`]. Joints the mapping does
    /// not feed are set to 0.
    pub fn apply(&self, row: &[f64], q: &mut [f64]) -> Result<(), OpenSimError> {
        if row.len() != self.n_columns {
            return Err(OpenSimError::LengthMismatch {
                what: "BoundMapping::apply(row)",
                expected: self.n_columns,
                found: row.len(),
            });
        }
        if q.len() != self.n_joints {
            return Err(OpenSimError::LengthMismatch {
                what: "BoundMapping::apply(q)",
                expected: self.n_joints,
                found: q.len(),
            });
        }
        q.fill(0.0);
        for l in &self.linear {
            q[l.q] = l.sign * row[l.column] + l.offset;
        }
        for g in &self.groups {
            let r = compose(
                [g.from[0].1, g.from[1].1, g.from[2].1],
                [row[g.from[0].0], row[g.from[1].0], row[g.from[2].0]],
            );
            let p = decompose(&r, [g.to[0].1, g.to[1].1, g.to[2].1]);
            for k in 0..3 {
                q[g.to[k].0] = p[k];
            }
            if let Some((d, joints)) = &g.correction {
                for k in 0..3 {
                    let rd = r[k][0] * d[0] + r[k][1] * d[1] + r[k][2] * d[2];
                    q[joints[k]] += rd - d[k];
                }
            }
        }
        Ok(())
    }

    /// Which recording columns are angles according to the mapping file
    /// (argument for [`StorageReader::set_angle_columns`]). Columns the
    /// mapping does not use are `false`.
    pub fn angle_columns(&self) -> &[bool] {
        &self.angle
    }

    /// Worker joints the mapping does not feed; [`BoundMapping::apply`]
    /// holds them at 0.
    pub fn unmapped_worker_joints(&self) -> &[String] {
        &self.unmapped
    }

    /// Recording columns the mapping does not use (ignored).
    pub fn ignored_columns(&self) -> &[IgnoredColumn] {
        &self.ignored
    }

    /// Number of worker joints (`q` length).
    pub fn joint_count(&self) -> usize {
        self.n_joints
    }

    /// A short human-readable report of what is held at 0 and what is ignored.
    pub fn report(&self) -> String {
        let mut s = String::new();
        if self.unmapped.is_empty() {
            s.push_str("every worker joint is fed by the recording\n");
        } else {
            s.push_str("worker joints not in the recording, held at 0: ");
            s.push_str(&self.unmapped.join(", "));
            s.push('\n');
        }
        let on_purpose: Vec<&str> = self
            .ignored
            .iter()
            .filter(|c| c.declared)
            .map(|c| c.name.as_str())
            .collect();
        let other: Vec<&str> = self
            .ignored
            .iter()
            .filter(|c| !c.declared)
            .map(|c| c.name.as_str())
            .collect();
        if !on_purpose.is_empty() {
            s.push_str("recording columns ignored by the mapping: ");
            s.push_str(&on_purpose.join(", "));
            s.push('\n');
        }
        if !other.is_empty() {
            s.push_str("recording columns not mentioned in the mapping, ignored: ");
            s.push_str(&other.join(", "));
            s.push('\n');
        }
        s
    }
}

// ---------------------------------------------------------------------------
// Reader + mapping together
// ---------------------------------------------------------------------------

/// A recording read through a mapping: yields the worker's `q` frame by frame.
///
/// This is the usual entry point: it declares the mapping's angle columns to
/// the reader so degrees are converted exactly where they should be.
#[derive(Debug)]
pub struct MappedMotion<R> {
    reader: StorageReader<R>,
    bound: BoundMapping,
    row: Vec<f64>,
}

impl<R: BufRead> MappedMotion<R> {
    /// Binds `mapping` to the reader's columns and the worker's joints.
    pub fn new(
        mut reader: StorageReader<R>,
        mapping: &Mapping,
        worker_joints: &[&str],
    ) -> Result<Self, OpenSimError> {
        let bound = mapping.bind(reader.header(), reader.origin(), worker_joints)?;
        reader.set_angle_columns(bound.angle_columns())?;
        let row = Vec::with_capacity(reader.header().columns.len());
        Ok(MappedMotion { reader, bound, row })
    }

    /// The recording's header.
    pub fn header(&self) -> &StorageHeader {
        self.reader.header()
    }

    /// The bound mapping (unmapped joints, ignored columns).
    pub fn mapping(&self) -> &BoundMapping {
        &self.bound
    }

    /// Reads the next frame into `q` (length = number of worker joints) and
    /// returns its time in seconds, or `None` at the end.
    pub fn next_frame(&mut self, q: &mut [f64]) -> Result<Option<f64>, OpenSimError> {
        if q.len() != self.bound.joint_count() {
            return Err(OpenSimError::LengthMismatch {
                what: "MappedMotion::next_frame(q)",
                expected: self.bound.joint_count(),
                found: q.len(),
            });
        }
        match self.reader.next_row(&mut self.row)? {
            Some(t) => {
                self.bound.apply(&self.row, q)?;
                Ok(Some(t))
            }
            None => Ok(None),
        }
    }

    /// Frames returned so far.
    pub fn frames_read(&self) -> usize {
        self.reader.rows_read()
    }
}

#[cfg(test)]
mod tests;
