//! `ontogeny bench`'s measurements: a chain creature of known size, one evaluation timed
//! (total and physics), one core's figures for a setting, and the stepping settings
//! `--fidelity-also` names. The fidelity experiment itself is [`super::fidelity`].

use std::time::Instant;

use crate::creature::Creature;
use crate::develop::creature_from_commands;
use crate::sim::{SimOptions, StepSetting, World};

/// A chain of `parts` parts on revolute2 hinges, each driven by an output from the
/// oscillator: a walker-like creature of known size.
pub fn chain(parts: usize) -> Creature {
    let text = format!(
        "width(0.3) thickness(0.2) forward(0.5) {{ revolute2 forward(0.5) output(1) }}({})",
        parts.saturating_sub(1)
    );
    creature_from_commands(&text).expect("the bench creature compiles")
}

/// Runs one evaluation: `seconds` of controller-on stepping. Returns (total, physics) seconds.
/// The creature must build (check with [`World::new`] first).
pub fn time_evaluation(creature: &Creature, sim: &SimOptions, seconds: f64) -> (f64, f64) {
    let start = Instant::now();
    let mut world = World::new(creature, sim).expect("the bench creature builds");
    let steps = (seconds / sim.control_step).round() as usize;
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

/// One core's figures for one setting, over `n` evaluations of `seconds` (after a warm-up):
/// evaluations per second, µs per control step, and the share of time outside rapier's
/// pipeline (%).
pub fn one_core(creature: &Creature, sim: &SimOptions, n: usize, seconds: f64) -> (f64, f64, f64) {
    time_evaluation(creature, sim, 1.0); // warm up
    let started = Instant::now();
    let (mut total, mut physics) = (0.0, 0.0);
    for _ in 0..n {
        let (t, p) = time_evaluation(creature, sim, seconds);
        total += t;
        physics += p;
    }
    let rate = n as f64 / started.elapsed().as_secs_f64();
    let steps = (seconds / sim.control_step).round();
    (
        rate,
        total / n as f64 / steps * 1e6,
        (total - physics) / total * 100.0,
    )
}

/// A stepping setting of `--fidelity-also` over `base`: a named one (`fast`, `default`,
/// `fine`), or `SxIxP` (substeps, solver iterations, PGS passes while walking), optionally
/// followed by `/SxI` (substeps and iterations while waiting for rest); e.g. `1x2x3/2x4`.
/// Checked as every setting is ([`SimOptions::check`]).
pub fn parse_stepping(text: &str, base: &SimOptions) -> Result<SimOptions, String> {
    if let Ok(named) = text.parse::<StepSetting>() {
        return Ok(named.apply(base));
    }
    let bad = || {
        format!(
            "--fidelity-also: '{text}' is not a setting such as fast, 1x2x3 or 1x2x3/2x4 (a named setting, or substeps x iterations x PGS passes / rest substeps x rest iterations)"
        )
    };
    let numbers = |part: &str, count: usize| -> Result<Vec<usize>, String> {
        let n: Vec<usize> = part
            .split('x')
            .map(|x| x.trim().parse::<usize>())
            .collect::<Result<_, _>>()
            .map_err(|_| bad())?;
        if n.len() != count {
            return Err(bad());
        }
        Ok(n)
    };
    let (walking, resting) = match text.split_once('/') {
        Some((w, r)) => (w, Some(r)),
        None => (text, None),
    };
    // The stepping knobs in their order: the walking three, then the resting two.
    let mut values = crate::sim::knobs::stepping_of(base);
    values[..3].copy_from_slice(&numbers(walking, 3)?);
    if let Some(r) = resting {
        values[3..].copy_from_slice(&numbers(r, 2)?);
    }
    let mut sim = base.clone();
    crate::sim::knobs::set_stepping(&mut sim, values);
    sim.check()
        .map_err(|e| format!("--fidelity-also {text}: {e}"))?;
    Ok(sim)
}
