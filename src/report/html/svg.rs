//! A small SVG writer for the figures: every coordinate is checked to be finite (an element
//! with a non-finite coordinate is left out), every text escaped. Figures are inline `<svg>`
//! elements: they use the page's font and need no ids (nested `<svg>` viewports clip).

use super::fmt::esc;
use std::fmt::Write;

/// An SVG element being written.
pub struct Svg {
    out: String,
    open: usize,
}

fn ok(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// A coordinate with one decimal.
fn c(x: f64) -> String {
    let s = format!("{x:.1}");
    if s == "-0.0" { "0.0".into() } else { s }
}

/// Points as an SVG `points` attribute.
fn points(pts: &[(f64, f64)]) -> String {
    let mut s = String::with_capacity(pts.len() * 12);
    for (i, p) in pts.iter().enumerate() {
        if i > 0 {
            s.push(' ');
        }
        let _ = write!(s, "{},{}", c(p.0), c(p.1));
    }
    s
}

impl Svg {
    /// An SVG `w`×`h` px, described by `label` (screen readers, tests).
    pub fn new(w: f64, h: f64, label: &str) -> Self {
        let (w, h) = (w.max(1.0).ceil(), h.max(1.0).ceil());
        let mut out = String::new();
        let _ = write!(
            out,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" role=\"img\" aria-label=\"{}\">",
            esc(label)
        );
        Svg { out, open: 0 }
    }

    /// A nested, clipping viewport at (x, y), `w`×`h` px, with its own user coordinates.
    pub fn viewport(&mut self, x: f64, y: f64, w: f64, h: f64) {
        if ok(&[x, y, w, h]) {
            let _ = write!(
                self.out,
                "<svg x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" overflow=\"hidden\">",
                c(x),
                c(y),
                c(w.max(0.0)),
                c(h.max(0.0))
            );
        } else {
            self.out.push_str("<svg width=\"0\" height=\"0\">");
        }
        self.open += 1;
    }

    /// Closes the innermost viewport.
    pub fn end_viewport(&mut self) {
        if self.open > 0 {
            self.out.push_str("</svg>");
            self.open -= 1;
        }
    }

    pub fn line(&mut self, x1: f64, y1: f64, x2: f64, y2: f64, style: &str) {
        if ok(&[x1, y1, x2, y2]) {
            let _ = write!(
                self.out,
                "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" {style}/>",
                c(x1),
                c(y1),
                c(x2),
                c(y2)
            );
        }
    }

    pub fn polyline(&mut self, pts: &[(f64, f64)], style: &str) {
        let pts: Vec<(f64, f64)> = pts.iter().copied().filter(|p| ok(&[p.0, p.1])).collect();
        if pts.len() >= 2 {
            let _ = write!(
                self.out,
                "<polyline points=\"{}\" fill=\"none\" {style}/>",
                points(&pts)
            );
        }
    }

    /// A polygon; `title` (escaped) shows on hover.
    pub fn polygon(&mut self, pts: &[(f64, f64)], style: &str, title: Option<&str>) {
        if pts.len() >= 2 && pts.iter().all(|p| ok(&[p.0, p.1])) {
            match title {
                Some(t) => {
                    let _ = write!(
                        self.out,
                        "<polygon points=\"{}\" {style}><title>{}</title></polygon>",
                        points(pts),
                        esc(t)
                    );
                }
                None => {
                    let _ = write!(self.out, "<polygon points=\"{}\" {style}/>", points(pts));
                }
            }
        }
    }

    pub fn rect(&mut self, x: f64, y: f64, w: f64, h: f64, style: &str) {
        if ok(&[x, y, w, h]) {
            let _ = write!(
                self.out,
                "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" {style}/>",
                c(x),
                c(y),
                c(w.max(0.0)),
                c(h.max(0.0))
            );
        }
    }

    pub fn circle(&mut self, x: f64, y: f64, r: f64, style: &str) {
        if ok(&[x, y, r]) {
            let _ = write!(
                self.out,
                "<circle cx=\"{}\" cy=\"{}\" r=\"{}\" {style}/>",
                c(x),
                c(y),
                c(r.max(0.0))
            );
        }
    }

    /// A path from pre-built data (only numbers and commands, built by the caller).
    pub fn path(&mut self, d: &str, style: &str) {
        if !d.is_empty() && !d.contains("NaN") && !d.contains("inf") {
            let _ = write!(self.out, "<path d=\"{d}\" {style}/>");
        }
    }

    /// Text at (x, y) (escaped); `attrs` are the element's other attributes.
    pub fn text(&mut self, x: f64, y: f64, s: &str, attrs: &str) {
        if ok(&[x, y]) {
            let _ = write!(
                self.out,
                "<text x=\"{}\" y=\"{}\" {attrs}>{}</text>",
                c(x),
                c(y),
                esc(s)
            );
        }
    }

    /// Closes the figure.
    pub fn finish(mut self) -> String {
        while self.open > 0 {
            self.end_viewport();
        }
        self.out.push_str("</svg>");
        self.out
    }
}

/// Round tick values covering [lo, hi] with about `n` intervals.
pub fn nice_ticks(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    if !(lo.is_finite() && hi.is_finite()) || hi <= lo || n == 0 {
        return vec![];
    }
    let raw = (hi - lo) / n as f64;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 2.5, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * mag);
    let first = (lo / step - 1e-9).ceil() as i64;
    let last = (hi / step + 1e-9).floor() as i64;
    (first..=last).map(|i| i as f64 * step).collect()
}

