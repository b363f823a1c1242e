//! Setting a grammar's `define`s from outside its file, and the range of each define's slider.
//!
//! A [`DefineOverride`] (`NAME=VALUE`: the command line's `--define`, Python's `defines=`)
//! replaces the value of the grammar's `define NAME`; the defines after it are computed as the
//! file says, so a define that uses an overridden one follows it (`define TWICE = GROWTH * 2`
//! doubles the new `GROWTH`). A name the grammar does not define is an error that lists the
//! ones it does ([`unknown_define`]).
//!
//! A [`Slider`] is how the viewer offers a define: its range comes from a trailing comment
//! `# range A..B` (optionally `step S`) on the define's line, else from its value
//! ([`default_range`]).

use std::str::FromStr;

use serde::Serialize;

use crate::lang::ast::Define;
use crate::lang::{Diagnostic, DiagnosticKind, Source};

/// A value given to one of a grammar's defines from outside its file: `NAME=VALUE`.
#[derive(Clone, Debug, PartialEq)]
pub struct DefineOverride {
    /// The define's name.
    pub name: String,
    /// Its value, a finite number.
    pub value: f64,
}

impl FromStr for DefineOverride {
    type Err = String;

    /// Reads `NAME=VALUE`: NAME a define's name (a letter or `_`, then letters, digits or
    /// `_`), VALUE a finite number (`1.5`, `-2`, `1e-3`).
    fn from_str(text: &str) -> Result<Self, String> {
        let Some((name, value)) = text.split_once('=') else {
            return Err(format!("'{text}' is not NAME=VALUE (e.g. GROWTH=1.5)"));
        };
        let (name, value) = (name.trim(), value.trim());
        let mut chars = name.chars();
        let named = chars
            .next()
            .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
            && chars.all(|c| c.is_ascii_alphanumeric() || c == '_');
        if !named {
            return Err(format!(
                "'{name}' is not a define's name (a letter or _, then letters, digits or _)"
            ));
        }
        match value.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(DefineOverride {
                name: name.to_string(),
                value: v,
            }),
            _ => Err(format!("the value of {name}, '{value}', is not a number")),
        }
    }
}

/// The value `overrides` give `name`: the last one that names it.
pub(crate) fn override_of(overrides: &[DefineOverride], name: &str) -> Option<f64> {
    overrides
        .iter()
        .rev()
        .find(|o| o.name == name)
        .map(|o| o.value)
}

/// The error of an override that names no define of the grammar read from `source`: it
/// names the define, suggests the closest of the grammar's, and lists them all.
pub(crate) fn unknown_define(source: &Source, name: &str, defines: &[Define]) -> Diagnostic {
    let names: Vec<&str> = defines.iter().map(|d| d.name.as_str()).collect();
    let known = if names.is_empty() {
        "it has no defines".to_string()
    } else {
        format!("its defines are {}", names.join(", "))
    };
    Diagnostic::without_location(
        DiagnosticKind::Semantic,
        format!(
            "{}: cannot set {name}: the grammar has no define by that name{}; {known}",
            source.name(),
            crate::lang::suggest::did_you_mean(name, names.iter().copied()),
        ),
    )
}

/// A define as a slider: its name, value, range and step.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Slider {
    /// The define's name.
    pub name: String,
    /// Its value as the grammar was grown.
    pub value: f64,
    /// The slider's low end.
    pub min: f64,
    /// The slider's high end.
    pub max: f64,
    /// The slider's step: the comment's `step S`, else 1 for a count, a hundredth of the range otherwise (see `default_step`).
    pub step: f64,
    /// Why the define's `# range` comment was not used, when it was not.
    pub note: Option<String>,
}

/// The default range of a define of value `value`: from 0 to twice the value (from twice
/// the value to 0 when it is negative), and -1 to 1 for 0.
pub fn default_range(value: f64) -> (f64, f64) {
    if value == 0.0 {
        (-1.0, 1.0)
    } else {
        let twice = 2.0 * value;
        (twice.min(0.0), twice.max(0.0))
    }
}

/// The slider of the define `name` of value `value` whose line is `line`: the range of its
/// trailing comment `# range A..B [step S]`, else [`default_range`] (with a note saying why
/// when the comment is there but is not a range).
pub fn slider(name: &str, value: f64, line: &str) -> Slider {
    let comment = line.split_once('#').map(|(_, c)| c.trim());
    let range = comment
        .filter(|c| c.starts_with("range"))
        .map(|c| parse_range(c.trim_start_matches("range")));
    let (min, max, step, note) = match range {
        Some(Ok((min, max, step))) => (min, max, step, None),
        Some(Err(why)) => {
            let (min, max) = default_range(value);
            let note = format!("{why}: the slider runs from {min} to {max}");
            (min, max, None, Some(note))
        }
        None => {
            let (min, max) = default_range(value);
            (min, max, None, None)
        }
    };
    Slider {
        name: name.to_string(),
        value,
        min,
        max,
        step: step.unwrap_or_else(|| default_step(value, min, max)),
        note,
    }
}

