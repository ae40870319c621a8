//! Evaluating recorded work: joint-angle and hand-load histories to a fatigue timeline, offline
//! or sample by sample (live), through one [`Evaluator`] so both paths agree exactly.
//!
//! **Hold rule** (zero-order hold): each sample's posture and hand load are held from its time
//! until the next sample's. On receiving sample i+1 every half-joint holds the load computed from
//! sample i for `t(i+1) − t(i)` with the exact closed forms of the fatigue model, so any sampling
//! rate, irregular too, is exact for that rule. The state reported with a sample is the state at
//! its time (before its own load acts); the last sample's load acts for no time.
//!
//! **Recording format** (CSV, header first): `t_s`, then one column per joint of the URDF (radians,
//! or degrees with `degrees = true`; joints without a column stay at 0), then the hand load:
//! `load_kg`, or `force_x_n, force_y_n, force_z_n` (force the environment applies on the hand,
//! world frame). Times must increase strictly; empty cells and non-finite numbers are refused
//! with their line and column.

use crate::body::{holding_torques, BodyModel, HalfJoint, StaticsData};
use crate::fatigue::{MaParams, MaState};
use nalgebra::Vector3;
use serde::Serialize;
use std::fmt::Write;

/// Why a recording was refused (line and column are 1-based).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RecordingError {
    #[error("{source_name}: line 1: {problem}")]
    Header {
        source_name: String,
        problem: String,
    },
    #[error("{source_name}: line {line}, column {column} ({name}): {problem}")]
    Cell {
        source_name: String,
        line: usize,
        column: usize,
        name: String,
        problem: String,
    },
    #[error("{source_name}: line {line}: {problem}")]
    Line {
        source_name: String,
        line: usize,
        problem: String,
    },
}

