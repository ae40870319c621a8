//! Text for the reports: escaping, numbers that never print as NaN or infinity ("—" instead),
//! durations, severity levels and tables.

use std::fmt::Write;

/// What is shown for a missing or non-finite value.
pub const DASH: &str = "—";

/// Escapes text for HTML and SVG (element content and quoted attributes).
pub fn esc(s: &str) -> String {
    let mut o = String::with_capacity(s.len() + 8);
    for c in s.chars() {
        match c {
            '&' => o.push_str("&amp;"),
            '<' => o.push_str("&lt;"),
            '>' => o.push_str("&gt;"),
            '"' => o.push_str("&quot;"),
            '\'' => o.push_str("&#39;"),
            _ => o.push(c),
        }
    }
    o
}

/// `x` with `dp` decimals; "—" when not finite; no "-0".
pub fn num(x: f64, dp: usize) -> String {
    if !x.is_finite() {
        return DASH.into();
    }
    let s = format!("{x:.dp$}");
    if s.starts_with('-') && s[1..].chars().all(|c| c == '0' || c == '.') {
        s[1..].to_string()
    } else {
        s
    }
}

/// A fraction as a percentage with `dp` decimals ("37 %").
pub fn pct_dp(x: f64, dp: usize) -> String {
    if x.is_finite() {
        format!("{}\u{a0}%", num(100.0 * x, dp))
    } else {
        DASH.into()
    }
}

/// A fraction as a whole percentage ("37 %").
pub fn pct(x: f64) -> String {
    pct_dp(x, 0)
}

/// A share of people strong enough, as a whole percentage rounded down: 98.6 % reads "98 %",
/// never the 99 % design limit it falls short of.
pub fn share(x: f64) -> String {
    if x.is_finite() {
        format!(
            "{}\u{a0}%",
            num(crate::assess::share_percent_floor(x, 0), 0)
        )
    } else {
        DASH.into()
    }
}

/// A value with its unit, joined by a non-breaking space ("1.52 m"); "—" when not finite.
pub fn unit(x: f64, dp: usize, u: &str) -> String {
    if x.is_finite() {
        format!("{}\u{a0}{u}", num(x, dp))
    } else {
        DASH.into()
    }
}

/// A length in millimetres from metres ("12 mm").
pub fn mm(m: f64) -> String {
    unit(1000.0 * m, 0, "mm")
}

/// A duration from seconds: "45 s", "6.6 min", "2.3 h", "3.1 days".
pub fn dur(s: f64) -> String {
    if !s.is_finite() {
        return DASH.into();
    }
    if s.abs() < 120.0 {
        unit(s, if s.abs() < 10.0 { 1 } else { 0 }, "s")
    } else if s.abs() < 2.0 * 3600.0 {
        unit(s / 60.0, 1, "min")
    } else if s.abs() < 2.0 * 86400.0 {
        unit(s / 3600.0, 1, "h")
    } else {
        unit(s / 86400.0, 1, "days")
    }
}

/// An optional value, formatted, or "—".
pub fn opt<T>(o: Option<T>, f: impl FnOnce(T) -> String) -> String {
    o.map(f).unwrap_or_else(|| DASH.into())
}

/// The first letter in upper case.
pub fn capitalise(s: &str) -> String {
    let mut c = s.chars();
    match c.next() {
        Some(f) => f.to_uppercase().chain(c).collect(),
        None => String::new(),
    }
}

/// How a finding or a row is to be read.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Level {
    Bad,
    Warn,
    Ok,
    Info,
}

impl Level {
    pub fn class(self) -> &'static str {
        match self {
            Level::Bad => "bad",
            Level::Warn => "warn",
            Level::Ok => "ok",
            Level::Info => "info",
        }
    }
    pub fn label(self) -> &'static str {
        match self {
            Level::Bad => "problem",
            Level::Warn => "caution",
            Level::Ok => "fine",
            Level::Info => "note",
        }
    }
}

