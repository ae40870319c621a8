//! Evaluating a whole recording (streamed through, bounded memory) and live evaluation.

use super::csv_recording::{Columns, MAX_LINE_BYTES, read_line_bounded};
use super::evaluator::{Evaluator, ExhaustionEvent};
use super::opensim::{MappedMotion, Mapping, StorageReader};
use super::{EvalError, RecordingError, Sample};
use crate::plan::Task;
use serde::Serialize;
use std::io::{BufRead, Write};

/// The hold rule, as stated in outputs.
pub const HOLD_RULE: &str =
    "zero-order hold: each sample's posture and loads hold until the next sample";

/// Most timeline points kept in the document (the CSV output has every sample).
pub const TIMELINE_POINTS: usize = 2000;

/// A recording to read.
pub enum Input<R> {
    /// CSV (see [`super::csv_recording`]).
    Csv { reader: R, name: String },
    /// OpenSim `.mot`/`.sto` with a mapping onto the body's joints.
    OpenSim {
        reader: R,
        name: String,
        mapping: Mapping,
    },
}

/// How to read it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// CSV angles in degrees (OpenSim files say so in their header).
    pub degrees: bool,
    /// Constant loads \[kg\] on the (right, left) hand when the recording has no load columns.
    pub hand_load_kg: [f64; 2],
}

impl Default for Options {
    fn default() -> Self {
        Options {
            degrees: false,
            hand_load_kg: [0.0; 2],
        }
    }
}

/// Samples read one at a time from either format.
enum Reader<R: BufRead> {
    Csv {
        reader: R,
        name: String,
        cols: Columns,
        line: usize,
        buf: String,
        bytes: Vec<u8>,
    },
    OpenSim {
        motion: Box<MappedMotion<R>>,
        name: String,
        /// The mapping file: a sample refused after mapping may be the mapping's fault.
        mapping_name: String,
    },
}

fn opensim_err(e: impl std::fmt::Display) -> RecordingError {
    RecordingError::OpenSim(e.to_string())
}

impl<R: BufRead> Reader<R> {
    fn open(input: Input<R>, task: &Task) -> Result<Self, RecordingError> {
        match input {
            Input::Csv { mut reader, name } => {
                let (mut buf, mut bytes, mut line) = (String::new(), Vec::new(), 0);
                loop {
                    line += 1;
                    if !read_line_bounded(
                        &mut reader,
                        &mut buf,
                        &mut bytes,
                        MAX_LINE_BYTES,
                        &name,
                        line,
                    )? {
                        return Err(RecordingError::Header {
                            source_name: name,
                            problem: "the recording is empty".into(),
                        });
                    }
                    if !buf.trim().is_empty() {
                        break;
                    }
                }
                let cols = Columns::parse(&buf, &task.model, &name)?;
                Ok(Reader::Csv {
                    reader,
                    name,
                    cols,
                    line,
                    buf,
                    bytes,
                })
            }
            Input::OpenSim {
                reader,
                name,
                mapping,
            } => {
                let storage = StorageReader::new(reader, &name).map_err(opensim_err)?;
                let joints = task.joint_names();
                let refs: Vec<&str> = joints.iter().map(String::as_str).collect();
                let motion = MappedMotion::new(storage, &mapping, &refs).map_err(opensim_err)?;
                Ok(Reader::OpenSim {
                    motion: Box::new(motion),
                    name,
                    mapping_name: mapping.origin().to_string(),
                })
            }
        }
    }

    /// Whether hand `h`'s load comes from the file.
    fn hand_from_file(&self, h: usize) -> bool {
        match self {
            Reader::Csv { cols, .. } => cols.hand_from_file[h],
            Reader::OpenSim { .. } => false,
        }
    }

    fn name(&self) -> &str {
        match self {
            Reader::Csv { name, .. } | Reader::OpenSim { name, .. } => name,
        }
    }

    /// The current line (CSV) or row (OpenSim) for messages.
    fn line(&self) -> usize {
        match self {
            Reader::Csv { line, .. } => *line,
            Reader::OpenSim { motion, .. } => motion.frames_read(),
        }
    }