/// A slider's step when its comment gives none: 1 for a whole value on a whole range at least
/// 10 wide (a count, such as a derivation length, takes whole values only), else a hundredth
/// of the range.
pub fn default_step(value: f64, min: f64, max: f64) -> f64 {
    let whole = |x: f64| x.fract() == 0.0;
    if whole(value) && whole(min) && whole(max) && max - min >= 10.0 {
        1.0
    } else {
        (max - min) / 100.0
    }
}

/// `A..B` or `A..B step S` (after the word `range`): A below B, S above 0.
fn parse_range(text: &str) -> Result<(f64, f64, Option<f64>), String> {
    let shape = || format!("'# range{text}' is not '# range A..B' (or '# range A..B step S')");
    let number = |t: &str| t.trim().parse::<f64>().ok().filter(|v| v.is_finite());
    let (range, step) = match text.split_once("step") {
        Some((range, step)) => (range, Some(number(step).ok_or_else(shape)?)),
        None => (text, None),
    };
    let (a, b) = range.split_once("..").ok_or_else(shape)?;
    let (a, b) = (number(a).ok_or_else(shape)?, number(b).ok_or_else(shape)?);
    if a >= b {
        return Err(format!(
            "'# range {a}..{b}': the low end must be below the high end"
        ));
    }
    if step.is_some_and(|s| s <= 0.0) {
        return Err(format!("'# range{text}': the step must be more than 0"));
    }
    Ok((a, b, step))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_override_is_a_name_and_a_finite_number() {
        let o: DefineOverride = " GROWTH = -1.5e0 ".parse().unwrap();
        assert_eq!(
            o,
            DefineOverride {
                name: "GROWTH".into(),
                value: -1.5
            }
        );
        for (text, message) in [
            ("GROWTH", "'GROWTH' is not NAME=VALUE (e.g. GROWTH=1.5)"),
            (
                "2X=1",
                "'2X' is not a define's name (a letter or _, then letters, digits or _)",
            ),
            (
                "GROWTH=fast",
                "the value of GROWTH, 'fast', is not a number",
            ),
            ("GROWTH=inf", "the value of GROWTH, 'inf', is not a number"),
        ] {
            assert_eq!(text.parse::<DefineOverride>().unwrap_err(), message);
        }
    }

    #[test]
    fn the_default_range_runs_from_zero_to_twice_the_value() {
        assert_eq!(default_range(1.5), (0.0, 3.0));
        assert_eq!(default_range(-2.0), (-4.0, 0.0));
        assert_eq!(default_range(0.0), (-1.0, 1.0));
    }

    #[test]
    fn a_range_comment_sets_the_sliders_ends_and_step() {
        let s = slider("N", 4.0, "define N = 4  # range 1..8 step 1");
        assert_eq!((s.min, s.max, s.step, s.note), (1.0, 8.0, 1.0, None));
        let s = slider("A", 0.5, "define A = 0.5 # range -1..1");
        assert_eq!((s.min, s.max, s.step), (-1.0, 1.0, 0.02));
        let s = slider("A", 0.5, "define A = 0.5 # the angle");
        assert_eq!((s.min, s.max, s.step, s.note), (0.0, 1.0, 0.01, None));
        // A whole number on a whole range 10 or more wide is a count: whole steps.
        let s = slider("N", 3.0, "define N = 3 # range 0..10");
        assert_eq!((s.min, s.max, s.step), (0.0, 10.0, 1.0));
        let s = slider("N", 5.0, "define N = 5");
        assert_eq!((s.min, s.max, s.step), (0.0, 10.0, 1.0));
        let s = slider("L", 2.0, "define L = 2");
        assert_eq!((s.min, s.max, s.step), (0.0, 4.0, 0.04));
    }

    #[test]
    fn a_range_comment_that_is_no_range_falls_back_with_a_note() {
        let s = slider("A", 1.0, "define A = 1 # range 5..2");
        assert_eq!((s.min, s.max), (0.0, 2.0));
        assert_eq!(
            s.note.as_deref(),
            Some(
                "'# range 5..2': the low end must be below the high end: the slider runs from 0 to 2"
            )
        );
        let s = slider("A", 1.0, "define A = 1 # range wide");
        assert_eq!(
            s.note.as_deref(),
            Some(
                "'# range wide' is not '# range A..B' (or '# range A..B step S'): the slider runs from 0 to 2"
            )
        );
    }
}
