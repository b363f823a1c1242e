//! Plasticity (`ontogeny runs plasticity DIR`): what a comparison's champions do in each
//! habitat and how their bodies answer the chemical cue. For each run's champion (the last
//! generation's best, the individual its `best.*` holds) it gives
//!
//! - its **fitness in each habitat**, walked again with the run's own task, trials and
//!   simulator setting (the trials as drawn for generation 0, as `ontogeny eval` walks them;
//!   a habitat's fitness is the aggregate of its trials, the failure floor if one failed),
//!   beside the same figure taken from the evaluation the run stored;
//! - its **reaction norm**: the champion developed in each *cue* its task gives, and how the
//!   morphs differ ([`phenotype_differences`]).
//!
//! **Cues.** Development reads a habitat's chemical array and nothing else of it (its world
//! comes later, in the walk), so habitats with the same array grow the same body. The cues are
//! the task's distinct arrays, in the order their first habitat comes: habitats `flat` `[0]` and
//! `steps` `[1]` are two cues of one habitat each; the random-cue control's `flat-0` `[0]`,
//! `flat-1` `[1]`, `steps-0` `[0]` and `steps-1` `[1]` are two cues of two habitats each, so its
//! norm is between the cue's values, not between grounds. A habitat without an array (the
//! genome's own) is a cue of its own. Arrays are the same when every value is, bit for bit.
//!
//! **The norm's figures**, for the morphs of the cues (with more than two cues, the largest
//! over every pair): |Δparts|, |Δjoints| and |Δneurons|; the change of the total volume
//! relative to the earlier cue's morph, |ΔV|/V; the summed size difference Σ|Δsize|, over the
//! parts both morphs have (the same id: the same place in order) the sum of the differences of
//! their three edge lengths (m); and whether the body **depends on the cue**: whether any two
//! morphs differ at all (a count, a size, a placement, a joint's kind, or the brain's neurons
//! and links).
//!
//! Runs are found as `runs list` finds them; a run's **condition** is the folder that holds
//! it: in a comparison, the condition's (or encoding's) name, elsewhere the folder's path
//! under DIR (or its name, for a run directly in DIR or DIR itself). Read-only: nothing is
//! written.

use std::path::{Path, PathBuf};

use serde::Serialize;

use super::compare::{self, CompareError};
use super::listing::{self, Kind};
use super::stats::median;
use crate::creature::{Creature, phenotype_differences};
use crate::encoding::Genome;
use crate::evolve::habitats::{Growth, develop_with_seedlings, evaluate_here};
use crate::number::{format_number, format_numbers};
use crate::run::pick::{PickError, individual_by_rank};
use crate::run::store::RunStore;
use crate::run::{Run, RunError, encoding_of_run, unknown_encoding_of_run};
use crate::task::{Evaluation, FAILURE_FITNESS, Status, TaskSpec};

