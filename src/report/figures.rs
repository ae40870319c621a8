//! SVG figures for the HTML report: capacity and fatigue-index curves over time (plotters), and
//! side / front stick-figure views of a posture with the workstation's obstacles.
//!
//! Views: side = world x to the right, z up (the worker seen from their right); front = world
//! y to the right, z up (seen from in front, so the worker's left is on the viewer's right).

use crate::body::{forward_kinematics, BodyModel, StaticsData};
use crate::fatigue::{MaParams, MaState};
use crate::plan::Plan;
use crate::workstation::{ShapeSpec, Workstation};
use nalgebra::{Point3, Vector3};
use plotters::prelude::*;
use std::fmt::Write;

/// Which curve to draw.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Curve {
    Capacity,
    FatigueU,
}

/// How many groups get a colour and a legend entry; the others are drawn in light grey.
pub const HIGHLIGHTED: usize = 6;

/// Time series (minutes, value) per half-joint, sampled at step ends and, for long steps,
/// inside them from the model's closed form.
pub fn series(plan: &Plan, curve: Curve) -> Vec<(String, Vec<(f64, f64)>)> {
    let total_s = plan.summary.duration_s.max(1e-9);
    let dt_s = total_s / 600.0;
    plan.half_joints
        .iter()
        .map(|h| {
            let params = MaParams::new(h.k_per_min, h.recovery_per_min).unwrap_or_default();
            let mut state = MaState::FRESH;
            let value = |s: &MaState| match curve {
                Curve::Capacity => s.capacity,
                Curve::FatigueU => s.fatigue_u_min,
            };
            let mut pts = vec![(0.0, value(&state))];
            for step in &plan.steps {
                let f = step.load.get(&h.id).copied().unwrap_or(0.0);
                let inner = (step.duration_s / dt_s).floor().min(50.0) as usize;
                for i in 1..=inner {
                    let mut s = state;
                    let t = step.duration_s * i as f64 / (inner + 1) as f64;
                    params.hold(&mut s, f, t);
                    pts.push(((step.t_s + t) / 60.0, value(&s)));
                }
                state = MaState {
                    capacity: step.capacity.get(&h.id).copied().unwrap_or(state.capacity),
                    fatigue_u_min: step
                        .fatigue_u
                        .get(&h.id)
                        .copied()
                        .unwrap_or(state.fatigue_u_min),
                };
                pts.push(((step.t_s + step.duration_s) / 60.0, value(&state)));
            }
            (h.id.clone(), pts)
        })
        .collect()
}

/// The half-joints to highlight: lowest minimum capacity first.
fn highlighted(plan: &Plan) -> Vec<String> {
    let mut v: Vec<(String, f64)> = plan
        .half_joints
        .iter()
        .map(|h| {
            let min = plan
                .steps
                .iter()
                .filter_map(|s| s.capacity.get(&h.id))
                .fold(1.0_f64, |a, &b| a.min(b));
            (h.id.clone(), min)
        })
        .collect();
    v.sort_by(|a, b| a.1.total_cmp(&b.1));
    v.into_iter().take(HIGHLIGHTED).map(|x| x.0).collect()
}

