//! Habitats: the places one evaluation spans (`[[task.habitats]]`: a world and the chemical
//! array's initial values, and a habitat's own noise ranges), the units of that work ([`Unit`]:
//! a habitat, a trial and its drawn [`Perturbation`]), and how the units' results combine into
//! the individual's evaluation. The trials themselves (`[task.trials]`) are `trials`'s.
//!
//! A specification without habitats and with the default trials is *plain*: one implicit
//! habitat (the specification's own world, the genome's own array), one trial, no noise —
//! evaluated exactly as before habitats existed. This file does not develop creatures (the
//! encodings do, in each habitat's array) nor decide which units run where (the genetic
//! algorithm and its evaluator do).

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::{Evaluation, FAILURE_FITNESS, Perturbation, Status, TaskSpec, Trials};
use crate::creature::Creature;
use crate::sim::{SettingError, WorldSpec};

/// The most habitats a specification may list.
pub const MAX_HABITATS: usize = 16;

/// One place a creature is evaluated in (an entry of `[[task.habitats]]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Habitat {
    /// Its name, unique among the specification's habitats (reports and `--habitat` use it).
    pub name: String,
    /// Its world (level ground in air when absent; the task's `[task.world]` is refused beside
    /// habitats).
    #[serde(default, skip_serializing_if = "WorldSpec::is_flat")]
    pub world: WorldSpec,
    /// The chemical array's initial values in this habitat; absent, the genome's own.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub environment: Option<Vec<f64>>,
    /// The noise ranges of its trials that differ from `[task.trials]`'s
    /// (`[task.habitats.trials]`); absent, the task's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub trials: Option<Noise>,
}

/// A habitat's own noise ranges (`[task.habitats.trials]`): each one set replaces
/// `[task.trials]`'s in that habitat ([`TaskSpec::trials_in`]); how many trials and how they
/// combine stay the task's.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Noise {
    /// See [`Trials::heading`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub heading: Option<f64>,
    /// See [`Trials::offset`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub offset: Option<f64>,
    /// See [`Trials::strength`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub strength: Option<f64>,
    /// See [`Trials::friction`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction: Option<f64>,
    /// See [`Trials::roughness`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub roughness: Option<f64>,
}

/// One unit of an individual's evaluation: a trial in a habitat, with its draw.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Unit {
    /// The habitat's index in `[[task.habitats]]` (0 for the implicit one).
    pub habitat: u32,
    /// The trial's index, from 0.
    pub trial: u32,
    /// What the trial changes.
    pub perturbation: Perturbation,
}

/// The result of one unit, as an individual's evaluation keeps it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct HabitatResult {
    /// The habitat's name (empty for the implicit habitat).
    pub name: String,
    /// The trial's index, from 0.
    pub trial: u32,
    /// Parts and joints of the creature as it developed in the habitat (its morph).
    pub parts: u32,
    /// See `parts`.
    pub joints: u32,
    /// Its fitness ([`FAILURE_FITNESS`] unless its status is `ok`).
    pub fitness: f64,
    /// How it ended.
    pub status: Status,
    /// The terms behind its fitness.
    pub terms: BTreeMap<String, f64>,
    /// What went wrong, when something did.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub message: Option<String>,
}

impl TaskSpec {
    /// Whether the specification is plain: no habitats and the default trials, evaluated as
    /// one unit exactly as before habitats existed.
    pub fn is_plain(&self) -> bool {
        self.habitats.is_empty() && self.trials.is_default()
    }

    /// How many habitats an individual is developed in (1 without `[[task.habitats]]`).
    pub fn habitat_count(&self) -> usize {
        self.habitats.len().max(1)
    }

    /// How many walks one individual's evaluation simulates: trials × habitats.
    pub fn walks_per_evaluation(&self) -> usize {
        self.trials.count as usize * self.habitat_count()
    }

    /// The name of habitat `index` (empty for the implicit habitat).
    pub fn habitat_name(&self, index: usize) -> &str {
        self.habitats.get(index).map_or("", |h| h.name.as_str())
    }

    /// The index of the habitat named `name`; an error listing the names when none is.
    pub fn habitat_named(&self, name: &str) -> Result<usize, String> {
        self.habitats
            .iter()
            .position(|h| h.name == name)
            .ok_or_else(|| {
                let names: Vec<&str> = self.habitats.iter().map(|h| h.name.as_str()).collect();
                if names.is_empty() {
                    format!("no habitat '{name}': the task has no [[task.habitats]]")
                } else {
                    format!("no habitat '{name}'; the habitats are {}", names.join(", "))
                }
            })
    }