/// Why plasticity could not be measured.
#[derive(Debug, thiserror::Error)]
pub enum PlasticityError {
    /// Bad input: no run under the directory, a run without a complete generation, a
    /// comparison's file that does not read.
    #[error("{0}")]
    Input(String),
    /// A run could not be read.
    #[error(transparent)]
    Run(#[from] RunError),
    /// Anything else.
    #[error("{0}")]
    Other(String),
}

impl From<PickError> for PlasticityError {
    fn from(e: PickError) -> Self {
        match e {
            PickError::Run(e) => PlasticityError::Run(e),
            PickError::Input(m) => PlasticityError::Input(m),
        }
    }
}

impl From<CompareError> for PlasticityError {
    fn from(e: CompareError) -> Self {
        match e {
            CompareError::Input(m) => PlasticityError::Input(m),
            other => PlasticityError::Other(other.to_string()),
        }
    }
}

/// A run found under the directory measured.
#[derive(Clone, Debug, PartialEq)]
pub struct FoundRun {
    /// Its condition: the folder that holds it (see the module's documentation).
    pub condition: String,
    /// Its name in the tables: `rep-K` in a comparison, else its folder's name.
    pub name: String,
    /// Its directory.
    pub dir: PathBuf,
}

/// The runs under `dir`, condition by condition, and a note for each replicate of a
/// comparison not started yet. `dir` is a comparison (its conditions in its order, replicate
/// by replicate), a run, or a directory with runs under it (in path order, numbers in names
/// by value: `rep-2` before `rep-10`). `Err` when there is no run.
pub fn find_runs(dir: &Path) -> Result<(Vec<FoundRun>, Vec<String>), PlasticityError> {
    let mut notes = Vec::new();
    if dir.join("compare.toml").is_file() {
        let (manifest, _) = compare::open(dir)?;
        let mut found = Vec::new();
        for name in manifest.names() {
            for k in 1..=manifest.replicates {
                let run = compare::replicate_dir(dir, name, k);
                if RunStore::is_vacant(&run.join("run.sqlite")) {
                    notes.push(format!("{name} rep-{k}: not started; left out"));
                    continue;
                }
                found.push(FoundRun {
                    condition: name.clone(),
                    name: format!("rep-{k}"),
                    dir: run,
                });
            }
        }
        if found.is_empty() {
            return Err(PlasticityError::Input(format!(
                "{}: no replicate of the comparison has started",
                dir.display()
            )));
        }
        return Ok((found, notes));
    }
    let listed = listing::list(dir)
        .map_err(|e| PlasticityError::Input(format!("{}: cannot read it: {e}", dir.display())))?;
    let mut runs: Vec<PathBuf> = listed
        .into_iter()
        .filter(|l| l.kind == Kind::Run)
        .map(|l| l.path)
        .collect();
    if runs.is_empty() {
        return Err(PlasticityError::Input(format!(
            "{} holds no run (no run.sqlite in it or under it) and is no comparison (no compare.toml)",
            dir.display()
        )));
    }
    runs.sort_by_key(|p| natural_key(&p.to_string_lossy()));
    let found = runs
        .into_iter()
        .map(|run| FoundRun {
            condition: condition_of(dir, &run),
            name: file_name(&run),
            dir: run,
        })
        .collect();
    Ok((found, notes))
}

/// The last component of `path`, or the path itself when it has none (`.`).
fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

/// The condition of the run in `run`, found under `root`: the folder that holds it, as a
/// path under `root`; for a run directly in `root`, or `root` itself, that folder's name.
fn condition_of(root: &Path, run: &Path) -> String {
    let parent = run.parent().unwrap_or(run);
    match parent.strip_prefix(root) {
        Ok(rel) if !rel.as_os_str().is_empty() => rel.display().to_string(),
        Ok(_) => file_name(root),
        Err(_) => {
            // `root` is the run: its parent's name (`.` when it has none).
            let parent = std::fs::canonicalize(run)
                .ok()
                .and_then(|p| p.parent().map(file_name));
            parent.unwrap_or_else(|| ".".into())
        }
    }
}

/// A key that orders names with numbers by the numbers' values: `rep-2` before `rep-10`.
fn natural_key(text: &str) -> Vec<(String, u128)> {
    let mut key = Vec::new();
    let mut word = String::new();
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        if c.is_ascii_digit() {
            let mut digits = c.to_string();
            while let Some(d) = chars.next_if(char::is_ascii_digit) {
                digits.push(d);
            }
            key.push((
                std::mem::take(&mut word),
                digits.parse().unwrap_or(u128::MAX),
            ));
        } else {
            word.push(c);
        }
    }
    key.push((word, 0));
    key
}

/// A champion's fitness in one habitat.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct HabitatFitness {
    /// The habitat's name (empty for a task without habitats: its one implicit habitat).
    pub name: String,
    /// Its array's initial values (`None`: the genome's own).
    pub environment: Option<Vec<f64>>,
    /// The fitness walked again: the aggregate of the habitat's trials (the failure floor if
    /// one failed).
    pub fitness: f64,
    /// How those walks ended: `ok`, or the first failure's status.
    pub status: String,
    /// The same figure from the evaluation the run stored (`None` when it kept no walk of
    /// this habitat).
    pub stored: Option<f64>,
}

/// The body a champion grows under one cue.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CueMorph {
    /// The cue: the array's initial values (`None`: the genome's own).
    pub environment: Option<Vec<f64>>,
    /// The habitats that give it, in order.
    pub habitats: Vec<String>,
    /// Parts of the morph.
    pub parts: usize,
    /// Joints.
    pub joints: usize,
    /// Neurons.
    pub neurons: usize,
    /// Its parts' total volume (m³).
    pub volume: f64,
    /// Its height as built, before it is dropped: the vertical extent of its bounding box (m).
    pub height: f64,
}