/// A line chart of `curve` for every half-joint, as an SVG document string. `floor` draws a
/// dashed capacity floor on the capacity chart.
pub fn curve_svg(plan: &Plan, curve: Curve, floor: Option<f64>) -> Result<String, String> {
    let data = series(plan, curve);
    let hi = highlighted(plan);
    let t_max = (plan.summary.duration_s / 60.0).max(1e-6);
    let y_max = match curve {
        Curve::Capacity => 1.0,
        Curve::FatigueU => {
            data.iter()
                .flat_map(|(_, p)| p.iter().map(|x| x.1))
                .fold(0.0_f64, f64::max)
                .max(1e-6)
                * 1.05
        }
    };
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, (900, 360)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let (title, ydesc) = match curve {
            Curve::Capacity => ("Capacity per muscle group", "capacity c = F_cem / MVC"),
            Curve::FatigueU => ("Fatigue index per muscle group", "U [min]"),
        };
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(0.0..t_max, 0.0..y_max)
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc("time [min]")
            .y_desc(ydesc)
            .light_line_style(RGBColor(235, 235, 235))
            .draw()
            .map_err(|e| e.to_string())?;
        for (id, pts) in data.iter().filter(|(id, _)| !hi.contains(id)) {
            let _ = id;
            chart
                .draw_series(LineSeries::new(
                    pts.iter().copied(),
                    RGBColor(200, 200, 200).stroke_width(1),
                ))
                .map_err(|e| e.to_string())?;
        }
        for (j, id) in hi.iter().enumerate() {
            let color = Palette99::pick(j).to_rgba();
            if let Some((_, pts)) = data.iter().find(|(i, _)| i == id) {
                chart
                    .draw_series(LineSeries::new(pts.iter().copied(), color.stroke_width(2)))
                    .map_err(|e| e.to_string())?
                    .label(id.clone())
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                    });
            }
        }
        if let (Curve::Capacity, Some(fl)) = (curve, floor) {
            let dashes: Vec<(f64, f64)> = (0..40)
                .flat_map(|i| {
                    let a = t_max * i as f64 / 40.0;
                    [(a, fl), (a + t_max / 80.0, fl), (f64::NAN, f64::NAN)]
                })
                .collect();
            for seg in dashes.split(|p| p.0.is_nan()) {
                chart
                    .draw_series(LineSeries::new(seg.iter().copied(), BLACK.stroke_width(1)))
                    .map_err(|e| e.to_string())?;
            }
        }
        chart
            .configure_series_labels()
            .position(match curve {
                Curve::Capacity => SeriesLabelPosition::LowerLeft,
                Curve::FatigueU => SeriesLabelPosition::UpperLeft,
            })
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(out)
}

/// A 2-D view: world point → (horizontal, vertical).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum View {
    Side,
    Front,
}

impl View {
    fn project(self, p: &Vector3<f64>) -> (f64, f64) {
        match self {
            View::Side => (p.x, p.z),
            View::Front => (p.y, p.z),
        }
    }
    /// The world axis the viewer looks along.
    fn depth_axis(self) -> Vector3<f64> {
        match self {
            View::Side => Vector3::y(),
            View::Front => Vector3::x(),
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            View::Side => "side",
            View::Front => "front",
        }
    }
}

/// What a posture drawing shows, in world coordinates.
pub struct Scene {
    /// Capsules: (a, b, radius) \[m\].
    pub capsules: Vec<(Vector3<f64>, Vector3<f64>, f64)>,
    /// Kinematic tree segments (parent frame origin → child frame origin).
    pub bones: Vec<(Vector3<f64>, Vector3<f64>)>,
    pub hand_m: Vector3<f64>,
    pub target_m: Option<Vector3<f64>>,
}

/// The body in posture `q_rad`.
pub fn scene(
    model: &BodyModel,
    data: &mut StaticsData,
    q_rad: &[f64],
    hand_link: usize,
    target_m: Option<Vector3<f64>>,
) -> Scene {
    forward_kinematics(model, data, q_rad);
    let o = Vector3::zeros();
    let mut capsules = Vec::new();
    for (l, link) in model.links.iter().enumerate() {
        for c in &link.capsules {
            capsules.push((
                data.link_point(model, l, &c.a.coords),
                data.link_point(model, l, &c.b.coords),
                c.radius_m,
            ));
        }
    }
    let bones = model
        .joints
        .iter()
        .map(|j| {
            (
                data.link_point(model, j.parent_link, &o),
                data.link_point(model, j.child_link, &o),
            )
        })
        .collect();
    Scene {
        capsules,
        bones,
        hand_m: data.link_point(model, hand_link, &o),
        target_m,
    }
}

