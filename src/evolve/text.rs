//! What the command line says about runs and comparisons, as text: a generation's progress
//! line, a run's closing lines, a run's generation table (`runs show`), a comparison's progress
//! line and its report's summary. Every function returns text (lines joined by newlines, no
//! final newline); printing is the caller's.

use std::path::Path;

use super::compare::{Manifest, Report, Shared};
use super::run::{GenerationReport, exploits_stepping};
use super::store::{RunStore, StoreError};

/// A generation's progress line: its best (and the best's fine reference), mean, valid share
/// and speed, after the task's `fitness` label.
pub fn generation_line(fitness: &str, r: &GenerationReport) -> String {
    let fine = match &r.best_fine {
        Some(f) => format!(" (fine reference {:.4})", f.fitness),
        None => String::new(),
    };
    format!(
        "{fitness}: best {:.4}{fine}  mean {:.4}  valid {:.0}%  {:.1} evaluations/s",
        r.stats.best,
        r.stats.mean,
        r.stats.valid_fraction * 100.0,
        r.stats.evaluations as f64 / r.wall_seconds.max(1e-9)
    )
}

/// The evaluations of a run's generations run by one command, counted as they come.
#[derive(Clone, Debug, Default)]
pub struct RunTally {
    /// Evaluations made.
    pub evaluations: u64,
    /// Of which taken from the cache rather than simulated.
    pub reused: u64,
    /// Seconds spent evaluating.
    pub evaluating: f64,
}

impl RunTally {
    /// Counts one more generation.
    pub fn add(&mut self, r: &GenerationReport) {
        self.evaluations += r.stats.evaluations;
        self.reused += r.stats.reused;
        self.evaluating += r.evaluation_seconds;
    }

    /// The closing lines of a run of the encoding `encoding` (its genomes' files end in
    /// `extension`) in `dir`, whose last generation is `last`, after `wall` seconds: a note on
    /// children made by fallback, the final line (best, fine reference, counts, speed), a
    /// warning when the champion may exploit the step setting, and the files written.
    pub fn closing_lines(
        &self,
        dir: &Path,
        fitness: &str,
        encoding: &str,
        extension: &str,
        last: &GenerationReport,
        wall: f64,
    ) -> String {
        let r = last;
        let mut lines = Vec::new();
        let fallbacks = r.fallbacks.crossover + r.fallbacks.graft;
        if fallbacks > 0 {
            lines.push(format!(
                "note: the {encoding} encoding lacks an operator of the schedule; {fallbacks} children of this run were made by mutation instead (see log.txt)"
            ));
        }
        let fine = match &r.best_fine {
            Some(f) if f.status == "ok" => format!(" (fine reference {:.6})", f.fitness),
            Some(f) => format!(" (fine reference {:.6}, {})", f.fitness, f.status),
            None => String::new(),
        };
        lines.push(format!(
            "{}: {fitness}: generation {} best {:.6}{fine}; {} evaluations, {} simulated in {wall:.1} s ({:.1} evaluations/s), {:.1}% of the time outside evaluation",
            dir.display(),
            r.generation,
            r.stats.best,
            self.evaluations,
            self.evaluations - self.reused,
            self.evaluations as f64 / wall.max(1e-9),
            (wall - self.evaluating).max(0.0) / wall.max(1e-9) * 100.0
        ));
        if let Some(f) = &r.best_fine
            && exploits_stepping(r.stats.best, f.fitness)
        {
            lines.push(format!(
                "warning: the champion scores {:.6} at the fine reference setting, down more than half of its {:.6}: it may exploit the simulator's step setting (see docs/guide/evolving.md, \"Re-walking the best at the fine reference\")",
                f.fitness, r.stats.best
            ));
        }
        lines.push(format!(
            "wrote {0}/run.sqlite, {0}/fitness.svg, {0}/best.{extension} and {0}/log.txt",
            dir.display()
        ));
        lines.join("\n")
    }
}

/// The generation table of the run in `dir` (`ontogeny runs show`): a line on the run, a
/// header, and a row per generation. Read-only: an old run's file is shown as it is, not
/// migrated.
pub fn generation_table(dir: &Path) -> Result<String, StoreError> {
    let store = RunStore::open_read_only(&dir.join("run.sqlite"))?;
    let run = store.run()?;
    // The task and its fitness as the run's settings name them; a settings text this
    // version cannot read names the task alone.
    let task = run
        .task_spec()
        .map_or_else(|| format!("{} task", run.task), |spec| spec.fitness_label());
    let mut lines = vec![
        format!(
            "{}: {} encoding, {task}, seed {}, ontogeny {}",
            dir.display(),
            run.encoding,
            run.seed,
            run.version
        ),
        format!(
            "{:>5} {:>12} {:>12} {:>12} {:>12} {:>10} {:>7} {:>6} {:>8} {:>8}",
            "gen",
            "best",
            "best fine",
            "mean",
            "median",
            "sd",
            "valid",
            "evals",
            "seconds",
            "evals/s"
        ),
    ];
    for g in store.generations()? {
        // "–" where the best was not re-walked at the fine reference; a status other than ok
        // follows the value.
        let fine = match &g.best_fine {
            None => "–".to_string(),
            Some(f) if f.status == "ok" => format!("{:.6}", f.fitness),
            Some(f) => format!("{:.6} {}", f.fitness, f.status),
        };
        lines.push(format!(
            "{:>5} {:>12.6} {fine:>12} {:>12.6} {:>12.6} {:>10.6} {:>6.0}% {:>6} {:>8.1} {:>8.1}",
            g.index,
            g.best,
            g.mean,
            g.median,
            g.sd,
            g.valid_fraction * 100.0,
            g.evaluations,
            g.wall_seconds,
            g.evaluations_per_second
        ));
    }
    Ok(lines.join("\n"))
}

