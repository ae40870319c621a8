//! Whole-body figures of a planned posture: the body's collision capsules and foot boxes placed
//! by forward kinematics at the phase's joint angles, both sides coloured apart and drawn far
//! to near; the held object, the hand targets and the hands; the workstation's obstacles, the
//! floor and a height ruler in metres.
//!
//! Views (none mirrored):
//! * side: seen from the worker's right, world x (forward) to the right, z up;
//! * front: facing the worker, world y to the right (the worker's left on the viewer's right);
//! * top: from above, forward up, the worker's right on the right; with the support polygon of
//!   the feet and the centre of mass.

use super::ReportError;
use super::fmt::{esc, num, unit};
use super::svg::Svg;
use crate::body::stance::FeetNow;
use crate::body::{StaticsData, forward_kinematics};
use crate::plan::Task;
use crate::plan::task::HeldObject;
use crate::workstation::ShapeSpec;
use nalgebra::{Point3, Vector3};
use std::fmt::Write;

/// A view of the scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum View {
    Side,
    Front,
    Top,
}

impl View {
    /// World point → (horizontal, vertical) in metres, vertical up.
    pub fn project(self, p: &Vector3<f64>) -> (f64, f64) {
        match self {
            View::Side => (p.x, p.z),
            View::Front => (p.y, p.z),
            View::Top => (-p.y, p.x),
        }
    }
    /// Unit vector toward the viewer.
    fn toward_viewer(self) -> Vector3<f64> {
        match self {
            View::Side => -Vector3::y(),
            View::Front => Vector3::x(),
            View::Top => Vector3::z(),
        }
    }
    fn depth(self, p: &Vector3<f64>) -> f64 {
        self.toward_viewer().dot(p)
    }
    fn index(self) -> usize {
        self as usize
    }
    pub fn title(self) -> &'static str {
        match self {
            View::Side => "side, from the worker’s right",
            View::Front => "front, facing the worker",
            View::Top => "top, from above (front up)",
        }
    }
    fn tiny(self) -> &'static str {
        match self {
            View::Side => "side",
            View::Front => "front",
            View::Top => "top",
        }
    }
    fn short(self) -> &'static str {
        match self {
            View::Side => "side view",
            View::Front => "front view",
            View::Top => "top view",
        }
    }
    fn has_ruler(self) -> bool {
        self != View::Top
    }
}

/// Which side of the body a part belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Side {
    Right,
    Left,
    Mid,
}

impl Side {
    fn of(name: &str) -> Side {
        let n = name.to_ascii_lowercase();
        if n.starts_with("r_") || n.starts_with("right") || n.contains("_r_") {
            Side::Right
        } else if n.starts_with("l_") || n.starts_with("left") || n.contains("_l_") {
            Side::Left
        } else {
            Side::Mid
        }
    }
    /// (fill, outline) colours.
    fn colours(self) -> (&'static str, &'static str) {
        match self {
            Side::Right => ("#5b8fd6", "#1f4a85"),
            Side::Left => ("#f2b173", "#9a5a1c"),
            Side::Mid => ("#b4bdca", "#465366"),
        }
    }
}

/// Something drawn, in world coordinates.
#[derive(Debug, Clone)]
enum Item {
    Capsule {
        a: Vector3<f64>,
        b: Vector3<f64>,
        r: f64,
        side: Side,
    },
    Solid {
        corners: Vec<Vector3<f64>>,
        side: Side,
    },
    Bone {
        a: Vector3<f64>,
        b: Vector3<f64>,
    },
    Object {
        corners: Vec<Vector3<f64>>,
    },
    Nose {
        at: Vector3<f64>,
    },
}

impl Item {
    fn points(&self) -> Vec<Vector3<f64>> {
        match self {
            Item::Capsule { a, b, .. } | Item::Bone { a, b } => vec![*a, *b],
            Item::Solid { corners, .. } | Item::Object { corners } => corners.clone(),
            Item::Nose { at } => vec![*at],
        }
    }
    fn depth(&self, v: View) -> f64 {
        let pts = self.points();
        let d = pts.iter().map(|p| v.depth(p)).sum::<f64>() / pts.len().max(1) as f64;
        // a bone is drawn just after the capsule around it; the nose on the head
        match self {
            Item::Bone { .. } => d + 1e-4,
            Item::Nose { .. } => d + 0.2,
            _ => d,
        }
    }
}