/// Andrew's monotone chain convex hull of 2-D points.
fn hull(mut pts: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    pts.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let cross = |o: (f64, f64), a: (f64, f64), b: (f64, f64)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    let mut h: Vec<(f64, f64)> = Vec::with_capacity(2 * pts.len());
    for pass in 0..2 {
        let start = h.len();
        let iter: Box<dyn Iterator<Item = &(f64, f64)>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while h.len() >= start + 2 && cross(h[h.len() - 2], h[h.len() - 1], p) <= 0.0 {
                h.pop();
            }
            h.push(p);
        }
        h.pop();
    }
    h
}

/// Projected outline of each obstacle (name, polygon) or, for planes seen edge-on, a line
/// across the view (two points far apart).
/// An obstacle's projected outline: a polygon, or a line for a plane seen edge-on.
struct Outline {
    name: String,
    points: Vec<(f64, f64)>,
    is_line: bool,
}

fn obstacle_outlines(ws: &Workstation, view: View) -> Vec<Outline> {
    let mut out = Vec::new();
    for ob in &ws.obstacles {
        let pose = ob.world_from_obstacle();
        let pts: Vec<Vector3<f64>> = match &ob.spec.shape {
            ShapeSpec::Box { size_m } => (0..8)
                .map(|i| {
                    let s = |b: usize, v: f64| if i & b == 0 { -v / 2.0 } else { v / 2.0 };
                    pose * Point3::new(s(1, size_m[0]), s(2, size_m[1]), s(4, size_m[2]))
                })
                .map(|p| p.coords)
                .collect(),
            ShapeSpec::Cylinder { radius_m, height_m } => (0..32)
                .map(|i| {
                    let a = std::f64::consts::TAU * (i % 16) as f64 / 16.0;
                    let z = if i < 16 {
                        -height_m / 2.0
                    } else {
                        height_m / 2.0
                    };
                    (pose * Point3::new(radius_m * a.cos(), radius_m * a.sin(), z)).coords
                })
                .collect(),
            ShapeSpec::Plane { normal } => {
                let n = pose.rotation * Vector3::from(*normal);
                if n.dot(&view.depth_axis()).abs() > 1e-6 * n.norm() {
                    continue; // seen face-on: it would cover the whole view
                }
                let along = view.depth_axis().cross(&n).normalize();
                let p0 = pose.translation.vector;
                let a = p0 - along * 50.0;
                let b = p0 + along * 50.0;
                out.push(Outline {
                    name: ob.spec.name.clone(),
                    points: vec![view.project(&a), view.project(&b)],
                    is_line: true,
                });
                continue;
            }
        };
        let proj = pts.iter().map(|p| view.project(p)).collect();
        out.push(Outline {
            name: ob.spec.name.clone(),
            points: hull(proj),
            is_line: false,
        });
    }
    out
}

/// Bounds (min, max) of everything finite in the scenes and obstacles, for one view.
pub fn bounds(scenes: &[&Scene], ws: &Workstation, view: View) -> ((f64, f64), (f64, f64)) {
    let mut lo = (f64::INFINITY, f64::INFINITY);
    let mut hi = (f64::NEG_INFINITY, f64::NEG_INFINITY);
    let mut add = |p: (f64, f64)| {
        lo = (lo.0.min(p.0), lo.1.min(p.1));
        hi = (hi.0.max(p.0), hi.1.max(p.1));
    };
    for s in scenes {
        for (a, b) in &s.bones {
            add(view.project(a));
            add(view.project(b));
        }
        for (a, b, r) in &s.capsules {
            for p in [a, b] {
                let (x, y) = view.project(p);
                add((x - r, y - r));
                add((x + r, y + r));
            }
        }
        if let Some(t) = &s.target_m {
            add(view.project(t));
        }
    }
    for o in obstacle_outlines(ws, view) {
        if !o.is_line {
            o.points.into_iter().for_each(&mut add);
        }
    }
    let pad = 0.1;
    ((lo.0 - pad, lo.1 - pad), (hi.0 + pad, hi.1 + pad))
}

