//! SVG figures of the validations, after the paper's Fig. 1–8 and 10.

use super::{DynamicValidation, StaticValidation};
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// Failure to draw or write a figure.
#[derive(Debug, thiserror::Error)]
#[error("cannot write figure {path}: {message}")]
pub struct PlotError {
    pub path: PathBuf,
    pub message: String,
}

fn err(path: &Path, e: impl std::fmt::Display) -> PlotError {
    PlotError {
        path: path.to_path_buf(),
        message: e.to_string(),
    }
}

/// Writes the drawn figures through [`crate::io::OutputSet`] (regular files only, all or none).
fn write_figures(figures: Vec<(PathBuf, String)>) -> Result<Vec<PathBuf>, PlotError> {
    let mut set = crate::io::OutputSet::new();
    for (path, svg) in &figures {
        set.add("--plot", path, svg.clone().into_bytes());
    }
    set.write_all().map_err(|e| PlotError {
        path: figures.first().map(|f| f.0.clone()).unwrap_or_default(),
        message: e.to_string(),
    })?;
    Ok(figures.into_iter().map(|(p, _)| p).collect())
}

const GROUPS: [(&str, &[&str], &str); 4] = [
    ("general", &["general"], "General models"),
    ("shoulder", &["shoulder"], "Shoulder models"),
    ("elbow", &["elbow", "hand"], "Elbow and hand models"),
    ("back-hip", &["back/hip"], "Back/hip models"),
];

/// Writes fig1..fig8 (MET curves and ICC bars per body region) into `dir`; returns the paths.
pub fn static_figures(v: &StaticValidation, dir: &Path) -> Result<Vec<PathBuf>, PlotError> {
    std::fs::create_dir_all(dir).map_err(|e| err(dir, e))?;
    let mut out = Vec::new();
    for (i, (slug, groups, title)) in GROUPS.iter().enumerate() {
        // The paper leaves Huijgens and Sjogaard out of Fig. 1-2 (derived from other rows' data).
        let rows: Vec<_> = v
            .models
            .iter()
            .filter(|m| {
                groups.contains(&m.group.as_str()) && m.id != "huijgens" && m.id != "sjogaard"
            })
            .collect();
        let path = dir.join(format!("fig{}-met-{slug}.svg", 2 * i + 1));
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, (900, 600)).into_drawing_area();
            root.fill(&WHITE).map_err(|e| err(&path, e))?;
            let mut chart = ChartBuilder::on(&root)
                .caption(
                    format!(
                        "Fig. {}: endurance time, {title} and Eq. 8 (k = {})",
                        2 * i + 1,
                        v.k_per_min
                    ),
                    ("sans-serif", 22),
                )
                .margin(15)
                .x_label_area_size(45)
                .y_label_area_size(60)
                .build_cartesian_2d(20f64..100f64, (0.01f64..100f64).log_scale())
                .map_err(|e| err(&path, e))?;
            chart
                .configure_mesh()
                .x_desc("%MVC")
                .y_desc("MET [min] (log scale)")
                .draw()
                .map_err(|e| err(&path, e))?;
            for (j, m) in rows.iter().enumerate() {
                let color = Palette99::pick(j).to_rgba();
                let pts: Vec<(f64, f64)> = v
                    .fmvc
                    .iter()
                    .zip(&m.met_min)
                    .filter(|(_, y)| y.is_finite() && **y > 0.01)
                    .map(|(f, y)| (f * 100.0, y.min(100.0)))
                    .collect();
                chart
                    .draw_series(LineSeries::new(pts, color.stroke_width(2)))
                    .map_err(|e| err(&path, e))?
                    .label(format!("{} ({})", m.reference, m.id))
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                    });
            }
            let dyn_pts: Vec<(f64, f64)> = v
                .fmvc
                .iter()
                .zip(&v.dynamic_met_min)
                .filter(|(_, y)| **y > 0.01)
                .map(|(f, y)| (f * 100.0, *y))
                .collect();
            chart
                .draw_series(LineSeries::new(dyn_pts, BLACK.stroke_width(4)))
                .map_err(|e| err(&path, e))?
                .label("dynamic model, Eq. 8")
                .legend(|(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(4))
                });
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .position(SeriesLabelPosition::UpperRight)
                .draw()
                .map_err(|e| err(&path, e))?;
            root.present().map_err(|e| err(&path, e))?;
        }
        out.push((path, svg));

        let path = dir.join(format!("fig{}-icc-{slug}.svg", 2 * i + 2));

        let mut svg = String::new();
        {
            let n = rows.len();
            let root = SVGBackend::with_string(&mut svg, (900, 500)).into_drawing_area();
            root.fill(&WHITE).map_err(|e| err(&path, e))?;
            let mut chart = ChartBuilder::on(&root)
                .caption(
                    format!(
                        "Fig. {}: ICC with Eq. 8, {title} (bars: computed, dots: printed)",
                        2 * i + 2
                    ),
                    ("sans-serif", 20),
                )
                .margin(15)
                .x_label_area_size(60)
                .y_label_area_size(50)
                .build_cartesian_2d(0f64..n as f64, -0.2f64..1.0f64)
                .map_err(|e| err(&path, e))?;
            let labels: Vec<String> = rows.iter().map(|m| m.id.clone()).collect();
            chart
                .configure_mesh()
                .disable_x_mesh()
                .x_labels(n.max(1) * 2 + 1)
                .x_label_formatter(&|x| {
                    let i = (*x - 0.5).round();
                    if (x - 0.5 - i).abs() < 1e-6 && i >= 0.0 && (i as usize) < labels.len() {
                        labels[i as usize].clone()
                    } else {
                        String::new()
                    }
                })
                .y_desc("ICC")
                .draw()
                .map_err(|e| err(&path, e))?;
            chart
                .draw_series(rows.iter().enumerate().map(|(j, m)| {
                    let c = Palette99::pick(j).to_rgba().filled();
                    Rectangle::new([(j as f64 + 0.15, 0.0), (j as f64 + 0.85, m.icc)], c)
                }))
                .map_err(|e| err(&path, e))?;
            chart
                .draw_series(rows.iter().enumerate().map(|(j, m)| {
                    Circle::new((j as f64 + 0.5, m.published_icc), 5, BLACK.filled())
                }))
                .map_err(|e| err(&path, e))?;
            root.present().map_err(|e| err(&path, e))?;
        }
        out.push((path, svg));
    }
    write_figures(out)
}

