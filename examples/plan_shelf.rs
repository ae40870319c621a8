//! Plans tasks/shelf.yaml (or the task given) from library code and prints the summary.
use posture_opt::plan::{Task, plan_task};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| concat!(env!("CARGO_MANIFEST_DIR"), "/tasks/shelf.yaml").to_string());
    let task = Task::from_file(&path)?;
    let t0 = std::time::Instant::now();
    let plan = plan_task(&task)?;
    let dt_s = t0.elapsed().as_secs_f64();
    println!(
        "{}: {} steps, total U {:.3} min, planned in {:.1} s",
        plan.task,
        plan.steps.t_s.len(),
        plan.summary.total_u,
        dt_s
    );
    for b in &plan.summary.baselines {
        println!(
            "  {}: U {:.3} min ({:+.1} %)",
            b.name,
            b.total_u,
            100.0 * b.change
        );
    }
    Ok(())
}
