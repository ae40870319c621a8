//! The HTML reports of `plan`, `compare` and `sweep`: self-contained, well-formed, complete,
//! escaping what task files say, never printing NaN or infinity; and, where Chromium is present,
//! printed to PDF and rendered to a screenshot by a real headless browser.
//!
//! The browser part runs when `chromium` (or another Chromium binary) is on the PATH, and must
//! run when `POSTURE_OPT_REQUIRE_CHROMIUM=1` (CI sets it): then a missing browser fails the test.
//! Run with `cargo test --release --test suite -- html_report::` (planning is slow without optimisation);
//! with `POSTURE_OPT_REPORT_DIR=DIR` the three reports are also written to DIR, to look at.

use posture_opt::assess::{Assessment, assess};
use posture_opt::body::{Sex, Worker};
use posture_opt::plan::result::Exhaustion;
use posture_opt::plan::{Plan, PlanOptions, Task, plan_task_with};
use posture_opt::report::html::{compare_report, plan_report, sweep_report};
use posture_opt::study::compare::{self, Comparison, Planned};
use posture_opt::study::sweep::{Problem, Sweep, WorkerOutcome};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use crate::common;
use common::run;

/// The phase and obstacle name every report must escape.
const NASTY: &str = r#"<b>&"x""#;
const NASTY_ESCAPED: &str = "&lt;b&gt;&amp;&quot;x&quot;";

/// A short two-handed task with a lift, a generated worker, and names that need escaping.
fn quick_yaml(board_z: f64, cycles: u32) -> String {
    format!(
        r#"name: 'Quick shelf <test> & "check"'
worker: {{sex: female, stature_m: 1.62, mass_kg: 62.0, strength_percentile: 40}}
workstation:
  obstacles:
    - {{name: '{NASTY}', box: {{size_m: [0.40, 1.20, 0.02]}}, position_m: [0.75, -0.10, {board_z}]}}
    - {{name: cart, box: {{size_m: [0.50, 0.40, 0.80]}}, position_m: [0.40, -0.65, 0.40]}}
    - {{name: floor, plane: {{normal: [0, 0, 1]}}, position_m: [0, 0, 0]}}
phases:
  - {{name: '{NASTY}', object: {{center_m: [0.40, -0.50, 0.92], grip_width_m: 0.30, size_m: [0.25, 0.30, 0.20]}}, load_kg: 0.0, duration_s: 2.0}}
  - {{name: lift, object: {{center_m: [0.38, -0.45, 0.95], grip_width_m: 0.30, size_m: [0.25, 0.30, 0.20]}}, load_kg: 4.0, duration_s: 2.0}}
  - {{name: place, object: {{center_m: [0.52, -0.15, {place_z}], grip_width_m: 0.30, size_m: [0.25, 0.30, 0.20]}}, load_kg: 4.0, duration_s: 3.0}}
lifts:
  - {{name: box to shelf, origin: lift, destination: place}}
rest_s: 6.0
cycles: {cycles}
"#,
        place_z = board_z + 0.13
    )
}

fn write_task(dir: &Path, name: &str, yaml: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, yaml).unwrap();
    p
}

struct Planned1 {
    task: Task,
    plan: Plan,
    assessment: Assessment,
}

/// The quick task planned and assessed once for every test.
fn planned() -> &'static Planned1 {
    static P: OnceLock<Planned1> = OnceLock::new();
    P.get_or_init(|| {
        let dir = tempfile::tempdir().unwrap();
        let path = write_task(dir.path(), "quick.yaml", &quick_yaml(1.09, 6));
        let task = Task::from_file(&path).unwrap();
        let plan = plan_task_with(&task, PlanOptions::default()).unwrap();
        let assessment = assess(&task, &plan, 0.7);
        Planned1 {
            task,
            plan,
            assessment,
        }
    })
}

fn plan_html() -> &'static str {
    static H: OnceLock<String> = OnceLock::new();
    H.get_or_init(|| {
        let p = planned();
        plan_report(&p.task, &p.plan, &p.assessment, &[]).unwrap()
    })
}

