//! Canalization (`ontogeny runs canalization RUN`): how much a genome's phenotype varies
//! under small noise in the chemical values it develops in, and under mutation. For each
//! array it develops in (a habitat's initial chemical values, or the genome's own), the
//! reference body is developed; then samples of the array, each slot moved by a uniform
//! draw in ±`noise`, and mutants of the genome are developed in it and compared with the
//! reference ([`phenotype_differences`]). Measured for each generation's best individual of
//! a run, it says whether evolution made bodies more robust (canalized) or more plastic.
//!
//! Every draw comes from the seed, one random source per sample: the figures are the same
//! on any number of threads.

use std::path::Path;

use rand::RngExt;
use rayon::prelude::*;
use serde::Serialize;

use crate::creature::{Creature, phenotype_differences};
use crate::encoding::{Genome, Rng};
use crate::environment::Environment;
use crate::evolve::ga::individual_rng;
use crate::number::format_number;
use crate::run::Run;
use crate::run::pick::{PickError, individual_by_rank};
use crate::task::TaskSpec;

/// How a measurement draws its samples.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    /// Samples per array: noisy arrays, and mutants (at least 1).
    pub samples: usize,
    /// How far each slot of a noisy array moves: a uniform draw in ±`noise` (finite, ≥ 0).
    pub noise: f64,
    /// The chance that each mutation site changes ([`Genome::mutate`]'s rate), in [0, 1].
    pub mutation_rate: f64,
    /// The seed every draw comes from.
    pub seed: u64,
}

/// The samples per array when none is asked for.
pub const DEFAULT_SAMPLES: usize = 50;

/// The noise on each slot when none is asked for.
pub const DEFAULT_NOISE: f64 = 0.05;

impl Settings {
    /// `Err` with a message for people when a setting is out of its range.
    pub fn check(&self) -> Result<(), String> {
        if self.samples == 0 {
            return Err("--samples must be at least 1, not 0".into());
        }
        if !(self.noise.is_finite() && self.noise >= 0.0) {
            return Err(format!(
                "--noise must be a finite number of 0 or more, not {}",
                self.noise
            ));
        }
        if !(0.0..=1.0).contains(&self.mutation_rate) {
            return Err(format!(
                "--rate must be between 0 and 1, not {}",
                self.mutation_rate
            ));
        }
        Ok(())
    }
}

/// What samples of one kind (noisy arrays, or mutants) did to the phenotype. Each figure is
/// over the (array, sample) pairs measured, `None` when there are none.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Figures {
    /// The share of samples whose phenotype differs from the reference's (a sample that
    /// does not develop, or develops into an invalid creature, counts as differing).
    pub changed: Option<f64>,
    /// The share of samples that do not develop or develop into an invalid creature.
    pub failed: Option<f64>,
    /// The mean of |parts − the reference's parts| over the samples that developed into a
    /// valid creature.
    pub mean_parts_change: Option<f64>,
    /// The mean of |volume − the reference's volume| / the reference's volume over the
    /// samples that developed into a valid creature.
    pub mean_volume_change: Option<f64>,
}

/// A genome's canalization: its phenotype under noise in the arrays and under mutation.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Measurement {
    /// The arrays the reference developed in (of those given): pairs of the others are not
    /// measured.
    pub arrays_developed: usize,
    /// Samples of the arrays with noise on every slot.
    pub noise: Figures,
    /// Mutants developed in each array.
    pub mutation: Figures,
}

/// One sample compared with its reference: `None` when it did not develop into a valid
/// creature, else (differs, |Δparts|, |ΔV|/V).
type Outcome = Option<(bool, f64, f64)>;

fn compare(
    reference: &Creature,
    sample: Result<Creature, crate::encoding::DevelopError>,
) -> Outcome {
    let sample = sample.ok().filter(Creature::is_valid)?;
    let d = phenotype_differences(reference, &sample);
    let parts = (d.parts.0 as f64 - d.parts.1 as f64).abs();
    let volume = if d.volume.0 > 0.0 {
        (d.volume.1 - d.volume.0).abs() / d.volume.0
    } else {
        0.0
    };
    Some((!d.is_same(), parts, volume))
}

