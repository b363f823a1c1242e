//! The files derived from a run's store: `log.txt` (a line per generation, then a note on the
//! operators the encoding lacks), `fitness.svg`, and `best.lsys` (or the encoding's
//! extension: the last generation's best, with the record of its evaluation).
//!
//! [`Run::write_derived_files`] writes them whole from the store, when a run starts or is
//! resumed (a finished run too). While a run goes on, a generation costs the same whatever came
//! before it: its line is appended to `log.txt` (and the
//! note after it written again), `best.*` is written from the population in memory, and the
//! whole-run picture, `fitness.svg`, is redrawn only after every [`PLOT_EVERY`]th generation,
//! after the run's last, and when a run stops early. What a run leaves is byte for byte what
//! a resume writes from the store; a process killed between two writes may leave the files a
//! few generations behind the store (the plot up to [`PLOT_EVERY`] − 1), and `--resume`
//! writes them anew.

use super::{Run, RunError, status_name};
use crate::encoding::Genome;
use crate::evolve::ga::{Fallbacks, Individual, ranking};
use crate::output;
use crate::run::champion::ChampionRecord;
use crate::run::folder::{LOG_FILE, PLOT_FILE};
use crate::run::plot::{PlotError, fitness_svg_with_spreads};
use crate::run::spread::{Spread, stored_spreads};
use crate::run::store::{FineEvaluation, GenerationRecord};

/// `fitness.svg` is redrawn after every generation whose index is a multiple of this (0, 10,
/// 20, ...), after the run's last, and when a run stops early: drawing it costs as much as
/// the generations it shows, so drawing it after each would make a long run's generations
/// ever slower.
pub const PLOT_EVERY: u32 = 10;

/// Whether the plot is redrawn after generation `index` of a run of `generations`.
pub fn plot_due(index: u32, generations: u32) -> bool {
    index.is_multiple_of(PLOT_EVERY) || index + 1 >= generations
}

/// What the derived files hold, as this process wrote them.
pub(super) struct Written {
    /// Every stored generation's figures, for the plot.
    generations: Vec<GenerationRecord>,
    /// The spread of each generation's best over its walks (none without habitats or trials).
    spreads: Vec<Spread>,
    /// How many of them the plot shows.
    drawn: usize,
    /// The bytes of `log.txt`'s generation lines ...
    lines: u64,
    /// ... and of the whole file (the note after them).
    length: u64,
}

impl<G: Genome> Run<G> {
    /// Writes the files derived from the store anew, each whole through a temporary file:
    /// `log.txt` (a line per stored generation), `fitness.svg`, and `best.lsys` (or the
    /// encoding's extension: the best individual of the last stored generation).
    pub fn write_derived_files(&mut self) -> Result<(), RunError> {
        let generations = self.store.generations()?;
        let fallbacks = self.fallbacks_by_generation()?;
        let lines: String = generations.iter().map(|g| self.log_line(g)).collect();
        // The operators the encoding lacks, said once, with the count the store gives.
        let note = match (generations.last(), fallbacks.last()) {
            (Some(last), Some(fallen)) => fallback_note(fallen, G::NAME, last.index),
            _ => String::new(),
        };
        output::write(&self.dir.join(LOG_FILE), format!("{lines}{note}"))?;
        if let Some(last) = generations.last() {
            let population = self.population(last.index)?;
            self.write_best(&population, last)?;
        }
        // The best's walks are in its record: read only for a run that has some.
        let spreads = if self.config.task.is_plain() {
            Vec::new()
        } else {
            stored_spreads(&self.store)?
        };
        self.draw(&generations, &spreads)?;
        self.written = Some(Written {
            spreads,
            drawn: generations.len(),
            lines: lines.len() as u64,
            length: (lines.len() + note.len()) as u64,
            generations,
        });
        Ok(())
    }

    /// Advances the derived files by generation `stats.index`, just stored, whose members
    /// are `population` and after which `fallen` children in all were made by mutation
    /// instead of the scheduled operator: its line appended to `log.txt` (the file written
    /// whole instead if it is not as this process left it), `best.*` written from
    /// `population`, the plot redrawn when [`plot_due`].
    pub(super) fn advance_derived_files(
        &mut self,
        population: &[Individual<G>],
        stats: &GenerationRecord,
        fallen: &Fallbacks,
    ) -> Result<(), RunError> {
        let Some(mut written) = self.written.take() else {
            return self.write_derived_files();
        };
        written.generations.push(stats.clone());
        if let Some(&best) = ranking(population).first() {
            written
                .spreads
                .extend(Spread::of(stats.index, &population[best].evaluation));
        }
        let line = self.log_line(stats);
        let note = fallback_note(fallen, G::NAME, stats.index);
        let log = self.dir.join(LOG_FILE);
        let as_left = std::fs::symlink_metadata(&log)
            .is_ok_and(|m| m.file_type().is_file() && m.len() == written.length);
        if as_left {
            output::replace_tail(&log, written.lines, format!("{line}{note}"))?;
            written.lines += line.len() as u64;
        } else {
            let lines: String = written
                .generations
                .iter()
                .map(|g| self.log_line(g))
                .collect();
            output::write(&log, format!("{lines}{note}"))?;
            written.lines = lines.len() as u64;
        }
        written.length = written.lines + note.len() as u64;
        self.write_best(population, stats)?;
        if plot_due(stats.index, self.config.ga.generations as u32) {
            self.draw(&written.generations, &written.spreads)?;
            written.drawn = written.generations.len();
        }
        self.written = Some(written);
        Ok(())
    }

