//! `ontogeny bench`: the evaluator's speed on this machine, and whether the default
//! setting ranks creatures as a fine reference setting does (the experiment itself is
//! [`ontogeny::study::fidelity`]; this verb times it and prints it).

use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use clap::Args;
use ontogeny::sim::{JointModel, SimOptions, World};
use ontogeny::study::bench::{chain, one_core, parse_stepping, time_evaluation};
use ontogeny::study::fidelity::{FineReference, fidelity_creatures, setting_name};
use ontogeny::task::{self, WalkerOptions};
use rayon::prelude::*;

use serde_json::json;

use super::physics::{SteppingArgs, actuator_parser, flag_error};
use super::progress::Progress;

/// `say!` unless the output is JSON (`$json`): the text lines of the figures.
macro_rules! text {
    ($json:expr, $($arg:tt)*) => {
        if !$json {
            say!($($arg)*);
        }
    };
}

/// Measure the evaluator on this machine: evaluations per second on one core (the setting
/// measured, 2 substeps of 4 iterations and the fast one) and on all cores, its overhead over
/// rapier's own stepping, and impulse against multibody joints.
#[derive(Args)]
pub struct BenchArgs {
    /// Evaluations per measurement (more is steadier, slower).
    #[arg(long, default_value_t = 16)]
    evaluations: usize,
    /// Simulated seconds per evaluation, in (0, 3600].
    #[arg(long, default_value_t = 20.0)]
    seconds: f64,
    /// The step setting measured: a named one and the stepping flags over it (default: the
    /// evaluator's).
    #[command(flatten)]
    stepping: SteppingArgs,
    /// The actuator model measured (and of the fine reference).
    #[arg(long, value_parser = actuator_parser(), default_value = "muscle")]
    actuator: ontogeny::sim::ActuatorModel,
    /// Also measure fidelity: walk this many creatures (the shipped examples, then random
    /// command strings) `--runs` times with the setting and with a fine reference (1/240 s
    /// physics, 8 solver iterations), and print the Spearman rank correlation of their median
    /// fitness, a noise floor, and how many walks each setting brings to rest. 0 skips it.
    #[arg(long, default_value_t = 0)]
    fidelity: usize,
    /// With `--fidelity`: walks per creature and setting, from drop heights 0.1 mm apart;
    /// the median fitness ranks the creatures.
    #[arg(long, default_value_t = 5)]
    runs: usize,
    /// Seed of the random creatures of `--fidelity`.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// With `--fidelity`: more settings to rank against the fine reference in the same run,
    /// each a named setting (`fast`, `default`, `fine`) or `SxIxP` or `SxIxP/SxI` (substeps ×
    /// solver iterations × PGS passes while walking, then substeps × iterations while waiting
    /// for rest), e.g. `fast,1x4x1/2x8`.
    #[arg(long, value_name = "SETTING", value_delimiter = ',')]
    fidelity_also: Vec<String>,
    /// With `--fidelity`: print every creature's figures.
    #[arg(long)]
    verbose: bool,
    /// Measure only this creature (an `.lsys` grown to its last frame, or a
    /// `creature.json`) on one core, instead of the chains.
    #[arg(long, value_name = "FILE")]
    creature: Option<std::path::PathBuf>,
    /// Print the speed figures as one JSON object instead of text (not with --fidelity).
    #[arg(long)]
    json: bool,
}