/// A duration for people: `42s`, `3m07s`, `2h05m`.
pub fn duration(seconds: f64) -> String {
    let s = seconds.round() as u64;
    if s >= 3600 {
        format!("{}h{:02}m", s / 3600, s % 3600 / 60)
    } else if s >= 60 {
        format!("{}m{:02}s", s / 60, s % 60)
    } else {
        format!("{s}s")
    }
}

/// A comparison's progress, in evaluations.
#[derive(Clone, Debug)]
pub struct ComparisonProgress {
    /// Evaluations of the whole comparison.
    pub total: u64,
    /// Evaluations made so far.
    pub done: u64,
    /// Evaluations made before this command started.
    pub at_start: u64,
    /// When this command started.
    pub started: std::time::Instant,
}

impl ComparisonProgress {
    /// Counts generation `r` of a replicate labelled `label` (of `generations` generations)
    /// and says where the comparison stands, with an estimate of the time left.
    pub fn line(&mut self, label: &str, r: &GenerationReport, generations: usize) -> String {
        self.done += r.stats.evaluations;
        let elapsed = self.started.elapsed().as_secs_f64();
        let rate = (self.done - self.at_start) as f64 / elapsed.max(1e-9);
        let left = (self.total - self.done.min(self.total)) as f64 / rate.max(1e-9);
        format!(
            "{label} generation {}/{generations}: best {:.4}, {:.1} evaluations/s; comparison {}/{} evaluations ({:.1}%), about {} left",
            r.generation + 1,
            r.stats.best,
            r.stats.evaluations as f64 / r.wall_seconds.max(1e-9),
            self.done,
            self.total,
            self.done as f64 / self.total.max(1) as f64 * 100.0,
            duration(left)
        )
    }
}

/// The summary of a comparison's report `r` written in `root` from `finished` replicates
/// (`unfinished` names the others): a line per encoding, a line per pair, what is missing
/// and the files written.
pub fn comparison_summary(
    root: &Path,
    shared: &Shared,
    r: &Report,
    finished: usize,
    unfinished: &[String],
) -> String {
    let mut lines = vec![format!(
        "{}: {finished} replicates of {} evaluations each; {}",
        root.display(),
        r.evaluations,
        shared.task.fitness_label()
    )];
    for e in &r.encodings {
        lines.push(format!(
            "  {:<20} n {:>3}  best {:.4} ± {:.4} (sd {:.4}; at the fine reference {:.4}{})  parts {}  shapes/part {:.3}",
            e.encoding,
            e.replicates,
            e.best.mean,
            e.best.ci95,
            e.best.sd,
            e.mean_fine,
            if e.fine_failed > 0 {
                format!(", {} re-walk(s) failed", e.fine_failed)
            } else {
                String::new()
            },
            e.median_parts,
            e.median_shapes_per_part
        ));
    }
    for p in &r.pairs {
        lines.push(format!(
            "  {} vs {}: U {} p {:.4} (Holm {:.4}) A12 {:.3} ({})",
            p.a,
            p.b,
            p.test.u,
            p.test.p,
            p.holm_p,
            p.a12,
            super::stats::a12_magnitude(p.a12)
        ));
    }
    if !unfinished.is_empty() {
        lines.push(format!("not yet in the report: {}", unfinished.join(", ")));
    }
    lines.push(format!(
        "wrote {0}/report.md, {0}/summary.csv, {0}/fitness.svg and {0}/parts.svg",
        root.display()
    ));
    lines.join("\n")
}

/// The `ontogeny evolve` commands of a comparison's `--plan`, one per replicate, with
/// `--no-cache` when `no_cache`.
pub fn plan_commands(root: &Path, manifest: &Manifest, no_cache: bool) -> Vec<String> {
    let mut commands = Vec::new();
    for k in 1..=manifest.replicates {
        for encoding in &manifest.encodings {
            commands.push(format!(
                "ontogeny evolve --config {} --encoding {encoding} --seed {} --out {}{}",
                shell_word(&root.join("evolve.toml")),
                super::compare::replicate_seed(manifest.seed, k),
                shell_word(&super::compare::replicate_dir(root, encoding, k)),
                if no_cache { " --no-cache" } else { "" }
            ));
        }
    }
    commands
}

/// A path as a shell word: as it is when it is plain, else in single quotes.
pub fn shell_word(path: &Path) -> String {
    let s = path.display().to_string();
    if !s.is_empty()
        && s.bytes()
            .all(|b| b.is_ascii_alphanumeric() || b"/._-+=:,".contains(&b))
    {
        s
    } else {
        format!("'{}'", s.replace('\'', r"'\''"))
    }
}