/// How a champion's morphs differ (see the module's documentation).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Norm {
    /// Whether any two morphs differ at all.
    pub depends_on_cue: bool,
    /// |Δparts|.
    pub parts_change: f64,
    /// |Δjoints|.
    pub joints_change: f64,
    /// |Δneurons|.
    pub neurons_change: f64,
    /// |ΔV|/V, V the earlier cue's morph's volume (0 when it has none).
    pub volume_change: f64,
    /// Σ|Δsize| over the parts both morphs have (m).
    pub size_change: f64,
}

/// One run's champion measured.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ChampionPlasticity {
    /// Its run's condition.
    pub condition: String,
    /// Its run's name (`rep-K`).
    pub run: String,
    /// Its run's directory.
    pub dir: String,
    /// The generation it is the best of (the run's last complete one).
    pub generation: u32,
    /// The fitness the run stored for it (the aggregate over every habitat and trial).
    pub fitness: f64,
    /// Its fitness in each habitat, in the task's order.
    pub habitats: Vec<HabitatFitness>,
    /// Its morph under each cue, in order (none when it does not develop).
    pub cues: Vec<CueMorph>,
    /// Its reaction norm (`None` with fewer than two cues, or when it does not develop).
    pub norm: Option<Norm>,
    /// Why it does not develop, when it does not.
    pub error: Option<String>,
}

/// The cues of `task`: its distinct arrays in the order their first habitat comes, each with
/// the indices of the habitats that give it.
pub fn cues_of(task: &TaskSpec) -> Vec<(Option<Vec<f64>>, Vec<usize>)> {
    let bits = |v: Option<&[f64]>| v.map(|v| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>());
    let mut cues: Vec<(Option<Vec<f64>>, Vec<usize>)> = Vec::new();
    for h in 0..task.habitat_count() {
        let array = task.habitat_environment(h);
        match cues
            .iter_mut()
            .find(|(a, _)| bits(a.as_deref()) == bits(array))
        {
            Some((_, habitats)) => habitats.push(h),
            None => cues.push((array.map(<[f64]>::to_vec), vec![h])),
        }
    }
    cues
}

/// The morphs of `creatures` (one per habitat of `task`) under each cue, and their norm
/// (`None` with fewer than two cues).
pub fn reaction_norm(task: &TaskSpec, creatures: &[Creature]) -> (Vec<CueMorph>, Option<Norm>) {
    let cues = cues_of(task);
    let morphs: Vec<&Creature> = cues.iter().map(|(_, hs)| &creatures[hs[0]]).collect();
    let shown = cues
        .iter()
        .zip(&morphs)
        .map(|((environment, hs), c)| CueMorph {
            environment: environment.clone(),
            habitats: hs
                .iter()
                .map(|&h| task.habitat_name(h).to_string())
                .collect(),
            parts: c.parts.len(),
            joints: c.joints.len(),
            neurons: c.brain.neurons.len(),
            volume: c.parts.iter().map(|p| p.volume()).sum(),
            height: {
                let (lo, hi) = c.bounding_box();
                hi.y - lo.y
            },
        })
        .collect();
    if morphs.len() < 2 {
        return (shown, None);
    }
    let mut norm = Norm::default();
    let change = |(a, b): (usize, usize)| (a as f64 - b as f64).abs();
    for i in 0..morphs.len() {
        for j in i + 1..morphs.len() {
            let d = phenotype_differences(morphs[i], morphs[j]);
            norm.depends_on_cue |= !d.is_same();
            norm.parts_change = norm.parts_change.max(change(d.parts));
            norm.joints_change = norm.joints_change.max(change(d.joints));
            norm.neurons_change = norm.neurons_change.max(change(d.neurons));
            let volume = if d.volume.0 > 0.0 {
                (d.volume.1 - d.volume.0).abs() / d.volume.0
            } else {
                0.0
            };
            norm.volume_change = norm.volume_change.max(volume);
            norm.size_change = norm.size_change.max(d.summed_resize);
        }
    }
    (shown, Some(norm))
}