fn figures(outcomes: &[Outcome]) -> Figures {
    if outcomes.is_empty() {
        return Figures::default();
    }
    let n = outcomes.len() as f64;
    let grown: Vec<&(bool, f64, f64)> = outcomes.iter().flatten().collect();
    let failed = outcomes.len() - grown.len();
    let changed = failed + grown.iter().filter(|o| o.0).count();
    let mean = |f: fn(&(bool, f64, f64)) -> f64| {
        (!grown.is_empty()).then(|| grown.iter().map(|o| f(o)).sum::<f64>() / grown.len() as f64)
    };
    Figures {
        changed: Some(changed as f64 / n),
        failed: Some(failed as f64 / n),
        mean_parts_change: mean(|o| o.1),
        mean_volume_change: mean(|o| o.2),
    }
}

/// `env` with every slot moved by a uniform draw in ±`noise` from `rng`.
fn noisy(env: &Environment, noise: f64, rng: &mut Rng) -> Environment {
    Environment::new(
        env.values()
            .iter()
            .map(|v| v + rng.random_range(-noise..=noise))
            .collect(),
    )
}

/// The canalization of `genome` (with its `limits` and develop seed `develop_seed`) in each
/// of `arrays`: its reference body in each, then `settings.samples` noisy copies of each
/// array and as many mutants (the same mutants in every array, developed with the same
/// seed), each compared with the reference of its array. Sample `i` draws from a random
/// source of its own, made from `settings.seed`.
pub fn measure<G: Genome>(
    genome: &G,
    limits: &G::Limits,
    develop_seed: u64,
    arrays: &[Environment],
    settings: &Settings,
) -> Measurement {
    let references: Vec<Option<Creature>> = arrays
        .iter()
        .map(|env| genome.develop_held(limits, develop_seed, Some(env)).ok())
        .collect();
    let samples = settings.samples;
    let mutants: Vec<G> = (0..samples)
        .into_par_iter()
        .map(|i| {
            let mut rng = individual_rng(settings.seed, 0, i as u32, 1);
            genome.mutate(limits, settings.mutation_rate, &mut rng)
        })
        .collect();
    let pairs: Vec<(usize, usize)> = (0..arrays.len())
        .filter(|&a| references[a].is_some())
        .flat_map(|a| (0..samples).map(move |i| (a, i)))
        .collect();
    let noise: Vec<Outcome> = pairs
        .par_iter()
        .map(|&(a, i)| {
            let mut rng = individual_rng(settings.seed, a as u32 + 1, i as u32, 0);
            let env = noisy(&arrays[a], settings.noise, &mut rng);
            let reference = references[a].as_ref().expect("a measured array");
            compare(
                reference,
                genome.develop_held(limits, develop_seed, Some(&env)),
            )
        })
        .collect();
    let mutation: Vec<Outcome> = pairs
        .par_iter()
        .map(|&(a, i)| {
            let reference = references[a].as_ref().expect("a measured array");
            compare(
                reference,
                mutants[i].develop_held(limits, develop_seed, Some(&arrays[a])),
            )
        })
        .collect();
    Measurement {
        arrays_developed: references.iter().flatten().count(),
        noise: figures(&noise),
        mutation: figures(&mutation),
    }
}

/// The arrays a genome of a run with `task` develops in: each habitat's initial chemical
/// values, or, for a habitat without them (and a task without habitats), the genome's own
/// ([`Genome::environment`]).
pub fn arrays_of<G: Genome>(genome: &G, task: &TaskSpec) -> Vec<Environment> {
    (0..task.habitat_count())
        .map(|h| match task.habitat_environment(h) {
            Some(values) => Environment::new(values.to_vec()),
            None => genome.environment(),
        })
        .collect()
}

/// The canalization of one generation's best individual.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GenerationCanalization {
    /// The generation.
    pub generation: u32,
    /// Its best individual's fitness.
    pub best: f64,
    /// Its best individual's canalization.
    #[serde(flatten)]
    pub measurement: Measurement,
}

/// The generations measured of a run whose last complete generation is `last`: every
/// `every`-th from 0, and the last.
pub fn generations_measured(last: u32, every: u32) -> Vec<u32> {
    let every = every.max(1);
    let mut measured: Vec<u32> = (0..=last).step_by(every as usize).collect();
    if measured.last() != Some(&last) {
        measured.push(last);
    }
    measured
}

