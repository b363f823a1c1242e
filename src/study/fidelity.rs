//! The fidelity experiment (`ontogeny bench --fidelity`): does a step setting rank creatures
//! as the fine reference setting does? A set of creatures (the shipped examples, then random
//! command strings) walks several times from drop heights 0.1 mm apart with each setting and
//! with the fine reference; the Spearman rank correlation of their median fitness says how
//! alike the rankings are, the fine reference against itself from other drop heights gives
//! the noise floor, and the walks that end at rest say which settings keep creatures stable.
//!
//! This module computes the figures; the `bench` verb times the settings and prints them.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use super::stats::{median, spearman};
use crate::creature::Creature;
use crate::develop::{BuildOptions, creature_from_commands, grow};
use crate::lang::Diagnostic;
use crate::lsystem::{DeriveOptions, LSystem};
use crate::sim::{SimOptions, StepSetting};
use crate::task::{self, Evaluation, Status, WalkerOptions};

/// The shipped examples that grow into creatures, as (name, text).
const SHIPPED: [(&str, &str); 4] = [
    ("snake", include_str!("../../examples/snake.lsys")),
    ("quadruped", include_str!("../../examples/quadruped.lsys")),
    ("thrower", include_str!("../../examples/thrower.lsys")),
    ("plastic", include_str!("../../examples/plastic.lsys")),
];

/// A random string of body and brain commands: a walker-like creature of 2 to 8 parts.
pub fn random_commands(rng: &mut ChaCha8Rng) -> String {
    let mut out = format!(
        "width({:.2}) thickness({:.2}) forward({:.2})",
        rng.random_range(0.2..0.6),
        rng.random_range(0.1..0.3),
        rng.random_range(0.3..1.0)
    );
    let parts = rng.random_range(1..8);
    let mut open = 0;
    for _ in 0..parts {
        if rng.random_bool(0.3) {
            out.push_str(" [");
            open += 1;
        }
        let turn = ["left", "right", "up", "down", "clockwise"][rng.random_range(0..5)];
        if rng.random_bool(0.6) {
            out.push_str(&format!(" {turn}(1)"));
        }
        let joint = ["revolute1", "revolute2", "twist90", "revolute2"][rng.random_range(0..4)];
        out.push_str(&format!(
            " {joint} width({:.2}) thickness({:.2}) forward({:.2})",
            rng.random_range(0.1..0.4),
            rng.random_range(0.1..0.3),
            rng.random_range(0.2..0.8)
        ));
        if rng.random_bool(0.5) {
            out.push_str(&format!(" split({:.2})", rng.random_range(-1.0..1.0)));
        }
        out.push_str(&format!(" output({:.2})", rng.random_range(-1.0..1.0)));
        if open > 0 && rng.random_bool(0.4) {
            out.push_str(" ]");
            open -= 1;
        }
    }
    out.push_str(&" ]".repeat(open));
    out
}

/// The creatures of the fidelity measurement, as (name, creature): the shipped examples, then
/// valid random ones drawn from `seed`, `count` in all (fewer if 100 × `count` draws do not
/// give enough valid ones).
pub fn fidelity_creatures(count: usize, seed: u64) -> Result<Vec<(String, Creature)>, Diagnostic> {
    let mut creatures = Vec::new();
    for (name, text) in SHIPPED {
        let lsys = LSystem::from_text(&format!("examples/{name}.lsys"), text)?;
        let frames = grow(
            &lsys,
            &DeriveOptions::default(),
            None,
            &BuildOptions::default(),
        )?;
        if let Some(last) = frames.into_iter().last() {
            creatures.push((name.to_string(), last.creature));
        }
    }
    creatures.truncate(count);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut tries = 0;
    while creatures.len() < count && tries < 100 * count {
        tries += 1;
        let commands = random_commands(&mut rng);
        let creature = creature_from_commands(&commands)?;
        if creature.is_valid() && creature.brain.neurons.len() > 1 {
            creatures.push((commands, creature));
        }
    }
    Ok(creatures)
}

