//! Obstacle clearances against closed-form distances, and refusal of absurd obstacles.
//!
//! Body shapes: capsules (segment + radius), spheres (capsules of zero length) and boxes (the
//! feet); obstacle shapes: boxes, cylinders and planes (half-spaces), each also turned by its
//! roll-pitch-yaw. Every expected distance is worked out in the comment beside it: face, edge or
//! corner distances for boxes, radial, cap or rim distances for cylinders, the signed height above
//! a plane for its nearest point. Negative distances are penetration depths.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use posture_opt::workstation::{
    Clearance, MAX_SIZE_M, Obstacle, ObstacleSpec, ShapeSpec, Workstation,
};
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, SQRT_2};

fn obstacle(shape: ShapeSpec, position_m: [f64; 3], rpy_rad: [f64; 3]) -> Obstacle {
    Obstacle::new(ObstacleSpec {
        name: "o".into(),
        shape,
        position_m,
        rpy_rad,
    })
    .unwrap()
}

fn cuboid(size: [f64; 3], at: [f64; 3], rpy: [f64; 3]) -> Obstacle {
    obstacle(ShapeSpec::Box { size_m: size }, at, rpy)
}

fn cylinder(radius: f64, height: f64, at: [f64; 3], rpy: [f64; 3]) -> Obstacle {
    obstacle(
        ShapeSpec::Cylinder {
            radius_m: radius,
            height_m: height,
        },
        at,
        rpy,
    )
}

fn plane(normal: [f64; 3], at: [f64; 3], rpy: [f64; 3]) -> Obstacle {
    obstacle(ShapeSpec::Plane { normal }, at, rpy)
}

fn v(x: f64, y: f64, z: f64) -> Vector3<f64> {
    Vector3::new(x, y, z)
}

/// Clearance of the capsule a–b, radius r (within 10 m).
fn capsule(o: &Obstacle, a: Vector3<f64>, b: Vector3<f64>, r: f64) -> Clearance {
    o.clearance(3, &a, &b, r, 10.0).expect("within 10 m")
}

fn sphere(o: &Obstacle, c: Vector3<f64>, r: f64) -> Clearance {
    capsule(o, c, c, r)
}

fn body_box(o: &Obstacle, at: Vector3<f64>, rpy: [f64; 3], half: Vector3<f64>) -> Clearance {
    let pose = Isometry3::from_parts(
        Translation3::from(at),
        UnitQuaternion::from_euler_angles(rpy[0], rpy[1], rpy[2]),
    );
    o.box_clearance(3, &pose, &half, 10.0).expect("within 10 m")
}

/// Distance (and, when given, the normal toward the obstacle) against the closed form.
/// `tol` bounds the distance error; normals are checked to 1e-9 where the distance is exact to
/// 1e-9 or better (closed forms in the library) and to 1e-4 where it comes from parry's iterative
/// queries (GJK/EPA on cylinders, which converge to about 1e-6 m).
fn check(c: &Clearance, distance: f64, normal: Option<Vector3<f64>>, tol: f64, what: &str) {
    let ntol = if tol < 1e-9 { 1e-9 } else { 1e-4 };
    assert!(
        (c.distance_m - distance).abs() < tol,
        "{what}: distance {} vs closed form {distance}",
        c.distance_m
    );
    assert_eq!(
        c.obstacle, 3,
        "{what}: the obstacle's index is passed through"
    );
    if let Some(n) = normal {
        assert!(
            (c.normal - n.normalize()).norm() < ntol,
            "{what}: normal {} vs {}",
            c.normal,
            n.normalize()
        );
    }
}