/// The canalization of the best individual of each generation of `generations` of `run`
/// (whose directory is `dir`), in the arrays its task gives ([`arrays_of`]), with its
/// limits. Each generation draws from a random source of its own, made from
/// `settings.seed`; `progress(done, total)` is called after each generation.
pub fn measure_run<G: Genome>(
    run: &Run<G>,
    dir: &Path,
    generations: &[u32],
    settings: &Settings,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Vec<GenerationCanalization>, PickError> {
    let config = run.config();
    let mut rows = Vec::with_capacity(generations.len());
    for (done, &g) in generations.iter().enumerate() {
        let (generation, best) = individual_by_rank(run, dir, Some(g), 1)?;
        let seeded = Settings {
            seed: individual_rng(settings.seed, generation, 0, 2).random::<u64>(),
            ..settings.clone()
        };
        let arrays = arrays_of(&best.genome, &config.task);
        rows.push(GenerationCanalization {
            generation,
            best: best.evaluation.fitness,
            measurement: measure(
                &best.genome,
                &config.limits,
                best.develop_seed,
                &arrays,
                &seeded,
            ),
        });
        progress(done + 1, generations.len());
    }
    Ok(rows)
}

/// A figure for a table: four decimals, `-` where there is none.
fn cell(v: Option<f64>) -> String {
    v.map_or_else(|| "-".into(), |v| format!("{v:.4}"))
}

/// A figure for CSV: in full, empty where there is none.
fn csv_cell(v: Option<f64>) -> String {
    v.map_or_else(String::new, |v| v.to_string())
}

/// The settings of a measurement in words: samples, arrays, noise, rate and seed.
pub fn settings_line(settings: &Settings, arrays: usize) -> String {
    format!(
        "{} sample(s) per array, {arrays} array(s); noise ±{} on every slot; mutation rate {}; seed {}",
        settings.samples,
        format_number(settings.noise),
        format_number(settings.mutation_rate),
        settings.seed
    )
}

/// The rows as a table for people: a header of two lines, then a row per generation.
pub fn table(rows: &[GenerationCanalization]) -> String {
    let mut lines = vec![
        format!(
            "{:>5} {:>12} | {:>30} | {:>39}",
            "", "", "noise", "mutation"
        ),
        format!(
            "{:>5} {:>12} | {:>8} {:>10} {:>10} | {:>8} {:>8} {:>10} {:>10}",
            "gen",
            "best",
            "changed",
            "|Δparts|",
            "|ΔV|/V",
            "changed",
            "failed",
            "|Δparts|",
            "|ΔV|/V"
        ),
    ];
    for r in rows {
        let (n, m) = (&r.measurement.noise, &r.measurement.mutation);
        lines.push(format!(
            "{:>5} {:>12.4} | {:>8} {:>10} {:>10} | {:>8} {:>8} {:>10} {:>10}",
            r.generation,
            r.best,
            cell(n.changed),
            cell(n.mean_parts_change),
            cell(n.mean_volume_change),
            cell(m.changed),
            cell(m.failed),
            cell(m.mean_parts_change),
            cell(m.mean_volume_change),
        ));
    }
    lines.join("\n")
}

/// The columns of [`csv`].
pub const CSV_COLUMNS: &str = "generation,best,arrays_developed,noise_changed,noise_failed,noise_mean_parts_change,noise_mean_volume_change,mutation_changed,mutation_failed,mutation_mean_parts_change,mutation_mean_volume_change";

/// The rows as CSV: [`CSV_COLUMNS`], then a row per generation, every number in full (empty
/// where there is none).
pub fn csv(rows: &[GenerationCanalization]) -> String {
    let mut lines = vec![CSV_COLUMNS.to_string()];
    for r in rows {
        let m = &r.measurement;
        let mut cells = vec![
            r.generation.to_string(),
            r.best.to_string(),
            m.arrays_developed.to_string(),
        ];
        for f in [&m.noise, &m.mutation] {
            cells.extend(
                [
                    f.changed,
                    f.failed,
                    f.mean_parts_change,
                    f.mean_volume_change,
                ]
                .map(csv_cell),
            );
        }
        lines.push(cells.join(","));
    }
    lines.join("\n")
}

/// The measurement as one JSON object: the run's directory, the settings and a row per
/// generation (the figures of [`csv`], `null` where there is none).
pub fn json(dir: &Path, settings: &Settings, rows: &[GenerationCanalization]) -> String {
    let value = serde_json::json!({
        "dir": dir.display().to_string(),
        "samples": settings.samples,
        "noise": settings.noise,
        "mutation_rate": settings.mutation_rate,
        "seed": settings.seed,
        "generations": rows,
    });
    serde_json::to_string_pretty(&value).unwrap_or_default()
}