/// Two layouts of the quick task planned and compared once.
fn compare_html() -> &'static (String, Comparison) {
    static H: OnceLock<(String, Comparison)> = OnceLock::new();
    H.get_or_init(|| {
        let dir = tempfile::tempdir().unwrap();
        let files: Vec<String> = [("low.yaml", 1.09), ("high.yaml", 1.30)]
            .iter()
            .map(|(n, z)| {
                write_task(dir.path(), n, &quick_yaml(*z, 4))
                    .display()
                    .to_string()
            })
            .collect();
        let tasks: Vec<Task> = files.iter().map(|f| Task::from_file(f).unwrap()).collect();
        let opts = PlanOptions {
            baselines: false,
            ..PlanOptions::default()
        };
        let (c, planned): (Comparison, Vec<Planned>) =
            compare::compare(&files, &tasks, opts, 0.7, &|| {}).unwrap();
        let ordered: Vec<&Task> = c.layouts.iter().map(|o| &tasks[o.index]).collect();
        (compare_report(&c, &ordered, &planned).unwrap(), c)
    })
}

fn outcome(
    index: usize,
    label: &str,
    sex: Sex,
    stature_m: f64,
    problems: Vec<Problem>,
) -> WorkerOutcome {
    let exhaustion = problems.iter().find_map(|p| match p {
        Problem::Exhaustion {
            t_s,
            group,
            phase,
            load,
        } => Some(Exhaustion {
            t_s: *t_s,
            half_joint: "r_shoulder_flexion+".into(),
            group: group.clone(),
            phase: phase.clone(),
            load: *load,
            exceeds_strength: false,
        }),
        _ => None,
    });
    WorkerOutcome {
        index,
        label: label.into(),
        worker: Worker {
            sex,
            stature_m,
            mass_kg: 70.0,
            strength_percentile: 10.0 + 20.0 * index as f64,
        },
        can_do: problems.is_empty(),
        problems,
        could_not_plan: Vec::new(),
        retried_from: None,
        total_u_min: 12.5,
        simulated_s: 3600.0,
        worst_group: "right shoulder flexors".into(),
        lowest_capacity: 0.42,
        lowest_capacity_group: "right shoulder flexors".into(),
        minutes_to_exhaustion: if index == 0 { None } else { Some(95.0) },
        exhaustion_verdict: if index == 0 { "never" } else { "gives_out" }.into(),
        shift_status: posture_opt::assess::verdict::Status::Acceptable,
        shift_verdict:
            "acceptable: this pace can be kept up indefinitely by every criterion checked".into(),
        minutes_followed: if index == 0 { 7.0 * 24.0 * 60.0 } else { 95.0 },
        exhaustion,
        rula_max: Some(5),
        reba_max: None,
        back_compression_max_n: Some(2100.0),
        rest_needed_s: if index == 1 { None } else { Some(4.5) },
        exhausted_in_variants: Some(index.min(9)),
    }
}

fn sweep_html() -> &'static str {
    static H: OnceLock<String> = OnceLock::new();
    H.get_or_init(|| {
        let workers = vec![
            outcome(0, "P50 woman", Sex::Female, 1.625, vec![]),
            outcome(
                1,
                NASTY,
                Sex::Male,
                1.64,
                vec![
                    Problem::Exhaustion {
                        t_s: 1234.0,
                        group: "right shoulder flexors".into(),
                        phase: NASTY.into(),
                        load: 0.41,
                    },
                    Problem::OutOfReach {
                        phase: "place".into(),
                        hand_error_m: 0.034,
                        proven: true,
                    },
                ],
            ),
            outcome(
                2,
                "#002",
                Sex::Female,
                1.52,
                vec![
                    Problem::ExceedsStrength {
                        group: "left shoulder flexors".into(),
                        phase: "place".into(),
                        load: 1.2,
                    },
                    Problem::Collision {
                        phase: "lift".into(),
                        clearance_m: -0.012,
                        with: Some("cart".into()),
                    },
                    Problem::OffBalance {
                        phase: "lift".into(),
                        margin_m: -0.02,
                    },
                ],
            ),
            outcome(3, "#003", Sex::Male, 1.87, vec![]),
        ];
        let s = Sweep::from_outcomes(NASTY, "sampled (n = 4, seed 1)", true, true, 0.7, workers);
        sweep_report(&s, None).unwrap()
    })
}

/// Void elements: no closing tag.
const VOID: [&str; 6] = ["meta", "br", "hr", "img", "input", "link"];