/// The fitness habitat `habitat` of `task` gets from `evaluation`'s walks: the aggregate of
/// its trials, the failure floor if one failed; `None` when it has none. A plain task's one
/// habitat gets the evaluation's fitness.
pub fn habitat_fitness(task: &TaskSpec, evaluation: &Evaluation, habitat: usize) -> Option<f64> {
    if task.is_plain() {
        return Some(evaluation.fitness);
    }
    let name = task.habitat_name(habitat);
    let walks: Vec<_> = evaluation
        .units()
        .iter()
        .filter(|u| u.name == name)
        .collect();
    if walks.is_empty() {
        return None;
    }
    if walks.iter().any(|u| u.status != Status::Ok) {
        return Some(FAILURE_FITNESS);
    }
    let fitnesses: Vec<f64> = walks.iter().map(|u| u.fitness).collect();
    Some(task.trials.aggregate.of(&fitnesses))
}

/// Measures the champion of `found`, a run of genome `G`; `None` for a run without a complete
/// generation.
pub fn measure_run<G: Genome>(
    found: &FoundRun,
) -> Result<Option<ChampionPlasticity>, PlasticityError> {
    let dir = &found.dir;
    let run = Run::<G>::open_read_only(dir)?;
    if run.last_generation()?.is_none() {
        return Ok(None);
    }
    let (generation, best) = individual_by_rank(&run, dir, None, 1)?;
    let task = &run.config().task;
    let mut measured = ChampionPlasticity {
        condition: found.condition.clone(),
        run: found.name.clone(),
        dir: dir.display().to_string(),
        generation,
        fitness: best.evaluation.fitness,
        habitats: Vec::new(),
        cues: Vec::new(),
        norm: None,
        error: None,
    };
    let habitat = |h: usize, fitness: f64, status: String| HabitatFitness {
        name: task.habitat_name(h).to_string(),
        environment: task.habitat_environment(h).map(<[f64]>::to_vec),
        fitness,
        status,
        stored: habitat_fitness(task, &best.evaluation, h),
    };
    match develop_with_seedlings(&best.genome, run.limits(), best.develop_seed, task) {
        Ok((creatures, seedlings)) => {
            let text = best.genome.to_text();
            for h in 0..task.habitat_count() {
                let walked =
                    evaluate_here(task, &creatures, Growth::of(&seedlings, &text), Some(h))
                        .map_err(|e| PlasticityError::Other(e.to_string()))?;
                measured
                    .habitats
                    .push(habitat(h, walked.fitness, walked.status.name().into()));
            }
            (measured.cues, measured.norm) = reaction_norm(task, &creatures);
        }
        Err(e) => {
            for h in 0..task.habitat_count() {
                measured
                    .habitats
                    .push(habitat(h, FAILURE_FITNESS, Status::Invalid.name().into()));
            }
            measured.error = Some(e.0);
        }
    }
    Ok(Some(measured))
}

/// Measures the champion of every run of `runs`, in order, with a note for each run left out
/// for want of a complete generation; `progress(done, total)` is called after each. The first
/// run that cannot be read stops the measurement, its error naming it; `Err` too when no run
/// has a complete generation.
pub fn measure_runs(
    runs: &[FoundRun],
    progress: &mut dyn FnMut(usize, usize),
) -> Result<(Vec<ChampionPlasticity>, Vec<String>), PlasticityError> {
    let mut measured = Vec::with_capacity(runs.len());
    let mut notes = Vec::new();
    for (done, found) in runs.iter().enumerate() {
        let encoding = encoding_of_run(&found.dir)?;
        let champion = crate::with_genome!(
            encoding.as_str(),
            G => measure_run::<G>(found),
            |other| Err(PlasticityError::Input(unknown_encoding_of_run(&found.dir, other)))
        )?;
        match champion {
            Some(champion) => measured.push(champion),
            None => notes.push(format!(
                "{}: no complete generation yet; left out",
                found.dir.display()
            )),
        }
        progress(done + 1, runs.len());
    }
    if measured.is_empty() {
        return Err(PlasticityError::Input(match runs {
            [one] => format!("{}: no complete generation yet", one.dir.display()),
            _ => "no run has a complete generation yet".to_string(),
        }));
    }
    Ok((measured, notes))
}

/// A condition's summary: medians over its champions.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Summary {
    /// The condition.
    pub condition: String,
    /// Its champions.
    pub champions: usize,
    /// The median fitness (walked again) in each habitat, in the order the champions' tasks
    /// name them, over the champions that have it.
    pub median_fitness: Vec<(String, f64)>,
    /// Champions with a reaction norm (two cues or more, and a body).
    pub with_norm: usize,
    /// Of those, how many have a body that depends on the cue.
    pub depending: usize,
    /// `depending / with_norm` (`None` without a norm).
    pub share_depending: Option<f64>,
    /// The medians of the norms' figures, over the champions with one (NaN without).
    pub median_norm: NormMedians,
}

