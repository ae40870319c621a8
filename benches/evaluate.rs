//! Live evaluation: per-sample latency (parse a CSV line, statics, 20 exact fatigue updates,
//! format the JSON line) for the default worker.

use criterion::{black_box, criterion_group, criterion_main, Criterion, Throughput};
use posture_opt::body::Worker;
use posture_opt::evaluate::{parse_sample, Columns, EvalSetup, Sample};
use posture_opt::fatigue::MaParams;

fn bench(c: &mut Criterion) {
    let setup = EvalSetup::from_robot(
        concat!(env!("CARGO_MANIFEST_DIR"), "/robots/worker.urdf").as_ref(),
        "hand_grip",
        &Worker::MALE_50,
        MaParams::new(1.0, 0.3).unwrap(),
    )
    .unwrap();
    let header = "t_s,lumbar_flexion,lumbar_lateral_bending,lumbar_axial_rotation,r_shoulder_flexion,r_shoulder_abduction,r_shoulder_rotation,r_elbow_flexion,r_forearm_pronation,r_wrist_flexion,r_wrist_deviation,load_kg";
    let cols = Columns::parse(header, &setup.model, false, "bench").unwrap();
    let mut ev = setup.evaluator();
    let mut s = Sample {
        t_s: 0.0,
        q_rad: vec![0.0; setup.model.nq()],
        force_on_hand_n: nalgebra::Vector3::zeros(),
    };
    let mut out = String::with_capacity(2048);
    let mut t = 0.0;
    let mut g = c.benchmark_group("evaluate");
    g.throughput(Throughput::Elements(1));
    g.bench_function("live_sample_parse_update_json", |b| {
        b.iter(|| {
            t += 0.01;
            let line = format!("{t},0.3,-0.1,0.2,1.1,0.3,-0.2,0.8,0.4,-0.3,0.1,4.0");
            parse_sample(
                black_box(&line),
                2,
                &cols,
                &setup.gravity_m_s2,
                "bench",
                &mut s,
            )
            .unwrap();
            let n = ev.push(&s).unwrap();
            ev.write_json_line(s.t_s, n, &mut out);
            black_box(out.len())
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
