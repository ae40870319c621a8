use posture_opt::fatigue::MaState;
use posture_opt::plan::objective::FatigueCost;
use posture_opt::plan::search::{PhaseSolver, PhaseSpec};
use posture_opt::plan::sqp::SqpSettings;
use posture_opt::plan::Task;
fn main() {
    let task = Task::from_file("tasks/shelf.yaml").unwrap();
    let mut solver = PhaseSolver::new(&task, SqpSettings::default()).unwrap();
    let nh = task.half_joints.len();
    let p: usize = std::env::args().nth(1).map(|s| s.parse().unwrap()).unwrap_or(1);
    let loads = vec![vec![0.0; nh]; task.phases.len()];
    let state = vec![MaState::FRESH; nh];
    let mut cost = FatigueCost::new(&task, &[p], &loads, &vec![0.0; nh], &state, 180);
    let cap = vec![1.0; nh];
    let ph = &task.phases[p];
    let spec = PhaseSpec { targets_m: ph.targets_m, hand_force_n: ph.hand_force_n, discomfort_weight: 0.02, capacity: &cap };
    let mut q = vec![0.0; task.model.nq()];
    let start = q.clone();
    let t0 = std::time::Instant::now();
    let (out, _) = solver.solve(&spec, &mut cost, Some(&start), false, &mut q).unwrap();
    solver.pw.statics(&task, &q, &ph.hand_force_n);
    eprintln!("ground {:?}", solver.pw.ground.map(|g| (g.left_share, g.margin_m, g.cop_total_m)));
    let small: Vec<String> = (0..task.model.nq()).filter(|&k| solver.pw.data.tau_nm[k].abs() < 0.5).map(|k| format!("{} {:.3}", task.model.q_joint(k).name, solver.pw.data.tau_nm[k])).collect();
    eprintln!("small torques: {}", small.join(", "));
    eprintln!("{:?}\n{:.3} s, {} qp, {} ipm, sizes {:?} rows {}", out, t0.elapsed().as_secs_f64(), solver.work.qp.solves, solver.work.qp.ipm_iterations, solver.work.qp.sizes, solver.work.qp.rows.n_row);
}
#[allow(dead_code)]
fn unused() {}
