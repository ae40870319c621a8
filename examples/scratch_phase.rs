use posture_opt::fatigue::MaState;
use posture_opt::plan::objective::FatigueCost;
use posture_opt::plan::search::{PhaseSolver, PhaseSpec};
use posture_opt::plan::sqp::SqpSettings;
use posture_opt::plan::Task;
fn main() {
    let file = std::env::args().nth(1).unwrap();
    let task = Task::from_file(&file).unwrap();
    let mut solver = PhaseSolver::new(&task, SqpSettings { max_iterations: std::env::var("ITERS").ok().and_then(|v| v.parse().ok()).unwrap_or(60), ..SqpSettings::default() }).unwrap();
    let nh = task.half_joints.len();
    let p: usize = std::env::args().nth(2).map(|s| s.parse().unwrap()).unwrap_or(0);
    let seed: Option<usize> = std::env::args().nth(3).map(|s| s.parse().unwrap());
    let loads = vec![vec![0.0; nh]; task.phases.len()];
    let state = vec![MaState::FRESH; nh];
    let mut cost = FatigueCost::new(&task, &[p], &loads, &vec![0.0; nh], &state, 180);
    let cap = vec![1.0; nh];
    let ph = &task.phases[p];
    let spec = PhaseSpec { targets_m: ph.targets_m, hand_force_n: ph.hand_force_n, discomfort_weight: 0.1, capacity: &cap, memory: None };
    let mut q = vec![0.0; task.model.nq()];
    let t0 = std::time::Instant::now();
    let (out, st) = match seed {
        Some(i) => { let seeds = solver.seeds(&ph.targets_m); let s = seeds[i].clone(); solver.solve(&spec, &mut cost, Some(&s), false, &mut q).unwrap() }
        None => solver.solve(&spec, &mut cost, None, true, &mut q).unwrap(),
    };
    solver.pw.statics(&task, &q, &ph.hand_force_n);
    eprintln!("ground {:?}", solver.pw.ground.map(|g| (g.left_share, g.margin_m, g.cop_total_m)));
    for k in 0..task.model.nq() { let j = task.model.q_joint(k); eprint!("{} {:.2}{} ", j.name, q[k], if q[k] <= j.lower_rad + 1e-6 || q[k] >= j.upper_rad - 1e-6 {"*"} else {""}); }
    eprintln!();
    let mut f = vec![0.0; nh];
    solver.pw.half_joint_loads(&task, &q, &mut f);
    let mut idx: Vec<usize> = (0..nh).collect(); idx.sort_by(|a,b| f[*b].total_cmp(&f[*a]));
    for &h in idx.iter().take(6) { eprint!("{} {:.2}; ", task.half_joints[h].id, f[h]); }
    eprintln!();
    eprintln!("{:?}\n{:?}\n{:.3} s", out, st, t0.elapsed().as_secs_f64());
    solver.pw.clearances(&task, &solver.scene, 0.05);
    let mut cs = solver.pw.contacts.clone(); cs.sort_by(|a,b| a.distance_m.total_cmp(&b.distance_m));
    for c in cs.iter().take(5) { eprintln!("contact {:.4} link {} other {:?}", c.distance_m, task.model.links[c.link].name, c.other); }
}