/// One view of a posture as an SVG element (`width` px wide, height from the bounds' aspect).
pub fn posture_svg(
    scene: &Scene,
    ws: &Workstation,
    view: View,
    bounds: ((f64, f64), (f64, f64)),
    width_px: f64,
) -> String {
    let ((x0, y0), (x1, y1)) = bounds;
    let scale = width_px / (x1 - x0).max(1e-6);
    let height_px = (y1 - y0) * scale;
    let px = |p: (f64, f64)| ((p.0 - x0) * scale, (y1 - p.1) * scale);
    let mut s = String::new();
    let _ = write!(
        s,
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="{width_px:.0}" height="{height_px:.0}" viewBox="0 0 {width_px:.1} {height_px:.1}" role="img" aria-label="{} view"><rect width="100%" height="100%" fill="#fbfbf8"/>"##,
        view.name()
    );
    for Outline {
        name,
        points,
        is_line,
    } in obstacle_outlines(ws, view)
    {
        let pts: Vec<String> = points
            .iter()
            .map(|p| {
                let (x, y) = px(*p);
                format!("{x:.1},{y:.1}")
            })
            .collect();
        if is_line {
            let _ = write!(
                s,
                r##"<polyline points="{}" stroke="#8a7a5a" stroke-width="2" fill="none"><title>{}</title></polyline>"##,
                pts.join(" "),
                esc(&name)
            );
        } else {
            let _ = write!(
                s,
                r##"<polygon points="{}" fill="#e3d5b8" fill-opacity="0.8" stroke="#8a7a5a" stroke-width="1"><title>{}</title></polygon>"##,
                pts.join(" "),
                esc(&name)
            );
        }
    }
    for (a, b, r) in &scene.capsules {
        let (ax, ay) = px(view.project(a));
        let (bx, by) = px(view.project(b));
        let _ = write!(
            s,
            r##"<line x1="{ax:.1}" y1="{ay:.1}" x2="{bx:.1}" y2="{by:.1}" stroke="#6b95d6" stroke-opacity="0.55" stroke-linecap="round" stroke-width="{:.1}"/>"##,
            2.0 * r * scale
        );
    }
    for (a, b) in &scene.bones {
        let (ax, ay) = px(view.project(a));
        let (bx, by) = px(view.project(b));
        let _ = write!(
            s,
            r##"<line x1="{ax:.1}" y1="{ay:.1}" x2="{bx:.1}" y2="{by:.1}" stroke="#1d2b44" stroke-width="2.5" stroke-linecap="round"/><circle cx="{bx:.1}" cy="{by:.1}" r="2.5" fill="#1d2b44"/>"##
        );
    }
    let (hx, hy) = px(view.project(&scene.hand_m));
    let _ = write!(
        s,
        r##"<circle cx="{hx:.1}" cy="{hy:.1}" r="4" fill="#1d2b44"/>"##
    );
    if let Some(t) = &scene.target_m {
        let (tx, ty) = px(view.project(t));
        let _ = write!(
            s,
            r##"<path d="M{:.1},{:.1}L{:.1},{:.1}M{:.1},{:.1}L{:.1},{:.1}" stroke="#d62728" stroke-width="2"><title>hand target</title></path>"##,
            tx - 6.0,
            ty - 6.0,
            tx + 6.0,
            ty + 6.0,
            tx - 6.0,
            ty + 6.0,
            tx + 6.0,
            ty - 6.0
        );
    }
    let _ = write!(
        s,
        r##"<text x="6" y="16" font-family="sans-serif" font-size="12" fill="#444">{} view</text></svg>"##,
        view.name()
    );
    s
}

/// Escapes text for HTML / SVG.
pub fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
