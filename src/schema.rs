//! The task file's reference: its JSON Schema (generated from the task types with schemars), the
//! same reference as Markdown ([`task_schema_markdown`], what `docs/task-format.md` holds), and
//! the helpers that make parse errors say what the user meant.
//!
//! The Markdown is rendered from the schema alone: a field's meaning is its description (the doc
//! comment of the field in `src/plan/task.rs` and the types it uses), its unit the first
//! `[unit]` in the description (else the unit its name ends in: `_m`, `_s`, `_kg`, `_n`, `_deg`,
//! `_rad`, `_per_min`, `_fmvc`, `_m_s2`), its default the schema's `default` (else a "default …"
//! phrase of the description), its range the schema's bounds and enumerations and the ranges the
//! description writes as `a..b`, `a–b`, `> a`, `a or more` or `at most a`.

use schemars::schema_for;
use serde_json::{Map, Value};
use std::fmt::Write as _;

/// The JSON Schema of task files (what `posture-opt schema` prints and `docs/task.schema.json`
/// holds).
pub fn task_schema() -> serde_json::Value {
    let mut v = serde_json::to_value(schema_for!(crate::plan::task::TaskFile))
        .expect("a schema is plain JSON");
    add_bounds(&mut v);
    // a phase gives exactly one of a hand target, targets per hand, or an object
    if let Some(Value::Object(phase)) = v.pointer_mut("/$defs/PhaseFile") {
        phase.insert(
            "oneOf".into(),
            serde_json::json!([
                {"required": ["target_m"]},
                {"required": ["targets"]},
                {"required": ["object"]}
            ]),
        );
    }
    v
}

/// Writes the numeric range a field's description states (`1.2..2.3`, `> 0`, `1 or more`, `at
/// most 10`) into the schema as `minimum`, `maximum` or `exclusiveMinimum` (on the items of a
/// list of numbers), so that editors check ranges too. Descriptions with several ranges are left
/// to posture-opt's own checks.
fn add_bounds(v: &mut Value) {
    match v {
        Value::Object(m) => {
            if let Some(Value::Object(props)) = m.get_mut("properties") {
                for p in props.values_mut() {
                    bound_field(p);
                }
            }
            for x in m.values_mut() {
                add_bounds(x);
            }
        }
        Value::Array(a) => a.iter_mut().for_each(add_bounds),
        _ => {}
    }
}

fn bound_field(p: &mut Value) {
    let Some(text) = p.get("description").and_then(Value::as_str) else {
        return;
    };
    let Some(range) = range_in_text(text) else {
        return;
    };
    // several ranges, or one on a derived quantity (a vector's magnitude in g), are left to
    // posture-opt's own checks
    if range.contains(';') || text.contains("Magnitude") {
        return;
    }
    let num = |s: &str| -> Option<f64> {
        let t: String = s
            .trim()
            .replace('−', "-")
            .chars()
            .take_while(|c| c.is_ascii_digit() || *c == '.' || *c == '-' || *c == 'e')
            .collect();
        t.parse().ok()
    };
    let mut bounds = Map::new();
    if let Some((a, b)) = range.split_once(" to ") {
        if let (Some(a), Some(b)) = (num(a), num(b)) {
            bounds.insert("minimum".into(), a.into());
            bounds.insert("maximum".into(), b.into());
        }
    } else if let Some(a) = range.strip_prefix("> ") {
        if let Some(a) = num(a) {
            bounds.insert("exclusiveMinimum".into(), a.into());
        }
    } else if let Some(a) = range.strip_prefix("≥ ") {
        if let Some(a) = num(a) {
            bounds.insert("minimum".into(), a.into());
        }
    } else if let Some(b) = range.strip_prefix("at most ")
        && let Some(b) = num(b)
    {
        bounds.insert("maximum".into(), b.into());
    }
    if bounds.is_empty() {
        return;
    }
    let is_number = |v: &Value| {
        let t = |x: &Value| matches!(x.as_str(), Some("number" | "integer"));
        match v.get("type") {
            Some(Value::Array(ts)) => ts.iter().any(t),
            Some(x) => t(x),
            None => false,
        }
    };
    let target = if is_number(p) {
        Some(p)
    } else if p.get("items").is_some_and(is_number) {
        p.get_mut("items")
    } else {
        None
    };
    if let Some(Value::Object(m)) = target {
        // the tighter of the type's own bound (an unsigned integer's 0) and the description's
        for (k, b) in bounds {
            let new = b.as_f64().unwrap_or(f64::NAN);
            let keep = m.get(&k).and_then(Value::as_f64).is_some_and(|old| {
                if k == "maximum" {
                    old <= new
                } else {
                    old >= new
                }
            });
            if !keep {
                m.insert(k, b);
            }
        }
    }
}

