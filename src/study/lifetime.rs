//! Development during the walk, generation by generation (`ontogeny runs growth DIR`):
//! Kriegman, Cheney & Bongard's measure of how much development remains during an
//! evaluation, for runs whose creatures grow while they walk (`[task] develop = "during"`).
//! For every generation of every run found under DIR (as `runs plasticity` finds them), it
//! reads what each individual's stored evaluation says its creature grew during the walk:
//! the **body**'s parts added and length gained (m), the **brain**'s neurons and links added.
//! It gives the generation's best individual's figures (rank 1, as `replay` ranks) and the
//! mean over the generation's individuals that were walked; with habitats or trials, an
//! individual's figure is the mean over its walks. Nothing is walked again, nothing written.

use serde::Serialize;

use super::plasticity::{FoundRun, PlasticityError};
use super::stats::median;
use crate::evolve::ga::ranking_by;
use crate::run::folder::STORE_FILE;
use crate::run::store::{IndividualRecord, RunStore};
use crate::task::Evaluation;

/// The evaluation terms that say how much a creature grew during its walk, in the order of
/// [`Grown`]'s fields.
pub const GROWTH_TERMS: [&str; 4] = [
    "grown_parts",
    "grown_length",
    "grown_neurons",
    "grown_links",
];

/// How much a creature grew during its walk (or a mean of such figures).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Grown {
    /// Parts added.
    pub parts: f64,
    /// Length gained (m): the sum of the parts' lengthening and of the new parts' lengths.
    pub length: f64,
    /// Neurons added.
    pub neurons: f64,
    /// Links added.
    pub links: f64,
}

impl Grown {
    /// The figures of one evaluation: its terms, or with habitats or trials the mean over its
    /// walks of theirs; `None` when it has none (a creature that did not grow during its walk,
    /// or one that failed before walking).
    pub fn of(evaluation: &Evaluation) -> Option<Grown> {
        let read = |terms: &std::collections::BTreeMap<String, f64>| {
            let values: Option<Vec<f64>> = GROWTH_TERMS
                .iter()
                .map(|t| terms.get(*t).copied())
                .collect();
            values.map(|v| Grown {
                parts: v[0],
                length: v[1],
                neurons: v[2],
                links: v[3],
            })
        };
        if let Some(grown) = read(&evaluation.terms) {
            return Some(grown);
        }
        let walks: Vec<Grown> = evaluation
            .units()
            .iter()
            .filter_map(|u| read(&u.terms))
            .collect();
        Grown::mean(&walks)
    }

    /// The mean of `all`; `None` when it is empty.
    pub fn mean(all: &[Grown]) -> Option<Grown> {
        if all.is_empty() {
            return None;
        }
        let n = all.len() as f64;
        let sum = |f: fn(&Grown) -> f64| all.iter().map(f).sum::<f64>() / n;
        Some(Grown {
            parts: sum(|g| g.parts),
            length: sum(|g| g.length),
            neurons: sum(|g| g.neurons),
            links: sum(|g| g.links),
        })
    }

    /// Whether anything grew.
    pub fn any(&self) -> bool {
        self.parts > 0.0 || self.length != 0.0 || self.neurons > 0.0 || self.links > 0.0
    }
}

/// One run measured, generation by generation.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RunGrowth {
    /// Its condition (see `runs plasticity`).
    pub condition: String,
    /// Its name (`rep-K` in a comparison).
    pub run: String,
    /// Its complete generations, in order.
    pub generations: Vec<GenerationGrowth>,
}

/// One generation measured.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GenerationGrowth {
    /// The generation's index.
    pub generation: u32,
    /// The best individual's fitness.
    pub best: f64,
    /// What the best individual grew during its walk (`None`: no growth figures).
    pub champion: Option<Grown>,
    /// The mean over the individuals with growth figures (`None`: none has them).
    pub mean: Option<Grown>,
    /// How many of the generation grew.
    pub growers: Growers,
}

/// How many individuals of a generation grew during their walks.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Growers {
    /// Individuals with growth figures (walked, growing during the walk).
    pub measured: usize,
    /// Of which those that grew anything.
    pub growing: usize,
    /// The generation's individuals.
    pub population: usize,
}

/// What an individual stored in a run grew during its walk, from the evaluation its record
/// keeps (`None` when it keeps none, or none with growth figures).
fn stored_growth(record: &IndividualRecord) -> Option<Grown> {
    #[derive(serde::Deserialize)]
    struct Stored {
        evaluation: Evaluation,
    }
    let stored: Stored = serde_json::from_str(&record.genome_json).ok()?;
    Grown::of(&stored.evaluation)
}