#[test]
fn capsules_and_spheres_against_boxes() {
    let (a, b) = (v(0.0, 0.0, 1.0), v(0.0, 0.0, 1.5));
    // box 0.2 deep, centred 0.5 m ahead: face at x = 0.4, capsule surface at x = 0.05
    let bx = cuboid([0.2, 1.0, 1.0], [0.5, 0.0, 1.2], [0.0; 3]);
    let c = capsule(&bx, a, b, 0.05);
    check(&c, 0.35, Some(v(1.0, 0.0, 0.0)), 1e-9, "capsule–box face");
    assert!(
        (c.point_m.x - 0.05).abs() < 1e-9,
        "witness on the capsule surface: {}",
        c.point_m
    );
    // turned 90° about z it is 1.0 deep along x: face at x = 0.0, penetration 0.05
    let turned = cuboid([0.2, 1.0, 1.0], [0.5, 0.0, 1.2], [0.0, 0.0, FRAC_PI_2]);
    check(
        &capsule(&turned, a, b, 0.05),
        -0.05,
        None,
        1e-9,
        "capsule–turned box",
    );
    // a 0.2 × 0.2 column turned 45° about z: its edge points at the capsule from
    // x = 0.5 − 0.1·√2
    let column = cuboid([0.2, 0.2, 3.0], [0.5, 0.0, 1.2], [0.0, 0.0, FRAC_PI_4]);
    check(
        &capsule(&column, a, b, 0.05),
        0.5 - 0.1 * SQRT_2 - 0.05,
        Some(v(1.0, 0.0, 0.0)),
        1e-9,
        "capsule–box edge",
    );
    // a horizontal capsule along y past the box's top edge (x = 0.6, z = 1.7) at (0.7, ·, 1.8):
    // √(0.1² + 0.1²) − r
    let c = capsule(&bx, v(0.7, -0.2, 1.8), v(0.7, 0.2, 1.8), 0.03);
    check(
        &c,
        0.02f64.sqrt() - 0.03,
        Some(v(-1.0, 0.0, -1.0)),
        1e-6,
        "capsule–box edge from above",
    );
    // a capsule whose end points at the box face: end (0.0, 0, 1.2) along −x… from x = −0.3
    let c = capsule(&bx, v(-0.3, 0.0, 1.2), v(0.1, 0.0, 1.2), 0.02);
    check(
        &c,
        0.4 - 0.1 - 0.02,
        Some(v(1.0, 0.0, 0.0)),
        1e-9,
        "capsule end cap–box",
    );
    // sphere off the corner (0.6, 0.5, 1.7) by (0.1, 0.1, 0.1): √0.03 − r
    let c = sphere(&bx, v(0.7, 0.6, 1.8), 0.04);
    check(
        &c,
        0.03f64.sqrt() - 0.04,
        Some(v(-1.0, -1.0, -1.0)),
        1e-9,
        "sphere–box corner",
    );
    // sphere inside the box: centre 0.05 behind the face x = 0.4, radius 0.02 → −0.07
    check(
        &sphere(&bx, v(0.45, 0.0, 1.2), 0.02),
        -0.07,
        None,
        1e-9,
        "sphere inside box",
    );
    // beyond the horizon: nothing
    assert!(bx.clearance(0, &a, &b, 0.05, 0.1).is_none());
}