/// One creature's walks with one setting.
#[derive(Clone, Debug)]
pub struct Ensemble {
    /// The median fitness of the walks.
    pub median: f64,
    /// How many walks ended at rest (any status but `unstable`).
    pub rested: usize,
    /// The walks, in order of drop height.
    pub walks: Vec<Evaluation>,
}

/// Whether a walk ended at rest: any status but `unstable`.
fn rested(walk: &Evaluation) -> bool {
    walk.status != Status::Unstable
}

/// One creature's walks with one setting, dropped from `runs` heights: the drop height plus
/// `first + k` × 0.1 mm for k in 0..runs. `tick` is called after each walk.
pub fn ensemble(
    creature: &Creature,
    sim: &SimOptions,
    options: &WalkerOptions,
    (first, runs): (usize, usize),
    tick: &(dyn Fn() + Sync),
) -> Ensemble {
    let walks: Vec<Evaluation> = (first..first + runs)
        .map(|k| {
            let nudged = SimOptions {
                drop_height: sim.drop_height + 1e-4 * k as f64,
                ..sim.clone()
            };
            let walk = task::walker(creature, &nudged, options, false);
            tick();
            walk
        })
        .collect();
    let fitness: Vec<f64> = walks.iter().map(|e| e.fitness).collect();
    Ensemble {
        median: median(&fitness),
        rested: walks.iter().filter(|e| rested(e)).count(),
        walks,
    }
}

/// Creatures at rest, given how many of each creature's `runs` walks came to rest with a
/// setting (`measured`) and with the fine reference (`fine`): a creature is at rest when most
/// of its walks are (so its median fitness is a rested walk's). Returns (creatures at rest
/// with both, creatures at rest with the fine reference).
pub fn creatures_at_rest(measured: &[usize], fine: &[usize], runs: usize) -> (usize, usize) {
    let mostly = |at_rest: usize| 2 * at_rest > runs;
    let fine_rested = fine.iter().filter(|&&f| mostly(f)).count();
    let both = measured
        .iter()
        .zip(fine)
        .filter(|&(&m, &f)| mostly(m) && mostly(f))
        .count();
    (both, fine_rested)
}

/// A setting's short name: its name when it is a named setting (`fast`, `default`, `fine`),
/// else `SxIxP/SxI` (substeps × solver iterations × PGS passes while walking, then substeps ×
/// iterations while waiting for rest).
pub fn setting_name(sim: &SimOptions) -> String {
    if let Some(named) = StepSetting::of(sim) {
        return named.name().to_string();
    }
    crate::sim::knobs::stepping_notation(sim)
}

/// The fine reference's walks of every creature: `runs` walks from the first drop heights
/// (the reference the settings are ranked against) and `runs` from the next ones (the noise
/// floor), with the figures of the noise floor.
#[derive(Clone, Debug)]
pub struct FineReference {
    /// Per creature: the reference walks and the noise floor's walks.
    pub ensembles: Vec<(Ensemble, Ensemble)>,
    /// The Spearman correlation of the noise floor's median fitness with the reference's.
    pub floor_medians: f64,
    /// The same, for each creature's first walk only.
    pub floor_single: f64,
    /// How many of the reference walks ended at rest.
    pub walks_rested: usize,
    /// How many creatures came to rest in most of their reference walks.
    pub creatures_rested: usize,
    /// Walks per creature.
    pub runs: usize,
}

impl FineReference {
    /// Walks `creatures` with `fine` (the fine reference setting), `runs` times from the
    /// first drop heights and `runs` times from the next, in parallel; `tick` is called after
    /// each walk.
    pub fn walk(
        creatures: &[(String, Creature)],
        fine: &SimOptions,
        options: &WalkerOptions,
        runs: usize,
        tick: &(dyn Fn() + Sync),
    ) -> FineReference {
        let ensembles: Vec<(Ensemble, Ensemble)> = creatures
            .par_iter()
            .map(|(_, c)| {
                (
                    ensemble(c, fine, options, (0, runs), tick),
                    ensemble(c, fine, options, (runs, runs), tick),
                )
            })
            .collect();
        let reference: Vec<f64> = ensembles.iter().map(|(b, _)| b.median).collect();
        let floor: Vec<f64> = ensembles.iter().map(|(_, c)| c.median).collect();
        let first_fine: Vec<f64> = ensembles.iter().map(|(b, _)| b.walks[0].fitness).collect();
        let first_floor: Vec<f64> = ensembles.iter().map(|(_, c)| c.walks[0].fitness).collect();
        let walks_rested = ensembles
            .iter()
            .map(|(b, _)| b.walks.iter().filter(|e| rested(e)).count())
            .sum();
        let at_rest: Vec<usize> = ensembles.iter().map(|(b, _)| b.rested).collect();
        let (_, creatures_rested) = creatures_at_rest(&at_rest, &at_rest, runs);
        FineReference {
            floor_medians: spearman(&floor, &reference),
            floor_single: spearman(&first_floor, &first_fine),
            walks_rested,
            creatures_rested,
            runs,
            ensembles,
        }
    }