/// One posture, ready to draw.
#[derive(Debug, Clone)]
pub struct Scene {
    items: Vec<Item>,
    grips: [Option<Vector3<f64>>; 2],
    targets: [Option<Vector3<f64>>; 2],
    com: Vector3<f64>,
    /// The support polygon of the feet where this posture puts them (world x, y) \[m\].
    support_m: Vec<nalgebra::Vector2<f64>>,
}

fn box_corners(center: [f64; 3], size: [f64; 3]) -> Vec<Vector3<f64>> {
    (0..8)
        .map(|i| {
            let s = |bit: usize, k: usize| {
                center[k]
                    + if i & bit == 0 {
                        -size[k] / 2.0
                    } else {
                        size[k] / 2.0
                    }
            };
            Vector3::new(s(1, 0), s(2, 1), s(4, 2))
        })
        .collect()
}

/// The body of `task` in posture `q_rad`, with phase `phase`'s targets and held object.
pub fn scene(task: &Task, q_rad: &[f64], phase: Option<usize>) -> Result<Scene, ReportError> {
    let m = &task.model;
    if q_rad.len() != m.nq() || q_rad.iter().any(|x| !x.is_finite()) {
        return Err(ReportError::Figure(format!(
            "a posture has {} joint angles (some not finite?), the body {}",
            q_rad.len(),
            m.nq()
        )));
    }
    let mut data = StaticsData::new(m, 0);
    forward_kinematics(m, &mut data, q_rad);
    let zero = Vector3::zeros();
    let mut items = Vec::new();
    // links that are part of the body: with mass or shape, or below one
    let mut physical = vec![false; m.links.len()];
    for j in &m.joints {
        let l = &m.links[j.parent_link];
        if l.mass_kg > 0.0 || !l.capsules.is_empty() || !l.boxes.is_empty() {
            physical[j.parent_link] = true;
        }
    }
    for j in &m.joints {
        let c = &m.links[j.child_link];
        if physical[j.parent_link]
            || c.mass_kg > 0.0
            || !c.capsules.is_empty()
            || !c.boxes.is_empty()
        {
            physical[j.child_link] = true;
        }
    }
    for (l, link) in m.links.iter().enumerate() {
        let side = Side::of(&link.name);
        for c in &link.capsules {
            items.push(Item::Capsule {
                a: data.link_point(m, l, &c.a.coords),
                b: data.link_point(m, l, &c.b.coords),
                r: c.radius_m,
                side,
            });
        }
        for b in &link.boxes {
            let h = b.half_extents_m;
            let corners = (0..8)
                .map(|i| {
                    let s = |bit: usize, v: f64| if i & bit == 0 { -v } else { v };
                    let p = b.link_from_box * Point3::new(s(1, h.x), s(2, h.y), s(4, h.z));
                    data.link_point(m, l, &p.coords)
                })
                .collect();
            items.push(Item::Solid { corners, side });
        }
        if link.name == "head"
            && let Some(c) = link.capsules.first()
        {
            let (r, _) = data.link_pose(m, l);
            let mid = data.link_point(m, l, &((c.a.coords + c.b.coords) / 2.0));
            items.push(Item::Nose {
                at: mid + r * Vector3::x() * (0.8 * c.radius_m),
            });
        }
    }
    // bones of the body, and the girdles joining a link's right and left children
    // (shoulders, hips) when the model has no shape there
    for (l, _) in m.links.iter().enumerate() {
        if !physical[l] {
            continue;
        }
        let o = data.link_point(m, l, &zero);
        let mut right = None;
        let mut left = None;
        for j in m.joints.iter().filter(|j| j.parent_link == l) {
            let c = data.link_point(m, j.child_link, &zero);
            if (c - o).norm() > 1e-6 {
                items.push(Item::Bone { a: o, b: c });
            }
            match Side::of(&j.name) {
                Side::Right if right.is_none() => right = Some(c),
                Side::Left if left.is_none() => left = Some(c),
                _ => {}
            }
        }
        if let (Some(a), Some(b)) = (right, left) {
            let r = m.links[l]
                .capsules
                .iter()
                .map(|c| c.radius_m)
                .fold(f64::INFINITY, f64::min);
            let r = if r.is_finite() {
                (0.45 * r).clamp(0.02, 0.06)
            } else {
                0.04
            };
            items.push(Item::Capsule {
                a,
                b,
                r,
                side: Side::Mid,
            });
        }
    }
    let mut com = Vector3::zeros();
    let mut mass = 0.0;
    for (b, body) in m.bodies.iter().enumerate() {
        if body.mass_kg > 0.0 {
            com += body.mass_kg * (data.body_rot[b] * body.com_m + data.body_pos[b]);
            mass += body.mass_kg;
        }
    }
    if mass > 0.0 {
        com /= mass;
    }
    let grips = [0, 1].map(|h| {
        task.hand_links[h]
            .as_ref()
            .map(|(l, _)| data.link_point(m, *l, &zero))
    });
    let ph = phase.and_then(|p| task.phases.get(p));
    if let Some(HeldObject { center_m, size_m }) = ph.and_then(|p| p.object) {
        items.push(Item::Object {
            corners: box_corners(center_m, size_m),
        });
    }
    let support_m = task
        .stance
        .as_ref()
        .map(|st| match &st.seat {
            // a seated worker's support is the seat's outline with the (fixed) feet
            Some(_) => st.support_polygon_m.clone(),
            None => FeetNow::at(m, &data, &st.feet).support().polygon_m(),
        })
        .unwrap_or_default();
    Ok(Scene {
        items,
        grips: if ph.is_some() { grips } else { [None, None] },
        targets: ph.map(|p| p.targets_m).unwrap_or([None, None]),
        com,
        support_m,
    })
}