/// The medians of the figures of several norms ([`Norm`]).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NormMedians {
    /// Of |Δparts|.
    pub parts_change: f64,
    /// Of |Δjoints|.
    pub joints_change: f64,
    /// Of |Δneurons|.
    pub neurons_change: f64,
    /// Of |ΔV|/V.
    pub volume_change: f64,
    /// Of Σ|Δsize| (m).
    pub size_change: f64,
}

/// Groups `champions` by condition, in the order the conditions first come.
pub fn by_condition(champions: &[ChampionPlasticity]) -> Vec<(String, Vec<&ChampionPlasticity>)> {
    let mut groups: Vec<(String, Vec<&ChampionPlasticity>)> = Vec::new();
    for c in champions {
        match groups.iter_mut().find(|(name, _)| *name == c.condition) {
            Some((_, group)) => group.push(c),
            None => groups.push((c.condition.clone(), vec![c])),
        }
    }
    groups
}

/// The summary of one condition's `champions`.
pub fn summarise(condition: &str, champions: &[&ChampionPlasticity]) -> Summary {
    let mut names: Vec<String> = Vec::new();
    for c in champions {
        for h in &c.habitats {
            if !names.contains(&h.name) {
                names.push(h.name.clone());
            }
        }
    }
    let median_fitness = names
        .into_iter()
        .map(|name| {
            let values: Vec<f64> = champions
                .iter()
                .flat_map(|c| c.habitats.iter().filter(|h| h.name == name))
                .map(|h| h.fitness)
                .collect();
            let m = median(&values);
            (name, m)
        })
        .collect();
    let norms: Vec<&Norm> = champions.iter().filter_map(|c| c.norm.as_ref()).collect();
    let depending = norms.iter().filter(|n| n.depends_on_cue).count();
    let of = |f: fn(&Norm) -> f64| median(&norms.iter().map(|n| f(n)).collect::<Vec<_>>());
    Summary {
        condition: condition.to_string(),
        champions: champions.len(),
        median_fitness,
        with_norm: norms.len(),
        depending,
        share_depending: (!norms.is_empty()).then(|| depending as f64 / norms.len() as f64),
        median_norm: NormMedians {
            parts_change: of(|n| n.parts_change),
            joints_change: of(|n| n.joints_change),
            neurons_change: of(|n| n.neurons_change),
            volume_change: of(|n| n.volume_change),
            size_change: of(|n| n.size_change),
        },
    }
}

/// A habitat's name in a table: `-` for the implicit one.
fn habitat_label(name: &str) -> &str {
    if name.is_empty() { "-" } else { name }
}

/// An array for people: `[0 0.5]`, or `own` (the genome's own).
fn array_text(values: Option<&[f64]>) -> String {
    match values {
        Some(v) => format!("[{}]", format_numbers(v)),
        None => "own".to_string(),
    }
}

/// A figure for a table: four decimals, `-` for NaN.
fn cell(v: f64) -> String {
    if v.is_nan() {
        "-".into()
    } else {
        format!("{v:.4}")
    }
}

/// The counts of each cue's morph, `5/7`.
fn counts(cues: &[CueMorph], f: fn(&CueMorph) -> usize) -> String {
    let counts: Vec<String> = cues.iter().map(|c| f(c).to_string()).collect();
    counts.join("/")
}

