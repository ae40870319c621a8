//! Plans tasks/shelf.yaml from library code and prints the summary.
use posture_opt::plan::plan_with_baseline;
use posture_opt::task::Task;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| concat!(env!("CARGO_MANIFEST_DIR"), "/tasks/shelf.yaml").to_string());
    let task = Task::from_file(&path)?;
    let t0 = std::time::Instant::now();
    let (plan, baseline) = plan_with_baseline(&task, true)?;
    let dt = t0.elapsed().as_secs_f64();
    println!(
        "{}: {} steps, total U {:.3} min (baseline {:.3}), planned in {:.3} s ({:.0}x real time)",
        plan.task,
        plan.steps.len(),
        plan.summary.total_u,
        baseline.summary.total_u,
        dt,
        task.duration_s() / dt
    );
    if std::env::var("PLAN_PROFILE").is_ok() {
        let mut planner = posture_opt::plan::Planner::new(&task);
        for adapt in [false, true] {
            let t0 = std::time::Instant::now();
            let p = planner.plan(adapt)?;
            println!(
                "  interior-point iterations so far: {}",
                planner.ipm_iterations()
            );
            println!(
                "adapt={adapt}: {:.3} s, {} QP solves, {} SQP iterations, {} replans",
                t0.elapsed().as_secs_f64(),
                p.summary.qp_solves,
                p.summary.sqp_iterations,
                p.summary.replans
            );
        }
    } else {
        println!("{}", serde_json::to_string_pretty(&plan.summary)?);
    }
    Ok(())
}