#[test]
fn capsules_and_spheres_against_cylinders() {
    // vertical cylinder r = 0.1 at x = 0.5: surface at x = 0.4, capsule surface at 0.05
    let cyl = cylinder(0.1, 2.0, [0.5, 0.0, 1.0], [0.0; 3]);
    let c = capsule(&cyl, v(0.0, 0.0, 1.0), v(0.0, 0.0, 1.5), 0.05);
    check(
        &c,
        0.35,
        Some(v(1.0, 0.0, 0.0)),
        1e-6,
        "capsule–cylinder side",
    );
    // obliquely: capsule at (0.5 − 0.3/√2·…): a vertical capsule at (0.2, 0.3, ·) is
    // √(0.3² + 0.3²) from the axis
    let c = capsule(&cyl, v(0.2, 0.3, 0.8), v(0.2, 0.3, 1.2), 0.05);
    check(
        &c,
        0.18f64.sqrt() - 0.1 - 0.05,
        Some(v(0.3, -0.3, 0.0)),
        1e-6,
        "capsule–cylinder oblique",
    );
    // above the top cap (z = 2.0): a horizontal capsule at z = 2.3 over the axis
    let c = capsule(&cyl, v(0.45, -0.1, 2.3), v(0.55, 0.1, 2.3), 0.05);
    check(
        &c,
        0.25,
        Some(v(0.0, 0.0, -1.0)),
        1e-6,
        "capsule–cylinder cap",
    );
    // past the rim: the rim point (0.6, 0, 2.0), capsule along y at (0.8, ·, 2.2): √0.08 − r
    let c = capsule(&cyl, v(0.8, -0.2, 2.2), v(0.8, 0.2, 2.2), 0.05);
    check(
        &c,
        0.08f64.sqrt() - 0.05,
        Some(v(-1.0, 0.0, -1.0)),
        1e-6,
        "capsule–cylinder rim",
    );
    // a cylinder lying along y (rolled 90° about x), axis at x = 0, z = 1, radius 0.1; a vertical
    // capsule at x = 0.5: 0.5 − 0.1 − 0.05
    let lying = cylinder(0.1, 2.0, [0.0, 0.0, 1.0], [FRAC_PI_2, 0.0, 0.0]);
    let c = capsule(&lying, v(0.5, 0.3, 0.5), v(0.5, 0.3, 1.5), 0.05);
    check(
        &c,
        0.35,
        Some(v(-1.0, 0.0, 0.0)),
        1e-6,
        "capsule–lying cylinder",
    );
    // and its end cap at y = 1: a sphere on the axis at y = 1.3, radius 0.1 → 0.2
    check(
        &sphere(&lying, v(0.0, 1.3, 1.0), 0.1),
        0.2,
        Some(v(0.0, -1.0, 0.0)),
        1e-6,
        "sphere–cylinder end cap",
    );
    // sphere beside the vertical one: 0.3 from the axis → 0.3 − 0.1 − 0.05
    check(
        &sphere(&cyl, v(0.5, 0.3, 1.0), 0.05),
        0.15,
        Some(v(0.0, -1.0, 0.0)),
        1e-6,
        "sphere–cylinder side",
    );
    // sphere inside: on the axis, 0.1 below the top cap, radius 0.05 → −0.15
    check(
        &sphere(&cyl, v(0.5, 0.0, 1.9), 0.05),
        -0.15,
        None,
        1e-6,
        "sphere inside cylinder",
    );
}

#[test]
fn capsules_and_spheres_against_planes() {
    // ceiling at z = 2 (solid above): the capsule top (1.5 + 0.05) is 0.45 below
    let ceiling = plane([0.0, 0.0, -1.0], [0.0, 0.0, 2.0], [0.0; 3]);
    let c = capsule(&ceiling, v(0.0, 0.0, 1.0), v(0.0, 0.0, 1.5), 0.05);
    check(&c, 0.45, Some(v(0.0, 0.0, 1.0)), 1e-12, "capsule–ceiling");
    assert!(
        (c.point_m - v(0.0, 0.0, 1.55)).norm() < 1e-12,
        "witness {}",
        c.point_m
    );
    // floor at z = 0.8 (solid below): bottom at 0.95 → 0.15
    let floor = plane([0.0, 0.0, 1.0], [0.0, 0.0, 0.8], [0.0; 3]);
    check(
        &capsule(&floor, v(0.0, 0.0, 1.0), v(0.0, 0.0, 1.5), 0.05),
        0.15,
        Some(v(0.0, 0.0, -1.0)),
        1e-12,
        "capsule–floor",
    );
    // a wall through (1, 0, 0), normal (−1, −1, 0)/√2 (solid toward +x+y): the nearer end
    // (0.2, 0.3, ·) is (1 − 0.2 − 0.3)/√2 from it
    let wall = plane([-1.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0; 3]);
    let c = capsule(&wall, v(0.2, 0.3, 1.0), v(-0.4, 0.1, 0.2), 0.02);
    check(
        &c,
        0.5 / SQRT_2 - 0.02,
        Some(v(1.0, 1.0, 0.0)),
        1e-12,
        "capsule–tilted wall",
    );
    // the normal turned by the rpy: (0, 0, 1) rolled +90° about x is (0, −1, 0): a wall at
    // y = 0.4 with free space toward −y; sphere at y = 0.1 → 0.3 − r
    let rolled = plane([0.0, 0.0, 1.0], [3.0, 0.4, 7.0], [FRAC_PI_2, 0.0, 0.0]);
    check(
        &sphere(&rolled, v(0.0, 0.1, 1.0), 0.1),
        0.2,
        Some(v(0.0, 1.0, 0.0)),
        1e-12,
        "sphere–rolled plane",
    );
    // sphere below the floor: −(0.8 − 0.7) − 0.05
    check(
        &sphere(&floor, v(0.3, 0.3, 0.7), 0.05),
        -0.15,
        None,
        1e-12,
        "sphere under the floor",
    );
    assert!(!floor.is_floor(), "a plane at 0.8 m is not the floor");
    assert!(plane([0.0, 0.0, 1.0], [0.0, 0.0, 0.0], [0.0; 3]).is_floor());
}