/// A rectangle in view coordinates (metres).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    pub h0: f64,
    pub h1: f64,
    pub v0: f64,
    pub v1: f64,
}

impl Bounds {
    fn empty() -> Self {
        Bounds {
            h0: f64::INFINITY,
            h1: f64::NEG_INFINITY,
            v0: f64::INFINITY,
            v1: f64::NEG_INFINITY,
        }
    }
    fn add(&mut self, (h, v): (f64, f64)) {
        if h.is_finite() && v.is_finite() {
            self.h0 = self.h0.min(h);
            self.h1 = self.h1.max(h);
            self.v0 = self.v0.min(v);
            self.v1 = self.v1.max(v);
        }
    }
    fn is_empty(&self) -> bool {
        !(self.h0 <= self.h1 && self.v0 <= self.v1)
    }
    fn grow(&self, dh: f64, dv: f64) -> Self {
        Bounds {
            h0: self.h0 - dh,
            h1: self.h1 + dh,
            v0: self.v0 - dv,
            v1: self.v1 + dv,
        }
    }
    fn w(&self) -> f64 {
        (self.h1 - self.h0).max(0.1)
    }
    fn h(&self) -> f64 {
        (self.v1 - self.v0).max(0.1)
    }
}

/// An obstacle's outline in one view.
enum Outline {
    /// A projected solid (convex hull).
    Solid(Vec<(f64, f64)>),
    /// A plane seen edge-on: a point on its line, the line's direction and the direction into
    /// the solid side (view coordinates).
    Plane {
        at: (f64, f64),
        along: (f64, f64),
        into: (f64, f64),
    },
}

/// Andrew's monotone chain convex hull.
fn hull(mut pts: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    pts.retain(|p| p.0.is_finite() && p.1.is_finite());
    pts.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    pts.dedup_by(|a, b| (a.0 - b.0).abs() < 1e-12 && (a.1 - b.1).abs() < 1e-12);
    if pts.len() < 3 {
        return pts;
    }
    let cross = |o: (f64, f64), a: (f64, f64), b: (f64, f64)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    let mut h: Vec<(f64, f64)> = Vec::with_capacity(2 * pts.len());
    for pass in 0..2 {
        let start = h.len();
        let seq: Vec<(f64, f64)> = if pass == 0 {
            pts.clone()
        } else {
            pts.iter().rev().copied().collect()
        };
        for p in seq {
            while h.len() >= start + 2 && cross(h[h.len() - 2], h[h.len() - 1], p) <= 0.0 {
                h.pop();
            }
            h.push(p);
        }
        h.pop();
    }
    h
}