/// Every element opened is closed, in order (a small tag parser: the reports write no raw `<`
/// or `>` inside text or attributes, and no `<` inside their style sheet).
fn assert_well_formed(html: &str) {
    let mut stack: Vec<String> = Vec::new();
    let mut rest = html;
    while let Some(i) = rest.find('<') {
        rest = &rest[i + 1..];
        let end = rest.find('>').expect("a tag is not closed by '>'");
        let tag = &rest[..end];
        rest = &rest[end + 1..];
        if tag.starts_with('!') {
            continue;
        }
        assert!(!tag.contains('<'), "'<' inside a tag: {tag}");
        if let Some(name) = tag.strip_prefix('/') {
            let name = name.trim();
            let open = stack
                .pop()
                .unwrap_or_else(|| panic!("</{name}> closes nothing"));
            assert_eq!(open, name, "<{open}> closed by </{name}>");
            continue;
        }
        let name: String = tag
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric())
            .collect::<String>()
            .to_ascii_lowercase();
        assert!(!name.is_empty(), "bad tag <{tag}>");
        if tag.ends_with('/') || VOID.contains(&name.as_str()) {
            continue;
        }
        if name == "style" {
            let close = rest.find("</style>").expect("<style> not closed");
            rest = &rest[close + "</style>".len()..];
            continue;
        }
        stack.push(name);
    }
    assert!(stack.is_empty(), "never closed: {stack:?}");
}

/// The text without its tags.
fn text_of(html: &str) -> String {
    let mut out = String::with_capacity(html.len());
    let mut in_tag = false;
    for c in html.chars() {
        match c {
            '<' => in_tag = true,
            '>' => {
                in_tag = false;
                out.push(' ');
            }
            _ if !in_tag => out.push(c),
            _ => {}
        }
    }
    out
}

/// No NaN, no infinity, no "undefined", as words or inside numbers, in the text or the markup.
fn assert_no_bad_numbers(html: &str) {
    for bad in ["NaN", "undefined", "Infinity"] {
        assert!(!html.contains(bad), "'{bad}' in the report");
    }
    let b = html.as_bytes();
    let mut from = 0;
    while let Some(i) = html[from..].find("inf") {
        let at = from + i;
        let before = at.checked_sub(1).map(|j| b[j]);
        let after = b.get(at + 3).copied();
        let letter = |c: Option<u8>| c.is_some_and(|c| c.is_ascii_alphabetic());
        assert!(
            letter(before) || letter(after),
            "'inf' as a value near: {}",
            &html[at.saturating_sub(60)..(at + 40).min(html.len())]
        );
        from = at + 3;
    }
}

fn assert_self_contained(html: &str) {
    assert!(html.starts_with("<!DOCTYPE html>"));
    assert!(html.trim_end().ends_with("</html>"));
    for external in [
        "src=", "href=", "<script", "@import", "url(", "<link", "<img", "<iframe",
    ] {
        assert!(
            !html.contains(external),
            "external resource or script: {external}"
        );
    }
    let http = html.matches("http").count();
    let xmlns = html.matches("http://www.w3.org/2000/svg").count();
    assert_eq!(http, xmlns, "only SVG namespaces may mention http");
    assert!(html.contains("@media print"), "print style sheet");
    assert!(html.contains("@page"), "page size for printing");
}

/// Writes a report to `$POSTURE_OPT_REPORT_DIR`, when set.
fn keep(name: &str, html: &str) {
    if let Some(dir) = std::env::var_os("POSTURE_OPT_REPORT_DIR") {
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(Path::new(&dir).join(name), html).unwrap();
    }
}

fn assert_sound(html: &str) {
    assert_self_contained(html);
    assert_well_formed(html);
    assert_no_bad_numbers(html);
    assert!(!html.contains(NASTY), "an unescaped name");
}

