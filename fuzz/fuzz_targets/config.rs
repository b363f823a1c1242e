//! A configuration TOML, read as `ontogeny evolve --config`, `evolve --resume` (a run
//! directory's `config.toml`) and `ontogeny compare --config` / `--resume` (`compare.toml`,
//! `evolve.toml`) read it, for every encoding's limits.

#![no_main]

use libfuzzer_sys::fuzz_target;
use ontogeny::encoding::{
    CheckedLimits, ContinuousGenome, ContinuousLimits, DirectGenome, DirectLimits, Genome,
    GraphGenome, GraphLimits, LSystemGenome, LSystemLimits,
};
use ontogeny::evolve::ga::GaSettings;
use ontogeny::lang::Source;
use ontogeny::run::config::{
    ConfigFile, RunConfig, check_settings, encoding_of, read_config, read_run_config,
};
use ontogeny::study::compare::{self, evaluations_of, generations_for};
use ontogeny::task::{TaskKind, TaskSpec};
use serde::de::DeserializeOwned;

/// What the CLI derives from a checked GA setting before it evolves anything.
fn use_settings(ga: &GaSettings, fresh: bool) {
    let _ = ga.survivors();
    let _ = ga.breeder_count();
    let _ = evaluations_of(ga, fresh);
    let _ = generations_for(ga, fresh, 1_000);
    let _ = generations_for(ga, fresh, u64::MAX);
}

/// `evolve --config FILE`: the file's settings with the preset under them (`start`).
fn evolve_config<G: Genome>(source: &Source) {
    let file: ConfigFile<G::Limits> = match read_config(source) {
        Ok(f) => f,
        Err(e) => {
            let _ = e.to_string();
            return;
        }
    };
    let ga = file.ga.resolve();
    let task = file.task.as_ref().map_or_else(
        || TaskSpec::new(TaskKind::Walker),
        |tables| tables.spec(tables.kind()),
    );
    match check_settings(&ga, &task, &[G::NAME]) {
        Ok(()) => use_settings(&ga, task.trials.fresh),
        Err(e) => {
            let _ = e.to_string();
            return;
        }
    }
    let config = RunConfig {
        encoding: G::NAME.to_string(),
        seed: file.seed.unwrap_or(1),
        init: None,
        verify_best: file.verify_best.unwrap_or(true),
        cache: file.cache.unwrap_or(true),
        ga,
        task,
        limits: file.limits.unwrap_or_default(),
    };
    // What `Run::start` writes, read back as `--resume` reads it.
    if let Ok(text) = config.to_toml() {
        let written = Source::new("config.toml", text);
        let _ = read_run_config::<G::Limits>(&written);
    }
}

/// `evolve --resume DIR`: the run directory's `config.toml`.
fn run_config<L: DeserializeOwned + CheckedLimits>(source: &Source) {
    match read_run_config::<L>(source) {
        // The genetic algorithm starts from these settings as they are.
        Ok(config) => use_settings(&config.ga, config.task.trials.fresh),
        Err(e) => {
            let _ = e.to_string();
        }
    }
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let source = Source::new("fuzz.toml", text);
    match encoding_of(&source) {
        Ok(encoding) => {
            let _ = encoding;
        }
        Err(e) => {
            let _ = e.to_string();
            return;
        }
    }
    evolve_config::<LSystemGenome>(&source);
    evolve_config::<ContinuousGenome>(&source);
    evolve_config::<DirectGenome>(&source);
    evolve_config::<GraphGenome>(&source);
    run_config::<LSystemLimits>(&source);
    run_config::<ContinuousLimits>(&source);
    run_config::<DirectLimits>(&source);
    run_config::<GraphLimits>(&source);
    // `compare --config FILE`: limits are refused there, so any TOML value reads.
    if let Ok(file) = read_config::<toml::Value>(&source) {
        let mut ga = file.ga.resolve();
        ga.generations = 1;
        let task = file.task.as_ref().map_or_else(
            || TaskSpec::new(TaskKind::Walker),
            |tables| tables.spec(tables.kind()),
        );
        if check_settings(&ga, &task, &[]).is_ok() {
            let _ = generations_for(&ga, task.trials.fresh, 1_000_000);
        }
    }
    // `compare --resume DIR` / `--merge DIR`: the text as `compare.toml` beside a valid
    // `evolve.toml`, then as `evolve.toml` beside a valid `compare.toml`, read by
    // `compare::open`, then the budget `run_all` computes from them.
    let root = std::env::temp_dir().join(format!("ontogeny-fuzz-config-{}", std::process::id()));
    if std::fs::create_dir_all(&root).is_err() {
        return;
    }
    for (name, other, other_text) in [
        ("compare.toml", "evolve.toml", VALID_SHARED),
        ("evolve.toml", "compare.toml", VALID_MANIFEST),
    ] {
        if std::fs::write(root.join(name), text).is_err()
            || std::fs::write(root.join(other), other_text).is_err()
        {
            return;
        }
        match compare::open(&root) {
            Ok((manifest, arms)) => {
                let _ = arms.len() * manifest.replicates;
                for arm in &arms {
                    use_settings(&arm.settings.ga, arm.settings.task.trials.fresh);
                }
            }
            Err(e) => {
                let _ = e.to_string();
            }
        }
    }
});

/// A comparison's `compare.toml` as `compare --plan` writes it.
const VALID_MANIFEST: &str =
    "encodings = [\"lsystem\", \"graph\"]\nreplicates = 10\nevaluations = 10\nseed = 1\n";

/// A comparison's `evolve.toml`: a preset's settings and the default walker.
const VALID_SHARED: &str = "[ga]\npreset = \"chaumont\"\npopulation = 4\ngenerations = 3\nelite = 0.2\nbreeders = 0.0\nasexual = 0.4\ncrossover = 0.3\nmutation_rate = 0.1\nmutation_chance_after_mating = 0.1\nmutation_rate_after_mating = 0.05\n\n[task]\ntask = \"walker\"\n";