/// Measures and prints the figures docs/results/speed.md reports.
pub fn run(args: &BenchArgs) -> anyhow::Result<()> {
    task::check_duration("seconds", args.seconds).map_err(flag_error)?;
    if args.json && args.fidelity > 0 {
        return Err(super::bad(
            "--json is for the speed figures: give it without --fidelity",
        ));
    }
    let base = SimOptions {
        actuator: args.actuator,
        ..SimOptions::default()
    };
    let sim = args.stepping.apply(&base)?;
    let n = args.evaluations.max(1);
    let steps = (args.seconds / sim.control_step).round();
    if let Some(file) = &args.creature {
        let creature = super::input::load_creature(
            file,
            &Default::default(),
            ontogeny::develop::BuildOptions::default().max_parts,
        )?;
        World::new(&creature, &sim)
            .map_err(|e| super::bad(format!("{}: cannot simulate: {e}", file.display())))?;
        time_evaluation(&creature, &sim, 1.0); // warm up
        let started = Instant::now();
        for _ in 0..n {
            time_evaluation(&creature, &sim, args.seconds);
        }
        let seconds = started.elapsed().as_secs_f64();
        text!(
            args.json,
            "{}: {} s at {} s ({} substeps), {n} evaluations, one core: {:.2} evaluations/s ({:.1} µs per step)",
            file.display(),
            args.seconds,
            sim.control_step,
            sim.substeps,
            n as f64 / seconds,
            seconds / n as f64 / steps * 1e6
        );
        if args.json {
            let object = json!({
                "creature": file.display().to_string(),
                "seconds": args.seconds,
                "control_step": sim.control_step,
                "substeps": sim.substeps,
                "evaluations": n,
                "evaluations_per_second": n as f64 / seconds,
                "us_per_step": seconds / n as f64 / steps * 1e6,
            });
            say!("{}", serde_json::to_string_pretty(&object)?);
        }
        return Ok(());
    }
    let mut reference = base.clone();
    ontogeny::sim::knobs::set_stepping(&mut reference, [2, 4, 1, 2, 4]);
    let fast = base.fast();
    let walker = chain(10);
    text!(
        args.json,
        "10-part walker, {} s at 1/60 s, {} evaluations per row; {} threads available",
        args.seconds,
        n,
        rayon::current_num_threads()
    );
    text!(
        args.json,
        "{:<44} {:>12} {:>10} {:>10}",
        "setting (one core)",
        "evaluations/s",
        "µs/step",
        "overhead"
    );
    let (measured, measured_step, measured_overhead) = one_core(&walker, &sim, n, args.seconds);
    text!(
        args.json,
        "{:<44} {measured:>12.1} {measured_step:>10.1} {measured_overhead:>9.1}%",
        format!("measured: {}", setting_name(&sim))
    );
    let (slow, slow_step, slow_overhead) = one_core(&walker, &reference, n, args.seconds);
    text!(
        args.json,
        "{:<44} {slow:>12.1} {slow_step:>10.1} {slow_overhead:>9.1}%",
        format!("{} (2 substeps, 4 iterations)", setting_name(&reference))
    );
    let (quick, quick_step, quick_overhead) = one_core(&walker, &fast, n, args.seconds);
    text!(
        args.json,
        "{:<44} {quick:>12.1} {quick_step:>10.1} {quick_overhead:>9.1}%",
        setting_name(&fast)
    );
    text!(
        args.json,
        "ratio:     {:.2}× the evaluations/s of {} (fast: {:.2}×)",
        measured / slow,
        setting_name(&reference),
        quick / slow
    );

    let started = Instant::now();
    (0..n).into_par_iter().for_each(|_| {
        time_evaluation(&walker, &sim, args.seconds);
    });
    let all_cores = n as f64 / started.elapsed().as_secs_f64();
    text!(
        args.json,
        "all cores: {all_cores:.1} evaluations/s (speed-up {:.2} on {} threads)",
        all_cores / measured,
        rayon::current_num_threads()
    );

    text!(
        args.json,
        "\nµs per step, controller on, by joint model (chains of N parts):"
    );
    text!(
        args.json,
        "{:>6} {:>10} {:>10}",
        "parts",
        "impulse",
        "multibody"
    );
    let mut joint_models = Vec::new();
    for parts in [2, 5, 10, 20, 30] {
        let creature = chain(parts);
        let mut row = Vec::new();
        for joints in [JointModel::Impulse, JointModel::Multibody] {
            let sim = SimOptions {
                joints,
                ..sim.clone()
            };
            let (t, _) = time_evaluation(&creature, &sim, 5.0);
            row.push(t / (5.0 / sim.control_step) * 1e6);
        }
        text!(args.json, "{parts:>6} {:>10.1} {:>10.1}", row[0], row[1]);
        joint_models.push(json!({
            "parts": parts,
            "impulse_us_per_step": row[0],
            "multibody_us_per_step": row[1],
        }));
    }
    if args.json {
        let setting = |name: String, (rate, step, overhead): (f64, f64, f64)| {
            json!({
                "setting": name,
                "evaluations_per_second": rate,
                "us_per_step": step,
                "overhead_percent": overhead,
            })
        };
        let object = json!({
            "seconds": args.seconds,
            "evaluations": n,
            "threads": rayon::current_num_threads(),
            "settings": [
                setting(setting_name(&sim), (measured, measured_step, measured_overhead)),
                setting(setting_name(&reference), (slow, slow_step, slow_overhead)),
                setting(setting_name(&fast), (quick, quick_step, quick_overhead)),
            ],
            "ratio": measured / slow,
            "fast_ratio": quick / slow,
            "all_cores": {
                "evaluations_per_second": all_cores,
                "speed_up": all_cores / measured,
            },
            "joint_models": joint_models,
        });
        say!("{}", serde_json::to_string_pretty(&object)?);
    }
    if args.fidelity > 0 {
        fidelity(args, &sim)?;
    }
    Ok(())
}