#[test]
fn the_checks_catch_what_they_look_for() {
    let fails = |f: fn()| std::panic::catch_unwind(f).is_err();
    assert!(fails(|| assert_well_formed("<div><p></div>")));
    assert!(fails(|| assert_well_formed("<section><div></div>")));
    assert!(fails(|| assert_well_formed("</td>")));
    assert_well_formed("<div><br><svg><rect x=\"1\"/></svg><style>a>b{}</style></div>");
    assert!(fails(|| assert_no_bad_numbers("<td>1.5 inf</td>")));
    assert!(fails(|| assert_no_bad_numbers("x=\"-inf\"")));
    assert!(fails(|| assert_no_bad_numbers("<td>NaN</td>")));
    assert_no_bad_numbers("information, infeasible, Buchanan");
    assert!(fails(|| assert_self_contained(
        "<!DOCTYPE html><img src=\"x.png\"></html>"
    )));
}

#[test]
fn plan_report_is_self_contained_well_formed_and_complete() {
    let p = planned();
    let html = plan_html();
    keep("plan.html", html);
    assert_sound(html);
    // the title escapes the task name
    assert!(html.contains("<title>Plan: Quick shelf &lt;test&gt; &amp; &quot;check&quot;</title>"));
    // findings first, with a verdict
    let verdict = html.find("class=\"verdict").unwrap();
    let findings = html.find("<h2>Findings</h2>").unwrap();
    assert!(verdict < findings && findings < html.find("<h2>Postures</h2>").unwrap());
    assert!(html.contains("Hardest phase"));
    // the worker
    let text = text_of(html);
    for w in [
        "female",
        "1.620\u{a0}m",
        "62.0\u{a0}kg",
        "strength percentile",
        "40 (of the worker’s sex)",
    ] {
        assert!(text.contains(w), "worker: {w}");
    }
    // every phase: in the table, a card, three views
    for ph in &p.task.phases {
        let name = ph
            .name
            .replace('&', "&amp;")
            .replace('<', "&lt;")
            .replace('>', "&gt;")
            .replace('"', "&quot;");
        assert!(
            html.matches(name.as_str()).count() >= 3,
            "phase {}",
            ph.name
        );
    }
    assert!(html.contains(NASTY_ESCAPED));
    let n = p.task.phases.len();
    for view in ["side view", "front view", "top view"] {
        assert_eq!(
            html.matches(&format!("aria-label=\"{view} — ")).count(),
            n,
            "{view}s"
        );
    }
    // obstacles named in the figures (the floor is drawn as such)
    assert!(html.contains(&format!("<title>{NASTY_ESCAPED}</title>")));
    assert!(html.contains("<title>cart</title>"));
    assert!(html.contains("<title>held object</title>"));
    // capacity curves: the overview and one panel per group
    assert!(html.contains("aria-label=\"capacity over time, the groups that fall lowest\""));
    assert!(html.contains("aria-label=\"capacity over time, one panel per muscle group\""));
    // what an ergonomist looks for
    for needle in [
        "RULA",
        "REBA",
        "L5/S1",
        "3400\u{a0}N",
        "6400\u{a0}N",
        "of women",
        "of men",
        "lifting index",
        "Rohmert (1973) rest allowance",
        "How much the muscle parameters matter",
        "tires fastest",
        "Against simpler ways to choose postures",
        "fatigue unaware",
        "right shoulder flexors",
        "Strength sources",
        "lowest capacity at any time",
    ] {
        assert!(html.contains(needle), "missing: {needle}");
    }
    // every muscle group's parameters, with its k
    for h in &p.plan.half_joints {
        assert!(
            html.contains(&format!("<small>{}</small>", h.id)),
            "{}",
            h.id
        );
    }
    // big sections are marked as such
    assert!(html.matches("<section class=\"major\">").count() >= 3);
}

#[test]
fn compare_report_has_every_layout_in_ranked_order() {
    let (html, c) = compare_html();
    keep("compare.html", html);
    assert_sound(html);
    assert_eq!(c.layouts.len(), 2);
    assert!(html.contains("<h2>Ranking</h2>"));
    assert!(html.contains("How robust is the ranking?"));
    // the cards in ranked order, each with its hardest phase drawn
    let mut last = 0;
    for o in &c.layouts {
        let head = format!("<h3>#{} ", o.rank);
        let at = html
            .find(&head)
            .unwrap_or_else(|| panic!("card {}", o.rank));
        assert!(at > last, "cards in ranked order");
        last = at;
        assert!(html.contains(&fmt_esc(&o.file)), "{}", o.file);
    }
    assert_eq!(html.matches("aria-label=\"side view — #").count(), 2);
    assert!(html.contains("Hardest phase"));
    for f in &c.findings {
        assert!(html.contains(&fmt_esc(&f[1..])), "finding {f}");
    }
    for r in &c.robustness {
        assert!(html.contains(&format!("{} of {}", r.wins, r.variants)));
    }
}

