use posture_opt::fatigue::MaState;
use posture_opt::plan::objective::{FatigueCost, LoadCost, NoLoadCost};
use posture_opt::plan::search::{PhaseSolver, PhaseSpec};
use posture_opt::plan::sqp::SqpSettings;
use posture_opt::plan::Task;
use nalgebra::Vector3;
fn main() {
    let task = Task::from_file("tasks/shelf.yaml").unwrap();
    let mut solver = PhaseSolver::new(&task, SqpSettings::default()).unwrap();
    let nh = task.half_joints.len();
    let p: usize = std::env::args().nth(1).map(|s| s.parse().unwrap()).unwrap_or(5);
    let ph = &task.phases[p];
    let cap = vec![10.0; nh];
    let spec = PhaseSpec { targets_m: ph.targets_m, hand_force_n: ph.hand_force_n, discomfort_weight: 1.0, capacity: &cap };
    let mut qn = vec![0.0; task.model.nq()];
    let (o, _) = solver.solve(&spec, &mut NoLoadCost, None, false, &mut qn).unwrap();
    println!("neutral: {:?}", o.converged);
    let loads_of = |solver: &mut PhaseSolver, q: &[f64], f: &[Vector3<f64>;2]| { let mut v = vec![0.0; nh]; solver.pw.statics(&task, q, f); solver.pw.half_joint_loads(&task, q, &mut v); v };
    let fl = loads_of(&mut solver, &qn, &ph.hand_force_n);
    let rest = loads_of(&mut solver, &vec![0.0; task.model.nq()], &[Vector3::zeros(); 2]);
    let loads = vec![fl.clone(); task.phases.len()];
    let state = vec![MaState::FRESH; nh];
    let mut cost = FatigueCost::new(&task, &[p], &loads, &rest, &state, 180);
    println!("J at neutral {:.4}", cost.value(&fl));
    let spec2 = PhaseSpec { targets_m: ph.targets_m, hand_force_n: ph.hand_force_n, discomfort_weight: 0.0, capacity: &cap };
    let mut q = qn.clone();
    let (o2, _) = solver.solve(&spec2, &mut cost, Some(&qn), false, &mut q).unwrap();
    let fo = loads_of(&mut solver, &q, &ph.hand_force_n);
    println!("J after opt {:.4} (reported {:.4}) conv {} it {}", cost.value(&fo), o2.objective, o2.converged, o2.iterations);
    let mut top: Vec<(f64, usize)> = fl.iter().enumerate().map(|(h, f)| (*f, h)).collect(); top.sort_by(|a,b| b.0.total_cmp(&a.0));
    for (f, h) in top.iter().take(5) { println!("neutral {} {:.3} -> opt {:.3}", task.half_joints[*h].id, f, fo[*h]); }
    let mut top: Vec<(f64, usize)> = fo.iter().enumerate().map(|(h, f)| (*f, h)).collect(); top.sort_by(|a,b| b.0.total_cmp(&a.0));
    for (f, h) in top.iter().take(5) { println!("opt {} {:.3} (neutral {:.3})", task.half_joints[*h].id, f, fl[*h]); }
    let tn = cost.totals_now();
    println!("sum totals now {:.3}", tn.iter().sum::<f64>());
}