#[test]
fn boxes_against_boxes_cylinders_and_planes() {
    let half = v(0.1, 0.1, 0.1);
    // face to face: obstacle face at x = 0.4, body box face at x = 0.1
    let bx = cuboid([0.2, 0.2, 0.2], [0.5, 0.0, 0.0], [0.0; 3]);
    check(
        &body_box(&bx, v(0.0, 0.0, 0.0), [0.0; 3], half),
        0.3,
        Some(v(1.0, 0.0, 0.0)),
        1e-9,
        "box–box face",
    );
    // the body box turned 45° about z points an edge at x = 0.1·√2
    check(
        &body_box(&bx, v(0.0, 0.0, 0.0), [0.0, 0.0, FRAC_PI_4], half),
        0.4 - 0.1 * SQRT_2,
        Some(v(1.0, 0.0, 0.0)),
        1e-9,
        "box edge–box face",
    );
    // corner to corner: body box corner (0.1, 0.1, 0.1), obstacle corner (0.4, 0.4, 0.4)
    let diag = cuboid([0.2, 0.2, 0.2], [0.5, 0.5, 0.5], [0.0; 3]);
    check(
        &body_box(&diag, v(0.0, 0.0, 0.0), [0.0; 3], half),
        0.27f64.sqrt(),
        Some(v(1.0, 1.0, 1.0)),
        1e-9,
        "box corner–box corner",
    );
    // overlapping by 0.05 along x: body box 0.25..0.45, obstacle 0.4..0.6
    check(
        &body_box(&bx, v(0.35, 0.0, 0.0), [0.0; 3], half),
        -0.05,
        None,
        1e-9,
        "box–box overlap",
    );
    // a foot-like box (0.26 × 0.1 × 0.07) 0.3 m below a cylinder's bottom cap
    let cyl = cylinder(0.2, 1.0, [0.0, 0.0, 1.0], [0.0; 3]);
    check(
        &body_box(
            &cyl,
            v(0.0, 0.0, 0.2 - 0.035),
            [0.0; 3],
            v(0.13, 0.05, 0.035),
        ),
        0.3,
        Some(v(0.0, 0.0, 1.0)),
        1e-6,
        "box–cylinder cap",
    );
    // beside the cylinder: box face at x = −0.5 + 0.1, cylinder surface at x = −0.2
    check(
        &body_box(&cyl, v(-0.5, 0.0, 1.0), [0.0; 3], half),
        0.2,
        Some(v(1.0, 0.0, 0.0)),
        1e-6,
        "box–cylinder side",
    );
    // on planes the lowest corner counts: a box at height 0.5 turned 45° about x reaches down
    // 0.1·√2 below its centre; the floor plane at z = 0.2
    let floor = plane([0.0, 0.0, 1.0], [0.3, -0.2, 0.2], [0.0; 3]);
    check(
        &body_box(&floor, v(1.0, 2.0, 0.5), [FRAC_PI_4, 0.0, 0.0], half),
        0.3 - 0.1 * SQRT_2,
        Some(v(0.0, 0.0, -1.0)),
        1e-9,
        "box–floor plane",
    );
    // a tilted wall through (1, 0, 0), normal (−1, 0, 0) (solid toward +x): face at x = 0.1 → 0.9
    let wall = plane([-1.0, 0.0, 0.0], [1.0, 0.5, 0.3], [0.0; 3]);
    check(
        &body_box(&wall, v(0.0, 0.0, 0.0), [0.0; 3], half),
        0.9,
        Some(v(1.0, 0.0, 0.0)),
        1e-9,
        "box–wall plane",
    );
    // through the floor: centre at z = 0.25, half height 0.1, floor at 0.2 → −0.05
    check(
        &body_box(&floor, v(0.0, 0.0, 0.25), [0.0; 3], half),
        -0.05,
        None,
        1e-9,
        "box through the floor",
    );
}

