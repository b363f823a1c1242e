//! `ontogeny bench`: the evaluator's speed on this machine.

use std::time::Instant;

use clap::Args;
use ontogeny::creature::Creature;
use ontogeny::develop::creature_from_commands;
use ontogeny::sim::{JointModel, SimOptions, World};
use rayon::prelude::*;

/// Flags of `ontogeny bench`.
#[derive(Args)]
pub struct BenchArgs {
    /// Evaluations per measurement (more is steadier, slower).
    #[arg(long, default_value_t = 16)]
    evaluations: usize,
    /// Simulated seconds per evaluation.
    #[arg(long, default_value_t = 20.0)]
    seconds: f64,
    /// Physics substeps per control step.
    #[arg(long, default_value_t = SimOptions::default().substeps)]
    substeps: usize,
    /// Solver iterations per substep.
    #[arg(long, default_value_t = SimOptions::default().solver_iterations)]
    solver_iterations: usize,
    /// Measure only this creature (an `.lsys` grown to its last frame, or a
    /// `creature.json`) on one core, instead of the chains.
    #[arg(long, value_name = "FILE")]
    creature: Option<std::path::PathBuf>,
}

/// A chain of `parts` parts on revolute2 hinges, each driven by an output from the
/// oscillator: a walker-like creature of known size.
fn chain(parts: usize) -> Creature {
    let text = format!(
        "width(0.3) thickness(0.2) forward(0.5) {{ revolute2 forward(0.5) output(1) }}({})",
        parts.saturating_sub(1)
    );
    creature_from_commands(&text).expect("the bench creature compiles")
}

/// Runs one evaluation: `seconds` of controller-on stepping. Returns (total, physics) seconds.
fn evaluate(creature: &Creature, sim: &SimOptions, seconds: f64) -> (f64, f64) {
    let start = Instant::now();
    let mut world = World::new(creature, sim).expect("the bench creature builds");
    let steps = (seconds / sim.dt).round() as usize;
    for _ in 0..steps {
        if world.step(true).is_err() {
            break;
        }
    }
    (
        start.elapsed().as_secs_f64(),
        world.physics_time().as_secs_f64(),
    )
}

/// Measures and prints the figures the README reports.
pub fn run(args: &BenchArgs) -> anyhow::Result<()> {
    let sim = SimOptions {
        substeps: args.substeps.clamp(1, 64),
        solver_iterations: args.solver_iterations.clamp(1, 256),
        ..SimOptions::default()
    };
    let n = args.evaluations.max(1);
    let steps = (args.seconds / sim.dt).round();
    if let Some(file) = &args.creature {
        let creature = super::eval::load_creature(file, &Default::default(), None)?;
        World::new(&creature, &sim).map_err(|e| {
            ontogeny::lang::Diagnostic::without_location(
                ontogeny::lang::DiagnosticKind::Semantic,
                format!("{}: cannot simulate: {e}", file.display()),
            )
        })?;
        evaluate(&creature, &sim, 1.0); // warm up
        let started = Instant::now();
        for _ in 0..n {
            evaluate(&creature, &sim, args.seconds);
        }
        let seconds = started.elapsed().as_secs_f64();
        say!(
            "{}: {} s at {} s ({} substeps), {n} evaluations, one core: {:.2} evaluations/s ({:.1} µs per step)",
            file.display(),
            args.seconds,
            sim.dt,
            sim.substeps,
            n as f64 / seconds,
            seconds / n as f64 / steps * 1e6
        );
        return Ok(());
    }
    let walker = chain(10);
    say!(
        "10-part walker, {} s at 1/60 s ({} substeps), {} evaluations; {} threads available",
        args.seconds,
        sim.substeps,
        n,
        rayon::current_num_threads()
    );

    evaluate(&walker, &sim, 1.0); // warm up
    let started = Instant::now();
    let (mut total, mut physics) = (0.0, 0.0);
    for _ in 0..n {
        let (t, p) = evaluate(&walker, &sim, args.seconds);
        total += t;
        physics += p;
    }
    let one_core = n as f64 / started.elapsed().as_secs_f64();
    let overhead = (total - physics) / physics * 100.0;
    say!(
        "one core:  {one_core:.1} evaluations/s ({:.1} µs per step)",
        total / n as f64 / steps * 1e6
    );
    say!(
        "overhead:  {overhead:.1}% of the time is outside rapier's pipeline (sensors, brain, motors, checks, setup)"
    );

    let started = Instant::now();
    (0..n).into_par_iter().for_each(|_| {
        evaluate(&walker, &sim, args.seconds);
    });
    let all_cores = n as f64 / started.elapsed().as_secs_f64();
    say!(
        "all cores: {all_cores:.1} evaluations/s (speed-up {:.2} on {} threads)",
        all_cores / one_core,
        rayon::current_num_threads()
    );

    say!("\nµs per step, controller on, by joint model (chains of N parts):");
    say!("{:>6} {:>10} {:>10}", "parts", "impulse", "multibody");
    for parts in [2, 5, 10, 20, 30] {
        let creature = chain(parts);
        let mut row = Vec::new();
        for joints in [JointModel::Impulse, JointModel::Multibody] {
            let sim = SimOptions {
                joints,
                ..sim.clone()
            };
            let (t, _) = evaluate(&creature, &sim, 5.0);
            row.push(t / (5.0 / sim.dt) * 1e6);
        }
        say!("{parts:>6} {:>10.1} {:>10.1}", row[0], row[1]);
    }
    Ok(())
}