/// A finding: its level and its text as HTML (every user-given part already escaped).
#[derive(Debug, Clone)]
pub struct Finding {
    pub level: Level,
    pub html: String,
    /// Listed first whatever its level.
    pub pinned: bool,
}

impl Finding {
    pub fn new(level: Level, html: String) -> Self {
        Finding {
            level,
            html,
            pinned: false,
        }
    }
    pub fn pinned(mut self) -> Self {
        self.pinned = true;
        self
    }
}

/// A badge with the level's label.
pub fn badge(level: Level) -> String {
    format!(
        "<span class=\"badge {}\">{}</span>",
        level.class(),
        level.label()
    )
}

/// Findings as a list, worst first (stable within a level).
pub fn findings_list(f: &[Finding]) -> String {
    let mut v: Vec<&Finding> = f.iter().collect();
    v.sort_by_key(|x| (!x.pinned, x.level));
    let mut o = String::from("<ul class=\"findings\">");
    for x in v {
        let _ = write!(
            o,
            "<li class=\"{}\">{} {}</li>",
            x.level.class(),
            badge(x.level),
            x.html
        );
    }
    o.push_str("</ul>");
    o
}

/// A table: header cells and rows of HTML cells (already escaped), with an optional class per
/// row; columns listed in `numeric` are right-aligned.
#[derive(Debug, Default)]
pub struct Table {
    class: String,
    head: Vec<String>,
    numeric: Vec<usize>,
    rows: Vec<(Option<Level>, Vec<String>)>,
}

impl Table {
    /// A table with plain-text headings (escaped here).
    pub fn new(class: &str, head: &[&str]) -> Self {
        Table {
            class: class.into(),
            head: head.iter().map(|h| esc(h)).collect(),
            numeric: Vec::new(),
            rows: Vec::new(),
        }
    }
    /// Right-aligns these columns.
    pub fn numeric(mut self, cols: &[usize]) -> Self {
        self.numeric = cols.to_vec();
        self
    }
    pub fn row(&mut self, level: Option<Level>, cells: Vec<String>) {
        self.rows.push((level, cells));
    }
    pub fn render(&self) -> String {
        let mut o = String::new();
        let _ = write!(o, "<table class=\"{}\"><thead><tr>", esc(&self.class));
        for (i, h) in self.head.iter().enumerate() {
            let n = if self.numeric.contains(&i) {
                " class=\"n\""
            } else {
                ""
            };
            let _ = write!(o, "<th{n}>{h}</th>");
        }
        o.push_str("</tr></thead><tbody>");
        for (level, cells) in &self.rows {
            match level {
                Some(l) => {
                    let _ = write!(o, "<tr class=\"{}\">", l.class());
                }
                None => o.push_str("<tr>"),
            }
            for (i, c) in cells.iter().enumerate() {
                let n = if self.numeric.contains(&i) {
                    " class=\"n\""
                } else {
                    ""
                };
                let _ = write!(o, "<td{n}>{c}</td>");
            }
            o.push_str("</tr>");
        }
        o.push_str("</tbody></table>");
        o
    }
}

/// A two-column table of (heading, HTML value) rows.
pub fn kv_table(rows: &[(&str, String)]) -> String {
    let mut o = String::from("<table class=\"kv\"><tbody>");
    for (k, v) in rows {
        let _ = write!(o, "<tr><th>{}</th><td>{}</td></tr>", esc(k), v);
    }
    o.push_str("</tbody></table>");
    o
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_never_print_nan_or_infinity() {
        assert_eq!(num(f64::NAN, 2), DASH);
        assert_eq!(num(f64::INFINITY, 0), DASH);
        assert_eq!(num(-0.0001, 2), "0.00");
        assert_eq!(pct(0.371), "37\u{a0}%");
        assert_eq!(dur(f64::NEG_INFINITY), DASH);
        assert_eq!(dur(394.0), "6.6\u{a0}min");
        assert_eq!(esc("<b>&\"x\"'"), "&lt;b&gt;&amp;&quot;x&quot;&#39;");
    }
}