/// The measurement for people: a line naming the directory, then, for each condition, a line
/// naming its cues, a table (a row per champion: its stored fitness, its fitness in each
/// habitat, whether its body depends on the cue, each cue's parts, joints and neurons, |ΔV|/V
/// and Σ|Δsize|) and its summary.
pub fn text(dir: &Path, champions: &[ChampionPlasticity]) -> String {
    let groups = by_condition(champions);
    let mut lines = vec![format!(
        "{}: plasticity of {} champion(s) in {} condition(s); a cue is a distinct array, its morph the body grown in it",
        dir.display(),
        champions.len(),
        groups.len()
    )];
    for (condition, group) in &groups {
        let summary = summarise(condition, group);
        let cues: Vec<String> = group
            .iter()
            .find(|c| !c.cues.is_empty())
            .map_or(&[][..], |c| &c.cues[..])
            .iter()
            .map(|c| {
                let names: Vec<&str> = c.habitats.iter().map(|h| habitat_label(h)).collect();
                format!(
                    "{} ({})",
                    array_text(c.environment.as_deref()),
                    names.join(", ")
                )
            })
            .collect();
        lines.push(String::new());
        lines.push(format!(
            "condition {condition}: {} champion(s); cues {}",
            group.len(),
            if cues.is_empty() {
                "none".to_string()
            } else {
                cues.join(", ")
            }
        ));
        let names: Vec<&str> = summary
            .median_fitness
            .iter()
            .map(|(n, _)| habitat_label(n))
            .collect();
        let width = names
            .iter()
            .map(|n| n.chars().count())
            .max()
            .unwrap_or(0)
            .max(10);
        let mut header = format!("{:<8} {:>10} |", "run", "fitness");
        for n in &names {
            header.push_str(&format!(" {n:>width$}"));
        }
        header.push_str(&format!(
            " | {:>4} {:>7} {:>7} {:>7} {:>8} {:>9}",
            "cue", "parts", "joints", "neurons", "|ΔV|/V", "Σ|Δsize|"
        ));
        lines.push(header);
        for c in group {
            let mut row = format!("{:<8} {:>10} |", c.run, cell(c.fitness));
            for (name, _) in &summary.median_fitness {
                let f = c
                    .habitats
                    .iter()
                    .find(|h| h.name == *name)
                    .map_or(f64::NAN, |h| h.fitness);
                row.push_str(&format!(" {:>width$}", cell(f)));
            }
            match (&c.error, &c.norm) {
                (Some(e), _) => row.push_str(&format!(" | does not develop: {e}")),
                (None, norm) => row.push_str(&format!(
                    " | {:>4} {:>7} {:>7} {:>7} {:>8} {:>9}",
                    norm.as_ref()
                        .map_or("-", |n| if n.depends_on_cue { "yes" } else { "no" }),
                    counts(&c.cues, |m| m.parts),
                    counts(&c.cues, |m| m.joints),
                    counts(&c.cues, |m| m.neurons),
                    norm.as_ref().map_or("-".into(), |n| cell(n.volume_change)),
                    norm.as_ref().map_or("-".into(), |n| cell(n.size_change)),
                )),
            }
            lines.push(row);
        }
        lines.push(summary_line(&summary));
    }
    lines.join("\n")
}

/// A condition's summary in words.
fn summary_line(s: &Summary) -> String {
    let fitness: Vec<String> = s
        .median_fitness
        .iter()
        .map(|(n, f)| format!("{} {}", habitat_label(n), cell(*f)))
        .collect();
    let mut line = format!("median fitness: {}", fitness.join(", "));
    match s.share_depending {
        Some(share) => {
            let m = &s.median_norm;
            line.push_str(&format!(
                "; the body depends on the cue in {} of {} champion(s) ({}%); median |Δparts| {}, |Δjoints| {}, |Δneurons| {}, |ΔV|/V {}, Σ|Δsize| {} m",
                s.depending,
                s.with_norm,
                format_number((share * 1000.0).round() / 10.0),
                format_number(m.parts_change),
                format_number(m.joints_change),
                format_number(m.neurons_change),
                cell(m.volume_change),
                cell(m.size_change),
            ));
        }
        None => line.push_str("; no reaction norm (fewer than two cues, or no body)"),
    }
    line
}

/// The columns of [`csv`].
pub const CSV_COLUMNS: &str = "condition,run,habitat,environment,fitness,status,stored_fitness,parts,joints,neurons,volume,height,depends_on_cue,parts_change,joints_change,neurons_change,volume_change,size_change";