/// How the columns of a recording map onto the model.
#[derive(Debug, Clone)]
pub struct Columns {
    names: Vec<String>,
    /// For each column after `t_s`: what it is.
    kinds: Vec<ColumnKind>,
    degrees: bool,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum ColumnKind {
    Joint(usize),
    LoadKg,
    Force(usize),
}

impl Columns {
    /// Parses the header line against the model.
    pub fn parse(
        header: &str,
        model: &BodyModel,
        degrees: bool,
        source_name: &str,
    ) -> Result<Self, RecordingError> {
        let bad = |problem: String| RecordingError::Header {
            source_name: source_name.into(),
            problem,
        };
        let names: Vec<String> = header
            .trim()
            .split(',')
            .map(|s| s.trim().to_string())
            .collect();
        if names.first().map(String::as_str) != Some("t_s") {
            return Err(bad(format!(
                "the first column must be t_s, got '{}'",
                names.first().cloned().unwrap_or_default()
            )));
        }
        let mut kinds = Vec::with_capacity(names.len() - 1);
        for (i, n) in names.iter().enumerate().skip(1) {
            let k = match n.as_str() {
                "load_kg" => ColumnKind::LoadKg,
                "force_x_n" => ColumnKind::Force(0),
                "force_y_n" => ColumnKind::Force(1),
                "force_z_n" => ColumnKind::Force(2),
                _ => ColumnKind::Joint(model.q_index(n).map_err(|_| bad(format!("column {} '{n}' is not a moving joint of the model, nor load_kg / force_*_n", i + 1)))?),
            };
            if kinds.contains(&k) {
                return Err(bad(format!("column {} '{n}' appears twice", i + 1)));
            }
            kinds.push(k);
        }
        let forces = kinds
            .iter()
            .filter(|k| matches!(k, ColumnKind::Force(_)))
            .count();
        if forces != 0 && forces != 3 {
            return Err(bad(
                "a hand force needs all of force_x_n, force_y_n, force_z_n".into(),
            ));
        }
        if forces == 3 && kinds.contains(&ColumnKind::LoadKg) {
            return Err(bad("give load_kg or force_*_n columns, not both".into()));
        }
        Ok(Columns {
            names,
            kinds,
            degrees,
        })
    }
}

/// The error for a sample whose time does not increase.
fn time_not_increasing(
    source_name: &str,
    line: usize,
    t_s: f64,
    previous_t_s: f64,
) -> RecordingError {
    RecordingError::Cell {
        source_name: source_name.into(),
        line,
        column: 1,
        name: "t_s".into(),
        problem: format!("time {t_s} does not increase (previous sample at {previous_t_s})"),
    }
}

/// One parsed sample.
#[derive(Debug, Clone, PartialEq)]
pub struct Sample {
    pub t_s: f64,
    pub q_rad: Vec<f64>,
    pub force_on_hand_n: Vector3<f64>,
}

/// Parses one data line (`line` is its 1-based line number) into `out`.
pub fn parse_sample(
    text: &str,
    line: usize,
    cols: &Columns,
    gravity: &Vector3<f64>,
    source_name: &str,
    out: &mut Sample,
) -> Result<(), RecordingError> {
    let mut fields = text.trim_end_matches(['\r', '\n']).split(',');
    let cell = |column: usize, problem: String| RecordingError::Cell {
        source_name: source_name.into(),
        line,
        column,
        name: cols.names.get(column - 1).cloned().unwrap_or_default(),
        problem,
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
    out.q_rad.iter_mut().for_each(|q| *q = 0.0);
    out.force_on_hand_n = Vector3::zeros();
    for (i, kind) in cols.kinds.iter().enumerate() {
        let v = num(i + 2)?;
        match *kind {
            ColumnKind::Joint(k) => out.q_rad[k] = if cols.degrees { v.to_radians() } else { v },
            ColumnKind::LoadKg => {
                if v < 0.0 {
                    return Err(cell(i + 2, format!("load_kg must be >= 0, got {v}")));
                }
                out.force_on_hand_n = gravity * v;
            }
            ColumnKind::Force(a) => out.force_on_hand_n[a] = v,
        }
    }
    if fields.next().is_some() {
        return Err(RecordingError::Line {
            source_name: source_name.into(),
            line,
            problem: format!("more values than the {} header columns", cols.names.len()),
        });
    }
    Ok(())
}

/// A group that could no longer hold its load.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ExhaustionEvent {
    pub t_s: f64,
    pub half_joint: String,
    pub group: String,
    pub load: f64,
}

/// The evaluation state: model, workspace and every half-joint's fatigue state.
pub struct Evaluator<'m> {
    pub model: &'m BodyModel,
    pub hand_link: usize,
    pub half_joints: &'m [HalfJoint],
    pub params: &'m [MaParams],
    pub gravity_m_s2: Vector3<f64>,
    data: StaticsData,
    pub state: Vec<MaState>,
    /// Loads of the last sample (held until the next one).
    pub loads: Vec<f64>,
    exhausted: Vec<bool>,
    last_t_s: Option<f64>,
    pub events: Vec<ExhaustionEvent>,
}

impl<'m> Evaluator<'m> {
    pub fn new(
        model: &'m BodyModel,
        hand_link: usize,
        half_joints: &'m [HalfJoint],
        params: &'m [MaParams],
        gravity_m_s2: Vector3<f64>,
    ) -> Self {
        let n = half_joints.len();
        Evaluator {
            model,
            hand_link,
            half_joints,
            params,
            gravity_m_s2,
            data: StaticsData::new(model),
            state: vec![MaState::FRESH; n],
            loads: vec![0.0; n],
            exhausted: vec![false; n],
            last_t_s: None,
            events: Vec::new(),
        }
    }

    /// Takes the next sample: holds the previous loads until its time (exactly), records any
    /// group that could no longer hold its load, then computes this sample's loads. Returns the
    /// number of new exhaustion events. `Err` with the previous time if time does not increase.
    pub fn push(&mut self, s: &Sample) -> Result<usize, f64> {
        let before = self.events.len();
        if let Some(t0) = self.last_t_s {
            if s.t_s <= t0 || s.t_s.is_nan() {
                return Err(t0);
            }
            let dt = s.t_s - t0;
            for h in 0..self.state.len() {
                let f = self.loads[h];
                if !self.exhausted[h] {
                    if let Some(te) = self.params[h].time_to_exhaustion_s(self.state[h].capacity, f)
                    {
                        if te < dt {
                            self.exhausted[h] = true;
                            let hj = &self.half_joints[h];
                            self.events.push(ExhaustionEvent {
                                t_s: t0 + te,
                                half_joint: hj.id.clone(),
                                group: hj.group.clone(),
                                load: f,
                            });
                        }
                    }
                }
                self.params[h].hold(&mut self.state[h], f, dt);
            }
        }
        self.last_t_s = Some(s.t_s);
        holding_torques(
            self.model,
            &mut self.data,
            &s.q_rad,
            self.hand_link,
            &s.force_on_hand_n,
            &self.gravity_m_s2,
        );
        for (h, hj) in self.half_joints.iter().enumerate() {
            let q = s.q_rad[hj.q_index];
            self.loads[h] = hj.load(self.data.tau_nm[hj.q_index], q);
            if self.exhausted[h] && self.state[h].capacity >= self.loads[h] {
                self.exhausted[h] = false; // able again: a later exhaustion is a new event
            }
        }
        Ok(self.events.len() - before)
    }

