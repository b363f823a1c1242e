//! What the command line says about runs and comparisons, as text: a generation's progress
//! line, a run's closing lines, a run's generation table (`runs show`), a comparison's progress
//! line and its report's summary, and a run's generations as CSV or JSON. Every function returns text (lines joined by newlines, no
//! final newline); printing is the caller's.

use std::path::Path;

use crate::evolve::ga::GaSettings;
use crate::run::store::{RunStore, StoreError};
use crate::run::{GenerationReport, exploits_stepping};
use crate::study::compare::{Arm, Manifest, Report};

/// A generation's progress line: its best (and the best's fine reference), mean, valid share
/// and speed, after the task's `fitness` label.
pub fn generation_line(fitness: &str, r: &GenerationReport) -> String {
    let fine = match &r.stats.best_fine {
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

/// The evaluations a run of `ga` makes in its generations from `first` on (see
/// [`evaluations_of`](crate::study::compare::evaluations_of); `fresh`: its trials are).
pub fn evaluations_from(ga: &GaSettings, fresh: bool, first: usize) -> u64 {
    let before = GaSettings {
        generations: first,
        ..ga.clone()
    };
    let made = if first == 0 {
        0
    } else {
        crate::study::compare::evaluations_of(&before, fresh)
    };
    crate::study::compare::evaluations_of(ga, fresh).saturating_sub(made)
}

/// What a run is about to do, said before it starts: its size (population × generations =
/// evaluations), encoding, task and threads, from generation `first` on; its time is
/// estimated once a generation is measured ([`estimate_line`]). `fresh`: the trials are, so
/// the elite is walked again each generation.
pub fn start_line(
    encoding: &str,
    fitness: &str,
    ga: &GaSettings,
    fresh: bool,
    first: usize,
    threads: usize,
) -> String {
    let evaluations = crate::study::compare::evaluations_of(ga, fresh);
    let elite = if fresh {
        "is walked again on fresh trials"
    } else {
        "is not evaluated again"
    };
    let size = match ga.algorithm.is_generational() {
        true => format!(
            "population {} × {} generations = {evaluations} evaluations (the elite of {} {elite})",
            ga.population,
            ga.generations,
            ga.survivors()
        ),
        false => format!(
            "steady-state, {} births in flight: population {} × {} generations = {evaluations} evaluations (after generation 0, a generation every {} births, each replacing the population's worst if it is better)",
            ga.in_flight(),
            ga.population,
            ga.generations,
            ga.children()
        ),
    };
    let left = if first == 0 {
        String::new()
    } else {
        format!(
            "; generations {first} to {} left, {} evaluations",
            ga.generations.saturating_sub(1),
            evaluations_from(ga, fresh, first)
        )
    };
    format!(
        "evolving {encoding} on {fitness}: {size}{left}; {threads} thread{}; the time it takes is estimated after the first generation",
        if threads == 1 { "" } else { "s" }
    )
}

/// The time a run has left, estimated from the generation `r` just measured: its rate, over
/// `left` evaluations still to make. Evaluations reused from identical creatures make later
/// generations quicker; larger creatures slower: it is an estimate.
pub fn estimate_line(r: &GenerationReport, left: u64) -> String {
    let rate = r.stats.evaluations as f64 / r.wall_seconds.max(1e-9);
    format!(
        "generation {} took {} ({rate:.1} evaluations/s): about {} left for the other {left} evaluations at that rate",
        r.generation,
        duration(r.wall_seconds),
        duration(left as f64 / rate.max(1e-9))
    )
}

/// A line the command line prints: a result (standard output) or a message for the user
/// (standard error: notes, warnings, the files written).
#[derive(Clone, Debug, PartialEq)]
pub enum Line {
    /// What the command was asked for.
    Result(String),
    /// Something the user should know about it.
    Message(String),
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

/// A run that has ended, as its closing lines and `evolve --json` tell it.
#[derive(Clone, Copy, Debug)]
pub struct RunEnd<'a> {
    /// The run's directory.
    pub dir: &'a Path,
    /// The task and what its fitness measures ([`crate::task::TaskSpec::fitness_label`]).
    pub fitness: &'a str,
    /// The encoding's name.
    pub encoding: &'a str,
    /// The extension of its genomes' files.
    pub extension: &'a str,
    /// Its last generation.
    pub last: &'a GenerationReport,
    /// The seconds it took.
    pub wall: f64,
}

impl RunTally {
    /// Counts one more generation.
    pub fn add(&mut self, r: &GenerationReport) {
        self.evaluations += r.stats.evaluations;
        self.reused += r.stats.reused;
        self.evaluating += r.evaluation_seconds;
    }

    /// The closing lines of the run `end` says: a note on
    /// children made by fallback, the final line (best, fine reference, counts, speed), a
    /// warning when the champion may exploit the step setting, and the files written; all
    /// but the final line are messages.
    pub fn closing_lines(&self, end: &RunEnd<'_>) -> Vec<Line> {
        let (dir, fitness, encoding) = (end.dir, end.fitness, end.encoding);
        let (extension, last, wall) = (end.extension, end.last, end.wall);
        let r = last;
        let mut lines = Vec::new();
        let fallbacks = r.fallbacks.crossover + r.fallbacks.graft;
        if fallbacks > 0 {
            lines.push(Line::Message(format!(
                "note: the {encoding} encoding lacks an operator of the schedule; {fallbacks} children of this run were made by mutation instead (see log.txt)"
            )));
        }
        let fine = match &r.stats.best_fine {
            Some(f) if f.status == "ok" => format!(" (fine reference {:.6})", f.fitness),
            Some(f) => format!(" (fine reference {:.6}, {})", f.fitness, f.status),
            None => String::new(),
        };
        lines.push(Line::Result(format!(
            "{}: {fitness}: generation {} best {:.6}{fine}; {} evaluations, {} simulated in {wall:.1} s ({:.1} evaluations/s), {:.1}% of the time outside evaluation",
            dir.display(),
            r.generation,
            r.stats.best,
            self.evaluations,
            self.evaluations - self.reused,
            self.evaluations as f64 / wall.max(1e-9),
            (wall - self.evaluating).max(0.0) / wall.max(1e-9) * 100.0
        )));
        if let Some(f) = &r.stats.best_fine
            && exploits_stepping(r.stats.best, f.fitness)
        {
            lines.push(Line::Message(format!(
                "warning: the champion scores {:.6} at the fine reference setting, down more than half of its {:.6}: it may exploit the simulator's step setting (see docs/guide/evolving.md, \"Re-walking the best at the fine reference\")",
                f.fitness, r.stats.best
            )));
        }
        let best = format!("best.{extension}");
        let files = ["run.sqlite", "fitness.svg", &best, "log.txt"].map(|f| dir.join(f));
        lines.push(Line::Message(crate::output::wrote(&files)));
        lines
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
    // A run whose projectile evolves shows each generation's best's projectile.
    let evolves_projectile = run.task_spec().is_some_and(|spec| {
        spec.task
            .get::<crate::task::CatapultOptions>()
            .is_some_and(|c| c.evolve_projectile)
    });
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
        ) + if evolves_projectile {
            "  projectile (m; kg)"
        } else {
            ""
        },
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
        if evolves_projectile {
            let shown = best_projectile(&store, g.index)?;
            if let Some(row) = lines.last_mut() {
                row.push_str(&format!("  {shown}"));
            }
        }
    }
    Ok(lines.join("\n"))
}

/// The projectile generation `generation`'s best threw, from its terms: `0.31 × 0.29 × 0.07,
/// 6.3`; "–" when the best has none (it failed before throwing).
fn best_projectile(store: &RunStore, generation: u32) -> Result<String, StoreError> {
    let individuals = store.individuals(generation)?;
    let best = individuals
        .iter()
        .filter(|i| !i.fitness.is_nan())
        .reduce(|b, i| if i.fitness > b.fitness { i } else { b });
    let terms: Option<std::collections::BTreeMap<String, f64>> =
        best.and_then(|i| serde_json::from_str(&i.terms_json).ok());
    let term = |name: &str| terms.as_ref().and_then(|t| t.get(name).copied());
    Ok(
        match (
            term("projectile_x"),
            term("projectile_y"),
            term("projectile_z"),
            term("projectile_mass"),
        ) {
            (Some(x), Some(y), Some(z), Some(m)) => format!("{x:.3} × {y:.3} × {z:.3}; {m:.2}"),
            _ => "–".to_string(),
        },
    )
}

/// The columns of [`generation_csv`], in order.
pub const GENERATION_CSV_COLUMNS: &str = "generation,best,best_fine,best_fine_status,mean,median,sd,valid_fraction,evaluations,reused,wall_seconds,evaluations_per_second";

/// The generations of the run in `dir` as CSV (`ontogeny runs show --csv`): a header
/// ([`GENERATION_CSV_COLUMNS`]) and a row per generation, every number in full (the shortest
/// text that reads back to the same value); a value that is missing or not a number (the fine
/// reference where it was not re-walked, a statistic of no valid individual) is empty.
pub fn generation_csv(dir: &Path) -> Result<String, StoreError> {
    let store = RunStore::open_read_only(&dir.join("run.sqlite"))?;
    let cell = |v: f64| {
        if v.is_finite() {
            v.to_string()
        } else {
            String::new()
        }
    };
    let mut lines = vec![GENERATION_CSV_COLUMNS.to_string()];
    for g in store.generations()? {
        let (fine, status) = match &g.best_fine {
            Some(f) => (cell(f.fitness), f.status.clone()),
            None => (String::new(), String::new()),
        };
        lines.push(format!(
            "{},{},{fine},{status},{},{},{},{},{},{},{},{}",
            g.index,
            cell(g.best),
            cell(g.mean),
            cell(g.median),
            cell(g.sd),
            cell(g.valid_fraction),
            g.evaluations,
            g.reused,
            cell(g.wall_seconds),
            cell(g.evaluations_per_second)
        ));
    }
    Ok(lines.join("\n"))
}

/// The run in `dir` as one JSON object (`ontogeny runs show --json`): `dir`, `encoding`,
/// `task` (its name), `fitness` (the task and fitness as progress lines name them), `seed`,
/// `version`, `planned_generations`, `settings` (the run's `config.toml` as an object) and
/// `generations`, an array of objects with the fields of [`GenerationRecord`]
/// (`generation`, `best`, ..., `best_fine` as `{fitness, status}` or `null`; a number that is
/// not one is `null`).
///
/// [`GenerationRecord`]: crate::run::store::GenerationRecord
pub fn generation_json(dir: &Path) -> Result<String, StoreError> {
    let store = RunStore::open_read_only(&dir.join("run.sqlite"))?;
    let run = store.run()?;
    let settings = crate::run::config::parse_table(&run.config)
        .ok()
        .and_then(|t| serde_json::to_value(t).ok());
    let value = serde_json::json!({
        "dir": dir.display().to_string(),
        "encoding": run.encoding,
        "task": run.task,
        "fitness": run.task_spec().map(|spec| spec.fitness_label()),
        "seed": run.seed,
        "version": run.version,
        "planned_generations": run.planned_generations(),
        "settings": settings,
        "generations": store.generations()?,
    });
    Ok(serde_json::to_string_pretty(&value).unwrap_or_default())
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

/// A comparison's progress, in walks (evaluations times the walks of each).
#[derive(Clone, Debug)]
pub struct ComparisonProgress {
    /// Walks of the whole comparison.
    pub total: u64,
    /// Walks made so far.
    pub done: u64,
    /// Walks made before this command started.
    pub at_start: u64,
    /// When this command started.
    pub started: std::time::Instant,
}

impl ComparisonProgress {
    /// Counts generation `r` of a replicate labelled `label` (of `generations` generations,
    /// `walks` per evaluation) and says where the comparison stands, with an estimate of the
    /// time left.
    pub fn line(
        &mut self,
        label: &str,
        r: &GenerationReport,
        generations: usize,
        walks: u64,
    ) -> String {
        self.done += r.stats.evaluations * walks;
        let elapsed = self.started.elapsed().as_secs_f64();
        let rate = (self.done - self.at_start) as f64 / elapsed.max(1e-9);
        let left = (self.total - self.done.min(self.total)) as f64 / rate.max(1e-9);
        format!(
            "{label} generation {}/{generations}: best {:.4}, {:.1} evaluations/s; comparison {}/{} {} ({:.1}%), about {} left",
            r.generation + 1,
            r.stats.best,
            r.stats.evaluations as f64 / r.wall_seconds.max(1e-9),
            self.done,
            self.total,
            if walks == 1 { "evaluations" } else { "walks" },
            self.done as f64 / self.total.max(1) as f64 * 100.0,
            duration(left)
        )
    }
}

/// The summary of a comparison's report `r` written in `root` from `finished` replicates of
/// `arms` (`unfinished` names the others): a line per encoding or condition, a line per pair
/// with what it found, the effect the comparison can detect, why there are no statistics,
/// what is missing (results); and the files written (a message).
pub fn comparison_summary(
    root: &Path,
    arms: &[Arm],
    r: &Report,
    finished: usize,
    unfinished: &[String],
) -> Vec<Line> {
    let fewest = r.arms.iter().map(|e| e.replicates).min().unwrap_or(0);
    let most = r.arms.iter().map(|e| e.replicates).max().unwrap_or(0);
    let least_walks = r.arms.iter().map(|e| e.walks).min().unwrap_or(0);
    let budget = if r.kind == "encoding" {
        format!("{} evaluations", r.evaluations)
    } else if least_walks == r.evaluations {
        format!("{} walks", r.evaluations)
    } else {
        format!("{least_walks} to {} walks", r.evaluations)
    };
    let mut lines = vec![format!(
        "{}: {finished} replicate{} of {budget} each ({} per {}); {}",
        root.display(),
        if finished == 1 { "" } else { "s" },
        if fewest == most {
            fewest.to_string()
        } else {
            format!("{fewest} to {most}")
        },
        r.kind,
        crate::study::compare::fitness_labels(arms)
    )];
    for e in &r.arms {
        let spread = if r.too_few.contains(&e.name) {
            String::from("no spread")
        } else {
            format!("± {:.4}, sd {:.4}", e.best.ci95, e.best.sd)
        };
        lines.push(format!(
            "  {:<20} n {:>3}  best {:.4} ({spread}; at the fine reference {:.4}{})  parts {}  repeated {:.2}  mirrored {:.2}  bytes/part {:.1}",
            e.name,
            e.replicates,
            e.best.mean,
            e.mean_fine,
            if e.fine_failed > 0 {
                format!(", {} re-walk(s) failed", e.fine_failed)
            } else {
                String::new()
            },
            e.median_parts,
            e.median_repeated,
            e.median_symmetry,
            e.median_description_bytes
        ));
    }
    for (pairs, what) in [(&r.pairs, ""), (&r.fine_pairs, "at the fine reference: ")] {
        for p in pairs {
            lines.push(format!(
                "  {what}{} vs {}{}: U {} p {:.4} ({} {:.4}) A12 {:.3} ({}): {}",
                p.a,
                p.b,
                if p.primary { " (primary)" } else { "" },
                p.test.u,
                p.test.p,
                if p.primary { "alone" } else { "Holm" },
                p.holm_p,
                p.a12,
                crate::study::stats::a12_magnitude(p.a12),
                p.verdict()
            ));
        }
    }
    if let Some(power) = &r.power {
        let line = power_line(power, r.kind);
        lines.push(match unfinished.is_empty() {
            true => line,
            false => format!("{line} (as planned; each pair's own is on its line)"),
        });
    }
    if !r.too_few.is_empty() {
        lines.push(format!(
            "no statistics {}",
            crate::study::compare::too_few_note(&r.too_few)
        ));
    }
    if !unfinished.is_empty() {
        lines.push(format!("not yet in the report: {}", unfinished.join(", ")));
    }
    let files = ["report.md", "summary.csv", "fitness.svg", "parts.svg"].map(|f| root.join(f));
    let mut lines: Vec<Line> = lines.into_iter().map(Line::Result).collect();
    lines.push(Line::Message(crate::output::wrote(&files)));
    lines
}

/// The summary's line on a comparison's power as planned: the primary pair's and the
/// secondary pairs' levels, the effects they detect and their power at a large effect.
pub fn power_line(power: &crate::study::compare::Power, kind: &str) -> String {
    use crate::study::compare::LARGE_A12;
    let mut parts = Vec::new();
    if let (Some((a, b)), Some(d), Some(p)) = (
        &power.primary,
        &power.primary_detectable,
        power.primary_power,
    ) {
        parts.push(format!(
            "primary {a} vs {b} tested at {:.4}: detects {}; power {p:.2} at A12 {LARGE_A12}",
            d.level,
            d.words()
        ));
    }
    if let (Some(d), Some(p)) = (&power.secondary_detectable, power.secondary_power) {
        let n = power.secondary;
        parts.push(format!(
            "{n} {}pair{}, each tested at {:.4}: detects {}; power {p:.2} at A12 {LARGE_A12}",
            if power.primary.is_some() {
                "secondary "
            } else {
                ""
            },
            if n == 1 { "" } else { "s" },
            d.level,
            d.words()
        ));
    }
    let needed = power.needed.map_or(String::new(), |n| {
        format!(" (one pair at 0.05 needs {n} a side for power 0.8 at A12 {LARGE_A12})")
    });
    format!(
        "power: {} replicates per {kind}, {}{needed}",
        power.replicates,
        parts.join("; ")
    )
}

/// The `ontogeny evolve` commands of a comparison's `--plan`, one per replicate, with
/// `--no-cache` when `no_cache`: an encoding's replicates read the shared `evolve.toml` and
/// name their encoding, a condition's read its own `<condition>/evolve.toml`.
pub fn plan_commands(root: &Path, manifest: &Manifest, no_cache: bool) -> Vec<String> {
    let mut commands = Vec::new();
    for k in 1..=manifest.replicates {
        for name in manifest.names() {
            let (config, encoding) = if manifest.conditions.is_empty() {
                (root.join("evolve.toml"), format!(" --encoding {name}"))
            } else {
                (
                    crate::study::compare::condition_file(root, name),
                    String::new(),
                )
            };
            commands.push(format!(
                "ontogeny evolve --config {}{encoding} --seed {} --out {}{}",
                shell_word(&config),
                crate::study::compare::replicate_seed(manifest.seed, k),
                shell_word(&crate::study::compare::replicate_dir(root, name, k)),
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::evolve::ga::Preset;
    use crate::run::store::{FineEvaluation, GenerationRecord};

    /// Generation `generation` of 10 evaluations in 2 s, best 10, re-walked at the fine
    /// reference to `fine`.
    fn report(generation: u32, fine: f64) -> GenerationReport {
        let stats = GenerationRecord {
            index: generation,
            best: 10.0,
            mean: 5.0,
            median: 5.0,
            sd: 1.0,
            valid_fraction: 1.0,
            evaluations: 10,
            reused: 0,
            wall_seconds: 2.0,
            evaluations_per_second: 5.0,
            best_fine: Some(FineEvaluation {
                fitness: fine,
                status: "ok".into(),
            }),
        };
        GenerationReport {
            generation,
            stats,
            wall_seconds: 2.0,
            evaluation_seconds: 2.0,
            fallbacks: crate::evolve::ga::Fallbacks {
                crossover: 3,
                graft: 0,
            },
        }
    }

    #[test]
    fn a_run_ends_with_its_result_alone_on_standard_output() {
        let last = report(3, 1.0);
        let lines = RunTally::default().closing_lines(&RunEnd {
            dir: Path::new("runs/x"),
            fitness: "walker, distance (m)",
            encoding: "lsystem",
            extension: "lsys",
            last: &last,
            wall: 2.0,
        });
        let results: Vec<&Line> = lines
            .iter()
            .filter(|l| matches!(l, Line::Result(_)))
            .collect();
        assert_eq!(results.len(), 1);
        assert!(
            matches!(results[0], Line::Result(l) if l.starts_with("runs/x: walker, distance (m): generation 3 best 10.000000"))
        );
        let messages: Vec<&str> = lines
            .iter()
            .filter_map(|l| match l {
                Line::Message(m) => Some(m.as_str()),
                Line::Result(_) => None,
            })
            .collect();
        // The fallbacks' note, the exploit warning (1 is below half of 10), the files.
        assert_eq!(messages.len(), 3, "{messages:?}");
        assert!(messages[0].starts_with("note: the lsystem encoding lacks an operator"));
        assert!(messages[1].starts_with("warning: the champion scores 1.000000"));
        assert_eq!(
            messages[2],
            "wrote runs/x/run.sqlite, runs/x/fitness.svg, runs/x/best.lsys and runs/x/log.txt"
        );
    }

    #[test]
    fn a_run_says_its_size_and_estimates_its_time_from_a_measured_generation() {
        let ga = GaSettings {
            population: 10,
            generations: 4,
            ..GaSettings::preset(Preset::Chaumont)
        };
        // 10, then 8 per generation (the elite of 2 carried over): 34 in all.
        assert_eq!(evaluations_from(&ga, false, 0), 34);
        assert_eq!(evaluations_from(&ga, false, 1), 24);
        assert_eq!(evaluations_from(&ga, false, 4), 0);
        assert_eq!(
            start_line("direct", "jump, height (m)", &ga, false, 0, 2),
            "evolving direct on jump, height (m): population 10 × 4 generations = 34 evaluations (the elite of 2 is not evaluated again); 2 threads; the time it takes is estimated after the first generation"
        );
        assert!(
            start_line("direct", "jump, height (m)", &ga, false, 2, 1)
                .contains("; generations 2 to 3 left, 16 evaluations; 1 thread;")
        );
        // Fresh trials: 10 every generation, the elite walked again.
        assert_eq!(evaluations_from(&ga, true, 1), 30);
        assert_eq!(
            start_line("direct", "jump, height (m)", &ga, true, 0, 2),
            "evolving direct on jump, height (m): population 10 × 4 generations = 40 evaluations (the elite of 2 is walked again on fresh trials); 2 threads; the time it takes is estimated after the first generation"
        );
        // Steady-state: the same births, said as births in flight and blocks of 8.
        let steady = GaSettings {
            algorithm: crate::evolve::ga::Algorithm::SteadyState,
            in_flight: Some(6),
            ..ga.clone()
        };
        assert_eq!(
            start_line("direct", "jump, height (m)", &steady, false, 0, 2),
            "evolving direct on jump, height (m): steady-state, 6 births in flight: population 10 × 4 generations = 34 evaluations (after generation 0, a generation every 8 births, each replacing the population's worst if it is better); 2 threads; the time it takes is estimated after the first generation"
        );
        // 10 evaluations in 2 s: 24 more take about 5 s.
        assert_eq!(
            estimate_line(&report(0, 10.0), 24),
            "generation 0 took 2s (5.0 evaluations/s): about 5s left for the other 24 evaluations at that rate"
        );
    }
}