fn fmt_esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
        .replace('\'', "&#39;")
}

#[test]
fn sweep_report_says_who_cannot_and_why() {
    let html = sweep_html();
    keep("sweep.html", html);
    assert_sound(html);
    assert!(html.contains("2 of 4 workers cannot do the task"));
    for label in ["P50 woman", "#002", "#003", NASTY_ESCAPED] {
        assert!(html.contains(&format!("<td>{label}</td>")), "{label}");
    }
    for why in [
        "exceeds strength (120 % MVC)",
        "exhausted at 20.6 min",
        "out of reach by 34 mm",
        "collides (12 mm into cart)",
        "off balance (20 mm outside the feet)",
    ] {
        assert!(html.contains(why), "{why}");
    }
    assert_eq!(html.matches("<b>cannot</b>").count(), 2);
    // the shares with their 95 % intervals, and the note about U
    assert!(html.contains("95 % CI"));
    assert!(html.contains(
        "aria-label=\"share who can do the whole task, with 95 % confidence intervals\""
    ));
    assert!(html.contains("U is summed over the simulated time"));
}

fn chromium() -> Option<PathBuf> {
    for name in ["chromium", "chromium-browser", "google-chrome", "chrome"] {
        if let Ok(out) = Command::new("which").arg(name).output()
            && out.status.success()
        {
            let p = String::from_utf8_lossy(&out.stdout).trim().to_string();
            if !p.is_empty() {
                return Some(PathBuf::from(p));
            }
        }
    }
    None
}

/// Runs the browser on `page` with `args`, at most two minutes.
fn browse(browser: &Path, dir: &Path, page: &Path, args: &[String]) -> std::process::Output {
    let profile = tempfile::tempdir_in(dir).unwrap();
    Command::new("timeout")
        .arg("120")
        .arg(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--hide-scrollbars",
        ])
        .arg(format!("--user-data-dir={}", profile.path().display()))
        .args(args)
        .arg(format!("file://{}", page.display()))
        .output()
        .unwrap()
}

/// Pages of a PDF (its page objects).
fn pdf_pages(pdf: &[u8]) -> usize {
    let s = String::from_utf8_lossy(pdf);
    s.match_indices("/Type /Page")
        .filter(|(i, _)| !s[i + "/Type /Page".len()..].starts_with('s'))
        .count()
        + s.match_indices("/Type/Page")
            .filter(|(i, _)| !s[i + "/Type/Page".len()..].starts_with('s'))
            .count()
}

/// Checks a screenshot: it decodes, has the window's size and is not one colour.
fn assert_screenshot(png_path: &Path, w: u32, h: u32) {
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(png_path).unwrap(),
    ));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (w, h));
    let channels = info.color_type.samples();
    assert!(channels >= 3);
    let img = &buf[..info.buffer_size()];
    let mut colours = std::collections::HashSet::new();
    let mut white = 0usize;
    for p in img.chunks(channels) {
        colours.insert((p[0], p[1], p[2]));
        if p[0] > 250 && p[1] > 250 && p[2] > 250 {
            white += 1;
        }
    }
    let n = (w * h) as usize;
    assert!(colours.len() > 50, "{} colours only", colours.len());
    assert!(
        white < n * 98 / 100,
        "almost blank: {white} of {n} pixels white"
    );
    assert!(white > n / 20, "no background: {white} of {n} pixels white");
}