    /// Draws the plot if it shows fewer generations than the store holds.
    pub(super) fn catch_up_plot(&mut self) -> Result<(), RunError> {
        if let Some(written) = &self.written
            && written.drawn < written.generations.len()
        {
            self.draw(&written.generations, &written.spreads)?;
        }
        if let Some(written) = &mut self.written {
            written.drawn = written.generations.len();
        }
        Ok(())
    }

    /// The line of `log.txt` of generation `g`.
    fn log_line(&self, g: &GenerationRecord) -> String {
        format!(
            "generation {}: {}: best {:.6}{}, mean {:.6}, median {:.6}, valid {:.0}%, {} evaluations, {} simulated in {:.1} s\n",
            g.index,
            self.config.task.fitness_label(),
            g.best,
            fine_note(g.best_fine.as_ref()),
            g.mean,
            g.median,
            g.valid_fraction * 100.0,
            g.evaluations,
            g.evaluations.saturating_sub(g.reused),
            g.wall_seconds,
        )
    }

    /// Writes `best.*`: the best of `population`, generation `g`, with the record of its
    /// evaluation.
    fn write_best(
        &self,
        population: &[Individual<G>],
        g: &GenerationRecord,
    ) -> Result<(), RunError> {
        let Some(&best) = ranking(population).first() else {
            return Ok(());
        };
        let b = &population[best];
        let fine = match &g.best_fine {
            Some(f) => format!(
                "; re-walked at the fine reference setting: {} ({})",
                f.fitness, f.status
            ),
            None => String::new(),
        };
        let note = format!(
            "The best individual of {} after generation {} ({}): fitness {} ({}){fine}.\nGrow it with `ontogeny grow`; `ontogeny eval` on this file repeats its evaluation, whose every input the line below records.",
            self.dir.display(),
            g.index,
            self.config.task.fitness_label(),
            b.evaluation.fitness,
            status_name(b),
        );
        let record = ChampionRecord::new(
            b.evaluation.fitness,
            &self.config.task,
            b.develop_seed,
            &self.config.limits,
        );
        let text = record.file_text(&b.genome, &note);
        let name = format!("best.{}", G::TEXT_EXTENSION);
        output::write(&self.dir.join(name), text.as_bytes())?;
        Ok(())
    }

    /// Draws `fitness.svg` of `generations`, with the spread of each one's best over its
    /// walks, `spreads` (none without habitats or trials).
    fn draw(&self, generations: &[GenerationRecord], spreads: &[Spread]) -> Result<(), RunError> {
        let ga = &self.config.ga;
        let algorithm = match ga.algorithm.is_generational() {
            true => String::new(),
            false => format!(", steady-state ({} in flight)", ga.in_flight()),
        };
        let title = format!(
            "{}: {} on the {} task{algorithm}",
            self.dir.display(),
            G::NAME,
            self.config.task.task.name()
        );
        let y_desc = format!("fitness: {}", self.config.task.fitness_measure());
        fitness_svg_with_spreads(
            &self.dir.join(PLOT_FILE),
            generations,
            spreads,
            &title,
            &y_desc,
        )
        .map_err(|e| match e {
            PlotError::Output(e) => RunError::Output(e),
            other => RunError::Plot(other.to_string()),
        })
    }
}

/// " (fine reference 4.100000)" for a log line, or nothing when the best was not verified.
fn fine_note(fine: Option<&FineEvaluation>) -> String {
    match fine {
        Some(f) if f.status == "ok" => format!(" (fine reference {:.6})", f.fitness),
        Some(f) => format!(" (fine reference {:.6}, {})", f.fitness, f.status),
        None => String::new(),
    }
}

/// The line of `log.txt` that says, once, how many children the encoding could not mate
/// (made by mutation instead) through generation `last`; nothing when there were none.
fn fallback_note(f: &Fallbacks, encoding: &str, last: u32) -> String {
    if f.crossover == 0 && f.graft == 0 {
        return String::new();
    }
    format!(
        "note: the {encoding} encoding has no {}: {} children of generations 1 to {last} were made by mutation instead\n",
        match (f.crossover > 0, f.graft > 0) {
            (true, true) => "crossover or grafting",
            (true, false) => "crossover",
            _ => "grafting",
        },
        f.crossover + f.graft
    )
}