/// Writes fig10 (Liu et al. at MVC vs the model) and an endurance-curve figure into `dir`.
pub fn dynamic_figures(v: &DynamicValidation, dir: &Path) -> Result<Vec<PathBuf>, PlotError> {
    std::fs::create_dir_all(dir).map_err(|e| err(dir, e))?;
    let mut out = Vec::new();
    let path = dir.join("fig10-liu-mvc.svg");
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900, 600)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(&path, e))?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                "Fig. 10: capacity at MVC, active-motor model (Liu et al.) vs dynamic model",
                ("sans-serif", 20),
            )
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(60)
            .build_cartesian_2d(0f64..180f64, 0f64..1.05f64)
            .map_err(|e| err(&path, e))?;
        chart
            .configure_mesh()
            .x_desc("time [s]")
            .y_desc("capacity (M_A + M_uc)/M0, F_cem/MVC")
            .draw()
            .map_err(|e| err(&path, e))?;
        for (j, c) in v.liu.cases.iter().enumerate() {
            let color = Palette99::pick(j + 1).to_rgba();
            chart
                .draw_series(LineSeries::new(
                    v.liu.t_s.iter().copied().zip(c.capacity.iter().copied()),
                    color.stroke_width(2),
                ))
                .map_err(|e| err(&path, e))?
                .label(format!(
                    "Liu et al., beta = {}, gamma = {}",
                    c.beta, c.gamma
                ))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
        }
        chart
            .draw_series(
                v.liu
                    .t_s
                    .iter()
                    .zip(&v.liu.model_capacity)
                    .step_by(10)
                    .map(|(t, c)| Circle::new((*t, *c), 4, BLACK.filled())),
            )
            .map_err(|e| err(&path, e))?
            .label(format!("dynamic model, k = {} /min", v.k_per_min))
            .legend(|(x, y)| Circle::new((x + 10, y), 4, BLACK.filled()));
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(|e| err(&path, e))?;
        root.present().map_err(|e| err(&path, e))?;
    }
    out.push((path, svg));

    let path = dir.join("endurance-frey-law-avin.svg");

    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900, 600)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(&path, e))?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                "Endurance time: Frey-Law & Avin (2010) per region vs Eq. 8",
                ("sans-serif", 20),
            )
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(60)
            .build_cartesian_2d(20f64..100f64, (0.01f64..100f64).log_scale())
            .map_err(|e| err(&path, e))?;
        chart
            .configure_mesh()
            .x_desc("%MVC")
            .y_desc("endurance [min] (log scale)")
            .draw()
            .map_err(|e| err(&path, e))?;
        for (j, a) in v.frey_law_avin.iter().enumerate() {
            let color = Palette99::pick(j).to_rgba();
            let pts: Vec<(f64, f64)> = (21..=99)
                .map(|i| (i as f64, a.b0_s * (i as f64 / 100.0).powf(a.b1) / 60.0))
                .collect();
            chart
                .draw_series(LineSeries::new(pts, color.stroke_width(2)))
                .map_err(|e| err(&path, e))?
                .label(format!(
                    "{} (fitted k = {:.2} /min)",
                    a.region, a.fitted_k_per_min
                ))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
        }
        let pts: Vec<(f64, f64)> = (21..=99)
            .map(|i| {
                (
                    i as f64,
                    crate::fatigue::met_min(i as f64 / 100.0, v.k_per_min),
                )
            })
            .collect();
        chart
            .draw_series(LineSeries::new(pts, BLACK.stroke_width(4)))
            .map_err(|e| err(&path, e))?
            .label(format!("dynamic model, Eq. 8, k = {}", v.k_per_min))
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(4)));
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(|e| err(&path, e))?;
        root.present().map_err(|e| err(&path, e))?;
    }
    out.push((path, svg));
    write_figures(out)
}