/// Decimals needed to print ticks of this spacing exactly (at most 4).
pub fn tick_decimals(ticks: &[f64]) -> usize {
    if ticks.len() < 2 {
        return 0;
    }
    let step = (ticks[1] - ticks[0]).abs();
    (0..4)
        .find(|&d| {
            let x = step * 10f64.powi(d as i32);
            (x - x.round()).abs() < 1e-6
        })
        .unwrap_or(4)
}

/// A linear map from data to pixels for one axis.
#[derive(Debug, Clone, Copy)]
pub struct Scale {
    pub d0: f64,
    pub d1: f64,
    pub p0: f64,
    pub p1: f64,
}

impl Scale {
    pub fn map(&self, x: f64) -> f64 {
        let span = self.d1 - self.d0;
        if span.abs() < 1e-300 {
            return self.p0;
        }
        self.p0 + (x - self.d0) / span * (self.p1 - self.p0)
    }
}

/// Spreads label positions (sorted or not) so that neighbours are at least `gap` apart within
/// [lo, hi]; returns the new positions in the input order.
pub fn spread(ys: &[f64], gap: f64, lo: f64, hi: f64) -> Vec<f64> {
    let mut idx: Vec<usize> = (0..ys.len()).collect();
    idx.sort_by(|a, b| ys[*a].total_cmp(&ys[*b]));
    let mut pos: Vec<f64> = idx.iter().map(|&i| ys[i].clamp(lo, hi)).collect();
    for k in 1..pos.len() {
        if pos[k] < pos[k - 1] + gap {
            pos[k] = pos[k - 1] + gap;
        }
    }
    if let Some(last) = pos.last().copied()
        && last > hi
    {
        let shift = last - hi;
        for p in pos.iter_mut() {
            *p -= shift;
        }
        for k in (0..pos.len().saturating_sub(1)).rev() {
            if pos[k] > pos[k + 1] - gap {
                pos[k] = pos[k + 1] - gap;
            }
        }
    }
    let mut out = vec![0.0; ys.len()];
    for (k, &i) in idx.iter().enumerate() {
        out[i] = pos[k];
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round() {
        assert_eq!(
            nice_ticks(0.0, 1.0, 5),
            vec![0.0, 0.2, 0.4, 0.6000000000000001, 0.8, 1.0]
        );
        assert_eq!(tick_decimals(&[0.0, 0.2]), 1);
        assert_eq!(tick_decimals(&[0.0, 0.25]), 2);
        assert_eq!(tick_decimals(&[0.0, 10.0]), 0);
        assert!(nice_ticks(1.0, f64::NAN, 4).is_empty());
    }

    #[test]
    fn labels_are_spread() {
        let s = spread(&[10.0, 11.0, 12.0], 5.0, 0.0, 100.0);
        assert!(s[1] - s[0] >= 5.0 - 1e-9 && s[2] - s[1] >= 5.0 - 1e-9);
        let s = spread(&[99.0, 100.0], 5.0, 0.0, 100.0);
        assert!(s.iter().all(|y| *y <= 100.0));
    }

    #[test]
    fn non_finite_elements_are_left_out() {
        let mut s = Svg::new(10.0, 10.0, "t");
        s.line(0.0, f64::NAN, 1.0, 1.0, "");
        s.text(1.0, 1.0, "<a>", "");
        let o = s.finish();
        assert!(!o.contains("NaN") && !o.contains("<line") && o.contains("&lt;a&gt;"));
    }
}