    /// The reference's median fitness per creature.
    fn medians(&self) -> Vec<f64> {
        self.ensembles.iter().map(|(b, _)| b.median).collect()
    }

    /// The fitness of each creature's first reference walk.
    fn first_walks(&self) -> Vec<f64> {
        self.ensembles
            .iter()
            .map(|(b, _)| b.walks[0].fitness)
            .collect()
    }

    /// How many of each creature's reference walks ended at rest.
    fn at_rest(&self) -> Vec<usize> {
        self.ensembles.iter().map(|(b, _)| b.rested).collect()
    }

    /// Ranks `setting` against this reference: walks every creature `runs` times with it
    /// from the reference's first drop heights, in parallel; `tick` is called after each walk.
    pub fn rank(
        &self,
        setting: &SimOptions,
        creatures: &[(String, Creature)],
        options: &WalkerOptions,
        tick: &(dyn Fn() + Sync),
    ) -> SettingFidelity {
        let runs = self.runs;
        let ensembles: Vec<Ensemble> = creatures
            .par_iter()
            .map(|(_, c)| ensemble(c, setting, options, (0, runs), tick))
            .collect();
        let measured: Vec<f64> = ensembles.iter().map(|a| a.median).collect();
        let first_measured: Vec<f64> = ensembles.iter().map(|a| a.walks[0].fitness).collect();
        let mut both_rested = 0;
        for (a, (b, _)) in ensembles.iter().zip(&self.ensembles) {
            for (x, y) in a.walks.iter().zip(&b.walks) {
                if rested(y) && rested(x) {
                    both_rested += 1;
                }
            }
        }
        let at_rest: Vec<usize> = ensembles.iter().map(|a| a.rested).collect();
        let (creatures_rested, _) = creatures_at_rest(&at_rest, &self.at_rest(), runs);
        SettingFidelity {
            spearman: spearman(&measured, &self.medians()),
            single: spearman(&first_measured, &self.first_walks()),
            both_rested,
            creatures_rested,
            ensembles,
        }
    }
}

/// How a setting ranks the creatures against the fine reference.
#[derive(Clone, Debug)]
pub struct SettingFidelity {
    /// The Spearman correlation of the creatures' median fitness with the reference's.
    pub spearman: f64,
    /// The same, for each creature's first walk only.
    pub single: f64,
    /// Walks at rest with both the setting and the reference (walk k against walk k).
    pub both_rested: usize,
    /// Creatures at rest in most of their walks with both the setting and the reference.
    pub creatures_rested: usize,
    /// Per creature: the setting's walks.
    pub ensembles: Vec<Ensemble>,
}

#[cfg(test)]
mod tests {
    use super::creatures_at_rest;

    #[test]
    fn a_creature_is_at_rest_when_most_of_its_walks_are() {
        // Three walks each: 2 of 3 at rest counts, 1 of 3 does not; a creature the fine
        // reference does not bring to rest is not counted for the setting either.
        let fine = [3, 2, 1, 3, 0];
        let measured = [2, 2, 3, 1, 3];
        assert_eq!(creatures_at_rest(&measured, &fine, 3), (2, 3));
        assert_eq!(creatures_at_rest(&fine, &fine, 3), (3, 3));
        // An even number of walks: half is not most.
        assert_eq!(creatures_at_rest(&[2, 3], &[4, 4], 4), (1, 2));
    }
}
