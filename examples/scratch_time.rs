use posture_opt::plan::{plan_task_with, PlanOptions, Task};
fn main() {
    let file = std::env::args().nth(1).unwrap();
    let task = Task::from_file(&file).unwrap();
    for (adapt, baselines) in [(false, false)] {
        let t0 = std::time::Instant::now();
        let p = plan_task_with(&task, PlanOptions { adapt, baselines, ..Default::default() }).unwrap();
        eprintln!("adapt {adapt} baselines {baselines}: {:.1} s, {} QPs, U {:.3}, passes {:?}", t0.elapsed().as_secs_f64(), p.summary.qp_solves, p.summary.total_u, p.summary.passes);
        for ph in &p.summary.phases { eprintln!("   {} conv {} kkt {:.1e} it {} seeds {} best {}", ph.phase, ph.converged, ph.kkt_residual, ph.iterations, ph.search.seeds, ph.search.best_seed); }
    }
}