#[test]
fn reports_print_to_pdf_and_render_in_headless_chromium() {
    let required = std::env::var("POSTURE_OPT_REQUIRE_CHROMIUM").is_ok_and(|v| v == "1");
    let Some(browser) = chromium() else {
        assert!(
            !required,
            "POSTURE_OPT_REQUIRE_CHROMIUM=1 but no chromium was found on the PATH"
        );
        eprintln!("chromium not found: browser rendering skipped (apt-get install chromium)");
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let reports = [
        ("plan", plan_html().to_string(), 3),
        ("compare", compare_html().0.clone(), 2),
        ("sweep", sweep_html().to_string(), 1),
    ];
    for (name, html, min_pages) in reports {
        let page = dir.path().join(format!("{name}.html"));
        std::fs::write(&page, &html).unwrap();
        let pdf = dir.path().join(format!("{name}.pdf"));
        let out = browse(
            &browser,
            dir.path(),
            &page,
            &[
                format!("--print-to-pdf={}", pdf.display()),
                "--no-pdf-header-footer".into(),
            ],
        );
        let bytes = std::fs::read(&pdf)
            .unwrap_or_else(|_| panic!("{name}: no PDF: {}", String::from_utf8_lossy(&out.stderr)));
        assert!(bytes.starts_with(b"%PDF"), "{name}: not a PDF");
        let pages = pdf_pages(&bytes);
        assert!(pages >= min_pages, "{name}: {pages} pages");
        assert!(
            bytes.len() > 20_000 * min_pages,
            "{name}: {} bytes",
            bytes.len()
        );
        let shot = dir.path().join(format!("{name}.png"));
        let out = browse(
            &browser,
            dir.path(),
            &page,
            &[
                format!("--screenshot={}", shot.display()),
                "--window-size=1100,1600".into(),
            ],
        );
        assert!(
            shot.exists(),
            "{name}: no screenshot: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert_screenshot(&shot, 1100, 1600);
    }
}

#[test]
fn report_outputs_are_atomic() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("report.html");
    std::fs::write(&path, "previous report").unwrap();
    // A bad second layout: nothing is written, the previous file is intact, no temporary left.
    let p = path.to_str().unwrap();
    let (code, _, err) = run(&[
        "compare",
        "tasks/shelf.yaml",
        "tests/data/two_link.urdf",
        "--report",
        p,
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("tests/data/two_link.urdf"), "{err}");
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "previous report");
    let names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, ["report.html"]);
    // An unwritable destination is a bad input naming the path; nothing is created.
    let missing = dir.path().join("no/such/dir/report.html");
    let (code, _, err) = run(&[
        "plan",
        "tasks/bench_assembly.yaml",
        "--report",
        missing.to_str().unwrap(),
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("no/such/dir/report.html"), "{err}");
    assert!(!dir.path().join("no").exists());
}

/// A sweep report of a task carries the task's phases and its fatigue parameters per muscle
/// group (the worker, the phases and the model's parameters, as a report handed on must).
#[test]
fn sweep_report_of_a_task_has_its_phases_and_parameters() {
    let task = Task::from_file(std::path::Path::new(&format!(
        "{}/tests/data/hostile/quick.yaml",
        env!("CARGO_MANIFEST_DIR")
    )))
    .unwrap();
    let s = Sweep::from_outcomes(
        "quick",
        "standard (3 workers)",
        false,
        true,
        0.7,
        vec![outcome(0, "P50 man", Sex::Male, 1.755, vec![])],
    );
    let html = sweep_report(&s, Some(&task)).unwrap();
    assert_sound(&html);
    assert!(html.contains("Phases of one cycle"));
    assert!(html.contains("<td>hold</td>"), "the phase named");
    assert!(html.contains("k and recovery per muscle group"));
    for h in &task.half_joints {
        assert!(html.contains(&h.group), "{}", h.group);
    }
    let escaped = task.fatigue_choice.k_source.replace('&', "&amp;");
    assert!(html.contains(&escaped), "the k source");
}

/// The report's work-and-rest table words Rohmert's allowance as the verdict and the text report
/// do: not applicable where no posture is held longer than ISO 11226's 4 s (the quick task's
/// phases last 2–3 s); it used to print an allowance in seconds there while the verdict and the
/// text said "not applicable".
#[test]
fn the_rohmert_row_agrees_with_the_verdict() {
    let p = planned();
    assert!(!p.assessment.rohmert_applies());
    let html = plan_html();
    let i = html.find("Rohmert (1973) rest allowance").unwrap();
    let row = &html[i..i + html[i..].find("</tr>").unwrap()];
    assert!(row.contains("not applicable"), "{row}");
    let text = posture_opt::report::text::rest_summary(
        &p.assessment.rest,
        &p.plan,
        p.assessment.rohmert_applies(),
    );
    assert!(
        text.contains("Rohmert (1973) rest allowance: not applicable"),
        "{text}"
    );
}
