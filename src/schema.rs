//! The task file's reference: its JSON Schema (generated from the task types with schemars) and
//! the helpers that make parse errors say what the user meant.

use schemars::schema_for;

/// The JSON Schema of task files (what `posture-opt schema` prints and `docs/task.schema.json`
/// holds).
pub fn task_schema() -> serde_json::Value {
    serde_json::to_value(schema_for!(crate::plan::task::TaskFile))
        .expect("a schema is plain JSON")
}

/// `" (did you mean 'x'?)"` when one of `candidates` is close to `word`, else "".
pub fn did_you_mean<'a>(word: &str, candidates: impl Iterator<Item = &'a str>) -> String {
    let best = candidates
        .map(|c| (strsim::normalized_damerau_levenshtein(word, c), c))
        .filter(|(s, c)| *s >= 0.5 || c.starts_with(word) || word.starts_with(c))
        .max_by(|a, b| a.0.total_cmp(&b.0));
    match best {
        Some((_, c)) if c != word => format!(" (did you mean '{c}'?)"),
        _ => String::new(),
    }
}

/// Adds a suggestion to a YAML parse error about an unknown field or variant: serde names the
/// expected ones, this picks the closest (`rpy` → `rpy_rad`).
pub fn explain_parse_error(message: &str) -> String {
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
        let list = &message[lp + list_marker.len()..];
        let names: Vec<&str> = list
            .split('`')
            .enumerate()
            .filter(|(i, _)| i % 2 == 1)
            .map(|(_, s)| s)
            .collect();
        let hint = did_you_mean(word, names.iter().copied());
        if !hint.is_empty() {
            return format!("{message}{hint}");
        }
        break;
    }
    message.to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggests_the_nearest_field() {
        assert_eq!(
            did_you_mean("rpy", ["position_m", "rpy_rad", "name"].into_iter()),
            " (did you mean 'rpy_rad'?)"
        );
        assert_eq!(did_you_mean("zzz", ["alpha", "beta"].into_iter()), "");
        let m = "unknown field `durations`, expected one of `name`, `target_m`, `duration_s`";
        assert!(explain_parse_error(m).ends_with("(did you mean 'duration_s'?)"));
    }
}