/// The task file reference as Markdown, rendered from [`task_schema`] (what
/// `posture-opt schema --markdown` prints and `docs/task-format.md` holds).
pub fn task_schema_markdown() -> String {
    schema_markdown(&task_schema())
}

/// Renders a JSON Schema of YAML files as a Markdown reference: an introduction (units, frame,
/// editor validation), then one table per object with every field's type, whether it is
/// required, unit, default, range or allowed values, and meaning.
pub fn schema_markdown(schema: &Value) -> String {
    let empty = Map::new();
    let defs = schema
        .get("$defs")
        .and_then(Value::as_object)
        .unwrap_or(&empty);
    let r = Renderer { defs };
    let mut o = String::new();
    o.push_str(INTRO);
    // breadth-first over the objects reachable from the root, each rendered once per path
    let mut queue: Vec<(String, &Value)> = vec![(String::new(), schema)];
    let mut i = 0;
    while i < queue.len() {
        let (path, obj) = (queue[i].0.clone(), queue[i].1);
        i += 1;
        let children = r.section(&mut o, &path, obj);
        queue.extend(children);
    }
    o
}

const INTRO: &str = "# Task file reference\n\n\
<!-- Generated by `posture-opt schema --markdown` from the task files' JSON Schema \
(`docs/task.schema.json`, written by `posture-opt schema`); do not edit by hand: change the doc \
comments in `src/plan/task.rs` (and the types it uses) and regenerate. -->\n\n\
A task file (YAML) describes one worker doing a cycle of phases (hand targets for one or both \
hands, the load held, a duration), repeated for a number of cycles with a rest per cycle, \
standing at a workstation with obstacles. The files in `tasks/` are examples.\n\n\
**Units and frame.** Metres, kilograms, newtons, seconds; degrees where a field's name ends in \
`_deg`, radians where it ends in `_rad`; rates per minute where it ends in `_per_min`; loads as \
a fraction of the maximum voluntary contraction where it ends in `_fmvc`. World frame: x forward, \
y left, z up, the floor at z = 0; the worker stands at the origin facing +x. A field's unit below \
is the one its description gives in brackets, otherwise the one its name ends in.\n\n\
**Unknown fields are errors.** Every object refuses fields it does not define, and the error \
names the nearest known field (`rpy` → `rpy_rad`).\n\n\
**Reading the tables.** *required*: the field must be given; *optional*: it may be left out \
(then its default applies; \"—\" means absent, i.e. not used); *one of*: exactly one of the \
fields so marked must be given. A type followed by \"or null\" may also be written as `null` \
(the same as leaving it out). Ranges are checked when the file is read.\n\n\
## Validating task files in an editor\n\n\
`docs/task.schema.json` is this schema (`posture-opt schema > docs/task.schema.json`). Editors \
that use the YAML language server (yaml-language-server, e.g. the Red Hat *YAML* extension of \
VS Code) check a task file against it while you type, complete field names and show each \
field's description on hover. Either put this comment on the first line of the task file (the \
path is relative to the task file):\n\n\
```yaml\n\
# yaml-language-server: $schema=../docs/task.schema.json\n\
name: Pallet to conveyor\n\
```\n\n\
or associate the schema with all task files in the workspace settings \
(`.vscode/settings.json`):\n\n\
```json\n\
{ \"yaml.schemas\": { \"./docs/task.schema.json\": \"tasks/*.yaml\" } }\n\
```\n\n\
The editor is a convenience, posture-opt is the judge: the schema is written in JSON Schema \
2020-12, while the YAML language server implements draft 7, so it ignores \
`unevaluatedProperties` (a misspelt key inside an obstacle is not flagged there), and it cannot \
check what the schema does not say (ranges written in descriptions, phase names used by `lifts`, \
frames of a custom robot). `posture-opt plan TASK.yaml` checks all of it and names the field.\n\n";

/// Renders one object's section and returns the objects below it.
struct Renderer<'a> {
    defs: &'a Map<String, Value>,
}

/// What a field holds, for its row.
struct FieldType<'a> {
    text: String,
    nullable: bool,
    /// Allowed values (enumerations).
    allowed: Option<String>,
    /// A bound written in the schema (numbers, items).
    bound: Option<String>,
    /// An object below this field: (path suffix, schema).
    child: Option<(String, &'a Value)>,
    /// Description of the type (when the field has none).
    type_description: Option<String>,
}

