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
use crate::encoding::Genome;
use crate::evolve::ga::ranking;
use crate::run::{Run, encoding_of_run};
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

/// One generation of one run measured.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GenerationGrowth {
    /// Its run's condition (see `runs plasticity`).
    pub condition: String,
    /// Its run's name (`rep-K` in a comparison).
    pub run: String,
    /// The generation's index.
    pub generation: u32,
    /// The best individual's fitness.
    pub best: f64,
    /// What the best individual grew during its walk (`None`: no growth figures).
    pub champion: Option<Grown>,
    /// The mean over the individuals with growth figures (`None`: none has them).
    pub mean: Option<Grown>,
    /// Individuals with growth figures.
    pub measured: usize,
    /// Of which those that grew anything during the walk.
    pub growing: usize,
    /// The generation's individuals.
    pub population: usize,
}

/// Measures every complete generation of `found`, a run of genome `G`.
pub fn measure_run<G: Genome>(found: &FoundRun) -> Result<Vec<GenerationGrowth>, PlasticityError> {
    let run = Run::<G>::open_read_only(&found.dir)?;
    let Some(last) = run.last_generation()? else {
        return Ok(Vec::new());
    };
    let mut rows = Vec::with_capacity(last as usize + 1);
    for generation in 0..=last {
        let population = run.population(generation)?;
        let grown: Vec<Grown> = population
            .iter()
            .filter_map(|i| Grown::of(&i.evaluation))
            .collect();
        let best = ranking(&population).first().map(|&b| &population[b]);
        rows.push(GenerationGrowth {
            condition: found.condition.clone(),
            run: found.name.clone(),
            generation,
            best: best.map_or(f64::NAN, |b| b.evaluation.fitness),
            champion: best.and_then(|b| Grown::of(&b.evaluation)),
            mean: Grown::mean(&grown),
            measured: grown.len(),
            growing: grown.iter().filter(|g| g.any()).count(),
            population: population.len(),
        });
    }
    Ok(rows)
}

/// Measures every run of `runs`, in order, with a note for each run left out (no complete
/// generation, or walks that did not grow); `progress(done, total)` after each. `Err` when
/// no run has growth figures.
pub fn measure_runs(
    runs: &[FoundRun],
    progress: &mut dyn FnMut(usize, usize),
) -> Result<(Vec<GenerationGrowth>, Vec<String>), PlasticityError> {
    let mut rows = Vec::new();
    let mut notes = Vec::new();
    for (done, found) in runs.iter().enumerate() {
        let encoding = encoding_of_run(&found.dir)?;
        let measured = crate::with_genome!(
            encoding.as_str(),
            G => measure_run::<G>(found),
            |other| Err(PlasticityError::Input(format!(
                "{}: unknown encoding '{other}'",
                found.dir.display()
            )))
        )?;
        if measured.is_empty() {
            notes.push(format!(
                "{}: no complete generation yet; left out",
                found.dir.display()
            ));
        } else if measured.iter().all(|r| r.measured == 0) {
            notes.push(format!(
                "{}: its creatures do not grow during their walks (develop = \"before\"); left out",
                found.dir.display()
            ));
        } else {
            rows.extend(measured);
        }
        progress(done + 1, runs.len());
    }
    if rows.is_empty() {
        return Err(PlasticityError::Input(match runs {
            [one] => format!(
                "{}: no generation with creatures that grow during their walks",
                one.dir.display()
            ),
            _ => "no run has a generation with creatures that grow during their walks".into(),
        }));
    }
    Ok((rows, notes))
}

/// The columns of [`csv`].
pub const CSV_COLUMNS: &str = "condition,run,generation,best,champion_parts,champion_length,champion_neurons,champion_links,mean_parts,mean_length,mean_neurons,mean_links,measured,growing,population";

/// The measurement as CSV: [`CSV_COLUMNS`], then a row per run and generation, every number
/// in full (empty where there is none).
pub fn csv(rows: &[GenerationGrowth]) -> String {
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
    for r in rows {
        let mut cells = vec![
            r.condition.clone(),
            r.run.clone(),
            r.generation.to_string(),
            number(r.best),
        ];
        cells.extend(four(r.champion));
        cells.extend(four(r.mean));
        cells.extend([r.measured, r.growing, r.population].map(|n| n.to_string()));
        lines.push(cells.join(","));
    }
    lines.join("\n")
}

/// The measurement as one JSON object: `dir` and `generations`, a row per run and generation
/// as [`GenerationGrowth`] serialises (a figure that is none is `null`).
pub fn json(dir: &std::path::Path, rows: &[GenerationGrowth]) -> String {
    let value = serde_json::json!({
        "dir": dir.display().to_string(),
        "generations": rows,
    });
    serde_json::to_string_pretty(&value).unwrap_or_default()
}

/// The measurement for people: per condition, a row per generation with the medians over its
/// runs of the best individual's figures and of the generation's means, and the share of the
/// walked individuals that grew anything.
pub fn text(rows: &[GenerationGrowth]) -> String {
    let mut out = Vec::new();
    let conditions: Vec<&str> = {
        let mut seen: Vec<&str> = Vec::new();
        for r in rows {
            if !seen.contains(&r.condition.as_str()) {
                seen.push(&r.condition);
            }
        }
        seen
    };
    let cell = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4}"));
    for condition in conditions {
        let of: Vec<&GenerationGrowth> = rows.iter().filter(|r| r.condition == condition).collect();
        let runs = {
            let mut names: Vec<&str> = of.iter().map(|r| r.run.as_str()).collect();
            names.dedup();
            names.len()
        };
        out.push(format!(
            "condition {condition}: {runs} run(s); medians over the runs of the best individual's growth during its walk and of the generation's mean"
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
        let last = of.iter().map(|r| r.generation).max().unwrap_or(0);
        for generation in 0..=last {
            let here: Vec<&&GenerationGrowth> =
                of.iter().filter(|r| r.generation == generation).collect();
            if here.is_empty() {
                continue;
            }
            let middle = |f: fn(&Grown) -> f64, pick: fn(&GenerationGrowth) -> Option<Grown>| {
                let values: Vec<f64> = here.iter().filter_map(|r| pick(r).map(|g| f(&g))).collect();
                (!values.is_empty()).then(|| median(&values))
            };
            let champion = |r: &GenerationGrowth| r.champion;
            let mean = |r: &GenerationGrowth| r.mean;
            let (measured, growing) = here
                .iter()
                .fold((0, 0), |(m, g), r| (m + r.measured, g + r.growing));
            let share = (measured > 0).then(|| growing as f64 / measured as f64);
            out.push(format!(
                "{generation:>5} {:>4} | {:>7} {:>8} {:>8} {:>6} | {:>7} {:>8} {:>8} {:>6} | {:>7}",
                here.len(),
                cell(middle(|g| g.parts, champion)),
                cell(middle(|g| g.length, champion)),
                cell(middle(|g| g.neurons, champion)),
                cell(middle(|g| g.links, champion)),
                cell(middle(|g| g.parts, mean)),
                cell(middle(|g| g.length, mean)),
                cell(middle(|g| g.neurons, mean)),
                cell(middle(|g| g.links, mean)),
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
