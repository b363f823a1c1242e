//! A configuration file's errors as a person reads them: TOML's and serde's messages ("invalid
//! type: string \"twenty\", expected usize", "unknown variant `walkr`") said in plain words
//! after the key they concern ("\[ga\] population must be a whole number, not \"twenty\""), with
//! the names allowed and the closest of them, and a setting out of range pointed at in the file
//! where the file set it.

use std::ops::Range;

use toml::de::{DeTable, DeValue};

use crate::evolve::ga::{GaSettings, Preset};
use crate::lang::suggest::did_you_mean;
use crate::lang::{Diagnostic, DiagnosticKind, Source, Span};
use crate::sim::{RENAMED_KEYS, SettingError, table_name};
use crate::task::{TaskKind, TaskSpec};

/// A diagnostic for a TOML error in `source`, in words, at its place when it has one.
pub fn toml_diagnostic(source: &Source, error: &toml::de::Error) -> Diagnostic {
    let Some(span) = error.span() else {
        return Diagnostic::without_location(
            DiagnosticKind::Semantic,
            format!("{}: {}", source.name(), error.message()),
        );
    };
    let path = DeTable::parse(source.text())
        .ok()
        .and_then(|table| path_at(table.get_ref(), &span))
        .unwrap_or_default();
    let written = source
        .text()
        .get(span.clone())
        .filter(|w| w.len() <= 60 && !w.contains('\n'));
    let (message, note) = in_words(error.message(), &path, written);
    let diagnostic = Diagnostic::at(
        DiagnosticKind::Semantic,
        source,
        Span::new(span.start, span.end.max(span.start + 1)),
        message,
    );
    match note {
        Some(note) => diagnostic.with_note(note),
        None => diagnostic,
    }
}

/// A setting out of range, as a config file `source` set it: at its key when the file sets it
/// there (under its older name too, [`RENAMED_KEYS`]), else after the file's name (a setting
/// of the preset's, or of two keys at once).
pub fn setting_diagnostic(source: &Source, error: &SettingError) -> Diagnostic {
    let table: Vec<&str> = error.table.split('.').filter(|t| !t.is_empty()).collect();
    let at = |key: &str| key_span(source, &[table.as_slice(), &[key]].concat());
    let before = RENAMED_KEYS
        .iter()
        .find(|(today, _)| *today == error.key)
        .and_then(|&(today, before)| Some((at(before)?, before, today)));
    match (at(error.key), before) {
        (Some(span), _) => {
            Diagnostic::at(DiagnosticKind::Semantic, source, span, error.to_string())
        }
        (None, Some((span, before, today))) => {
            Diagnostic::at(DiagnosticKind::Semantic, source, span, error.to_string())
                .with_note(format!("`{before}` is the older name of `{today}`"))
        }
        (None, None) => Diagnostic::without_location(
            DiagnosticKind::Semantic,
            format!("{}: {error}", source.name()),
        ),
    }
}

/// Where `source` sets the key at `path` (`["ga", "population"]`): the span of its value. An
/// entry of an array of tables is named by its index after the array's name (`["task",
/// "habitats", "1", "name"]`).
pub fn key_span(source: &Source, path: &[&str]) -> Option<Span> {
    let document = DeTable::parse(source.text()).ok()?;
    let mut table = document.get_ref();
    let mut i = 0;
    while i < path.len() {
        let (_, mut value) = table.iter().find(|(key, _)| key.get_ref() == path[i])?;
        // An entry of an array: the index after the array's name.
        if let (DeValue::Array(items), Some(index)) = (
            value.get_ref(),
            path.get(i + 1).and_then(|p| p.parse::<usize>().ok()),
        ) {
            value = items.get(index)?;
            i += 1;
        }
        match value.get_ref() {
            DeValue::Table(inner) if i + 1 < path.len() => table = inner,
            _ if i + 1 == path.len() => {
                let span = value.span();
                return Some(Span::new(span.start, span.end));
            }
            _ => return None,
        }
        i += 1;
    }
    None
}