impl<'a> Renderer<'a> {
    fn resolve(&self, v: &'a Value) -> &'a Value {
        let mut v = v;
        for _ in 0..16 {
            match v.get("$ref").and_then(Value::as_str) {
                Some(r) => match r.strip_prefix("#/$defs/").and_then(|n| self.defs.get(n)) {
                    Some(d) => v = d,
                    None => return v,
                },
                None => return v,
            }
        }
        v
    }

    fn is_object(v: &Value) -> bool {
        v.get("properties").is_some()
            || v.get("oneOf").is_some()
            || (type_names(v).contains(&"object") && v.get("additionalProperties").is_none())
    }

    fn field_type(&self, name: &str, prop: &'a Value) -> FieldType<'a> {
        let mut nullable = false;
        // `anyOf: [X, null]` is an optional X
        let mut v = prop;
        if let Some(any) = prop.get("anyOf").and_then(Value::as_array) {
            let non_null: Vec<&Value> = any
                .iter()
                .filter(|a| a.get("type") != Some(&Value::from("null")))
                .collect();
            nullable = non_null.len() < any.len();
            if non_null.len() == 1 {
                v = non_null[0];
            }
        }
        let has_ref = v.get("$ref").is_some();
        let target = self.resolve(v);
        let type_description = if has_ref { description(target) } else { None };
        let types = type_names(target);
        nullable |= types.contains(&"null");
        let allowed = target.get("enum").and_then(Value::as_array).map(|e| {
            e.iter()
                .map(|x| {
                    format!(
                        "`{}`",
                        x.as_str()
                            .map(str::to_string)
                            .unwrap_or_else(|| x.to_string())
                    )
                })
                .collect::<Vec<_>>()
                .join(", ")
        });
        let mut bound = number_bounds(target);
        let mut child = None;
        let text = if allowed.is_some() {
            "text (one of the allowed values)".to_string()
        } else if Self::is_object(target) {
            child = Some((name.to_string(), target));
            format!("object ([`{name}`](#{}))", ANCHOR_PLACEHOLDER)
        } else if types.contains(&"array") {
            let items = target.get("items").map(|it| self.resolve(it));
            let n = match (
                target.get("minItems").and_then(Value::as_u64),
                target.get("maxItems").and_then(Value::as_u64),
            ) {
                (Some(a), Some(b)) if a == b => Some(a),
                _ => None,
            };
            match items {
                Some(it) if Self::is_object(it) => {
                    let suffix = format!("{name}[]");
                    child = Some((suffix.clone(), it));
                    format!("list of objects ([`{suffix}`](#{}))", ANCHOR_PLACEHOLDER)
                }
                Some(it) => {
                    let each = scalar_name(it);
                    if bound.is_none() {
                        bound = number_bounds(it).map(|b| format!("each {b}"));
                    }
                    match n {
                        Some(3) if each == "number" => "3 numbers (x, y, z)".to_string(),
                        Some(n) => format!("{n} {each}s"),
                        None => format!("list of {each}s"),
                    }
                }
                None => "list".to_string(),
            }
        } else if let Some(ap) = target.get("additionalProperties").filter(|a| a.is_object()) {
            let it = self.resolve(ap);
            if Self::is_object(it) {
                let suffix = format!("{name}.<key>");
                child = Some((suffix.clone(), it));
                format!("map: key → object ([`{suffix}`](#{}))", ANCHOR_PLACEHOLDER)
            } else {
                format!("map: key → {}", scalar_name(it))
            }
        } else {
            scalar_name(target).to_string()
        };
        FieldType {
            text,
            nullable,
            allowed,
            bound,
            child,
            type_description,
        }
    }

    fn section(&self, o: &mut String, path: &str, obj: &'a Value) -> Vec<(String, &'a Value)> {
        let title = if path.is_empty() {
            "Top level".to_string()
        } else {
            format!("`{path}`")
        };
        let _ = writeln!(o, "<a id=\"{}\"></a>\n\n## {title}\n", anchor(path));
        if let Some(d) = description(obj) {
            let _ = writeln!(o, "{}\n", d);
        }
        let mut rows: Vec<(String, &'a Value, String)> = Vec::new();
        let required: Vec<&str> = obj
            .get("required")
            .and_then(Value::as_array)
            .map(|a| a.iter().filter_map(Value::as_str).collect())
            .unwrap_or_default();
        if let Some(props) = obj.get("properties").and_then(Value::as_object) {
            for (k, v) in props {
                let need = if required.contains(&k.as_str()) {
                    "required"
                } else {
                    "optional"
                };
                rows.push((k.clone(), v, need.to_string()));
            }
        }
        // `oneOf` variants that each add one field (obstacle shapes): exactly one of them
        let mut one_of_names = Vec::new();
        if let Some(variants) = obj.get("oneOf").and_then(Value::as_array) {
            for var in variants {
                if let Some(props) = var.get("properties").and_then(Value::as_object) {
                    for (k, v) in props {
                        one_of_names.push(format!("`{k}`"));
                        rows.push((k.clone(), v, String::new()));
                    }
                }
            }
            for (_, _, need) in rows.iter_mut() {
                if need.is_empty() {
                    *need = format!("one of {}", one_of_names.join(", "));
                }
            }
            // variants that only require one of the listed fields (a phase's target, targets or
            // object): exactly one of them
            let only: Vec<&str> = variants
                .iter()
                .filter(|v| v.get("properties").is_none())
                .filter_map(|v| v.get("required")?.as_array()?.first()?.as_str())
                .collect();
            if !only.is_empty() {
                let names: Vec<String> = only.iter().map(|k| format!("`{k}`")).collect();
                for (k, _, need) in rows.iter_mut() {
                    if only.contains(&k.as_str()) {
                        *need = format!("exactly one of {}", names.join(", "));
                    }
                }
            }
        }
        let variant_desc: Vec<(String, String)> = obj
            .get("oneOf")
            .and_then(Value::as_array)
            .map(|vs| {
                vs.iter()
                    .filter_map(|var| {
                        let d = description(var)?;
                        let k = var.get("properties")?.as_object()?.keys().next()?.clone();
                        Some((k, d))
                    })
                    .collect()
            })
            .unwrap_or_default();
        o.push_str(
            "| field | type | required | unit | default | range / allowed values | meaning |\n",
        );
        o.push_str("|---|---|---|---|---|---|---|\n");
        let mut children = Vec::new();
        for (k, v, need) in &rows {
            let ft = self.field_type(k, v);
            let child_path = ft.child.as_ref().map(|(suffix, _)| {
                if path.is_empty() {
                    suffix.clone()
                } else {
                    format!("{path}.{suffix}")
                }
            });
            let mut ty = ft.text.clone();
            if let Some(cp) = &child_path {
                ty = ty.replace(
                    &format!(
                        "[`{}`]",
                        ft.child.as_ref().map(|c| c.0.as_str()).unwrap_or("")
                    ),
                    &format!("[`{cp}`]"),
                );
                ty = ty.replace(ANCHOR_PLACEHOLDER, &anchor(cp));
            }
            if ft.nullable {
                ty.push_str(" or null");
            }
            let desc = description(v)
                .or_else(|| {
                    variant_desc
                        .iter()
                        .find(|(n, _)| n == k)
                        .map(|(_, d)| d.clone())
                })
                .or_else(|| ft.type_description.clone());
            let text = desc.clone().unwrap_or_default();
            let unit = unit_of(&text, k).unwrap_or_else(|| "—".into());
            let default = match v.get("default") {
                Some(Value::Null) | None => default_in_text(&text).unwrap_or_else(|| "—".into()),
                Some(d) => format_default(d),
            };
            let mut range = Vec::new();
            if let Some(a) = &ft.allowed {
                range.push(a.clone());
            }
            match range_in_text(&text) {
                Some(t) => range.push(t),
                None => {
                    if let Some(b) = &ft.bound {
                        range.push(b.clone());
                    }
                }
            }
            let range = if range.is_empty() {
                "—".to_string()
            } else {
                range.join("; ")
            };
            let meaning = if text.is_empty() {
                "—".to_string()
            } else {
                text.clone()
            };
            let _ = writeln!(
                o,
                "| `{k}` | {} | {need} | {} | {} | {} | {} |",
                cell(&ty),
                cell(&unit),
                cell(&default),
                cell(&range),
                cell(&meaning)
            );
            if let (Some(cp), Some((_, child))) = (child_path, ft.child) {
                children.push((cp, child));
            }
        }
        o.push('\n');
        children
    }
}

const ANCHOR_PLACEHOLDER: &str = "\u{0}anchor\u{0}";

/// The HTML anchor of a section.
fn anchor(path: &str) -> String {
    if path.is_empty() {
        return "top-level".into();
    }
    let mut a = String::new();
    for c in path.chars() {
        if c.is_ascii_alphanumeric() || c == '_' {
            a.push(c);
        } else if !a.ends_with('-') {
            a.push('-');
        }
    }
    a.trim_end_matches('-').to_string()
}

fn type_names(v: &Value) -> Vec<&str> {
    match v.get("type") {
        Some(Value::String(s)) => vec![s.as_str()],
        Some(Value::Array(a)) => a.iter().filter_map(Value::as_str).collect(),
        _ => Vec::new(),
    }
}

fn scalar_name(v: &Value) -> &'static str {
    let t = type_names(v);
    if t.contains(&"integer") {
        "integer"
    } else if t.contains(&"number") {
        "number"
    } else if t.contains(&"boolean") {
        "true/false"
    } else if t.contains(&"string") {
        "text"
    } else if t.contains(&"object") {
        "object"
    } else {
        "value"
    }
}

/// Bounds the schema itself writes (`minimum`, `maximum`, exclusive ones).
fn number_bounds(v: &Value) -> Option<String> {
    let num = |k: &str| v.get(k).and_then(Value::as_f64).map(fmt_num);
    let lo = num("minimum")
        .map(|x| format!("≥ {x}"))
        .or_else(|| num("exclusiveMinimum").map(|x| format!("> {x}")));
    let hi = num("maximum")
        .map(|x| format!("≤ {x}"))
        .or_else(|| num("exclusiveMaximum").map(|x| format!("< {x}")));
    match (lo, hi) {
        (Some(a), Some(b)) => Some(format!("{a}, {b}")),
        (a, b) => a.or(b),
    }
}

fn fmt_num(x: f64) -> String {
    if x.fract() == 0.0 && x.abs() < 1e15 {
        format!("{}", x as i64)
    } else {
        format!("{x}")
    }
}

/// A field's description as one line of plain Markdown (rustdoc's `\[` escapes removed).
fn description(v: &Value) -> Option<String> {
    let d = v.get("description")?.as_str()?;
    let d = d.replace("\\[", "[").replace("\\]", "]");
    let d = d.split_whitespace().collect::<Vec<_>>().join(" ");
    (!d.is_empty()).then_some(d)
}

fn format_default(d: &Value) -> String {
    match d {
        Value::Null => "—".into(),
        Value::Bool(b) => format!("`{b}`"),
        Value::Number(n) => n.as_f64().map(fmt_num).unwrap_or_else(|| n.to_string()),
        Value::String(s) => format!("`{s}`"),
        Value::Array(a) if a.is_empty() => "none (empty list)".into(),
        Value::Array(a) => format!(
            "`[{}]`",
            a.iter()
                .map(|x| x.as_f64().map(fmt_num).unwrap_or_else(|| x.to_string()))
                .collect::<Vec<_>>()
                .join(", ")
        ),
        Value::Object(m)
            if m.values().all(|x| {
                x.is_null()
                    || x.as_object().is_some_and(|o| o.is_empty())
                    || x.as_array().is_some_and(|a| a.is_empty())
            }) =>
        {
            "none".into()
        }
        Value::Object(_) => "each field's default".into(),
    }
}

/// The first `[unit]` of a description, else the unit the field's name ends in.
fn unit_of(text: &str, name: &str) -> Option<String> {
    if let Some(a) = text.find('[')
        && let Some(b) = text[a + 1..].find(']')
    {
        let u = &text[a + 1..a + 1 + b];
        if !u.is_empty() && u.len() <= 16 {
            return Some(u.to_string());
        }
    }
    let by_name = [
        ("_m_s2", "m/s²"),
        ("_per_min", "1/min"),
        ("_fmvc", "fraction of MVC"),
        ("_deg", "deg"),
        ("_rad", "rad"),
        ("_kg", "kg"),
        ("_nm", "N·m"),
        ("_n", "N"),
        ("_s", "s"),
        ("_m", "m"),
    ];
    by_name
        .iter()
        .find(|(suffix, _)| name.ends_with(suffix))
        .map(|(_, u)| u.to_string())
}

/// "default X" / "X by default" in a description.
fn default_in_text(text: &str) -> Option<String> {
    let lower = text.to_lowercase();
    if let Some(i) = lower.find("default ") {
        let rest = &text[i + "default ".len()..];
        let mut depth = 0i32;
        let mut end = rest.len();
        let chars: Vec<(usize, char)> = rest.char_indices().collect();
        for (n, &(j, c)) in chars.iter().enumerate() {
            let next = chars.get(n + 1).map(|x| x.1);
            match c {
                '(' => depth += 1,
                ')' if depth == 0 => {
                    end = j;
                    break;
                }
                ')' => depth -= 1,
                ';' if depth == 0 => {
                    end = j;
                    break;
                }
                ',' if depth == 0 && next != Some(' ') => {}
                ',' if depth == 0
                    // "`l_foot`, `r_foot`" continues a list of names
                    && chars.get(n + 2).map(|x| x.1) != Some('`') =>
                {
                    end = j;
                    break;
                }
                '.' if depth == 0 && (next.is_none() || next == Some(' ')) => {
                    end = j;
                    break;
                }
                _ => {}
            }
        }
        let v = rest[..end].trim();
        if !v.is_empty() {
            return Some(v.to_string());
        }
    }
    if let Some(i) = lower.find(" by default") {
        let before = text[..i].trim_end();
        let word = before.rsplit([' ', ';', ',']).next().unwrap_or("");
        if !word.is_empty() {
            return Some(word.to_string());
        }
    }
    None
}

/// A range written in a description: `a..b`, `a–b`, `> a`, `≥ a`, `a or more`, `at most a`.
fn range_in_text(text: &str) -> Option<String> {
    let is_num = |c: char| c.is_ascii_digit() || c == '.';
    let number_before = |end: usize| -> Option<(usize, String)> {
        let head = &text[..end];
        let start = head
            .char_indices()
            .rev()
            .take_while(|&(_, c)| is_num(c) || c == '-' || c == '−')
            .last()
            .map(|(i, _)| i)?;
        let n = head[start..].trim_end_matches('.');
        n.chars()
            .any(|c| c.is_ascii_digit())
            .then(|| (start, n.to_string()))
    };
    let number_after = |start: usize| -> Option<String> {
        let tail = &text[start..];
        let end = tail
            .char_indices()
            .find(|&(i, c)| !(is_num(c) || (i == 0 && (c == '-' || c == '−'))))
            .map(|(i, _)| i)
            .unwrap_or(tail.len());
        let n = tail[..end].trim_end_matches('.');
        n.chars().any(|c| c.is_ascii_digit()).then(|| n.to_string())
    };
    let mut found = Vec::new();
    for sep in ["..", "–"] {
        let mut from = 0;
        while let Some(p) = text[from..].find(sep) {
            let at = from + p;
            if let (Some((_, a)), Some(b)) = (number_before(at), number_after(at + sep.len())) {
                found.push((at, format!("{a} to {b}")));
            }
            from = at + sep.len();
        }
    }
    for (pat, word) in [("> ", "> "), ("≥ ", "≥ ")] {
        if let Some(p) = text.find(pat)
            && let Some(b) = number_after(p + pat.len())
        {
            found.push((p, format!("{word}{b}")));
        }
    }
    if let Some(p) = text.find(" or more")
        && let Some((_, a)) = number_before(p)
    {
        found.push((p, format!("≥ {a}")));
    }
    if let Some(p) = text.find("at most ") {
        let tail = &text[p + "at most ".len()..];
        let end = tail.find(['.', ';', ',', ')']).unwrap_or(tail.len());
        let t = tail[..end].trim();
        if t.chars().next().is_some_and(|c| c.is_ascii_digit()) {
            found.push((p, format!("at most {t}")));
        }
    }
    found.sort_by_key(|f| f.0);
    found.dedup_by(|a, b| a.1 == b.1);
    (!found.is_empty()).then(|| {
        found
            .into_iter()
            .map(|f| f.1)
            .collect::<Vec<_>>()
            .join("; ")
    })
}

/// Escapes a table cell.
fn cell(s: &str) -> String {
    s.replace('|', "\\|")
}

/// `" (did you mean 'x'?)"` when one of `candidates` is close to `word`, else "". The rule: the
/// candidates of the highest normalised Damerau-Levenshtein similarity (at least 0.5, or a
/// prefix either way) are suggested, all of them when several tie (`hand_grip` → `'l_hand_grip'
/// or 'r_hand_grip'`, in the candidates' order; at most four). A field written without its unit
/// suffix is that field whatever else is close: `target` → `'target_m'` (not `'targets'`),
/// `duration` → `'duration_s'`.
pub fn did_you_mean<'a>(word: &str, candidates: impl Iterator<Item = &'a str>) -> String {
    // a typo is short; comparing a long string costs O(n·m) for no useful hint
    if word.chars().count() > 64 {
        return String::new();
    }
    let candidates: Vec<&str> = candidates.collect();
    let with_unit = |c: &str| {
        c.strip_prefix(word)
            .and_then(|rest| rest.strip_prefix('_'))
            .is_some_and(|unit| UNIT_SUFFIXES.contains(&unit))
    };
    let close: Vec<(f64, &str)> = if candidates.iter().any(|c| with_unit(c)) {
        candidates
            .into_iter()
            .filter(|c| with_unit(c))
            .map(|c| (1.0, c))
            .collect()
    } else {
        candidates
            .into_iter()
            .map(|c| (strsim::normalized_damerau_levenshtein(word, c), c))
            .filter(|(s, c)| *s >= 0.5 || c.starts_with(word) || word.starts_with(c))
            .collect()
    };
    let Some(best) = close.iter().map(|x| x.0).max_by(f64::total_cmp) else {
        return String::new();
    };
    let mut names: Vec<&str> = Vec::new();
    for (s, c) in &close {
        if *s >= best - 1e-12 && !names.contains(c) {
            names.push(c);
        }
    }
    if names.contains(&word) {
        return String::new();
    }
    names.truncate(4);
    let quoted: Vec<String> = names.iter().map(|n| format!("'{n}'")).collect();
    format!(" (did you mean {}?)", quoted.join(" or "))
}

/// The unit suffixes of the input files' field names (`duration_s`, `load_kg`, `q_rad`, …).
const UNIT_SUFFIXES: &[&str] = &[
    "m", "s", "kg", "n", "nm", "rad", "deg", "min", "w", "k", "mvc",
];

/// The accepted range of an integer type the YAML reader names ("invalid u32").
fn integer_range(ty: &str) -> Option<(i128, i128)> {
    Some(match ty {
        "u8" => (0, u8::MAX as i128),
        "u16" => (0, u16::MAX as i128),
        "u32" => (0, u32::MAX as i128),
        "u64" | "usize" => (0, u64::MAX as i128),
        "i32" => (i32::MIN as i128, i32::MAX as i128),
        "i64" | "isize" => (i64::MIN as i128, i64::MAX as i128),
        _ => return None,
    })
}

/// Rewrites the YAML reader's "invalid u32" (a number out of an integer's range) into the field,
/// the value and the accepted range, read from the message's own source excerpt
/// (`line L column C` and the line `L | key: value`).
fn explain_invalid_integer(message: &str) -> Option<String> {
    let at = message.find("invalid ")?;
    let ty: String = message[at + 8..]
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric())
        .collect();
    let (lo, hi) = integer_range(&ty)?;
    let lp = message.find("line ")?;
    let rest = &message[lp + 5..];
    let line: usize = rest.split(' ').next()?.parse().ok()?;
    let cp = rest.find("column ")?;
    let col: usize = rest[cp + 7..]
        .split(|c: char| !c.is_ascii_digit())
        .next()?
        .parse()
        .ok()?;
    let prefix = format!("{line} | ");
    let src = message
        .lines()
        .find_map(|l| l.trim_start().strip_prefix(prefix.as_str()))?;
    let chars: Vec<char> = src.chars().collect();
    let before: String = chars.iter().take(col.saturating_sub(1)).collect();
    let value: String = chars
        .iter()
        .skip(col.saturating_sub(1))
        .take_while(|c| !matches!(c, ',' | '}' | ']' | ' ' | '#'))
        .collect();
    let key_part = before.trim_end().strip_suffix(':')?;
    let key: String = key_part
        .chars()
        .rev()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect::<Vec<_>>()
        .into_iter()
        .rev()
        .collect();
    if key.is_empty() || value.is_empty() {
        return None;
    }
    let what = format!(
        "{key}: {value} is not a whole number within {lo}..={hi} (the range this field accepts)"
    );
    let first = message.lines().next().unwrap_or("");
    let first = first.replacen(&format!("invalid {ty}"), &what, 1);
    Some(match message.split_once('\n') {
        Some((_, rest)) => format!("{first}\n{rest}"),
        None => first,
    })
}