    /// Reads the next sample into `out`: `Ok(false)` at the end.
    fn next(
        &mut self,
        task: &Task,
        degrees: bool,
        out: &mut Sample,
    ) -> Result<bool, RecordingError> {
        match self {
            Reader::Csv {
                reader,
                name,
                cols,
                line,
                buf,
                bytes,
            } => loop {
                *line += 1;
                if !read_line_bounded(reader, buf, bytes, MAX_LINE_BYTES, name, *line)? {
                    return Ok(false);
                }
                if buf.trim().is_empty() {
                    continue;
                }
                cols.parse_sample(buf, *line, degrees, &task.gravity_m_s2, name, out)?;
                return Ok(true);
            },
            Reader::OpenSim { motion, .. } => {
                match motion.next_frame(&mut out.q_rad).map_err(opensim_err)? {
                    Some(t) => {
                        out.t_s = t;
                        Ok(true)
                    }
                    None => Ok(false),
                }
            }
        }
    }
}

/// Why an evaluation stopped.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    #[error(transparent)]
    Recording(#[from] RecordingError),
    #[error("{source_name}: line {line}: {problem}")]
    Sample {
        source_name: String,
        line: usize,
        problem: String,
    },
    #[error("cannot write: {0}")]
    Write(String),
}

fn sample_err<R: BufRead>(r: &Reader<R>, problem: String) -> RunError {
    RunError::Sample {
        source_name: r.name().to_string(),
        line: r.line(),
        problem,
    }
}

/// [`sample_err`] for a sample the evaluator refused; a time error names the time column.
fn eval_err<R: BufRead>(r: &Reader<R>, e: EvalError) -> RunError {
    let problem = match e {
        // a recording's time is its first column
        EvalError::Time { .. } => format!("column 1 (time): {e}"),
        e => match r {
            // the worker's joint values come from the coordinates through the mapping
            Reader::OpenSim { mapping_name, .. } => {
                format!("{e} (the coordinates as mapped by {mapping_name})")
            }
            Reader::Csv { .. } => e.to_string(),
        },
    };
    sample_err(r, problem)
}

/// The evaluation timeline, thinned to at most [`TIMELINE_POINTS`] samples.
#[derive(Debug, Clone, Default, Serialize)]
pub struct Timeline {
    /// Every `stride`-th sample is kept.
    pub stride: u64,
    pub t_s: Vec<f64>,
    /// Per kept sample, per half-joint.
    pub capacity: Vec<Vec<f64>>,
    pub fatigue_u_min: Vec<Vec<f64>>,
    pub load: Vec<Vec<f64>>,
}

impl Timeline {
    /// Records sample `i` (at `t` s) of `ev` when it falls on the stride.
    pub fn push(&mut self, i: u64, t: f64, ev: &Evaluator) {
        if self.stride == 0 {
            self.stride = 1;
        }
        if !i.is_multiple_of(self.stride) {
            return;
        }
        if self.t_s.len() >= TIMELINE_POINTS {
            // keep every other point and double the stride
            let keep = |v: &mut Vec<Vec<f64>>| {
                let mut k = 0;
                v.retain(|_| {
                    k += 1;
                    k % 2 == 1
                });
            };
            let mut k = 0;
            self.t_s.retain(|_| {
                k += 1;
                k % 2 == 1
            });
            keep(&mut self.capacity);
            keep(&mut self.fatigue_u_min);
            keep(&mut self.load);
            self.stride *= 2;
            if !i.is_multiple_of(self.stride) {
                return;
            }
        }
        self.t_s.push(t);
        self.capacity
            .push(ev.state.iter().map(|s| s.capacity).collect());
        self.fatigue_u_min
            .push(ev.state.iter().map(|s| s.fatigue_u_min).collect());
        self.load.push(ev.loads.clone());
    }
}

/// The evaluation document (`posture-opt evaluate --json`).
#[derive(Debug, Clone, Serialize)]
pub struct Evaluation {
    pub source: String,
    pub robot: String,
    pub worker: crate::body::Worker,
    pub fatigue_parameters: String,
    pub hold_rule: &'static str,
    pub standing: bool,
    pub half_joint_ids: Vec<String>,
    pub groups: Vec<String>,
    pub samples: u64,
    pub duration_s: f64,
    /// Per half-joint at the last sample.
    pub final_capacity: Vec<f64>,
    pub final_fatigue_u_min: Vec<f64>,
    pub total_u_min: f64,
    pub worst_group: String,
    pub worst_u_min: f64,
    /// Lowest capacity at any time, whose and when.
    pub lowest_capacity: f64,
    pub lowest_capacity_group: String,
    pub lowest_capacity_t_s: f64,
    pub exhaustions: Vec<ExhaustionEvent>,
    /// Samples with an angle outside its joint's range by more than 0.1 rad.
    pub samples_outside_range: u64,
    pub timeline: Timeline,
}