/// The path of keys (`["ga", "population"]`) whose key or value holds `span`, the deepest; an
/// entry of an array of tables is named by its index (`["task", "habitats", "1", "colour"]`).
fn path_at(table: &DeTable<'_>, span: &Range<usize>) -> Option<Vec<String>> {
    for (key, value) in table {
        if let DeValue::Table(inner) = value.get_ref()
            && let Some(mut inside) = path_at(inner, span)
        {
            inside.insert(0, key.get_ref().to_string());
            return Some(inside);
        }
        if let DeValue::Array(items) = value.get_ref() {
            for (index, item) in items.iter().enumerate() {
                if let DeValue::Table(inner) = item.get_ref()
                    && let Some(mut inside) = path_at(inner, span)
                {
                    inside.splice(0..0, [key.get_ref().to_string(), index.to_string()]);
                    return Some(inside);
                }
            }
        }
        let holds = |r: Range<usize>| r.start <= span.start && span.end <= r.end;
        if holds(key.span()) || holds(value.span()) {
            return Some(vec![key.get_ref().to_string()]);
        }
    }
    None
}

/// The key at `path` as messages name it: `seed`, `[ga] population`.
fn key_name(path: &[String]) -> String {
    match path.split_last() {
        Some((key, [])) => key.clone(),
        Some((key, table)) => format!("{} {key}", table_name(&table.join("."))),
        None => "a value".to_string(),
    }
}

/// serde's and TOML's `message` about the key at `path` (`written` the value as the file
/// writes it, when short) in plain words, and a note (an example, or the names allowed).
fn in_words(message: &str, path: &[String], written: Option<&str>) -> (String, Option<String>) {
    let key = key_name(path);
    // "invalid type: string \"twenty\", expected usize"
    for (lead, negative) in [("invalid type: ", false), ("invalid value: ", true)] {
        if let Some(rest) = message.strip_prefix(lead)
            && let Some((found, expected)) = rest.rsplit_once(", expected ")
        {
            let found = written.unwrap_or(found);
            let wanted = kind_in_words(expected, negative);
            let example = default_of(path).map(|v| format!("e.g. {} = {v}", path[path.len() - 1]));
            return (format!("{key} must be {wanted}, not {found}"), example);
        }
    }
    // An enum's value of another type: toml says only "wanted string or table".
    if message == "wanted string or table" {
        let example = default_of(path).map(|v| format!("e.g. {} = {v}", path[path.len() - 1]));
        let found = written.map_or(String::new(), |w| format!(", not {w}"));
        return (
            format!("{key} must be a string in double quotes{found}"),
            example,
        );
    }
    // "unknown variant `walkr`, expected one of `walker`, `jump`"
    if let Some(rest) = message.strip_prefix("unknown variant `")
        && let Some((given, names)) = rest.split_once('`')
    {
        let names = quoted_names(names);
        let hint = did_you_mean(given, names.iter().copied());
        return (
            format!(
                "{key} must be one of {}, not \"{given}\"{hint}",
                names.join(", ")
            ),
            None,
        );
    }
    // "unknown field `populaton`, expected one of `preset`, `population`"
    if let Some(rest) = message.strip_prefix("unknown field `")
        && let Some((given, names)) = rest.split_once('`')
    {
        let names = quoted_names(names);
        let table = match path.split_last() {
            Some((_, table)) if !table.is_empty() => table_name(&table.join(".")),
            _ => "the top level".to_string(),
        };
        let hint = did_you_mean(given, names.iter().copied());
        let allowed = match names.is_empty() {
            true => "it has none".to_string(),
            false => format!("its keys are {}", names.join(", ")),
        };
        return (
            format!("unknown key {given} in {table}{hint}"),
            Some(allowed),
        );
    }
    (message.to_string(), None)
}

/// The names a serde message lists after the one it got: "`a`, `b`" or "`a` or `b`".
fn quoted_names(text: &str) -> Vec<&str> {
    text.split('`').skip(1).step_by(2).collect()
}