    /// Writes the current state as one JSON object (no newline) into `out`: time, capacity and
    /// U per half-joint, and the exhaustion events new with this sample. Numbers are written
    /// with ryu (shortest round-trip form, as serde_json does).
    pub fn write_json_line(&self, t_s: f64, new_events: usize, out: &mut String) {
        let mut fmt = ryu::Buffer::new();
        out.clear();
        out.push_str("{\"t_s\":");
        out.push_str(fmt.format_finite(t_s));
        for (key, get) in [("capacity", 0), ("fatigue_u", 1)] {
            out.push_str(",\"");
            out.push_str(key);
            out.push_str("\":{");
            for (h, hj) in self.half_joints.iter().enumerate() {
                let v = if get == 0 {
                    self.state[h].capacity
                } else {
                    self.state[h].fatigue_u_min
                };
                if h > 0 {
                    out.push(',');
                }
                out.push('"');
                out.push_str(&hj.id);
                out.push_str("\":");
                out.push_str(fmt.format_finite(v));
            }
            out.push('}');
        }
        out.push_str(",\"exhausted\":[");
        for (i, e) in self.events[self.events.len() - new_events..]
            .iter()
            .enumerate()
        {
            let _ = write!(
                out,
                "{}{{\"t_s\":{},\"half_joint\":\"{}\",\"group\":\"{}\",\"load\":{}}}",
                if i > 0 { "," } else { "" },
                e.t_s,
                e.half_joint,
                e.group,
                e.load
            );
        }
        out.push_str("]}");
    }
}

/// What an evaluation needs: the body, the hand frame, the half-joints and their fatigue.
pub struct EvalSetup {
    pub robot: String,
    pub model: BodyModel,
    pub hand_frame: String,
    pub hand_link: usize,
    pub half_joints: Vec<HalfJoint>,
    pub params: Vec<MaParams>,
    pub gravity_m_s2: Vector3<f64>,
}

