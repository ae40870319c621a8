use posture_opt::body::{worker_urdf, StrengthTable, Worker};
use posture_opt::plan::{plan_task_with, PlanOptions, Task};
use std::time::Instant;
fn main() {
    let urdf = worker_urdf(&Worker::MALE_50, &StrengthTable::default_table()).unwrap();
    std::fs::write("robots/worker.urdf", &urdf).unwrap();
    let path = std::env::args().nth(1).unwrap_or("tasks/shelf.yaml".into());
    let task = Task::from_file(&path).unwrap_or_else(|e| panic!("{e}"));
    println!("nq {} half-joints {} stance {}", task.model.nq(), task.half_joints.len(), task.stance.is_some());
    let t0 = Instant::now();
    let mut opts = PlanOptions::default();
    opts.baselines = std::env::args().nth(2).is_some();
    let plan = plan_task_with(&task, opts).unwrap();
    println!("plan in {:.3} s", t0.elapsed().as_secs_f64());
    let s = &plan.summary;
    println!("total U {:.2} min, lowest c {:.3} ({}), exhaustion {:?}", s.total_u, s.lowest_capacity, s.lowest_capacity_half_joint, s.exhaustion.as_ref().map(|e| e.describe()));
    println!("passes {:?} replans {} qp {} sqp {}", s.passes, s.replans, s.qp_solves, s.sqp_iterations);
    for ph in &s.phases {
        println!("phase {}: err {:.4} clear {:.3} margin {:?} conv {} kkt {:.2e} it {} stop {:?} seeds {} best {} limits {:?}",
            ph.phase, ph.hand_error_m, ph.min_clearance_m, ph.balance_margin_m, ph.converged, ph.kkt_residual, ph.iterations, ph.solve.stop, ph.search.seeds, ph.search.best_seed, ph.at_limits);
        let q: Vec<String> = plan.joints.iter().zip(&ph.q_rad).filter(|(_, v)| v.abs() > 0.02).map(|(j, v)| if j.starts_with("pelvis_t") && !j.contains("tilt") { format!("{j} {:.3}m", v) } else { format!("{j} {:.0}°", v.to_degrees()) }).collect();
        println!("   {}", q.join(", "));
        println!("   most loaded {:?}", ph.most_loaded);
    }
    for b in &s.baselines { println!("baseline {}: {:.2} ({:+.1}%)", b.name, b.total_u, 100.0*b.change); }
    let q: Vec<String> = plan.joints.iter().zip(&s.rest_posture_rad).filter(|(_, v)| v.abs() > 0.02).map(|(j, v)| format!("{j} {:.2}", v)).collect();
    println!("rest: {}  clear {:.3} {:?}", q.join(", "), s.rest_clearance_m, s.rest_closest);
}