fn check_sample<R: BufRead>(ev: &mut Evaluator, r: &Reader<R>, s: &Sample) -> Result<(), RunError> {
    if let Err((k, v)) = ev.check_range(&s.q_rad) {
        let j = ev.task().model.q_joint(k);
        let hint = match r {
            // OpenSim angles are converted by the file's inDegrees header, then mapped
            Reader::OpenSim { mapping_name, .. } => format!(
                "check the file's inDegrees header and the sign and offset of {}'s entry in {mapping_name}",
                j.name
            ),
            Reader::Csv { .. } => "is the recording in degrees? Use --degrees".into(),
        };
        return Err(sample_err(
            r,
            format!(
                "{} = {v} rad lies far outside its range [{:.2}, {:.2}] rad, and {v}° would fit: {hint}",
                j.name, j.lower_rad, j.upper_rad
            ),
        ));
    }
    Ok(())
}

fn constant_loads<R: BufRead>(task: &Task, r: &Reader<R>, opts: &Options, s: &mut Sample) {
    for h in 0..2 {
        if !r.hand_from_file(h) {
            s.hand_force_n[h] = task.gravity_m_s2 * opts.hand_load_kg[h];
        }
    }
}

/// Evaluates a whole recording: streams through it (memory bounded by the timeline's points),
/// writing every sample's state to `csv_out` if given.
pub fn evaluate<R: BufRead>(
    task: &Task,
    input: Input<R>,
    opts: &Options,
    mut csv_out: Option<&mut dyn Write>,
) -> Result<Evaluation, RunError> {
    let mut r = Reader::open(input, task)?;
    let mut ev = Evaluator::new(task);
    let mut s = Sample::zeros(task.model.nq());
    let ids: Vec<String> = task.half_joint_ids();
    let mut csv = csv_out
        .as_mut()
        .map(|w| ::csv::Writer::from_writer(&mut **w));
    if let Some(w) = csv.as_mut() {
        let mut head = vec!["t_s".to_string()];
        for h in &ids {
            head.push(format!("capacity_{h}"));
            head.push(format!("u_{h}_min"));
            head.push(format!("load_{h}"));
        }
        w.write_record(&head)
            .map_err(|e| RunError::Write(e.to_string()))?;
    }
    let mut timeline = Timeline::default();
    let mut i = 0u64;
    let mut row: Vec<String> = Vec::with_capacity(1 + 3 * ids.len());
    while r.next(task, opts.degrees, &mut s)? {
        constant_loads(task, &r, opts, &mut s);
        check_sample(&mut ev, &r, &s)?;
        ev.push(&s).map_err(|e| eval_err(&r, e))?;
        timeline.push(i, s.t_s, &ev);
        if let Some(w) = csv.as_mut() {
            row.clear();
            row.push(s.t_s.to_string());
            for h in 0..ids.len() {
                row.push(ev.state[h].capacity.to_string());
                row.push(ev.state[h].fatigue_u_min.to_string());
                row.push(ev.loads[h].to_string());
            }
            w.write_record(&row)
                .map_err(|e| RunError::Write(e.to_string()))?;
        }
        i += 1;
    }
    if let Some(mut w) = csv {
        w.flush().map_err(|e| RunError::Write(e.to_string()))?;
    }
    if i == 0 {
        return Err(sample_err(&r, "no samples after the header".into()));
    }
    Ok(Evaluation::new(r.name(), task, &ev, i, timeline))
}