/// Measures every complete generation of `found`, read from its store (whatever its genome).
pub fn measure_run(found: &FoundRun) -> Result<RunGrowth, PlasticityError> {
    let store = RunStore::open_read_only(&found.dir.join(STORE_FILE))
        .map_err(|e| PlasticityError::Run(e.into()))?;
    let complete = store
        .last_generation()
        .map_err(|e| PlasticityError::Run(e.into()))?
        .map_or(0, |last| last + 1);
    let mut generations = Vec::with_capacity(complete as usize);
    for generation in 0..complete {
        let population = store
            .individuals(generation)
            .map_err(|e| PlasticityError::Run(e.into()))?;
        let grown: Vec<Grown> = population.iter().filter_map(stored_growth).collect();
        let best = ranking_by(&population, |r| r.fitness)
            .first()
            .map(|&b| &population[b]);
        generations.push(GenerationGrowth {
            generation,
            best: best.map_or(f64::NAN, |b| b.fitness),
            champion: best.and_then(stored_growth),
            mean: Grown::mean(&grown),
            growers: Growers {
                measured: grown.len(),
                growing: grown.iter().filter(|g| g.any()).count(),
                population: population.len(),
            },
        });
    }
    Ok(RunGrowth {
        condition: found.condition.clone(),
        run: found.name.clone(),
        generations,
    })
}

/// Measures every run of `runs`, in order, with a note for each run left out (no complete
/// generation, or walks that did not grow); `progress(done, total)` after each. `Err` when
/// no run has growth figures.
pub fn measure_runs(
    runs: &[FoundRun],
    progress: &mut dyn FnMut(usize, usize),
) -> Result<(Vec<RunGrowth>, Vec<String>), PlasticityError> {
    let mut measured = Vec::new();
    let mut notes = Vec::new();
    for (done, found) in runs.iter().enumerate() {
        let run = measure_run(found)?;
        let why_not = if run.generations.is_empty() {
            Some("no complete generation yet")
        } else if run.generations.iter().all(|g| g.growers.measured == 0) {
            Some("its creatures do not grow during their walks (develop = \"before\")")
        } else {
            None
        };
        match why_not {
            Some(why) => notes.push(format!("{}: {why}", found.dir.display())),
            None => measured.push(run),
        }
        progress(done + 1, runs.len());
    }
    if measured.is_empty() {
        return Err(PlasticityError::Input(match (runs, notes.as_slice()) {
            ([_], [why]) => why.clone(),
            _ => format!(
                "no run has a generation with creatures that grow during their walks: {}",
                notes.join("; ")
            ),
        }));
    }
    for note in &mut notes {
        note.push_str("; left out");
    }
    Ok((measured, notes))
}

/// The columns of [`csv`].
pub const CSV_COLUMNS: &str = "condition,run,generation,best,champion_parts,champion_length,champion_neurons,champion_links,mean_parts,mean_length,mean_neurons,mean_links,measured,growing,population";

/// The measurement as CSV: [`CSV_COLUMNS`], then a row per run and generation, every number
/// in full (empty where there is none).
pub fn csv(runs: &[RunGrowth]) -> String {
    let number = |v: f64| {
        if v.is_finite() {
            v.to_string()
        } else {
            String::new()
        }
    };
    let four = |g: Option<Grown>| match g {
        Some(g) => [g.parts, g.length, g.neurons, g.links].map(number),
        None => Default::default(),
    };
    let mut lines = vec![CSV_COLUMNS.to_string()];
    for run in runs {
        for r in &run.generations {
            let mut cells = vec![
                run.condition.clone(),
                run.run.clone(),
                r.generation.to_string(),
                number(r.best),
            ];
            cells.extend(four(r.champion));
            cells.extend(four(r.mean));
            let g = r.growers;
            cells.extend([g.measured, g.growing, g.population].map(|n| n.to_string()));
            lines.push(cells.join(","));
        }
    }
    lines.join("\n")
}

/// The measurement as one JSON object: `dir` and `runs`, each as [`RunGrowth`] serialises (a
/// figure that is none is `null`).
pub fn json(dir: &std::path::Path, runs: &[RunGrowth]) -> String {
    let value = serde_json::json!({
        "dir": dir.display().to_string(),
        "runs": runs,
    });
    serde_json::to_string_pretty(&value).unwrap_or_default()
}

