//! Obstacle clearances against distances worked out by hand.

use nalgebra::Vector3;
use posture_opt::workstation::{Obstacle, ObstacleSpec, ShapeSpec};

fn obstacle(shape: ShapeSpec, position_m: [f64; 3], rpy_rad: [f64; 3]) -> Obstacle {
    Obstacle::new(ObstacleSpec {
        name: "o".into(),
        shape,
        position_m,
        rpy_rad,
    })
    .unwrap()
}

#[test]
fn planes_boxes_cylinders_by_hand() {
    let (a, b) = (Vector3::new(0.0, 0.0, 1.0), Vector3::new(0.0, 0.0, 1.5));
    // ceiling at z = 2 (solid above): the capsule top (z = 1.5 + 0.05) is 0.45 below
    let ceiling = obstacle(
        ShapeSpec::Plane {
            normal: [0.0, 0.0, -1.0],
        },
        [0.0, 0.0, 2.0],
        [0.0; 3],
    );
    let c = ceiling.clearance(0, &a, &b, 0.05, 1.0).unwrap();
    assert!((c.distance_m - 0.45).abs() < 1e-9, "{}", c.distance_m);
    assert!((c.normal - Vector3::z()).norm() < 1e-9);
    // floor at z = 0.8 (solid below): bottom at 0.95 → 0.15
    let floor = obstacle(
        ShapeSpec::Plane {
            normal: [0.0, 0.0, 1.0],
        },
        [0.0, 0.0, 0.8],
        [0.0; 3],
    );
    assert!((floor.clearance(0, &a, &b, 0.05, 1.0).unwrap().distance_m - 0.15).abs() < 1e-9);
    // a box 0.2 wide centred 0.5 m in front: face at x = 0.4, capsule surface at x = 0.05 → 0.35
    let bx = obstacle(
        ShapeSpec::Box {
            size_m: [0.2, 1.0, 1.0],
        },
        [0.5, 0.0, 1.2],
        [0.0; 3],
    );
    assert!((bx.clearance(0, &a, &b, 0.05, 1.0).unwrap().distance_m - 0.35).abs() < 1e-9);
    // the same box turned 90° about z is 1.0 deep along x: face at x = 0.0 → penetration 0.05
    let turned = obstacle(
        ShapeSpec::Box {
            size_m: [0.2, 1.0, 1.0],
        },
        [0.5, 0.0, 1.2],
        [0.0, 0.0, std::f64::consts::FRAC_PI_2],
    );
    assert!((turned.clearance(0, &a, &b, 0.05, 1.0).unwrap().distance_m + 0.05).abs() < 1e-9);
    // a vertical cylinder r = 0.1 at x = 0.5: surface at x = 0.4 → 0.35
    let cyl = obstacle(
        ShapeSpec::Cylinder {
            radius_m: 0.1,
            height_m: 2.0,
        },
        [0.5, 0.0, 1.0],
        [0.0; 3],
    );
    assert!((cyl.clearance(0, &a, &b, 0.05, 1.0).unwrap().distance_m - 0.35).abs() < 1e-6);
    // beyond the horizon: nothing
    assert!(bx.clearance(0, &a, &b, 0.05, 0.1).is_none());
}

#[test]
fn bad_obstacles_are_named() {
    let e = Obstacle::new(ObstacleSpec {
        name: "shelf".into(),
        shape: ShapeSpec::Box {
            size_m: [0.2, -1.0, 1.0],
        },
        position_m: [0.0; 3],
        rpy_rad: [0.0; 3],
    })
    .unwrap_err();
    assert!(e.to_string().contains("shelf") && e.to_string().contains("size_m"));
    let e = Obstacle::new(ObstacleSpec {
        name: "p".into(),
        shape: ShapeSpec::Plane { normal: [0.0; 3] },
        position_m: [0.0; 3],
        rpy_rad: [0.0; 3],
    })
    .unwrap_err();
    assert!(e.to_string().contains("normal"));
}
