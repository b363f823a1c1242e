//! Reading the creature a verb is given (`eval`, `export`, `bench`): an L-system grown to its
//! last frame, a `creature.json`, or a graph genome's JSON, each checked before use.

use std::path::Path;

use anyhow::Context;
use ontogeny::creature::{Creature, Severity};
use ontogeny::develop::{BuildOptions, grow_last};
use ontogeny::lang::FileKind;
use ontogeny::lsystem::{DEFAULT_MAX_MODULES, LSystem};

use super::derive::{DevelopmentArgs, derive_options, discrete_steps};
use super::progress::Progress;

/// Loads a creature from `file`: an L-system (`.lsys`, grown to its last frame with the
/// development flags and seed, invalid beyond `max_parts` parts), a `creature.json`, which
/// must be well formed and have at most `max_parts` parts, or a graph genome's JSON
/// (checked against the default limits before it develops, and developed with them).
pub(super) fn load_creature(
    file: &Path,
    development: &DevelopmentArgs,
    seed: Option<u64>,
    max_parts: usize,
) -> anyhow::Result<Creature> {
    if file.extension().is_some_and(|e| e == "json") {
        let given = development.given();
        if !given.is_empty() || seed.is_some() {
            let mut flags = given;
            if seed.is_some() {
                flags.push("--seed");
            }
            eprintln!(
                "warning: {} grow a creature from a grammar; {} is not one: ignored",
                flags.join(", "),
                file.display()
            );
        }
        let text = std::fs::read_to_string(file)
            .with_context(|| format!("cannot read {}", file.display()))?;
        // A graph genome (a run's best.json) develops with the default limits; a file that is
        // neither it nor a creature (a recording, ...) is refused with what it is.
        match FileKind::of(file, text.as_bytes()) {
            FileKind::GraphGenome => {
                let genome = super::genome::read_graph(file)?;
                return Ok(genome.creature(ontogeny::encoding::GraphLimits::default().max_parts));
            }
            FileKind::Creature | FileKind::Json | FileKind::Grammar => {}
            other => return Err(other.refusal(file, "a creature").into()),
        }
        let creature: Creature = serde_json::from_str(&text)
            .map_err(|e| super::bad(format!("{}: not a creature: {e}", file.display())))?;
        creature.check_file(max_parts).map_err(|problem| {
            super::bad(format!(
                "{}: not a usable creature: {problem}",
                file.display()
            ))
        })?;
        return Ok(creature);
    }
    let lsys = LSystem::from_path(file)?;
    let options = derive_options(development, seed, DEFAULT_MAX_MODULES);
    let steps = discrete_steps(&lsys, &options, development.steps, "building")?;
    let build_options = BuildOptions {
        max_parts,
        ..BuildOptions::default()
    };
    let mut progress = Progress::new("growing");
    let creature = grow_last(&lsys, &options, steps, &build_options, &mut |f| {
        progress.set(f)
    })?
    .creature;
    progress.finish();
    // The builder's warnings, as `grow` lists them (its errors make the creature invalid,
    // which the evaluation reports).
    for problem in &creature.problems {
        if problem.severity == Severity::Warning {
            eprintln!("{problem}");
        }
    }
    Ok(creature)
}
