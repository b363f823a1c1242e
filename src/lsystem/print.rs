//! A derivation as `ontogeny derive` prints it: a line per frame (text, or JSON Lines with
//! `step`, `t`, `modules` and `env`) and per event; and the development options checked
//! against the mode, discrete or continuous time.

use serde::Serialize;

use super::{DeriveOptions, Event, LSystem, ModuleString, NamedModule};
use crate::environment::Environment;
use crate::lang::{Diagnostic, DiagnosticKind};
use crate::number::format_number;

#[derive(Serialize)]
struct Frame<'a> {
    step: u64,
    t: f64,
    modules: Vec<NamedModule<'a>>,
    env: &'a [f64],
}

#[derive(Serialize)]
struct EventLine<'a> {
    event: &'a Event,
}

/// Whether `lsys` develops in continuous time with `options` (a `time:` in the file, or
/// `--time`).
pub fn continuous_mode(lsys: &LSystem, options: &DeriveOptions) -> bool {
    options.time.is_some() || lsys.is_continuous()
}

/// The line of frame `step` (at time `t`) of `lsys`: `string` and the environment `env`, as
/// text (`3: ...` in discrete time, `t=1.5: ...` in continuous time) or as a JSON object.
pub fn frame_line(
    lsys: &LSystem,
    options: &DeriveOptions,
    (step, t): (u64, f64),
    string: &ModuleString,
    env: &Environment,
    json: bool,
) -> Result<String, serde_json::Error> {
    if json {
        return serde_json::to_string(&Frame {
            step,
            t,
            modules: string.to_modules(lsys.symbols()),
            env: env.values(),
        });
    }
    let env_text = if env.is_empty() {
        String::new()
    } else {
        let values: Vec<String> = env.values().iter().map(|v| format!("{v}")).collect();
        format!("  env [{}]", values.join(" "))
    };
    Ok(if continuous_mode(lsys, options) {
        format!("t={}: {}{env_text}", format_number(t), lsys.display(string))
    } else {
        format!("{step}: {}{env_text}", lsys.display(string))
    })
}

/// The line of an event of continuous development, as text or as a JSON object.
pub fn event_line(event: &Event, json: bool) -> Result<String, serde_json::Error> {
    if json {
        return serde_json::to_string(&EventLine { event });
    }
    let rule = match event.rule_line {
        Some(line) => format!("the rule on line {line} applies"),
        None => "no rule applies".to_string(),
    };
    Ok(format!(
        "  event t={}: {}: {rule}",
        format_number(event.t),
        event.module
    ))
}

/// The development options checked against the mode (every verb that develops a grammar
/// calls this): `steps` (`--steps`) is an error in continuous time, `dt` and `timing` in
/// discrete time. Returns a note for a discrete file with productions but no derivation
/// length from it or `steps` (`doing` says what happens to the axiom alone, e.g. "growing").
pub fn check_mode(
    lsys: &LSystem,
    options: &DeriveOptions,
    steps: Option<u64>,
    doing: &str,
) -> Result<Option<String>, Diagnostic> {
    check_continuous_options(lsys, options)?;
    if continuous_mode(lsys, options) {
        if steps.is_some() {
            return Err(Diagnostic::without_location(
                DiagnosticKind::Semantic,
                "--steps counts discrete steps; in continuous time use --time and --dt",
            ));
        }
    } else if steps.is_none() && lsys.derivation_length().is_none() && lsys.has_productions() {
        return Ok(Some(format!(
            "note: {} has no 'derivation length:' and no --steps was given: {doing} the axiom only",
            lsys.source().name()
        )));
    }
    Ok(None)
}

/// `dt` and `timing` (`--dt`, `--timing`) for a discrete file (no differential rules, no
/// `time:`) and no `time`: an error, since they would change nothing.
pub fn check_continuous_options(lsys: &LSystem, options: &DeriveOptions) -> Result<(), Diagnostic> {
    if !continuous_mode(lsys, options) && (options.dt.is_some() || options.timing.is_some()) {
        return Err(Diagnostic::without_location(
            DiagnosticKind::Semantic,
            format!(
                "--dt and --timing are for continuous time: give --time T (or 'time:' in {})",
                lsys.source().name()
            ),
        ));
    }
    Ok(())
}

/// Parses an `--env INDEX=VALUE` assignment of an initial environment value.
pub fn parse_env_assignment(text: &str) -> Result<(usize, f64), String> {
    let (index, value) = text
        .split_once('=')
        .ok_or_else(|| format!("'{text}' is not INDEX=VALUE"))?;
    let index = index
        .trim()
        .parse()
        .map_err(|_| format!("'{index}' is not an index (0, 1, 2, ...)"))?;
    let value: f64 = value
        .trim()
        .parse()
        .map_err(|_| format!("'{value}' is not a number"))?;
    if !value.is_finite() {
        return Err(format!("'{value}' is not a finite number"));
    }
    Ok((index, value))
}