#[test]
fn containment_and_the_workstation_sweep() {
    let bx = cuboid([0.2, 1.0, 1.0], [0.5, 0.0, 1.2], [0.0; 3]);
    assert!(bx.contains(&v(0.5, 0.4, 1.6)) && !bx.contains(&v(0.7, 0.0, 1.2)));
    let cyl = cylinder(0.1, 2.0, [0.5, 0.0, 1.0], [0.0; 3]);
    assert!(cyl.contains(&v(0.55, 0.05, 0.1)) && !cyl.contains(&v(0.5, 0.0, 2.1)));
    let floor = plane([0.0, 0.0, 1.0], [0.0, 0.0, 0.0], [0.0; 3]);
    assert!(floor.contains(&v(5.0, -3.0, -0.01)) && !floor.contains(&v(0.0, 0.0, 0.01)));
    // all obstacles within 0.4 m of a capsule, with their indices
    let ws = Workstation::new(vec![
        ObstacleSpec {
            name: "shelf".into(),
            shape: ShapeSpec::Box {
                size_m: [0.2, 1.0, 1.0],
            },
            position_m: [0.5, 0.0, 1.2],
            rpy_rad: [0.0; 3],
        },
        ObstacleSpec {
            name: "far".into(),
            shape: ShapeSpec::Box {
                size_m: [0.2, 0.2, 0.2],
            },
            position_m: [5.0, 0.0, 1.2],
            rpy_rad: [0.0; 3],
        },
        ObstacleSpec {
            name: "floor".into(),
            shape: ShapeSpec::Plane {
                normal: [0.0, 0.0, 1.0],
            },
            position_m: [0.0; 3],
            rpy_rad: [0.0; 3],
        },
    ])
    .unwrap();
    let mut out = Vec::new();
    ws.clearances(&v(0.0, 0.0, 0.3), &v(0.0, 0.0, 1.5), 0.05, 0.4, &mut out);
    let got: Vec<(usize, f64)> = out.iter().map(|c| (c.obstacle, c.distance_m)).collect();
    assert_eq!(got.len(), 2, "{got:?}");
    assert!(got[0].0 == 0 && (got[0].1 - 0.35).abs() < 1e-9, "{got:?}");
    assert!(got[1].0 == 2 && (got[1].1 - 0.25).abs() < 1e-12, "{got:?}");
}