/// The median over `runs`' generation `generation` of `figure` of what `pick` takes from it
/// (`None` where no run has it).
fn median_of(
    runs: &[&RunGrowth],
    generation: usize,
    pick: fn(&GenerationGrowth) -> Option<Grown>,
    figure: fn(&Grown) -> f64,
) -> Option<f64> {
    let values: Vec<f64> = runs
        .iter()
        .filter_map(|r| {
            r.generations
                .get(generation)
                .and_then(pick)
                .map(|g| figure(&g))
        })
        .collect();
    (!values.is_empty()).then(|| median(&values))
}

/// The measurement for people: per condition, a row per generation with the medians over its
/// runs of the best individual's figures and of the generation's means, and the share of the
/// walked individuals that grew anything.
pub fn text(runs: &[RunGrowth]) -> String {
    let mut conditions: Vec<&str> = Vec::new();
    for r in runs {
        if !conditions.contains(&r.condition.as_str()) {
            conditions.push(&r.condition);
        }
    }
    let cell = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4}"));
    let figures: [fn(&Grown) -> f64; 4] = [|g| g.parts, |g| g.length, |g| g.neurons, |g| g.links];
    let mut out = Vec::new();
    for condition in conditions {
        let of: Vec<&RunGrowth> = runs.iter().filter(|r| r.condition == condition).collect();
        out.push(format!(
            "condition {condition}: {} run(s); medians over the runs of the best individual's growth during its walk and of the generation's mean",
            of.len()
        ));
        out.push(format!(
            "{:>5} {:>4} | {:>7} {:>8} {:>8} {:>6} | {:>7} {:>8} {:>8} {:>6} | {:>7}",
            "gen",
            "runs",
            "parts",
            "length",
            "neurons",
            "links",
            "parts",
            "length",
            "neurons",
            "links",
            "growing"
        ));
        let longest = of.iter().map(|r| r.generations.len()).max().unwrap_or(0);
        for generation in 0..longest {
            let here = of
                .iter()
                .filter(|r| r.generations.len() > generation)
                .count();
            let mut cells: Vec<String> = Vec::new();
            for pick in [
                (|g: &GenerationGrowth| g.champion) as fn(&GenerationGrowth) -> Option<Grown>,
                |g| g.mean,
            ] {
                for figure in figures {
                    cells.push(cell(median_of(&of, generation, pick, figure)));
                }
            }
            let (measured, growing) = of
                .iter()
                .filter_map(|r| r.generations.get(generation))
                .fold((0, 0), |(m, g), r| {
                    (m + r.growers.measured, g + r.growers.growing)
                });
            let share = (measured > 0).then(|| growing as f64 / measured as f64);
            out.push(format!(
                "{generation:>5} {here:>4} | {:>7} {:>8} {:>8} {:>6} | {:>7} {:>8} {:>8} {:>6} | {:>7}",
                cells[0], cells[1], cells[2], cells[3], cells[4], cells[5], cells[6], cells[7],
                cell(share),
            ));
        }
    }
    out.join("\n")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::task::Status;

    fn evaluation(terms: &[(&str, f64)]) -> Evaluation {
        let mut e = Evaluation::invalid("walker", String::new());
        e.status = Status::Ok;
        e.terms = terms.iter().map(|(k, v)| (k.to_string(), *v)).collect();
        e
    }

    #[test]
    fn an_evaluation_s_growth_is_read_from_its_terms() {
        let e = evaluation(&[
            ("grown_parts", 2.0),
            ("grown_length", 0.5),
            ("grown_neurons", 1.0),
            ("grown_links", 3.0),
            ("D_w", 4.0),
        ]);
        assert_eq!(
            Grown::of(&e),
            Some(Grown {
                parts: 2.0,
                length: 0.5,
                neurons: 1.0,
                links: 3.0
            })
        );
        assert_eq!(Grown::of(&evaluation(&[("D_w", 4.0)])), None);
    }

    #[test]
    fn the_mean_of_two_growths_is_taken_figure_by_figure() {
        let a = Grown {
            parts: 1.0,
            length: 0.2,
            neurons: 0.0,
            links: 2.0,
        };
        let b = Grown {
            parts: 0.0,
            length: 0.4,
            neurons: 2.0,
            links: 0.0,
        };
        let mean = Grown::mean(&[a, b]).unwrap();
        assert_eq!((mean.parts, mean.neurons, mean.links), (0.5, 1.0, 1.0));
        assert!((mean.length - 0.3).abs() < 1e-15);
        assert_eq!(Grown::mean(&[]), None);
        assert!(!Grown::default().any());
        assert!(a.any());
    }
}