/// Adds a suggestion to a YAML parse error about an unknown field or variant: serde names the
/// expected ones, this picks the closest (`rpy` → `rpy_rad`). A number out of an integer
/// field's range is reworded to name the field, the value and the range.
pub fn explain_parse_error(message: &str) -> String {
    if let Some(m) = explain_invalid_integer(message) {
        return m;
    }
    for (marker, list_marker) in [
        ("unknown field `", "expected one of "),
        ("unknown variant `", "expected one of "),
        ("unknown field `", "expected "),
        ("unknown variant `", "expected "),
    ] {
        let Some(start) = message.find(marker) else {
            continue;
        };
        let rest = &message[start + marker.len()..];
        let Some(end) = rest.find('`') else { continue };
        let word = &rest[..end];
        let Some(lp) = message.find(list_marker) else {
            continue;
        };
        // the expected names, backtick-quoted (serde) or bare (the YAML parser), up to the line end
        let list = message[lp + list_marker.len()..]
            .lines()
            .next()
            .unwrap_or("");
        let names: Vec<&str> = list
            .split(',')
            .map(|n| n.trim().trim_matches('`'))
            .filter(|n| !n.is_empty())
            .collect();
        let hint = did_you_mean(word, names.iter().copied());
        if !hint.is_empty() {
            // the hint goes at the end of the message's first line
            return match message.split_once('\n') {
                Some((first, rest)) => format!("{first}{hint}\n{rest}"),
                None => format!("{message}{hint}"),
            };
        }
        break;
    }
    message.to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_integer_out_of_range_names_the_field_value_and_range() {
        let m = "error: line 6 column 9: invalid u32\n --> t.yaml:6:9\n  |\n6 | cycles: 9223372036854775807\n  |         ^ invalid u32";
        let e = explain_parse_error(m);
        assert!(
            e.starts_with(
                "error: line 6 column 9: cycles: 9223372036854775807 is not a whole number within 0..=4294967295"
            ),
            "{e}"
        );
        let m = "error: line 3 column 24: invalid u32\n --> t.yaml:3:24\n  |\n3 | replan: {every_cycles: 99999999999}\n  |                      ^ invalid u32";
        let e = explain_parse_error(m);
        assert!(
            e.contains("every_cycles: 99999999999 is not a whole number"),
            "{e}"
        );
    }

    #[test]
    fn suggests_the_nearest_field() {
        assert_eq!(
            did_you_mean("rpy", ["position_m", "rpy_rad", "name"].into_iter()),
            " (did you mean 'rpy_rad'?)"
        );
        assert_eq!(did_you_mean("zzz", ["alpha", "beta"].into_iter()), "");
        // a tie names every candidate, both sides
        assert_eq!(
            did_you_mean(
                "hand_grip",
                ["l_hand_grip", "r_hand_grip", "head"].into_iter()
            ),
            " (did you mean 'l_hand_grip' or 'r_hand_grip'?)"
        );
        let m = "unknown field `durations`, expected one of `name`, `target_m`, `duration_s`";
        assert!(explain_parse_error(m).ends_with("(did you mean 'duration_s'?)"));
        // a field written without its unit is that field, although `targets` is closer by letters
        // (found by an ergonomist writing `target: [x, y, z]` in a phase)
        let m = "unknown field `target`, expected one of `name`, `target_m`, `hand`, `targets`";
        assert!(
            explain_parse_error(m).ends_with("(did you mean 'target_m'?)"),
            "{}",
            explain_parse_error(m)
        );
    }

    #[test]
    fn reads_units_defaults_and_ranges_from_descriptions() {
        assert_eq!(
            unit_of("Stature [m], 1.2..2.3.", "stature_m").as_deref(),
            Some("m")
        );
        assert_eq!(
            unit_of("Weight of the term", "toe_out_deg").as_deref(),
            Some("deg")
        );
        assert_eq!(unit_of("A title", "name"), None);
        assert_eq!(
            range_in_text("Stature [m], 1.2..2.3.").as_deref(),
            Some("1.2 to 2.3")
        );
        assert_eq!(
            range_in_text("Strength percentile (1–99) of the worker's sex").as_deref(),
            Some("1 to 99")
        );
        assert_eq!(
            range_in_text("How long the posture is held [s], > 0.").as_deref(),
            Some("> 0")
        );
        assert_eq!(
            range_in_text("How many times the cycle repeats (1 or more).").as_deref(),
            Some("≥ 1")
        );
        assert_eq!(range_in_text("A short title for reports."), None);
        // the ranges reach the schema as bounds editors check
        let v = task_schema();
        let w = &v["$defs"]["Worker"]["properties"]["stature_m"];
        assert_eq!(
            (w["minimum"].as_f64(), w["maximum"].as_f64()),
            (Some(1.2), Some(2.3))
        );
        assert_eq!(v["properties"]["cycles"]["minimum"].as_f64(), Some(1.0));
        let d = &v["$defs"]["PhaseFile"]["properties"]["duration_s"];
        assert_eq!(d["minimum"].as_f64(), Some(0.001));
        assert!(
            v["properties"]["gravity_m_s2"]["items"]
                .get("maximum")
                .is_none()
        );
        assert_eq!(
            v["$defs"]["PhaseFile"]["oneOf"].as_array().map(Vec::len),
            Some(3)
        );
        assert_eq!(
            default_in_text("Share on the left hand, 0..1; default 0.5.").as_deref(),
            Some("0.5")
        );
        assert_eq!(
            default_in_text("Gravity [m/s²]; default (0, 0, −9.81). Magnitude at most 3 g.")
                .as_deref(),
            Some("(0, 0, −9.81)")
        );
        assert_eq!(
            default_in_text("(default 0.01, 0..0.5)").as_deref(),
            Some("0.01")
        );
        assert_eq!(
            default_in_text("Foot links; default `l_foot`, `r_foot`.").as_deref(),
            Some("`l_foot`, `r_foot`")
        );
        assert_eq!(
            default_in_text("of the worker's sex; 50 by default.").as_deref(),
            Some("50")
        );
    }

    #[test]
    fn the_markdown_reference_covers_every_field_of_the_schema() {
        let schema = task_schema();
        let md = task_schema_markdown();
        fn walk(v: &Value, names: &mut Vec<String>) {
            match v {
                Value::Object(m) => {
                    if let Some(Value::Object(p)) = m.get("properties") {
                        names.extend(p.keys().cloned());
                    }
                    m.values().for_each(|x| walk(x, names));
                }
                Value::Array(a) => a.iter().for_each(|x| walk(x, names)),
                _ => {}
            }
        }
        let mut names = Vec::new();
        walk(&schema, &mut names);
        assert!(names.len() > 40);
        for n in names {
            assert!(
                md.contains(&format!("| `{n}` |")),
                "{n} missing from the Markdown reference"
            );
        }
        assert!(md.contains("yaml-language-server: $schema="));
        assert!(!md.contains(ANCHOR_PLACEHOLDER));
    }
}