    /// The chemical array habitat `index` gives development (`None`: the genome's own).
    pub fn habitat_environment(&self, index: usize) -> Option<&[f64]> {
        self.habitats
            .get(index)
            .and_then(|h| h.environment.as_deref())
    }

    /// The plain specification of habitat `index`: this one with the habitat's world, and no
    /// habitats or trials of its own. Its evaluation key is the habitat's part of an
    /// individual's key.
    pub fn in_habitat(&self, index: usize) -> TaskSpec {
        let mut spec = self.clone();
        if let Some(h) = self.habitats.get(index) {
            spec.world = h.world.clone();
        }
        spec.habitats = Vec::new();
        spec.trials = Trials::default();
        spec
    }

    /// The trials of habitat `index`: `[task.trials]` with the ranges the habitat sets in
    /// their place ([`Habitat::trials`]).
    pub fn trials_in(&self, index: usize) -> Trials {
        let mut trials = self.trials.clone();
        if let Some(own) = self.habitats.get(index).and_then(|h| h.trials.as_ref()) {
            for (range, set) in [
                (&mut trials.heading, own.heading),
                (&mut trials.offset, own.offset),
                (&mut trials.strength, own.strength),
                (&mut trials.friction, own.friction),
                (&mut trials.roughness, own.roughness),
            ] {
                *range = set.unwrap_or(*range);
            }
        }
        trials
    }

    /// The units of an individual whose key is `key`: every trial of every habitat, habitat
    /// by habitat, each with its draw from the habitat's ranges ([`TaskSpec::trials_in`];
    /// `generation` joins the seed when the trials are fresh).
    pub fn units(&self, key: [u8; 32], generation: u32) -> Vec<Unit> {
        let fresh = self.trials.fresh.then_some(generation);
        (0..self.habitat_count() as u32)
            .flat_map(|habitat| {
                let trials = self.trials_in(habitat as usize);
                (0..self.trials.count).map(move |trial| Unit {
                    habitat,
                    trial,
                    perturbation: if trials.noisy() {
                        Perturbation::draw(&trials, key, habitat, trial, fresh)
                    } else {
                        Perturbation::default()
                    },
                })
            })
            .collect()
    }

    /// The plain specification one unit is evaluated with: its habitat's
    /// ([`TaskSpec::in_habitat`]), its strength, friction and roughness scaled by the draw.
    pub fn unit_spec(&self, unit: &Unit) -> TaskSpec {
        let mut spec = self.in_habitat(unit.habitat as usize);
        let p = &unit.perturbation;
        spec.sim.strength *= p.strength;
        spec.sim.friction *= p.friction;
        if let Some(ground) = &mut spec.world.friction {
            ground.coefficient *= p.friction;
            for patch in &mut ground.patches {
                patch.coefficient *= p.friction;
            }
        }
        if let Some(rough) = &mut spec.world.rough {
            rough.amplitude *= p.roughness;
        }
        spec
    }

    /// Evaluates `creature` as `unit` says ([`TaskSpec::evaluate_unit_watched`]), or, for no
    /// unit, as [`TaskSpec::evaluate_watched`] does: one walk of any specification.
    pub fn evaluate_job(
        &self,
        creature: &Creature,
        unit: Option<&Unit>,
        watch: super::Watch<'_>,
    ) -> Result<Evaluation, crate::cancel::Interrupted> {
        match unit {
            None => self.evaluate_watched(creature, watch),
            Some(unit) => self.evaluate_unit_watched(creature, unit, watch),
        }
    }

    /// [`TaskSpec::evaluate_job`], not recorded, told or cancelled.
    pub fn evaluate_job_plainly(&self, creature: &Creature, unit: Option<&Unit>) -> Evaluation {
        match unit {
            None => self.evaluate(creature, false),
            Some(unit) => self
                .unit_spec(unit)
                .evaluate(&unit.perturbation.place(creature), false),
        }
    }