/// Absurd obstacles are refused by name and field, without panicking; sizes up to the limit
/// are accepted.
#[test]
fn absurd_obstacles_are_refused_by_name() {
    let spec = |shape: ShapeSpec, position_m: [f64; 3], rpy_rad: [f64; 3]| ObstacleSpec {
        name: "shelf_7".into(),
        shape,
        position_m,
        rpy_rad,
    };
    let b = |s: [f64; 3]| ShapeSpec::Box { size_m: s };
    let c = |r: f64, h: f64| ShapeSpec::Cylinder {
        radius_m: r,
        height_m: h,
    };
    let p = |n: [f64; 3]| ShapeSpec::Plane { normal: n };
    let o = [0.0; 3];
    let bad: Vec<(ObstacleSpec, &str)> = vec![
        (spec(b([0.2, 1001.0, 1.0]), o, o), "size_m"),
        (spec(b([0.2, 1e300, 1.0]), o, o), "size_m"),
        (spec(b([f64::NAN, 1.0, 1.0]), o, o), "size_m"),
        (spec(b([f64::INFINITY, 1.0, 1.0]), o, o), "size_m"),
        (spec(b([0.2, -1.0, 1.0]), o, o), "size_m"),
        (spec(b([0.0, 1.0, 1.0]), o, o), "size_m"),
        (spec(c(2000.0, 1.0), o, o), "radius_m"),
        (spec(c(0.1, 1e6), o, o), "height_m"),
        (spec(c(f64::NAN, 1.0), o, o), "radius_m"),
        (spec(c(0.1, f64::NEG_INFINITY), o, o), "height_m"),
        (spec(c(-0.1, 1.0), o, o), "radius_m"),
        (spec(p([0.0; 3]), o, o), "normal"),
        (spec(p([f64::NAN, 0.0, 1.0]), o, o), "normal"),
        (spec(p([0.0, f64::INFINITY, 1.0]), o, o), "normal"),
        (spec(b([1.0; 3]), [1e4, 0.0, 0.0], o), "position_m"),
        (spec(b([1.0; 3]), [0.0, f64::NAN, 0.0], o), "position_m"),
        (
            spec(b([1.0; 3]), [0.0, 0.0, f64::INFINITY], o),
            "position_m",
        ),
        (spec(c(0.1, 1.0), o, [0.0, f64::NAN, 0.0]), "rpy_rad"),
        (
            spec(p([0.0, 0.0, 1.0]), o, [f64::INFINITY, 0.0, 0.0]),
            "rpy_rad",
        ),
        (
            spec(p([0.0, 0.0, 1.0]), [0.0, 0.0, -2000.0], o),
            "position_m",
        ),
    ];
    for (s, field) in bad {
        let shown = format!("{:?}", s.shape);
        let e = std::panic::catch_unwind(|| Obstacle::new(s.clone()))
            .unwrap_or_else(|_| panic!("{shown}: panicked instead of refusing"))
            .expect_err(&format!("{shown} must be refused"));
        let msg = e.to_string();
        assert!(msg.contains("shelf_7"), "{msg}: names the obstacle");
        assert!(msg.contains(field), "{msg}: names {field}");
        assert_eq!(e.name, "shelf_7");
        // through the workstation too
        let err = Workstation::new(vec![s]).unwrap_err();
        assert!(err.to_string().contains("shelf_7"));
    }
    // at the limit: accepted, and distances stay sane
    let big = cuboid([MAX_SIZE_M, MAX_SIZE_M, 1.0], [0.0, 0.0, -0.5], [0.0; 3]);
    check(
        &sphere(&big, v(10.0, -20.0, 0.3), 0.1),
        0.2,
        Some(v(0.0, 0.0, -1.0)),
        1e-6,
        "1000 m slab",
    );
    let tall = cylinder(MAX_SIZE_M, MAX_SIZE_M, [0.0, 0.0, -500.0], [0.0; 3]);
    check(
        &sphere(&tall, v(0.0, 0.0, 1.0), 0.5),
        0.5,
        Some(v(0.0, 0.0, -1.0)),
        1e-6,
        "1000 m cylinder",
    );
}