/// A type serde expected (`usize`, `f64`, `a boolean`), in words; `negative`: the value had
/// the right type but was out of the type's range (a negative count).
fn kind_in_words(expected: &str, negative: bool) -> String {
    let unsigned = ["usize", "u8", "u16", "u32", "u64"].contains(&expected);
    match expected {
        _ if unsigned && negative => "a whole number, 0 or more".to_string(),
        _ if unsigned => "a whole number".to_string(),
        "isize" | "i8" | "i16" | "i32" | "i64" => "a whole number".to_string(),
        "f64" | "f32" => "a number".to_string(),
        "bool" | "a boolean" => "true or false".to_string(),
        "a string" | "string" => "a string in double quotes".to_string(),
        "a sequence" => "a list in brackets, [a, b, ...]".to_string(),
        _ if expected.starts_with("struct ") || expected == "a map" => "a table".to_string(),
        other => other.to_string(),
    }
}

/// The default value of the key at `path`, for an example (none for an encoding's limits).
fn default_of(path: &[String]) -> Option<toml::Value> {
    let mut top = toml::Table::new();
    top.insert("seed".into(), toml::Value::Integer(1));
    top.insert("verify_best".into(), toml::Value::Boolean(true));
    top.insert("cache".into(), toml::Value::Boolean(true));
    top.insert(
        "ga".into(),
        toml::Value::try_from(GaSettings::preset(Preset::Chaumont)).ok()?,
    );
    // Every task's table, as a config may hold them all.
    let mut task = toml::Table::new();
    for &kind in TaskKind::ALL {
        for (key, value) in toml::Table::try_from(TaskSpec::new(kind)).ok()? {
            task.entry(key).or_insert(value);
        }
    }
    top.insert("task".into(), toml::Value::Table(task));
    let mut value = top.get(path.first()?)?;
    for key in &path[1..] {
        value = value.as_table()?.get(key)?;
    }
    (!value.is_table()).then(|| value.clone())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn diagnostic(text: &str) -> String {
        let source = Source::new("run.toml", text);
        let error = toml::from_str::<super::super::config::ConfigFile<toml::Value>>(text)
            .expect_err("an error");
        toml_diagnostic(&source, &error).to_string()
    }

    /// Asserts that the diagnostic of the config `text` says every one of `parts`.
    fn says(text: &str, parts: &[&str]) {
        let message = diagnostic(text);
        for part in parts {
            assert!(message.contains(part), "{part:?} not in {message}");
        }
    }

    #[test]
    fn a_choice_of_the_wrong_type_is_named_with_an_example() {
        says(
            "[ga]\npreset = 3\n",
            &[
                "[ga] preset must be a string in double quotes, not 3",
                "e.g. preset = \"chaumont\"",
                "run.toml:2:10",
            ],
        );
    }

    #[test]
    fn a_value_of_the_wrong_type_is_named_in_words_at_its_key() {
        says(
            "[ga]\npopulation = \"twenty\"\n",
            &[
                "[ga] population must be a whole number, not \"twenty\"",
                "run.toml:2:14",
                "e.g. population = 300",
            ],
        );
        says(
            "[task.walker]\nseconds = \"long\"\n",
            &["[task.walker] seconds must be a number"],
        );
        says("cache = 1\n", &["cache must be true or false, not 1"]);
    }

    #[test]
    fn a_name_not_allowed_lists_the_names_and_the_closest() {
        says(
            "[task]\ntask = \"walkr\"\n",
            &[
                "[task] task must be one of walker, jump, catapult, aim, stand, swim, not \"walkr\" \
               (did you mean walker?)",
            ],
        );
        says(
            "[ga]\npopulaton = 3\n",
            &["unknown key populaton in [ga] (did you mean population?)"],
        );
    }

    #[test]
    fn a_key_is_found_in_its_table() {
        let source = Source::new("run.toml", "seed = 2\n[ga]\npopulation = 1\n");
        let span = key_span(&source, &["ga", "population"]).unwrap();
        assert_eq!(&source.text()[span.start..span.end], "1");
        assert!(key_span(&source, &["ga", "generations"]).is_none());
    }
}