impl Evaluation {
    /// The document of `samples` samples evaluated by `ev` for `task`, read from `source`.
    pub fn new(
        source: &str,
        task: &Task,
        ev: &Evaluator,
        samples: u64,
        timeline: Timeline,
    ) -> Evaluation {
        let ids = task.half_joint_ids();
        let final_c: Vec<f64> = ev.state.iter().map(|s| s.capacity).collect();
        let final_u: Vec<f64> = ev.state.iter().map(|s| s.fatigue_u_min).collect();
        let worst = (0..ids.len())
            .max_by(|&a, &b| final_u[a].total_cmp(&final_u[b]))
            .unwrap_or(0);
        let (t0, t1) = ev.span_s();
        let group = |h: usize| {
            task.half_joints
                .get(h)
                .map(|x| x.group.clone())
                .unwrap_or_default()
        };
        Evaluation {
            source: source.to_string(),
            robot: task.robot.clone(),
            worker: task.worker,
            fatigue_parameters: task.fatigue_choice.set.clone(),
            hold_rule: HOLD_RULE,
            standing: ev.standing,
            groups: task.half_joints.iter().map(|h| h.group.clone()).collect(),
            half_joint_ids: ids,
            samples,
            duration_s: t1 - t0,
            total_u_min: final_u.iter().sum(),
            worst_group: group(worst),
            worst_u_min: final_u.get(worst).copied().unwrap_or(0.0),
            final_capacity: final_c,
            final_fatigue_u_min: final_u,
            lowest_capacity: ev.lowest.0,
            lowest_capacity_group: group(ev.lowest.1),
            lowest_capacity_t_s: ev.lowest.2,
            exhaustions: ev.events.clone(),
            samples_outside_range: ev.outside_range,
            timeline,
        }
    }
}

/// One line of live output (`evaluate --stream`).
#[derive(Debug, Clone, Serialize)]
pub struct StreamLine<'a> {
    pub t_s: f64,
    /// Per half-joint (order of `half_joint_ids` in the first line).
    pub capacity: &'a [f64],
    pub fatigue_u_min: &'a [f64],
    /// Exhaustion events new with this sample.
    pub exhausted: &'a [ExhaustionEvent],
}

/// The first line of live output: what the columns are.
#[derive(Debug, Clone, Serialize)]
pub struct StreamHead<'a> {
    pub hold_rule: &'static str,
    pub half_joint_ids: &'a [String],
    pub groups: Vec<&'a str>,
}

/// Live evaluation of CSV samples from `input`: one JSON line per sample to `output` (after a
/// first line naming the half-joints). Output is flushed whenever no further input is waiting,
/// so a capture loop sees each sample's fatigue at once.
pub fn stream<R: std::io::Read>(
    task: &Task,
    input: R,
    name: &str,
    opts: &Options,
    output: &mut dyn Write,
) -> Result<u64, RunError> {
    let mut r = Reader::open(
        Input::Csv {
            reader: std::io::BufReader::with_capacity(1 << 16, input),
            name: name.to_string(),
        },
        task,
    )?;
    let ids = task.half_joint_ids();
    let mut out = std::io::BufWriter::with_capacity(1 << 16, output);
    let werr = |e: std::io::Error| RunError::Write(e.to_string());
    let head = StreamHead {
        hold_rule: HOLD_RULE,
        half_joint_ids: &ids,
        groups: task.half_joints.iter().map(|h| h.group.as_str()).collect(),
    };
    serde_json::to_writer(&mut out, &head).map_err(|e| RunError::Write(e.to_string()))?;
    out.write_all(b"\n").map_err(werr)?;
    out.flush().map_err(werr)?;
    let mut ev = Evaluator::new(task);
    let mut s = Sample::zeros(task.model.nq());
    let mut n = 0;
    let (mut capacity, mut fatigue_u_min) =
        (Vec::with_capacity(ids.len()), Vec::with_capacity(ids.len()));
    while r.next(task, opts.degrees, &mut s)? {
        constant_loads(task, &r, opts, &mut s);
        check_sample(&mut ev, &r, &s)?;
        let new = ev.push(&s).map_err(|e| eval_err(&r, e))?;
        capacity.clear();
        capacity.extend(ev.state.iter().map(|x| x.capacity));
        fatigue_u_min.clear();
        fatigue_u_min.extend(ev.state.iter().map(|x| x.fatigue_u_min));
        let line = StreamLine {
            t_s: s.t_s,
            capacity: &capacity,
            fatigue_u_min: &fatigue_u_min,
            exhausted: &ev.events[ev.events.len() - new..],
        };
        serde_json::to_writer(&mut out, &line).map_err(|e| RunError::Write(e.to_string()))?;
        out.write_all(b"\n").map_err(werr)?;
        n += 1;
        if let Reader::Csv { reader, .. } = &r
            && reader.buffer().is_empty()
        {
            out.flush().map_err(werr)?;
        }
    }
    out.flush().map_err(werr)?;
    Ok(n)
}
