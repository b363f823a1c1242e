//! The catapult and the aiming catapult (Chaumont et al. section 4): their settings, the
//! distance from a trajectory to a target (D_t), and their protocol.

use std::collections::BTreeMap;

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use super::protocol::{Setup, evaluate, on_flat_ground, steps_in};
use super::recording::Phase;
use super::registry::expression_fitness;
use super::{Evaluation, FitnessExpression, MAX_TARGET_DISTANCE, Status};
use crate::cancel::Interrupted;
use crate::creature::Creature;
use crate::sim::SimOptions;

/// Settings of the catapult and aim tasks (Chaumont et al. section 4).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CatapultOptions {
    /// The projectile's size (m).
    pub projectile_size: Vector3<f64>,
    /// The projectile's density (kg/m³).
    pub projectile_density: f64,
    /// Seconds after which the release mechanism fires without a signal (Figure 4: 30
    /// steps of 1/60 s).
    pub release_delay: f64,
    /// The projectile is at rest when slower than this (m/s) ...
    pub rest_speed: f64,
    /// ... for this long (s) after release.
    pub rest_duration: f64,
    /// A projectile not at rest this many seconds after the start is `unstable` (Chaumont's
    /// blocks "roll for almost 20 seconds").
    pub max_seconds: f64,
    /// Creatures taller than this (m) are not simulated.
    pub max_height: f64,
    /// The aim task's target, relative to where the projectile starts (metres; y is up).
    pub target: Option<Vector3<f64>>,
    /// Whether the projectile's edge lengths evolve with the thrower (Chaumont et al. 4.1:
    /// "mutations are allowed on the size and shape of the projectile"): every genome of the
    /// run carries them as genes, starting at `projectile_size`, and its creature throws its
    /// own projectile (of `projectile_density`; [`CatapultOptions::projectile_for`]). False:
    /// genomes carry none, and their creatures throw `projectile_size`.
    #[serde(skip_serializing_if = "is_false")]
    pub evolve_projectile: bool,
    /// Whether the aim task's creatures sense the target (their `target` sensors read its
    /// bearing). False, as Chaumont et al.'s aimers ("the individuals do not have sensors to
    /// retrieve information about the target", 4.3): every `target` sensor reads 0, as in
    /// the catapult task.
    #[serde(skip_serializing_if = "is_true")]
    pub target_sensor: bool,
    /// The fitness as an expression of the task's terms (`fitness = "D_p - release_time"`); none:
    /// the catapult's distance, the aim task's distance less the miss.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fitness: Option<FitnessExpression>,
}

impl Default for CatapultOptions {
    fn default() -> Self {
        CatapultOptions {
            projectile_size: Vector3::new(0.2, 0.2, 0.2),
            projectile_density: crate::creature::DEFAULT_DENSITY,
            release_delay: 0.5,
            rest_speed: 0.01,
            rest_duration: 0.5,
            max_seconds: 60.0,
            max_height: 15.0,
            target: None,
            evolve_projectile: false,
            target_sensor: true,
            fitness: None,
        }
    }
}

fn is_false(b: &bool) -> bool {
    !b
}

fn is_true(b: &bool) -> bool {
    *b
}

impl CatapultOptions {
    /// The edge lengths (m) of the projectile `creature` throws: its own
    /// ([`Creature::projectile`], which only a genome whose projectile evolved, or a file
    /// that names one, gives it), else `projectile_size`.
    pub fn projectile_for(&self, creature: &Creature) -> Vector3<f64> {
        match creature.projectile {
            Some([x, y, z]) => Vector3::new(x, y, z),
            None => self.projectile_size,
        }
    }

    /// The most control steps of `dt` the catapult and aim tasks can take: `max_seconds`.
    pub fn max_steps(&self, dt: f64) -> usize {
        steps_in(self.max_seconds, dt)
    }
}