    /// Evaluates `creature` (developed in the unit's habitat) as `unit` says: placed by its
    /// draw, with [`TaskSpec::unit_spec`].
    pub fn evaluate_unit_watched(
        &self,
        creature: &Creature,
        unit: &Unit,
        watch: super::Watch<'_>,
    ) -> Result<Evaluation, crate::cancel::Interrupted> {
        self.unit_spec(unit)
            .evaluate_watched(&unit.perturbation.place(creature), watch)
    }

    /// The evaluation of an individual from its units' evaluations (in the order of
    /// [`TaskSpec::units`]) and its creatures, one per habitat (for their sizes). Every unit `ok`: status `ok`, the fitness and each term the
    /// trials' aggregate. Any unit failed: the first failure's status and message (naming its
    /// habitat and trial) and the failure floor (0 when that failure is a creature that never
    /// came to rest, scored 0 by its task: [`super::UNSTABLE_FITNESS`]) — a creature that cheats the physics in one
    /// trial is refused, as the walker's guards refuse it in one walk.
    pub fn combine(
        &self,
        units: &[Unit],
        evaluations: Vec<Evaluation>,
        creatures: &[Creature],
    ) -> Evaluation {
        let sizes: Vec<(u32, u32)> = creatures
            .iter()
            .map(|c| (c.parts.len() as u32, c.joints.len() as u32))
            .collect();
        self.combine_sizes(units, evaluations, &sizes)
    }

    /// [`TaskSpec::combine`] for creatures known by their sizes alone: (parts, joints) per
    /// habitat (what rank 0 of an MPI job knows of creatures its workers developed).
    pub fn combine_sizes(
        &self,
        units: &[Unit],
        evaluations: Vec<Evaluation>,
        sizes: &[(u32, u32)],
    ) -> Evaluation {
        let results: Vec<HabitatResult> = units
            .iter()
            .zip(evaluations)
            .map(|(unit, e)| HabitatResult {
                name: self.habitat_name(unit.habitat as usize).to_string(),
                trial: unit.trial,
                parts: sizes.get(unit.habitat as usize).map_or(0, |s| s.0),
                joints: sizes.get(unit.habitat as usize).map_or(0, |s| s.1),
                fitness: e.fitness,
                status: e.status,
                terms: e.terms,
                message: e.message,
            })
            .collect();
        let task = self.task.name().to_string();
        if let Some(failed) = results.iter().find(|r| r.status != Status::Ok) {
            let place = if failed.name.is_empty() {
                format!("trial {}", failed.trial + 1)
            } else {
                format!("habitat {}, trial {}", failed.name, failed.trial + 1)
            };
            return Evaluation {
                task,
                // Its own task's score for that failure: 0 for a creature that never
                // came to rest where scores are never negative, else the floor.
                fitness: if failed.status == Status::Unstable {
                    failed.fitness
                } else {
                    FAILURE_FITNESS
                },
                status: failed.status,
                terms: BTreeMap::new(),
                message: Some(format!(
                    "{place}: {}",
                    failed.message.as_deref().unwrap_or(failed.status.name())
                )),
                recording: Vec::new(),
                habitats: Some(Box::new(results)),
            };
        }
        let aggregate = self.trials.aggregate;
        let fitnesses: Vec<f64> = results.iter().map(|r| r.fitness).collect();
        let mut terms = BTreeMap::new();
        if let Some(first) = results.first() {
            for name in first.terms.keys() {
                let values: Vec<f64> = results
                    .iter()
                    .filter_map(|r| r.terms.get(name).copied())
                    .collect();
                if values.len() == results.len() {
                    terms.insert(name.clone(), aggregate.of(&values));
                }
            }
        }
        Evaluation {
            task,
            fitness: aggregate.of(&fitnesses),
            status: Status::Ok,
            terms,
            message: None,
            recording: Vec::new(),
            habitats: Some(Box::new(results)),
        }
    }