/// Each obstacle's name and outline in `view` (the floor and planes seen face-on or at an angle
/// are left out: the floor is drawn as such).
fn outlines(task: &Task, view: View) -> Vec<(String, Outline)> {
    let mut out = Vec::new();
    for ob in &task.workstation.obstacles {
        let pose = ob.world_from_obstacle();
        let pts: Vec<Vector3<f64>> = match &ob.spec.shape {
            ShapeSpec::Box { size_m } => box_corners([0.0; 3], *size_m)
                .into_iter()
                .map(|p| (pose * Point3::from(p)).coords)
                .collect(),
            ShapeSpec::Cylinder { radius_m, height_m } => (0..48)
                .map(|i| {
                    let a = std::f64::consts::TAU * (i % 24) as f64 / 24.0;
                    let z = if i < 24 {
                        -height_m / 2.0
                    } else {
                        height_m / 2.0
                    };
                    (pose * Point3::new(radius_m * a.cos(), radius_m * a.sin(), z)).coords
                })
                .collect(),
            ShapeSpec::Plane { normal } => {
                if ob.is_floor() {
                    continue;
                }
                let n = pose.rotation * Vector3::from(*normal);
                if n.norm() < 1e-12 {
                    continue;
                }
                let n = n.normalize();
                if n.dot(&view.toward_viewer()).abs() > 1e-6 {
                    continue;
                }
                let p0 = Vector3::from(ob.spec.position_m);
                let (a0, a1) = view.project(&p0);
                let (n0, n1) = {
                    let (x, y) = view.project(&(p0 + n));
                    (x - a0, y - a1)
                };
                out.push((
                    ob.spec.name.clone(),
                    Outline::Plane {
                        at: (a0, a1),
                        along: (-n1, n0),
                        into: (-n0, -n1),
                    },
                ));
                continue;
            }
        };
        out.push((
            ob.spec.name.clone(),
            Outline::Solid(hull(pts.iter().map(|p| view.project(p)).collect())),
        ));
    }
    // the seat: a block from the floor to its top
    if let Some(seat) = task.stance.as_ref().and_then(|st| st.seat.as_ref()) {
        let pts: Vec<(f64, f64)> = seat
            .outline_m
            .iter()
            .flat_map(|c| [0.0, seat.height_m].map(|z| view.project(&Vector3::new(c.x, c.y, z))))
            .collect();
        out.push(("seat".to_string(), Outline::Solid(hull(pts))));
    }
    out
}

fn has_floor(task: &Task) -> bool {
    task.stance.is_some() || task.workstation.obstacles.iter().any(|o| o.is_floor())
}

/// What one row of views shows: the same scale for every view and posture.
#[derive(Debug, Clone)]
pub struct Frame {
    pub views: Vec<View>,
    bounds: [Bounds; 3],
    /// Pixels per metre.
    scale: f64,
}

const ML_RULER: f64 = 36.0;
const ML_PLAIN: f64 = 8.0;
const MR: f64 = 8.0;
const MT: f64 = 18.0;
const MB: f64 = 16.0;

fn margin_left(v: View) -> f64 {
    if v.has_ruler() { ML_RULER } else { ML_PLAIN }
}

/// The frame for drawing `scenes` of `task` in `views`, side by side within `width_px`, at most
/// `height_px` tall.
pub fn frame(
    task: &Task,
    scenes: &[&Scene],
    views: &[View],
    width_px: f64,
    height_px: f64,
) -> Frame {
    let mut bounds = [Bounds::empty(); 3];
    for &v in views {
        let mut b = Bounds::empty();
        for s in scenes {
            for it in &s.items {
                let r = match it {
                    Item::Capsule { r, .. } => *r,
                    _ => 0.0,
                };
                for p in it.points() {
                    let (h, w) = v.project(&p);
                    b.add((h - r, w - r));
                    b.add((h + r, w + r));
                }
            }
            for p in s.targets.iter().chain(&s.grips).flatten() {
                b.add(v.project(p));
            }
        }
        if b.is_empty() {
            b = Bounds {
                h0: -0.5,
                h1: 0.5,
                v0: 0.0,
                v1: 1.8,
            };
        }
        // obstacles near the body: clipped to its surroundings
        let near = b.grow(0.6, 0.45);
        let mut all = b;
        for (_, o) in outlines(task, v) {
            match o {
                Outline::Solid(pts) => {
                    let mut ob = Bounds::empty();
                    pts.into_iter().for_each(|p| ob.add(p));
                    let c = Bounds {
                        h0: ob.h0.max(near.h0),
                        h1: ob.h1.min(near.h1),
                        v0: ob.v0.max(near.v0),
                        v1: ob.v1.min(near.v1),
                    };
                    if !c.is_empty() {
                        all.add((c.h0, c.v0));
                        all.add((c.h1, c.v1));
                    }
                }
                Outline::Plane { at, along, .. } => {
                    // a horizontal plane adds its height, a vertical one its position
                    if along.1.abs() < 1e-9 && at.1 > near.v0 && at.1 < near.v1 {
                        all.add((b.h0, at.1));
                    } else if along.0.abs() < 1e-9 && at.0 > near.h0 && at.0 < near.h1 {
                        all.add((at.0, b.v0));
                    }
                }
            }
        }
        if v.has_ruler() && has_floor(task) {
            all.add((all.h0, -0.04));
        }
        bounds[v.index()] = all.grow(0.06, 0.06);
    }
    let sum_w: f64 = views.iter().map(|v| bounds[v.index()].w()).sum();
    let margins: f64 = views.iter().map(|&v| margin_left(v) + MR + 8.0).sum();
    let max_h = views
        .iter()
        .map(|v| bounds[v.index()].h())
        .fold(0.1, f64::max);
    let scale =
        ((width_px - margins).max(60.0) / sum_w).min((height_px - MT - MB).max(60.0) / max_h);
    Frame {
        views: views.to_vec(),
        bounds,
        scale,
    }
}