/// The minimum distance between the polyline `trajectory` and `target` (D_t of equation 3).
pub fn distance_to_trajectory(trajectory: &[Vector3<f64>], target: &Vector3<f64>) -> f64 {
    match trajectory {
        [] => f64::INFINITY,
        [only] => (only - target).norm(),
        _ => trajectory
            .windows(2)
            .map(|w| {
                let (a, b) = (w[0], w[1]);
                let ab = b - a;
                let len2 = ab.norm_squared();
                let s = if len2 > 0.0 {
                    ((target - a).dot(&ab) / len2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                (a + ab * s - target).norm()
            })
            .fold(f64::INFINITY, f64::min),
    }
}

/// Catapult (`options.target` = None, equation 2: F_D = D_p) or aim (equation 3:
/// F_a = D_p − D_t). The creature's root part is the arm; a projectile is held at its near
/// end and released after `release_delay` seconds, or earlier when the brain's first
/// `release` effector fires. D_p is the horizontal distance of the projectile's centre from
/// release to rest; the simulation ends when the projectile comes to rest, and a projectile
/// still moving after `max_seconds` is `unstable`. Once the projectile is placed, the aim
/// task's target in the world is in the terms (`target_x`, `target_y`, `target_z`), of a
/// failed evaluation too.
pub fn catapult(
    creature: &Creature,
    sim: &SimOptions,
    options: &CatapultOptions,
    record: bool,
) -> Evaluation {
    on_flat_ground(creature, sim, options, record, catapult_watched)
}

/// [`catapult`] in any world, watched: recorded, told its progress and stopped by a token
/// as `setup` says. The aim task's evaluation, and the catapult's of settings without a
/// target.
pub(super) fn catapult_watched(
    setup: Setup<'_, '_, CatapultOptions>,
) -> Result<Evaluation, Interrupted> {
    let Setup {
        sim,
        options,
        creature,
        ..
    } = setup;
    let task: &'static str = if options.target.is_some() {
        "aim"
    } else {
        "catapult"
    };
    if let Some(target) = options.target
        && !(target.iter().all(|v| v.is_finite()) && target.norm() <= MAX_TARGET_DISTANCE)
    {
        return Ok(Evaluation::failed(
            task,
            Status::Invalid,
            format!("the target must be within {MAX_TARGET_DISTANCE} m of the projectile"),
        ));
    }
    let projectile = options.projectile_for(creature);
    // The target in the world, once the projectile is placed: kept in the terms of a failed
    // evaluation too, so that its recording can show the target.
    let placed_target = std::cell::Cell::new(None);
    let mut evaluation = evaluate(task, setup, |run| {
        run.world
            .attach_projectile(projectile, options.projectile_density);
        run.projectile_size = Some(projectile);
        run.phase = Phase::Throwing;
        let (start_position, _) = run.world.projectile_state().expect("attached");
        let target = options.target.map(|t| start_position + t);
        placed_target.set(target);
        // Without the target sensor, `target` sensors read 0, as the catapult's do.
        run.world
            .set_target(target.filter(|_| options.target_sensor));
        let mut released_at = None;
        let mut release_point = start_position;
        let mut trajectory = Vec::new();
        let mut calm = 0;
        let mut step = 0usize;
        let limit = steps_in(options.max_seconds, sim.control_step);
        let release_step = steps_in(options.release_delay, sim.control_step);
        let calm_needed = steps_in(options.rest_duration, sim.control_step);
        let mut at_rest = false;
        while step < limit {
            run.step(true)?;
            step += 1;
            let (position, speed) = run.world.projectile_state().expect("attached");
            if released_at.is_none() && (step >= release_step || run.world.release_signalled()) {
                run.world.release();
                run.phase = Phase::Flying;
                released_at = Some(step);
                release_point = position;
            }
            if released_at.is_some() {
                trajectory.push(position);
                calm = if speed < options.rest_speed {
                    calm + 1
                } else {
                    0
                };
                if calm >= calm_needed {
                    at_rest = true;
                    break;
                }
            }
        }
        let Some(released_at) = released_at else {
            return Err(Evaluation::failed(
                task,
                Status::Invalid,
                format!(
                    "the run ended after {step} steps, before the projectile was released (step {release_step})"
                ),
            ));
        };
        if !at_rest {
            return Err(Evaluation::failed(
                task,
                Status::Unstable,
                format!(
                    "the projectile was still moving after {} s",
                    options.max_seconds
                ),
            ));
        }
        let (rest_point, _) = run.world.projectile_state().expect("attached");
        let d = rest_point - release_point;
        let distance = (d.x * d.x + d.z * d.z).sqrt();
        let mut terms = BTreeMap::from([
            ("D_p".to_string(), distance),
            ("release_step".to_string(), released_at as f64),
            (
                "release_time".to_string(),
                released_at as f64 * sim.control_step,
            ),
            ("seconds".to_string(), run.world.time()),
            ("projectile_x".to_string(), projectile.x),
            ("projectile_y".to_string(), projectile.y),
            ("projectile_z".to_string(), projectile.z),
            (
                "projectile_mass".to_string(),
                projectile.x * projectile.y * projectile.z * options.projectile_density,
            ),
        ]);
        let fitness = match target {
            Some(target) => {
                terms.insert("target_x".to_string(), target.x);
                terms.insert("target_y".to_string(), target.y);
                terms.insert("target_z".to_string(), target.z);
                let d_t = distance_to_trajectory(&trajectory, &target);
                terms.insert("D_t".to_string(), d_t);
                distance - d_t
            }
            None => distance,
        };
        Ok((fitness, terms))
    })?;
    if let Some(target) = placed_target.get() {
        for (name, value) in [
            ("target_x", target.x),
            ("target_y", target.y),
            ("target_z", target.z),
        ] {
            evaluation.terms.entry(name.to_string()).or_insert(value);
        }
    }
    Ok(evaluation)
}

/// Chaumont et al.'s catapult, in the registry ([`super::Task`]): the catapult's settings
/// without a target (the aim task, [`super::AimTask`], is the one with a target).
pub struct CatapultTask;

impl super::Task for CatapultTask {
    const NAME: &'static str = "catapult";
    const SUMMARY: &'static str =
        "Chaumont et al.'s catapult: distance the projectile travels (eq. 2)";
    const THROWS: bool = true;
    const TERMS: &'static [&'static str] = &[
        "D_p",
        "release_step",
        "release_time",
        "seconds",
        "projectile_x",
        "projectile_y",
        "projectile_z",
        "projectile_mass",
    ];
    type Options = CatapultOptions;

    expression_fitness!();

    fn reads(options: &CatapultOptions) -> CatapultOptions {
        CatapultOptions {
            target: None,
            target_sensor: true,
            ..options.clone()
        }
    }
    fn measure(_options: &CatapultOptions) -> &'static str {
        "distance (m)"
    }
    /// The catapult's protocol without the target: the settings it
    /// [reads](super::Task::reads).
    fn evaluate(setup: Setup<'_, '_, CatapultOptions>) -> Result<Evaluation, Interrupted> {
        let reads = Self::reads(setup.options);
        catapult_watched(Setup {
            options: &reads,
            ..setup
        })
    }
}
