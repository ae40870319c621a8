use posture_opt::plan::posture::Scene;
use posture_opt::plan::Task;
fn main() {
    let task = Task::from_file("tasks/shelf.yaml").unwrap();
    let s = Scene::new(&task);
    let name = |i: usize| task.model.links[s.capsules[i].link].name.clone();
    let mut pairs: Vec<String> = s.self_pairs.iter().map(|&(a, b)| format!("[{}, {}]", name(a), name(b))).collect();
    pairs.sort();
    println!("{} pairs: {}", pairs.len(), pairs.join(", "));
    let st = task.stance.as_ref().unwrap();
    println!("feet: {:?}", st.world_from_foot.iter().map(|p| (p.translation.vector.x, p.translation.vector.y, p.translation.vector.z)).collect::<Vec<_>>());
    println!("polygon: {:?}", st.support_polygon_m);
    println!("foot: {:?}", st.feet[0]);
}