/// Non-finite body shapes do not panic: a capsule with a NaN end gives no clearance or a NaN
/// one, never a crash.
#[test]
fn non_finite_capsules_do_not_panic() {
    let obstacles = [
        cuboid([0.2, 1.0, 1.0], [0.5, 0.0, 1.2], [0.0; 3]),
        cylinder(0.1, 2.0, [0.5, 0.0, 1.0], [0.0; 3]),
        plane([0.0, 0.0, 1.0], [0.0; 3], [0.0; 3]),
    ];
    for o in &obstacles {
        for (a, r) in [
            (v(f64::NAN, 0.0, 1.0), 0.05),
            (v(0.0, 0.0, 1.0), f64::NAN),
            (v(f64::INFINITY, 0.0, 0.0), 0.05),
        ] {
            let res = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                o.clearance(0, &a, &v(0.0, 0.0, 1.5), r, 1.0)
            }));
            eprintln!(
                "PROBE {:?} a={a:?} r={r}: {:?}",
                o.spec.shape,
                res.as_ref().map(|c| c.map(|c| c.distance_m))
            );
        }
    }
}

/// Offset planes (their in-plane position is irrelevant) and bodies sunk inside a cylinder or a
/// box: the distance is the height above the plane, or minus (the depth to the nearest face plus
/// the radius) inside.
#[test]
fn offset_planes_and_penetration_depths() {
    let half = v(0.1, 0.1, 0.1);
    for (pp, bp) in [
        ([0.0, 0.0, 0.0], v(0.0, 0.0, 0.5)),
        ([0.0, 0.0, 0.2], v(0.0, 0.0, 0.5)),
        ([0.3, -0.2, 0.2], v(0.0, 0.0, 0.5)),
        ([0.0, 0.0, 0.0], v(1.0, 2.0, 0.5)),
        ([0.0, 0.0, 0.2], v(1.0, 2.0, 0.5)),
        ([1.0, 2.0, 0.2], v(1.0, 2.0, 0.5)),
    ] {
        let floor = plane([0.0, 0.0, 1.0], pp, [0.0; 3]);
        // the box's bottom face and the sphere's lowest point are 0.1 below the centre
        let expected = bp.z - 0.1 - pp[2];
        let what = format!("plane at {pp:?}, body at {bp:?}");
        check(
            &body_box(&floor, bp, [0.0; 3], half),
            expected,
            None,
            1e-12,
            &what,
        );
        check(&sphere(&floor, bp, 0.1), expected, None, 1e-12, &what);
    }
    // a cylinder of radius 0.1 standing from z = 0 to z = 2 on the axis x = 0.5, y = 0
    let cyl = cylinder(0.1, 2.0, [0.5, 0.0, 1.0], [0.0; 3]);
    for (c, r, expected) in [
        (v(0.5, 0.0, 1.9), 0.05, -0.15), // side and top both 0.1 away
        (v(0.5, 0.0, 1.9), 0.01, -0.11),
        (v(0.5, 0.0, 1.0), 0.05, -0.15),   // side 0.1, top 1.0
        (v(0.52, 0.0, 1.95), 0.01, -0.06), // top 0.05 nearer than the side (0.08)
    ] {
        check(
            &sphere(&cyl, c, r),
            expected,
            None,
            1e-5,
            &format!("sphere at {c:?}"),
        );
    }
    // a capsule from z = 1.95 down to 1.94: its deepest point is 0.06 below the top
    let c = v(0.52, 0.0, 1.95);
    check(
        &capsule(&cyl, c, c + v(0.0, 0.0, -0.01), 0.01),
        -0.07,
        None,
        1e-5,
        "capsule inside the cylinder",
    );
    // a 0.2 × 0.2 × 2 box over the same axis: faces 0.1 from the sphere's centre
    let bx = cuboid([0.2, 0.2, 2.0], [0.5, 0.0, 1.0], [0.0; 3]);
    check(
        &sphere(&bx, v(0.5, 0.0, 1.9), 0.05),
        -0.15,
        None,
        1e-9,
        "sphere inside the box",
    );
}