/// A batch of walks run in parallel, counted into a progress bar on a terminal.
struct Walks {
    done: AtomicUsize,
    total: usize,
    progress: Mutex<Progress>,
}

impl Walks {
    fn new(what: &str, total: usize) -> Walks {
        Walks {
            done: AtomicUsize::new(0),
            total,
            progress: Mutex::new(Progress::new(what)),
        }
    }

    /// One more walk is done.
    fn tick(&self) {
        let done = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        if let Ok(mut progress) = self.progress.lock() {
            progress.set(done as f64 / self.total.max(1) as f64);
        }
    }

    /// The batch is done: the bar, if shown, is cleared.
    fn finish(self) {
        if let Ok(mut progress) = self.progress.into_inner() {
            progress.finish();
        }
    }
}

/// Walks every fidelity creature with `sim` (and every `--fidelity-also` setting) and with
/// the fine reference, each `--runs` times from drop heights 0.1 mm apart; prints the rank
/// correlation of their median fitness, a noise floor, how many walks each setting brings to
/// rest, and each setting's cost in whole walks (rest phases included) against the first
/// setting's (the one measured, the default unless flags change it).
fn fidelity(args: &BenchArgs, sim: &SimOptions) -> anyhow::Result<()> {
    // `sim` differs from the default only in its stepping, which the reference replaces.
    let fine = sim.fine_reference();
    let mut settings = vec![sim.clone()];
    for text in &args.fidelity_also {
        settings.push(parse_stepping(text, sim).map_err(super::bad)?);
    }
    let creatures = fidelity_creatures(args.fidelity, args.seed)?;
    let options = WalkerOptions {
        seconds: args.seconds,
        ..WalkerOptions::default()
    };
    let runs = args.runs.max(1);
    say!(
        "\nfidelity: {} creatures walked {} s, {runs} times each from drop heights 0.1 mm apart, with each setting and with the fine reference (the fine setting: 1/240 s physics, 8 iterations, also while settling)",
        creatures.len(),
        args.seconds
    );
    // The noise floor: the fine reference against itself, from other drop heights. No
    // setting can rank creatures more alike than the reference does itself.
    let walks = Walks::new("fine reference walks", 2 * runs * creatures.len());
    let reference = FineReference::walk(&creatures, &fine, &options, runs, &|| walks.tick());
    walks.finish();
    let fine_rested = reference.walks_rested;
    let fine_creatures_rested = reference.creatures_rested;
    say!(
        "noise floor, fine against fine from other drop heights: {:.3} (medians), {:.3} (single walks); the fine reference brings {fine_rested} of {} walks and {fine_creatures_rested} of {} creatures (most of their walks) to rest",
        reference.floor_medians,
        reference.floor_single,
        creatures.len() * runs,
        creatures.len()
    );
    say!(
        "{:<16} {:>10} {:>10} {:>16} {:>18} {:>10}",
        "setting",
        "Spearman",
        "single",
        "rested of fine's",
        "creatures rested",
        "cost"
    );
    let mut default_cost = None;
    for setting in &settings {
        let walks = Walks::new(&setting_name(setting), runs * creatures.len());
        let started = Instant::now();
        let ranked = reference.rank(setting, &creatures, &options, &|| walks.tick());
        let cost = started.elapsed().as_secs_f64();
        walks.finish();
        let default_cost = *default_cost.get_or_insert(cost);
        if args.verbose {
            say!(
                "{:>14} {:>14} {:>8} {:>8}  creature ({})",
                "measured",
                "fine",
                "at rest",
                "at rest",
                setting_name(setting)
            );
            for ((name, _), (a, (b, _))) in creatures
                .iter()
                .zip(ranked.ensembles.iter().zip(&reference.ensembles))
            {
                say!(
                    "{:>14.6} {:>14.6} {:>8} {:>8}  {name}",
                    a.median,
                    b.median,
                    format!("{}/{runs}", a.rested),
                    format!("{}/{runs}", b.rested),
                );
            }
        }
        say!(
            "{:<16} {:>10.3} {:>10.3} {:>16} {:>18} {:>9.2}×",
            setting_name(setting),
            ranked.spearman,
            ranked.single,
            format!("{}/{fine_rested}", ranked.both_rested),
            format!("{}/{fine_creatures_rested}", ranked.creatures_rested),
            cost / default_cost
        );
    }
    Ok(())
}