/// A CSV field: quoted when it holds a comma, a quote or a line break.
fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// The measurement as CSV: [`CSV_COLUMNS`], then a row per champion and habitat, every number
/// in full (empty where there is none): the habitat's array (its values separated by spaces;
/// empty for the genome's own), the fitness walked again and its status, the stored figure,
/// the morph grown there (parts, joints, neurons, volume, height as built) and the champion's norm.
pub fn csv(champions: &[ChampionPlasticity]) -> String {
    let mut lines = vec![CSV_COLUMNS.to_string()];
    let number = |v: f64| {
        if v.is_nan() {
            String::new()
        } else {
            v.to_string()
        }
    };
    for c in champions {
        for h in &c.habitats {
            let morph = c.cues.iter().find(|m| m.habitats.contains(&h.name));
            let environment = h.environment.as_ref().map_or(String::new(), |v| {
                v.iter().map(f64::to_string).collect::<Vec<_>>().join(" ")
            });
            let mut cells = vec![
                csv_field(&c.condition),
                csv_field(&c.run),
                csv_field(&h.name),
                environment,
                number(h.fitness),
                h.status.clone(),
                h.stored.map_or(String::new(), number),
            ];
            cells.extend(match morph {
                Some(m) => [
                    m.parts.to_string(),
                    m.joints.to_string(),
                    m.neurons.to_string(),
                    number(m.volume),
                    number(m.height),
                ],
                None => Default::default(),
            });
            cells.extend(match &c.norm {
                Some(n) => [
                    n.depends_on_cue.to_string(),
                    number(n.parts_change),
                    number(n.joints_change),
                    number(n.neurons_change),
                    number(n.volume_change),
                    number(n.size_change),
                ],
                None => Default::default(),
            });
            lines.push(cells.join(","));
        }
    }
    lines.join("\n")
}

/// The measurement as one JSON object: `dir`, and `conditions`, each with `name`,
/// `champions` (each as [`ChampionPlasticity`] serialises) and `summary` (as [`Summary`]
/// does, `median_fitness` an object from habitat to median); a number that is none is `null`.
pub fn json(dir: &Path, champions: &[ChampionPlasticity]) -> String {
    let conditions: Vec<serde_json::Value> = by_condition(champions)
        .into_iter()
        .map(|(name, group)| {
            let summary = summarise(&name, &group);
            let mut value = serde_json::to_value(&summary).unwrap_or_default();
            let medians: serde_json::Map<String, serde_json::Value> = summary
                .median_fitness
                .iter()
                .map(|(n, f)| (n.clone(), serde_json::json!(f)))
                .collect();
            value["median_fitness"] = serde_json::Value::Object(medians);
            serde_json::json!({
                "name": name,
                "champions": group,
                "summary": value,
            })
        })
        .collect();
    let value = serde_json::json!({
        "dir": dir.display().to_string(),
        "conditions": conditions,
    });
    serde_json::to_string_pretty(&value).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_with_numbers_are_ordered_by_value() {
        let mut names = vec!["a/rep-10", "a/rep-2", "b/rep-1", "a/rep-1"];
        names.sort_by_key(|n| natural_key(n));
        assert_eq!(names, ["a/rep-1", "a/rep-2", "a/rep-10", "b/rep-1"]);
    }

    #[test]
    fn a_run_s_condition_is_the_folder_that_holds_it() {
        let root = Path::new("runs/plasticity");
        assert_eq!(
            condition_of(root, Path::new("runs/plasticity/plastic/rep-1")),
            "plastic"
        );
        assert_eq!(
            condition_of(root, Path::new("runs/plasticity/a/b/rep-1")),
            "a/b"
        );
        assert_eq!(
            condition_of(root, Path::new("runs/plasticity/rep-1")),
            "plasticity"
        );
    }

    #[test]
    fn habitats_of_one_array_are_one_cue() {
        let habitat = |name: &str, environment: Option<Vec<f64>>| crate::task::Habitat {
            name: name.into(),
            world: Default::default(),
            environment,
            trials: None,
        };
        let task = TaskSpec {
            habitats: vec![
                habitat("flat-0", Some(vec![0.0])),
                habitat("flat-1", Some(vec![1.0])),
                habitat("steps-0", Some(vec![0.0])),
                habitat("own", None),
            ],
            ..TaskSpec::default()
        };
        assert_eq!(
            cues_of(&task),
            [
                (Some(vec![0.0]), vec![0, 2]),
                (Some(vec![1.0]), vec![1]),
                (None, vec![3]),
            ]
        );
    }

    #[test]
    fn a_csv_field_with_a_comma_is_quoted() {
        assert_eq!(csv_field("rep-1"), "rep-1");
        assert_eq!(csv_field("a,b"), "\"a,b\"");
        assert_eq!(csv_field("say \"x\""), "\"say \"\"x\"\"\"");
    }
}
