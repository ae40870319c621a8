//! Assessment speed: the observational scores of one posture (RULA, REBA), the NIOSH lifting
//! equation (one lift, a three-task composite), the L5/S1 model, the body angles of the
//! whole-body worker, and the per-phase and whole assessment of a planned task
//! (`tasks/shelf.yaml`).

use criterion::{Criterion, black_box, criterion_group, criterion_main};
use posture_opt::assess::angles::BodyAngles;
use posture_opt::assess::low_back::{BackParams, LumbarLoad, low_back};
use posture_opt::assess::niosh::{
    Coupling as NioshCoupling, EquationForm, KG_PER_LB, Lift, LiftGeometry, M_PER_IN, WorkDuration,
    assess_lift, composite,
};
use posture_opt::assess::phase::assess_phases;
use posture_opt::assess::reba::{
    self, Coupling, RebaActivity, RebaPosture, RebaSide, RebaThresholds,
};
use posture_opt::assess::rula::{self, RulaActivity, RulaPosture};
use posture_opt::assess::{assess, rest::rest_advice};
use posture_opt::body::{BodyModel, StaticsData};
use posture_opt::plan::{Task, plan_task};

fn rula_posture() -> RulaPosture {
    RulaPosture {
        upper_arm_flexion_deg: 50.0,
        upper_arm_abduction_deg: 25.0,
        elbow_flexion_deg: 80.0,
        hand_across_midline: false,
        hand_out_to_side: false,
        wrist_flexion_deg: 10.0,
        wrist_deviation_deg: 0.0,
        wrist_twist_fraction: 0.2,
        trunk_flexion_deg: 15.0,
        trunk_twist_deg: 12.0,
        trunk_side_bend_deg: 0.0,
        neck_flexion_deg: 5.0,
        neck_twist_deg: 0.0,
        neck_side_bend_deg: 0.0,
        legs_supported: true,
    }
}

fn reba_posture() -> RebaPosture {
    let side = RebaSide {
        upper_arm_flexion_deg: 50.0,
        upper_arm_abduction_deg: 25.0,
        shoulder_raised: false,
        arm_supported_or_leaning: false,
        elbow_flexion_deg: 80.0,
        wrist_flexion_deg: 10.0,
        wrist_deviated_or_twisted: false,
    };
    RebaPosture {
        trunk_flexion_deg: 25.0,
        trunk_side_bend_deg: 0.0,
        trunk_twist_deg: 12.0,
        neck_flexion_deg: 10.0,
        neck_side_bend_deg: 0.0,
        neck_twist_deg: 0.0,
        bilateral_weight_bearing: true,
        knee_flexion_deg: 20.0,
        sitting: false,
        right: side,
        left: RebaSide {
            upper_arm_flexion_deg: 10.0,
            ..side
        },
    }
}

/// The Applications Manual's Example 5 (dish-washing machine unloading).
fn example_5() -> Lift {
    let g = |h_in: f64, v_in: f64, a: f64| LiftGeometry {
        h_m: h_in * M_PER_IN,
        v_m: v_in * M_PER_IN,
        asymmetry_deg: a,
    };
    Lift {
        name: "dish trays".into(),
        load_kg: 20.0 * KG_PER_LB,
        max_load_kg: None,
        origin: g(20.0, 44.0, 30.0),
        destination: g(20.0, 7.0, 30.0),
        freq_per_min: 5.0,
        duration: WorkDuration::UpTo1h,
        coupling: NioshCoupling::Good,
        control_at_destination: true,
        form: EquationForm::UsCustomary,
    }
}

fn bench_scores(c: &mut Criterion) {
    let mut g = c.benchmark_group("assess");
    let rp = rula_posture();
    let ra = RulaActivity {
        load_kg: 4.0,
        held_s: 3.0,
        repeats_per_min: 6.0,
    };
    g.bench_function("rula_score", |b| {
        b.iter(|| rula::score(black_box(&rp), &ra))
    });

    let bp = reba_posture();
    let ba = RebaActivity {
        load_kg: 6.0,
        shock_or_rapid_force: false,
        coupling: Coupling::Fair,
        static_over_1_min: false,
        repeated_over_4_per_min: true,
        rapid_large_posture_change_or_unstable_base: false,
    };
    let t = RebaThresholds::default();
    g.bench_function("reba_score", |b| {
        b.iter(|| reba::score(black_box(&bp), &ba, &t))
    });

    let lift = example_5();
    g.bench_function("niosh_lift", |b| {
        b.iter(|| assess_lift(black_box(&lift)).unwrap())
    });
    let lifts = [
        example_5(),
        Lift {
            freq_per_min: 2.0,
            load_kg: 8.0,
            ..example_5()
        },
        Lift {
            freq_per_min: 1.0,
            load_kg: 12.0,
            control_at_destination: false,
            ..example_5()
        },
    ];
    g.bench_function("niosh_composite_3_tasks", |b| {
        b.iter(|| composite(black_box(&lifts)).unwrap())
    });

    let (sn, cs) = (45f64.to_radians().sin(), 45f64.to_radians().cos());
    let load = LumbarLoad {
        moment_nm: [0.0, 149.5, 0.0],
        force_n: [0.0, 0.0, -539.55],
        spine_axis: [sn, 0.0, cs],
        forward_axis: [cs, 0.0, -sn],
    };
    let params = BackParams::default();
    g.bench_function("low_back", |b| {
        b.iter(|| low_back(black_box(&load), &params).unwrap())
    });

    let model =
        BodyModel::from_urdf_file(concat!(env!("CARGO_MANIFEST_DIR"), "/robots/worker.urdf"))
            .unwrap();
    let mut data = StaticsData::new(&model, 2);
    let mut q = vec![0.0; model.nq()];
    for (name, deg) in [
        ("pelvis_tilt", 20.0_f64),
        ("lumbar_flexion", 30.0),
        ("lumbar_axial_rotation", 10.0),
        ("r_shoulder_flexion", 60.0),
        ("r_elbow_flexion", 90.0),
        ("neck_flexion", 15.0),
    ] {
        q[model.q_index(name).unwrap()] = deg.to_radians();
    }
    g.bench_function("body_angles_worker", |b| {
        b.iter(|| BodyAngles::measure(&model, &mut data, black_box(&q), Some(0.5)).unwrap())
    });
    g.finish();
}

fn bench_plan_assessment(c: &mut Criterion) {
    let task = Task::from_file(concat!(env!("CARGO_MANIFEST_DIR"), "/tasks/shelf.yaml")).unwrap();
    let plan = plan_task(&task).unwrap();
    let mut g = c.benchmark_group("assess_plan");
    g.sample_size(10);
    g.bench_function("phases_shelf", |b| b.iter(|| assess_phases(&task, &plan)));
    g.bench_function("rest_advice_shelf", |b| {
        b.iter(|| rest_advice(&task, &plan, 0.7))
    });
    g.bench_function("assess_shelf", |b| b.iter(|| assess(&task, &plan, 0.7)));
    g.finish();
}

criterion_group!(benches, bench_scores, bench_plan_assessment);
criterion_main!(benches);
