//! The timeline as CSV and the plan as a recording for `evaluate`, written with the csv crate.

use crate::plan::Plan;

fn writer() -> ::csv::Writer<Vec<u8>> {
    ::csv::WriterBuilder::new().from_writer(Vec::new())
}

fn finish(w: ::csv::Writer<Vec<u8>>) -> Vec<u8> {
    w.into_inner().unwrap_or_default()
}

/// One row per held step: time, phase, posture, torques, and per half-joint load, capacity and U,
/// written into `out` row by row (a long plan's timeline is hundreds of megabytes).
pub fn write_plan_csv(p: &Plan, out: &mut dyn std::io::Write) -> std::io::Result<()> {
    let mut w = ::csv::WriterBuilder::new().from_writer(out);
    let mut head: Vec<String> = ["t_s", "duration_s", "cycle", "phase"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    head.extend(p.joints.iter().map(|j| format!("q_{j}_rad")));
    head.extend(p.joints.iter().map(|j| format!("torque_{j}_nm")));
    for h in &p.half_joint_ids {
        head.push(format!("load_{h}"));
        head.push(format!("capacity_{h}"));
        head.push(format!("u_{h}_min"));
    }
    w.write_record(&head)?;
    let st = &p.steps;
    let mut row: Vec<String> = Vec::with_capacity(head.len());
    let mut states = st.replay();
    for i in 0..st.len() {
        let pr = &p.postures[st.posture[i]];
        let state = states.next().unwrap_or_default();
        row.clear();
        row.extend([
            st.t_s[i].to_string(),
            st.duration_s[i].to_string(),
            st.cycle[i].to_string(),
            st.phase(i).to_string(),
        ]);
        row.extend(pr.q_rad.iter().map(|v| v.to_string()));
        row.extend(pr.torque_nm.iter().map(|v| v.to_string()));
        for h in 0..p.half_joint_ids.len() {
            row.push(pr.load[h].to_string());
            let (c, u) = state
                .get(h)
                .map_or((f64::NAN, f64::NAN), |s| (s.capacity, s.fatigue_u_min));
            row.push(c.to_string());
            row.push(u.to_string());
        }
        w.write_record(&row)?;
    }
    w.flush()
}

/// The plan as a recording for `posture-opt evaluate`: one sample at the start of every step
/// (its posture and both hands' forces) and a closing sample at the end of the last step, so that
/// under the zero-order hold each step's load acts for exactly its duration.
pub fn plan_recording_csv(p: &Plan) -> Vec<u8> {
    let mut w = writer();
    let mut head = vec!["t_s".to_string()];
    head.extend(p.joints.iter().cloned());
    head.extend(
        [
            "force_x_n",
            "force_y_n",
            "force_z_n",
            "left_force_x_n",
            "left_force_y_n",
            "left_force_z_n",
        ]
        .iter()
        .map(|s| s.to_string()),
    );
    let _ = w.write_record(&head);
    let st = &p.steps;
    let row = |w: &mut ::csv::Writer<Vec<u8>>, t: f64, i: usize| {
        let pr = &p.postures[st.posture[i]];
        let mut r = vec![t.to_string()];
        r.extend(pr.q_rad.iter().map(|v| v.to_string()));
        for h in 0..2 {
            r.extend(pr.hand_force_n[h].iter().map(|v| v.to_string()));
        }
        let _ = w.write_record(&r);
    };
    for i in 0..st.t_s.len() {
        row(&mut w, st.t_s[i], i);
    }
    if let Some(last) = st.t_s.len().checked_sub(1) {
        row(&mut w, st.t_s[last] + st.duration_s[last], last);
    }
    finish(w)
}