    /// Checks the habitats and trials: at most [`MAX_HABITATS`] habitats with unique, non-empty
    /// names, each world as [`WorldSpec::check`] checks `[task.world]` (in air), each array
    /// finite, and each habitat's noise ranges as the trials' are; the trials in range. The error
    /// names the key as a config spells it (`[[task.habitats]] name`, `[task.trials] count`).
    pub(super) fn check_habitats(&self) -> Result<(), SettingError> {
        if self.habitats.len() > MAX_HABITATS {
            return Err(SettingError::out_of_range(
                "habitats",
                &format!("at most {MAX_HABITATS} tables"),
                self.habitats.len(),
            )
            .within("task"));
        }
        if !self.habitats.is_empty() && !self.world.is_flat() {
            return Err(SettingError::out_of_range(
                "world",
                "absent beside [[task.habitats]]: give each habitat its world",
                "given",
            )
            .within("task"));
        }
        for (i, h) in self.habitats.iter().enumerate() {
            // The entry's index names it in the file (a message leaves it out).
            let entry = format!("task.habitats.{i}");
            let within = |e: SettingError| e.within(&entry);
            if h.name.trim().is_empty() || h.name.chars().any(char::is_control) {
                return Err(within(SettingError::out_of_range(
                    "name",
                    "a word of printable characters",
                    format!("'{}'", h.name.escape_default()),
                )));
            }
            if self.habitats[..i].iter().any(|o| o.name == h.name) {
                return Err(within(SettingError::out_of_range(
                    "name",
                    "unique among the habitats",
                    format!("'{}' a second time", h.name),
                )));
            }
            if let Some(v) = h.environment.iter().flatten().find(|v| !v.is_finite()) {
                return Err(within(SettingError::out_of_range(
                    "environment",
                    &format!("finite numbers (habitat '{}')", h.name),
                    v,
                )));
            }
            if !h.world.medium.is_air() {
                return Err(within(
                    SettingError::out_of_range(
                        "medium",
                        &format!("air (habitat '{}'): water is not simulated yet", h.name),
                        "water",
                    )
                    .within("world"),
                ));
            }
            h.world.check().map_err(|mut e| {
                e.problem = format!("{} (habitat '{}')", e.problem, h.name);
                within(e.within("world"))
            })?;
            if h.trials.is_some() {
                self.trials_in(i).check_ranges().map_err(|mut e| {
                    e.problem = format!("{} (habitat '{}')", e.problem, h.name);
                    within(e.within("trials"))
                })?;
            }
        }
        self.trials.check().map_err(|e| e.within("task.trials"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::task::{Aggregate, MAX_TRIALS, TaskKind};

    fn evaluation(fitness: f64, status: Status, d: f64) -> Evaluation {
        Evaluation {
            task: "walker".into(),
            fitness,
            status,
            terms: BTreeMap::from([("D_w".to_string(), d)]),
            message: (status != Status::Ok).then(|| "it blew up".to_string()),
            recording: Vec::new(),
            habitats: None,
        }
    }

    fn two_habitats(k: u32, aggregate: Aggregate) -> TaskSpec {
        let mut spec = TaskSpec::new(TaskKind::Walker);
        spec.habitats = ["flat", "cued"]
            .map(|name| Habitat {
                name: name.into(),
                world: WorldSpec::default(),
                environment: None,
                trials: None,
            })
            .to_vec();
        spec.trials.count = k;
        spec.trials.aggregate = aggregate;
        spec
    }

    /// [`two_habitats`] with one trial and the mean, the cued habitat in `world`.
    fn cued_in(world: WorldSpec) -> TaskSpec {
        let mut spec = two_habitats(1, Aggregate::Mean);
        spec.habitats[1].world = world;
        spec
    }

    #[test]
    fn an_individual_scores_the_aggregate_of_its_units_and_keeps_each() {
        let spec = two_habitats(2, Aggregate::Median);
        let units = spec.units([7; 32], 0);
        assert_eq!(
            units
                .iter()
                .map(|u| (u.habitat, u.trial))
                .collect::<Vec<_>>(),
            [(0, 0), (0, 1), (1, 0), (1, 1)]
        );
        let e = spec.combine(
            &units,
            [1.0, 2.0, 4.0, 8.0]
                .map(|f| evaluation(f, Status::Ok, f * 10.0))
                .to_vec(),
            &[],
        );
        assert_eq!((e.fitness, e.status), (3.0, Status::Ok));
        assert_eq!(e.terms["D_w"], 30.0);
        assert_eq!(e.units().len(), 4);
        assert_eq!(
            (e.units()[3].name.as_str(), e.units()[3].trial),
            ("cued", 1)
        );
        assert_eq!(e.units()[3].fitness, 8.0);
    }

    #[test]
    fn one_failed_unit_fails_the_individual_and_names_where() {
        let spec = two_habitats(2, Aggregate::Mean);
        let units = spec.units([7; 32], 0);
        let mut evaluations: Vec<Evaluation> =
            (0..4).map(|_| evaluation(1.0, Status::Ok, 1.0)).collect();
        evaluations[3] = evaluation(FAILURE_FITNESS, Status::Exploded, 0.0);
        let e = spec.combine(&units, evaluations, &[]);
        assert_eq!((e.fitness, e.status), (FAILURE_FITNESS, Status::Exploded));
        assert_eq!(
            e.message.as_deref(),
            Some("habitat cued, trial 2: it blew up")
        );
        assert_eq!(e.units()[0].status, Status::Ok);
    }

    #[test]
    fn a_unit_that_never_came_to_rest_keeps_its_tasks_score_for_it() {
        // The walker scores a creature that never comes to rest 0 (Chaumont et al. 3.3); the
        // individual takes that score, not the floor, with the unit's status.
        let spec = two_habitats(2, Aggregate::Mean);
        let units = spec.units([7; 32], 0);
        let mut evaluations: Vec<Evaluation> =
            (0..4).map(|_| evaluation(5.0, Status::Ok, 1.0)).collect();
        evaluations[1] = evaluation(0.0, Status::Unstable, 0.0);
        let e = spec.combine(&units, evaluations, &[]);
        assert_eq!((e.fitness, e.status), (0.0, Status::Unstable));
    }

    #[test]
    fn a_unit_scales_the_simulator_and_the_world_by_its_draw() {
        let spec = cued_in(WorldSpec {
            rough: Some(crate::sim::world_spec::Rough {
                amplitude: 0.1,
                wavelength: 1.0,
                seed: 1,
                size: 20.0,
            }),
            ..WorldSpec::default()
        });
        let unit = Unit {
            habitat: 1,
            trial: 0,
            perturbation: Perturbation {
                strength: 1.5,
                friction: 0.5,
                roughness: 2.0,
                ..Perturbation::default()
            },
        };
        let s = spec.unit_spec(&unit);
        assert_eq!(s.sim.strength, spec.sim.strength * 1.5);
        assert_eq!(s.sim.friction, spec.sim.friction * 0.5);
        assert_eq!(s.world.rough.unwrap().amplitude, 0.2);
        assert!(s.habitats.is_empty() && s.trials.is_default());
    }

    #[test]
    fn the_checks_name_the_key_and_the_habitat() {
        let mut spec = two_habitats(1, Aggregate::Mean);
        spec.habitats[1].name = "flat".into();
        assert_eq!(
            spec.check().unwrap_err().to_string(),
            "[[task.habitats]] name must be unique among the habitats, not 'flat' a second time"
        );
        let mut spec = two_habitats(MAX_TRIALS + 1, Aggregate::Mean);
        assert_eq!(
            spec.check().unwrap_err().to_string(),
            "[task.trials] count must be 1 to 64, not 65"
        );
        spec.trials.count = 2;
        spec.trials.friction = 100.0;
        assert_eq!(
            spec.check().unwrap_err().to_string(),
            "[task.trials] friction must be in [0, 99], not 100"
        );
        spec.trials.friction = 5.0;
        spec.habitats[0].environment = Some(vec![f64::NAN]);
        assert_eq!(
            spec.check().unwrap_err().to_string(),
            "[[task.habitats]] environment must be finite numbers (habitat 'flat'), not NaN"
        );
    }

    #[test]
    fn a_habitats_world_is_checked_as_the_tasks_world_is() {
        let mut spec = cued_in(WorldSpec {
            slope: Some(crate::sim::world_spec::Slope {
                degrees: 95.0,
                direction: 0.0,
            }),
            ..WorldSpec::default()
        });
        assert_eq!(
            spec.check().unwrap_err().to_string(),
            "[task.habitats.world.slope] degrees must be at least 0 and below 80, not 95 \
             (habitat 'cued')"
        );
        spec.habitats[1].world.slope.as_mut().unwrap().degrees = 5.0;
        assert_eq!(spec.check(), Ok(()));
        spec.world = spec.habitats[1].world.clone();
        assert_eq!(
            spec.check().unwrap_err().to_string(),
            "[task] world must be absent beside [[task.habitats]]: give each habitat its world, \
             not given"
        );
        spec.world = WorldSpec::default();
        let unit = Unit {
            habitat: 1,
            trial: 0,
            perturbation: Perturbation::default(),
        };
        assert_eq!(spec.unit_spec(&unit).world, spec.habitats[1].world);
        assert!(spec.in_habitat(0).world.is_flat());
    }
}