impl Frame {
    /// Pixels per metre.
    pub fn scale(&self) -> f64 {
        self.scale
    }
    /// Draws at `px_per_m` instead (to share one scale between frames).
    pub fn set_scale(&mut self, px_per_m: f64) {
        if px_per_m.is_finite() && px_per_m > 0.0 {
            self.scale = px_per_m;
        }
    }
}

/// Pixel mapping of one view.
struct Px {
    b: Bounds,
    s: f64,
}

impl Px {
    fn p(&self, (h, v): (f64, f64)) -> (f64, f64) {
        ((h - self.b.h0) * self.s, (self.b.v1 - v) * self.s)
    }
}

/// A label box already placed (px), to keep labels apart.
type LabelBox = (f64, f64, f64, f64);

fn overlaps(a: &LabelBox, b: &LabelBox) -> bool {
    a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3
}

const HALO: &str =
    "paint-order=\"stroke\" stroke=\"#ffffff\" stroke-width=\"3\" stroke-linejoin=\"round\"";

/// One view of `scene` as an SVG element.
pub fn view_svg(task: &Task, scene: &Scene, frame: &Frame, view: View, label: &str) -> String {
    let b = frame.bounds[view.index()];
    let s = frame.scale;
    let ml = margin_left(view);
    let (pw, ph) = (b.w() * s, b.h() * s);
    let (w, h) = (ml + pw + MR, MT + ph + MB);
    let mut g = Svg::new(w, h, &format!("{} — {label}", view.short()));
    g.rect(0.0, 0.0, w, h, "fill=\"#ffffff\"");
    let title = if 6.0 * view.title().chars().count() as f64 <= pw + MR {
        view.title()
    } else {
        view.tiny()
    };
    g.text(
        ml,
        12.0,
        title,
        "font-size=\"11\" fill=\"#33415c\" font-weight=\"600\"",
    );
    let px = Px { b, s };
    // ruler and grid
    if view.has_ruler() {
        let step = 0.1;
        let first = (b.v0 / step).ceil() as i64;
        let last = (b.v1 / step).floor() as i64;
        g.line(
            ml - 4.0,
            MT,
            ml - 4.0,
            MT + ph,
            "stroke=\"#7a8394\" stroke-width=\"1\"",
        );
        for i in first..=last {
            let z = i as f64 * step;
            let y = MT + px.p((0.0, z)).1;
            let major = i % 5 == 0;
            g.line(
                ml - if major { 10.0 } else { 7.0 },
                y,
                ml - 4.0,
                y,
                "stroke=\"#7a8394\" stroke-width=\"1\"",
            );
            if major {
                g.text(
                    ml - 12.0,
                    y + 3.5,
                    &num(z, 1),
                    "font-size=\"9.5\" fill=\"#4a5468\" text-anchor=\"end\"",
                );
            }
        }
        g.text(
            ml - 12.0,
            MT + ph + 12.0,
            "m",
            "font-size=\"9.5\" fill=\"#4a5468\" text-anchor=\"end\"",
        );
    }
    g.viewport(ml, MT, pw, ph);
    g.rect(0.0, 0.0, pw, ph, "fill=\"#fbfbf8\" stroke=\"#d5dbe5\"");
    if view.has_ruler() {
        let first = (b.v0 / 0.5).ceil() as i64;
        let last = (b.v1 / 0.5).floor() as i64;
        for i in first.max(1)..=last {
            let y = px.p((0.0, i as f64 * 0.5)).1;
            g.line(0.0, y, pw, y, "stroke=\"#e6e9ef\" stroke-width=\"1\"");
        }
        if has_floor(task) {
            let y = px.p((0.0, 0.0)).1;
            g.rect(0.0, y, pw, (ph - y).max(0.0), "fill=\"#e4e0d6\"");
            g.line(0.0, y, pw, y, "stroke=\"#6b6455\" stroke-width=\"1.5\"");
        }
    }
    // the standing area, the support polygon and the feet on the floor (top view)
    if view == View::Top
        && let Some(st) = &task.stance
    {
        let on_floor = |pts: &[nalgebra::Vector2<f64>]| -> Vec<(f64, f64)> {
            pts.iter()
                .map(|p| px.p(view.project(&Vector3::new(p.x, p.y, 0.0))))
                .collect()
        };
        if let Some(pl) = &st.placement {
            g.polygon(
                &on_floor(&pl.area_m),
                "fill=\"none\" stroke=\"#7a8699\" stroke-width=\"1\" stroke-dasharray=\"1 3\"",
                Some("standing area: where the feet may be placed"),
            );
        }
        g.polygon(
            &on_floor(&scene.support_m),
            "fill=\"#e8f3e8\" stroke=\"#2e7d32\" stroke-width=\"1\" stroke-dasharray=\"4 3\"",
            Some(if st.seat.is_some() {
                "support polygon of the seat and the feet"
            } else {
                "support polygon of the feet"
            }),
        );
    }
    // obstacles
    let mut placed: Vec<LabelBox> = Vec::new();
    if view == View::Top {
        placed.push((pw - 0.5 * s - 12.0, 0.0, pw, 20.0));
    }
    let mut labels: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for (name, o) in outlines(task, view) {
        match o {
            Outline::Solid(pts) => {
                let p: Vec<(f64, f64)> = pts.iter().map(|q| px.p(*q)).collect();
                g.polygon(
                    &p,
                    "fill=\"#e7dcc5\" fill-opacity=\"0.85\" stroke=\"#8a7a5a\" stroke-width=\"1\"",
                    Some(&name),
                );
                labels.push((name, p));
            }
            Outline::Plane { at, along, into } => {
                let far = 50.0;
                let a = (at.0 - along.0 * far, at.1 - along.1 * far);
                let bb = (at.0 + along.0 * far, at.1 + along.1 * far);
                let depth = 0.05;
                let c = (bb.0 + into.0 * depth, bb.1 + into.1 * depth);
                let d = (a.0 + into.0 * depth, a.1 + into.1 * depth);
                let poly: Vec<(f64, f64)> = [a, bb, c, d].iter().map(|q| px.p(*q)).collect();
                g.polygon(&poly, "fill=\"#d9cdb2\" stroke=\"none\"", Some(&name));
                let (x1, y1) = px.p(a);
                let (x2, y2) = px.p(bb);
                g.line(x1, y1, x2, y2, "stroke=\"#6b5a3a\" stroke-width=\"1.5\"");
                let (cx, cy) = px.p(at);
                labels.push((
                    name,
                    vec![(cx.clamp(4.0, pw - 4.0), cy.clamp(4.0, ph - 4.0))],
                ));
            }
        }
    }
    // the body's box keeps obstacle labels off it
    {
        let mut bb = Bounds::empty();
        for it in &scene.items {
            if matches!(it, Item::Object { .. }) {
                continue;
            }
            for p in it.points() {
                bb.add(px.p(view.project(&p)));
            }
        }
        if !bb.is_empty() {
            placed.push((bb.h0 - 4.0, bb.v0 - 4.0, bb.h1 + 4.0, bb.v1 + 4.0));
        }
    }
    // body, object, far to near
    let mut order: Vec<(f64, &Item)> = scene.items.iter().map(|it| (it.depth(view), it)).collect();
    order.sort_by(|a, b| a.0.total_cmp(&b.0));
    for (_, it) in order {
        match it {
            Item::Capsule { a, b: e, r, side } => {
                let (fill, edge) = side.colours();
                let (x1, y1) = px.p(view.project(a));
                let (x2, y2) = px.p(view.project(e));
                let wpx = (2.0 * r * s).max(2.0);
                g.line(
                    x1,
                    y1,
                    x2,
                    y2,
                    &format!(
                        "stroke=\"{edge}\" stroke-width=\"{:.1}\" stroke-linecap=\"round\"",
                        wpx + 1.6
                    ),
                );
                g.line(
                    x1,
                    y1,
                    x2,
                    y2,
                    &format!(
                        "stroke=\"{fill}\" stroke-width=\"{wpx:.1}\" stroke-linecap=\"round\""
                    ),
                );
            }
            Item::Solid { corners, side } => {
                let (fill, edge) = side.colours();
                let p: Vec<(f64, f64)> = hull(corners.iter().map(|c| view.project(c)).collect())
                    .into_iter()
                    .map(|q| px.p(q))
                    .collect();
                g.polygon(&p, &format!("fill=\"{fill}\" stroke=\"{edge}\" stroke-width=\"1\" stroke-linejoin=\"round\""), None);
            }
            Item::Bone { a, b: e } => {
                let (x1, y1) = px.p(view.project(a));
                let (x2, y2) = px.p(view.project(e));
                g.line(x1, y1, x2, y2, "stroke=\"#27324a\" stroke-width=\"1.1\" stroke-opacity=\"0.7\" stroke-linecap=\"round\"");
            }
            Item::Object { corners } => {
                let p: Vec<(f64, f64)> = hull(corners.iter().map(|c| view.project(c)).collect())
                    .into_iter()
                    .map(|q| px.p(q))
                    .collect();
                g.polygon(
                    &p,
                    "fill=\"#d8b26e\" fill-opacity=\"0.9\" stroke=\"#7a5a1e\" stroke-width=\"1.2\"",
                    Some("held object"),
                );
            }
            Item::Nose { at } => {
                let (x, y) = px.p(view.project(at));
                g.circle(x, y, 2.2, "fill=\"#27324a\"");
            }
        }
    }
    // centre of mass (top view)
    if view == View::Top {
        let (x, y) = px.p(view.project(&scene.com));
        g.circle(
            x,
            y,
            4.5,
            "fill=\"#ffffff\" stroke=\"#111111\" stroke-width=\"1.2\"",
        );
        g.line(
            x - 4.5,
            y,
            x + 4.5,
            y,
            "stroke=\"#111111\" stroke-width=\"1\"",
        );
        g.line(
            x,
            y - 4.5,
            x,
            y + 4.5,
            "stroke=\"#111111\" stroke-width=\"1\"",
        );
    }
    // hands and targets
    let mut target_heights: Vec<f64> = Vec::new();
    for hnd in 0..2 {
        let (Some(t), grip) = (scene.targets[hnd], scene.grips[hnd]) else {
            if let Some(gp) = scene.grips[hnd] {
                let (x, y) = px.p(view.project(&gp));
                g.circle(x, y, 2.0, "fill=\"#27324a\"");
            }
            continue;
        };
        let (tx, ty) = px.p(view.project(&t));
        if let Some(gp) = grip {
            let (gx, gy) = px.p(view.project(&gp));
            if (gp - t).norm() > 0.01 {
                g.line(
                    gx,
                    gy,
                    tx,
                    ty,
                    "stroke=\"#c62828\" stroke-width=\"1.2\" stroke-dasharray=\"3 2\"",
                );
            }
            g.circle(gx, gy, 2.6, "fill=\"#111111\"");
        }
        let d = 4.5;
        let cross = format!(
            "M{:.1},{:.1}L{:.1},{:.1}M{:.1},{:.1}L{:.1},{:.1}",
            tx - d,
            ty - d,
            tx + d,
            ty + d,
            tx - d,
            ty + d,
            tx + d,
            ty - d
        );
        g.path(
            &cross,
            "stroke=\"#ffffff\" stroke-width=\"4\" stroke-linecap=\"round\"",
        );
        g.path(
            &cross,
            "stroke=\"#c62828\" stroke-width=\"2\" stroke-linecap=\"round\"",
        );
        if view == View::Side && !target_heights.iter().any(|z| (z - t.z).abs() < 0.03) {
            target_heights.push(t.z);
            let txt = unit(t.z, 2, "m");
            let tw = 5.6 * txt.chars().count() as f64;
            // right of the target, or left of it where the view ends
            let (x0, anchor) = if tx + 7.0 + tw <= pw {
                (tx + 7.0, "start")
            } else {
                (tx - 7.0, "end")
            };
            let bx0 = if anchor == "start" { x0 } else { x0 - tw };
            placed.push((bx0 - 1.0, ty - 9.0, bx0 + tw + 1.0, ty + 3.0));
            g.text(
                x0,
                ty + 1.0,
                &txt,
                &format!("font-size=\"9.5\" fill=\"#c62828\" text-anchor=\"{anchor}\" {HALO}"),
            );
        }
    }
    // obstacle labels where they fit
    for (name, p) in labels {
        if name.is_empty() {
            continue;
        }
        let (mut x0, mut y0, mut x1, mut y1) = (
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        );
        for q in &p {
            x0 = x0.min(q.0);
            y0 = y0.min(q.1);
            x1 = x1.max(q.0);
            y1 = y1.max(q.1);
        }
        let tw = 5.3 * name.chars().count() as f64;
        let cx = ((x0 + x1) / 2.0).clamp(tw / 2.0 + 2.0, (pw - tw / 2.0 - 2.0).max(tw / 2.0 + 2.0));
        let mut cands = Vec::new();
        if x1 - x0 >= tw + 4.0 && y1 - y0 >= 13.0 {
            cands.push((cx, (y0.max(0.0) + y1.min(ph)) / 2.0 + 3.0));
        }
        cands.push((cx, y0 - 3.0));
        cands.push((cx, y1 + 10.0));
        for (lx, ly) in cands {
            let bx: LabelBox = (lx - tw / 2.0, ly - 8.0, lx + tw / 2.0, ly + 2.0);
            if bx.0 < 0.0
                || bx.1 < 0.0
                || bx.2 > pw
                || bx.3 > ph
                || placed.iter().any(|o| overlaps(o, &bx))
            {
                continue;
            }
            placed.push(bx);
            g.text(
                lx,
                ly,
                &name,
                &format!("font-size=\"9\" fill=\"#6b5a3a\" text-anchor=\"middle\" {HALO}"),
            );
            break;
        }
    }
    g.end_viewport();
    // orientation
    let small = "font-size=\"9\" fill=\"#5b6472\"";
    let yb = MT + ph + 11.0;
    match view {
        View::Side => {
            g.text(
                ml + pw,
                yb,
                "front →",
                &format!("{small} text-anchor=\"end\""),
            );
        }
        View::Front | View::Top => {
            // the worker's right is on the viewer's left in the front view, on the right from above
            let (l, r) = if view == View::Front {
                ("right", "left")
            } else {
                ("left", "right")
            };
            let long = pw >= 190.0;
            let lt = if long {
                format!("← worker’s {l}")
            } else {
                format!("← {l}")
            };
            let rt = if long {
                format!("worker’s {r} →")
            } else {
                format!("{r} →")
            };
            g.text(ml, yb, &lt, small);
            g.text(ml + pw, yb, &rt, &format!("{small} text-anchor=\"end\""));
        }
    }
    if view == View::Top {
        {
            // scale bar: 0.5 m, at the top right inside the view
            let bar = 0.5 * s;
            let (x1, y0) = (ml + pw - 6.0, MT + 12.0);
            let x0 = x1 - bar;
            g.rect(
                x0 - 4.0,
                y0 - 10.0,
                bar + 8.0,
                16.0,
                "fill=\"#ffffff\" fill-opacity=\"0.8\"",
            );
            g.line(x0, y0, x1, y0, "stroke=\"#4a5468\" stroke-width=\"1.5\"");
            g.line(
                x0,
                y0 - 3.0,
                x0,
                y0 + 3.0,
                "stroke=\"#4a5468\" stroke-width=\"1\"",
            );
            g.line(
                x1,
                y0 - 3.0,
                x1,
                y0 + 3.0,
                "stroke=\"#4a5468\" stroke-width=\"1\"",
            );
            g.text(
                (x0 + x1) / 2.0,
                y0 - 3.0,
                "0.5 m",
                &format!("{small} text-anchor=\"middle\""),
            );
        }
    }
    g.finish()
}