/// Why an evaluation could not be set up.
#[derive(Debug, thiserror::Error)]
pub enum SetupError {
    #[error(transparent)]
    Body(#[from] crate::body::BodyError),
    #[error(transparent)]
    Strength(#[from] crate::body::StrengthError),
    #[error(transparent)]
    Worker(#[from] crate::body::WorkerError),
    #[error(transparent)]
    Fatigue(#[from] crate::fatigue::FatigueError),
}

impl EvalSetup {
    /// Loads the URDF, its strength table (`NAME.strength.yaml` beside it, else the shipped
    /// table with URDF-effort fallback), scales strength to `worker`, one (k, R) for all groups.
    pub fn from_robot(
        urdf: &std::path::Path,
        hand_frame: &str,
        worker: &crate::body::Worker,
        params: MaParams,
    ) -> Result<Self, SetupError> {
        worker.validate()?;
        let model = BodyModel::from_urdf_file(urdf)?;
        let hand_link = model.frame_link(hand_frame)?;
        let sp = crate::body::StrengthTable::path_beside(urdf);
        let table = if sp.exists() {
            crate::body::StrengthTable::from_file(&sp)?
        } else {
            crate::body::StrengthTable::default_table()
        };
        let robot = urdf.display().to_string();
        let half_joints = crate::body::resolve_half_joints(&model, &table, worker, &robot)?;
        let params = vec![MaParams::with_recovery(params.k_per_min, params.recovery)?; half_joints.len()];
        Ok(EvalSetup {
            robot,
            model,
            hand_frame: hand_frame.into(),
            hand_link,
            half_joints,
            params,
            gravity_m_s2: crate::body::GRAVITY_M_S2,
        })
    }

    pub fn evaluator(&self) -> Evaluator<'_> {
        Evaluator::new(
            &self.model,
            self.hand_link,
            &self.half_joints,
            &self.params,
            self.gravity_m_s2,
        )
    }
}

/// Offline result: the state at every sample, the exhaustion events and a summary.
#[derive(Debug, Clone, Serialize)]
pub struct EvaluationReport {
    pub robot: String,
    pub hand_frame: String,
    pub hold_rule: &'static str,
    pub half_joints: Vec<String>,
    pub t_s: Vec<f64>,
    /// `capacity[i][h]`, `fatigue_u[i][h]`, `load[i][h]`: sample i, half-joint h (order of `half_joints`).
    pub capacity: Vec<Vec<f64>>,
    pub fatigue_u: Vec<Vec<f64>>,
    pub load: Vec<Vec<f64>>,
    pub exhaustions: Vec<ExhaustionEvent>,
    pub summary: EvaluationSummary,
}

#[derive(Debug, Clone, Serialize)]
pub struct EvaluationSummary {
    pub samples: usize,
    pub duration_s: f64,
    pub total_u: f64,
    pub worst_half_joint: String,
    pub worst_u: f64,
    pub min_capacity: f64,
    pub min_capacity_half_joint: String,
}

/// The hold rule, as stated in outputs.
pub const HOLD_RULE: &str =
    "zero-order hold: each sample's posture and load hold until the next sample";

/// Evaluates a whole recording (CSV text; `source_name` names it in errors).
pub fn evaluate_recording(
    setup: &EvalSetup,
    text: &str,
    degrees: bool,
    source_name: &str,
) -> Result<EvaluationReport, RecordingError> {
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty());
    let (_, header) = lines.next().ok_or_else(|| RecordingError::Header {
        source_name: source_name.into(),
        problem: "the recording is empty".into(),
    })?;
    let cols = Columns::parse(header, &setup.model, degrees, source_name)?;
    let mut ev = setup.evaluator();
    let mut sample = Sample {
        t_s: 0.0,
        q_rad: vec![0.0; setup.model.nq()],
        force_on_hand_n: Vector3::zeros(),
    };
    let nh = setup.half_joints.len();
    let (mut t, mut cap, mut u, mut ld) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for (i, line) in lines {
        parse_sample(
            line,
            i + 1,
            &cols,
            &setup.gravity_m_s2,
            source_name,
            &mut sample,
        )?;
        ev.push(&sample)
            .map_err(|t0| time_not_increasing(source_name, i + 1, sample.t_s, t0))?;
        t.push(sample.t_s);
        cap.push(ev.state.iter().map(|s| s.capacity).collect::<Vec<_>>());
        u.push(ev.state.iter().map(|s| s.fatigue_u_min).collect::<Vec<_>>());
        ld.push(ev.loads.clone());
    }
    if t.is_empty() {
        return Err(RecordingError::Line {
            source_name: source_name.into(),
            line: 2,
            problem: "no samples after the header".into(),
        });
    }
    let last_c = cap.last().cloned().unwrap_or_default();
    let last_u = u.last().cloned().unwrap_or_default();
    let worst = (0..nh)
        .max_by(|&a, &b| last_u[a].total_cmp(&last_u[b]))
        .unwrap_or(0);
    let minc = (0..nh)
        .min_by(|&a, &b| last_c[a].total_cmp(&last_c[b]))
        .unwrap_or(0);
    Ok(EvaluationReport {
        robot: setup.robot.clone(),
        hand_frame: setup.hand_frame.clone(),
        hold_rule: HOLD_RULE,
        half_joints: setup.half_joints.iter().map(|h| h.id.clone()).collect(),
        summary: EvaluationSummary {
            samples: t.len(),
            duration_s: t[t.len() - 1] - t[0],
            total_u: last_u.iter().sum(),
            worst_half_joint: setup.half_joints[worst].id.clone(),
            worst_u: last_u[worst],
            min_capacity: last_c[minc],
            min_capacity_half_joint: setup.half_joints[minc].id.clone(),
        },
        t_s: t,
        capacity: cap,
        fatigue_u: u,
        load: ld,
        exhaustions: ev.events,
    })
}

impl EvaluationReport {
    /// The timeline as CSV: t_s, then capacity, U and load per half-joint.
    pub fn to_csv(&self) -> String {
        let mut o = String::from("t_s");
        for h in &self.half_joints {
            let _ = write!(o, ",capacity_{h},u_{h}_min,load_{h}");
        }
        o.push('\n');
        for i in 0..self.t_s.len() {
            let _ = write!(o, "{}", self.t_s[i]);
            for h in 0..self.half_joints.len() {
                let _ = write!(
                    o,
                    ",{},{},{}",
                    self.capacity[i][h], self.fatigue_u[i][h], self.load[i][h]
                );
            }
            o.push('\n');
        }
        o
    }

    /// A readable summary.
    pub fn summary_text(&self) -> String {
        let s = &self.summary;
        let mut o = String::new();
        let _ = writeln!(
            o,
            "{} samples over {:.1} s ({}), robot {}, hand frame {}",
            s.samples, s.duration_s, self.hold_rule, self.robot, self.hand_frame
        );
        let last = self.capacity.len() - 1;
        let mut idx: Vec<usize> = (0..self.half_joints.len()).collect();
        idx.sort_by(|&a, &b| self.capacity[last][a].total_cmp(&self.capacity[last][b]));
        let _ = writeln!(
            o,
            "{:<28} {:>9} {:>10}",
            "half-joint", "capacity", "U [min]"
        );
        for &h in idx.iter().take(8) {
            let _ = writeln!(
                o,
                "{:<28} {:>9.3} {:>10.3}",
                self.half_joints[h], self.capacity[last][h], self.fatigue_u[last][h]
            );
        }
        if self.exhaustions.is_empty() {
            let _ = writeln!(o, "no muscle group exhausted");
        }
        for e in &self.exhaustions {
            let _ = writeln!(
                o,
                "EXHAUSTION at {:.1} s: {} ({}) can no longer hold {:.0}% MVC",
                e.t_s,
                e.half_joint,
                e.group,
                100.0 * e.load
            );
        }
        let _ = writeln!(
            o,
            "total U = {:.3} min (worst {} {:.3} min)",
            s.total_u, s.worst_half_joint, s.worst_u
        );
        o
    }
}

/// Why live evaluation stopped.
#[derive(Debug, thiserror::Error)]
pub enum StreamError {
    #[error(transparent)]
    Recording(#[from] RecordingError),
    #[error("cannot read or write the stream: {0}")]
    Io(#[from] std::io::Error),
}

/// Live evaluation: reads the header and then one sample per line from `input`, writes one JSON
/// line per sample to `output`. Output is flushed whenever no further input is already waiting,
/// so every line is out before the evaluator waits for the next sample (a capture loop sees each
/// sample's fatigue at once), and a fast producer is not slowed by a write per line.
pub fn stream(
    setup: &EvalSetup,
    degrees: bool,
    input: impl std::io::Read,
    output: impl std::io::Write,
) -> Result<(), StreamError> {
    use std::io::BufRead;
    let mut reader = std::io::BufReader::with_capacity(1 << 16, input);
    let mut out = std::io::BufWriter::with_capacity(1 << 16, output);
    let mut cols: Option<Columns> = None;
    let mut ev = setup.evaluator();
    let mut sample = Sample {
        t_s: 0.0,
        q_rad: vec![0.0; setup.model.nq()],
        force_on_hand_n: Vector3::zeros(),
    };
    let mut line_buf = String::with_capacity(2048);
    let mut line = String::with_capacity(256);
    let mut line_no = 0;
    loop {
        line.clear();
        if reader.read_line(&mut line)? == 0 {
            break;
        }
        line_no += 1;
        if !line.trim().is_empty() {
            match &cols {
                None => cols = Some(Columns::parse(&line, &setup.model, degrees, "stdin")?),
                Some(c) => {
                    parse_sample(&line, line_no, c, &setup.gravity_m_s2, "stdin", &mut sample)?;
                    let new = ev
                        .push(&sample)
                        .map_err(|t0| time_not_increasing("stdin", line_no, sample.t_s, t0))?;
                    ev.write_json_line(sample.t_s, new, &mut line_buf);
                    line_buf.push('\n');
                    std::io::Write::write_all(&mut out, line_buf.as_bytes())?;
                }
            }
        }
        if reader.buffer().is_empty() {
            std::io::Write::flush(&mut out)?;
        }
    }
    std::io::Write::flush(&mut out)?;
    Ok(())
}
