//! A configuration and a genome together, as `ontogeny evolve --config FILE --init GENOME`
//! takes them: the input is a TOML configuration, a line `---`, then a grammar (`.lsys`) or,
//! for the `graph` encoding, a graph genome's JSON. The configuration goes through every
//! check a run's does (its settings, then its encoding's `[limits]` ranges); a configuration
//! that passes them has its genome read against those limits, derived and developed under
//! them: the grammar grown as `grow` grows it (the limits' `max_modules`, `max_parts` and
//! derivation length, or for a continuous genome its `time` and `dt`), and the genome
//! developed as evolution develops it. Nothing may panic, and the work stays bounded by the
//! limits (libFuzzer's `-timeout` catches a runaway).

#![no_main]

use libfuzzer_sys::fuzz_target;
use ontogeny::encoding::{
    ContinuousGenome, DirectGenome, Genome, GraphGenome, LSystemGenome, LoadOptions, grow_grammar,
};
use ontogeny::lang::Source;
use ontogeny::lsystem::{DeriveOptions, LSystem};
use ontogeny::run::config::{ConfigFile, check_limits, check_settings, encoding_of, read_config};
use ontogeny::task::{TaskKind, TaskSpec};

/// The configuration `config` read and checked as a run's is, with the encoding's limits;
/// `None` when a check refuses it.
fn checked<G: Genome>(config: &Source) -> Option<G::Limits> {
    let file: ConfigFile<G::Limits> = read_config(config).ok()?;
    let ga = file.ga.resolve();
    let task = file.task.as_ref().map_or_else(
        || TaskSpec::new(TaskKind::Walker),
        |tables| tables.spec(tables.kind()),
    );
    check_settings(&ga, &task, &[G::NAME]).ok()?;
    let limits = file.limits.unwrap_or_default();
    match check_limits(&limits, Some(config)) {
        Ok(()) => Some(limits),
        Err(e) => {
            let _ = e.to_string();
            None
        }
    }
}

/// The genome text read against `limits` and developed as evolution develops it.
fn develop<G: Genome>(genome: &str, limits: &G::Limits) {
    let read = match G::NAME {
        "graph" => G::read_text(genome, limits),
        _ => G::from_lsys(genome, limits),
    };
    match read {
        Ok(g) => {
            let _ = g.develop(limits, 7).map(|c| c.parts.len());
            let _ = g.to_text();
        }
        Err(e) => {
            let _ = e.to_string();
        }
    }
}

/// The grammar grown to its last frame as `ontogeny grow` grows it, under the limits.
fn grow(genome: &str, derive: DeriveOptions, steps: Option<u64>, max_parts: usize) {
    let Ok(lsys) = LSystem::from_text("genome.lsys", genome) else {
        return;
    };
    let options = LoadOptions {
        derive,
        steps,
        max_parts,
        ..LoadOptions::default()
    };
    match grow_grammar(&lsys, &options, &mut |_| {}) {
        Ok(loaded) => {
            let _ = loaded.creature.parts.len();
        }
        Err(e) => {
            let _ = e.to_string();
        }
    }
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let (config, genome) = text.split_once("\n---\n").unwrap_or((text, ""));
    let source = Source::new("fuzz.toml", config);
    let Ok(encoding) = encoding_of(&source) else {
        return;
    };
    match encoding.as_deref().unwrap_or("lsystem") {
        "lsystem-continuous" => {
            let Some(limits) = checked::<ContinuousGenome>(&source) else {
                return;
            };
            let derive = DeriveOptions {
                max_modules: limits.max_modules,
                time: Some(limits.time),
                dt: Some(limits.dt),
                ..DeriveOptions::default()
            };
            grow(genome, derive, None, limits.max_parts);
            develop::<ContinuousGenome>(genome, &limits);
        }
        "direct" => {
            let Some(limits) = checked::<DirectGenome>(&source) else {
                return;
            };
            develop::<DirectGenome>(genome, &limits);
        }
        "graph" => {
            let Some(limits) = checked::<GraphGenome>(&source) else {
                return;
            };
            develop::<GraphGenome>(genome, &limits);
        }
        _ => {
            let Some(limits) = checked::<LSystemGenome>(&source) else {
                return;
            };
            let derive = DeriveOptions {
                max_modules: limits.max_modules,
                ..DeriveOptions::default()
            };
            // A grammar asks for its own derivation length; the limits cap it.
            let steps = LSystem::from_text("genome.lsys", genome).ok().map(|l| {
                l.derivation_length()
                    .unwrap_or(0)
                    .min(limits.derivation_length)
            });
            grow(genome, derive, steps, limits.max_parts);
            develop::<LSystemGenome>(genome, &limits);
        }
    }
});