/// The views of `frame` of one scene, side by side, with a legend.
pub fn views_html(task: &Task, scene: &Scene, frame: &Frame, label: &str) -> String {
    // each view's share of the row, so that the row scales as one (same scale in every view),
    // never wider than drawn
    let widths: Vec<f64> = frame
        .views
        .iter()
        .map(|&v| margin_left(v) + frame.bounds[v.index()].w() * frame.scale + MR)
        .collect();
    let total: f64 = widths.iter().sum::<f64>().max(1.0);
    let mut o = format!(
        "<figure class=\"body\"><div class=\"views\" style=\"max-width:{:.0}px\">",
        total * 1.03
    );
    for (&v, w) in frame.views.iter().zip(&widths) {
        let _ = write!(
            o,
            "<div class=\"view\" style=\"width:{:.2}%\">{}</div>",
            (98.0 * w / total).clamp(1.0, 100.0),
            view_svg(task, scene, frame, v, label)
        );
    }
    let _ = write!(
        o,
        "</div><figcaption>{}: <span class=\"key right\">right side</span> <span class=\"key left\">left side</span> <span class=\"key obj\">held object</span> <span class=\"key obst\">obstacle</span> <span class=\"tgt\">×</span> hand target, ● hand{}; heights in metres above the floor.</figcaption></figure>",
        esc(label),
        if !frame.views.contains(&View::Top) {
            ""
        } else if task.seated() {
            "; top view: ⊕ centre of mass over the support polygon of the seat and the feet (dashed)"
        } else {
            "; top view: ⊕ centre of mass over the feet's support polygon (dashed)"
        }
    );
    o
}
