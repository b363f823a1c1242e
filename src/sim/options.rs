//! The simulator's options ([`SimOptions`]): every value a world is built and stepped with,
//! their defaults, the models they choose between (joints, actuators, whose cross-section sets
//! a joint's strength). Each value's key, flag, range and description are its entry in
//! [`KNOBS`](super::knobs::KNOBS), whose one range check ([`SimOptions::check`]) every path
//! that reads options (a config file, a command-line flag, a `creature.json`, the library's
//! [`World::new`](super::World::new)) goes through.

/// The shortest control step (s) a setting may have: 1 ms, a 1 kHz controller (its physics
/// runs up to [`MAX_SUBSTEPS`] times finer). Shorter steps would make an evaluation of the
/// longest task take billions of steps.
pub const MIN_DT: f64 = 0.001;
/// The longest control step (s) a setting may have: 0.1 s, a 10 Hz controller.
pub const MAX_DT: f64 = 0.1;
/// The most physics substeps per control step (walking or waiting for rest): 64, physics at
/// 1/3840 s at the default control step.
pub const MAX_SUBSTEPS: usize = 64;
/// The most solver iterations per substep, and the most Gauss-Seidel passes per iteration.
pub const MAX_ITERATIONS: usize = 256;

/// The default stepping, in the order of the stepping knobs
/// ([`stepping_knobs`](super::knobs::stepping_knobs)): 4 substeps of 4 solver iterations of
/// one Gauss-Seidel pass while walking, 4 substeps of 8 iterations while waiting for rest. The
/// named setting `default` ([`StepSetting::Default`](super::StepSetting::Default)) is these
/// values.
pub(super) const DEFAULT_STEPPING: [usize; 5] = [4, 4, 1, 4, 8];

/// How joints are simulated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum JointModel {
    /// Impulse-based constraints between free bodies (rapier's `ImpulseJointSet`).
    Impulse,
    /// Reduced coordinates (rapier's `MultibodyJointSet`).
    Multibody,
}

/// How an actuator neuron's signal s ∈ [−1, 1] drives its joint.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ActuatorModel {
    /// Chaumont et al. 5.3: the motor runs at saturation, its target velocity fixed high in
    /// the signal's sign, its maximum torque |s| × the joint's strength.
    Muscle,
    /// Chaumont et al. 5.3's muscle applied as what a saturated motor gives: a torque of
    /// s × the joint's strength about the joint's axis, equal and opposite on its two parts,
    /// with no motor row in the joint's constraint.
    MuscleTorque,
    /// Hornby & Pollack: s sets the target angle inside the joint's range.
    Angle,
    /// Matos & Arita: s sets the target angular velocity (s × `max_speed`).
    Velocity,
}

/// Which part's cross-section sets a joint's strength.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum StrengthFrom {
    /// The smaller of the two parts (Walking with Dinosaurs 3.4.4: "the smallest contact
    /// area").
    Smaller,
    /// The bigger of the two parts (the default: Chaumont et al. 3.4, after Sims 1994, and
    /// the assumption behind the size normalisation of their walker fitness, equation 1).
    Bigger,
}

/// The default joint strength: maximum torque per square metre of cross-section (N·m/m²).
///
/// Calibrated so that a joint can hold a horizontal one-part limb of its own cross-section
/// and the default density against gravity up to a length of
/// L = √(2 · strength / (ρ g)) = √(2 · 10⁴ / (1000 · 9.81)) ≈ 1.43 m: a 1 m limb with a
/// margin of 2.04 (the torque needed is ρ g A L² / 2).
pub const DEFAULT_STRENGTH: f64 = 1.0e4;

/// The muscle model's target speed V_des (rad/s), "fixed and high" (Chaumont et al. 5.3) so
/// that a muscle is torque-limited, never speed-limited, in every shipped creature.
pub const DEFAULT_MUSCLE_SPEED: f64 = 100.0;

/// The default [`SimOptions::energy_tolerance`] (J/kg): the energy a creature may gain from
/// nothing within about [`ENERGY_WINDOW`](crate::sim::ENERGY_WINDOW), what lifting it by 1 m takes: three times the
/// most the shipped and random creatures reach at the fast setting ([`SimOptions::fast`], 3.2 J/kg), well
/// below what the exploits evolution found reach (27 J/kg). See docs/reference/tasks.md, the energy audit.
pub const ENERGY_TOLERANCE: f64 = 10.0;

/// World settings. Read from a `[task.sim]` table as a person writes it (a named step setting
/// and any value over it, see [`setting`](super::setting)); checked by [`SimOptions::check`].
/// Each field is one entry of [`KNOBS`](super::knobs::KNOBS), in the same order.
#[derive(Clone, Debug, serde::Serialize)]
pub struct SimOptions {
    /// The control step in seconds: the brain runs once per step; physics runs `substeps`
    /// times per step, at `control_step / substeps`. A config file names it `control_step` (`dt`, its
    /// name in older files, is read as well), the command line `--time-step`; not to be
    /// confused with the developmental time step (`--dt`, an L-system's `dt:`).
    #[serde(rename = "control_step")]
    pub control_step: f64,
    /// Physics substeps per control step.
    pub substeps: usize,
    /// Solver iterations per substep (rapier's `num_solver_iterations`: each one re-linearises
    /// the constraints and integrates positions over a fraction of the substep).
    pub solver_iterations: usize,
    /// Gauss-Seidel passes inside each solver iteration (rapier's
    /// `num_internal_pgs_iterations`): cheaper than solver iterations, as the constraints are
    /// not rebuilt.
    pub pgs_iterations: usize,
    /// Physics substeps per control step while a task waits for the creature to come to rest
    /// (controller off): Chaumont's rest test compares per-step motion with Δx, so it wants
    /// a steadier solver than walking does.
    pub rest_substeps: usize,
    /// Solver iterations per substep while a task waits for rest (one PGS pass each).
    pub rest_solver_iterations: usize,
    /// Joint model.
    pub joints: JointModel,
    /// Whether parts of one creature that are not joint neighbours collide.
    pub self_collision: bool,
    /// Friction coefficient of the ground and the parts.
    pub friction: f64,
    /// Actuator model.
    pub actuator: ActuatorModel,
    /// Maximum joint torque per square metre of cross-section (N·m/m²), multiplied by the
    /// joint's own strength.
    pub strength: f64,
    /// Whose cross-section: the smaller or the bigger of the two parts.
    pub strength_from: StrengthFrom,
    /// The muscle model's target speed V_des (rad/s), fixed and high so that the motor runs
    /// at saturation (torque-limited).
    pub muscle_speed: f64,
    /// The velocity model's top speed (rad/s): a signal s asks for s × `max_speed`.
    pub max_speed: f64,
    /// Height of the creature's lowest point above the ground when it is dropped.
    pub drop_height: f64,
    /// A part moving farther than this in one control step means the world exploded.
    pub explosion_distance: f64,
    /// A part faster than this (m/s) means the world exploded.
    pub speed_limit: f64,
    /// Energy from nowhere (J per kg of creature) that means the world exploded: the sum,
    /// over control steps, of every rise of the creature's mechanical energy (kinetic plus
    /// gravitational) beyond the most work its motors could have done in that step. 0 turns
    /// the audit off.
    pub energy_tolerance: f64,
}

impl Default for SimOptions {
    fn default() -> Self {
        // Physics at 1/240 s: 4 substeps of 4 solver iterations (one PGS pass each) while
        // walking, 4 substeps of 8 iterations (the fine reference's own setting) while a task
        // waits for rest. The champions evolved at the faster `SimOptions::fast` setting lost
        // most of their distance at the fine reference; those of the few runs evolved at this
        // one kept most of theirs (lucky walks aside), and this setting ranks random creatures
        // about as alike to the fine reference as the reference ranks them to itself (see
        // `ontogeny bench --fidelity` and docs/results/speed.md).
        let [
            substeps,
            solver_iterations,
            pgs_iterations,
            rest_substeps,
            rest_solver_iterations,
        ] = DEFAULT_STEPPING;
        SimOptions {
            control_step: 1.0 / 60.0,
            substeps,
            solver_iterations,
            pgs_iterations,
            rest_substeps,
            rest_solver_iterations,
            joints: JointModel::Impulse,
            self_collision: true,
            friction: 1.0,
            actuator: ActuatorModel::Muscle,
            strength: DEFAULT_STRENGTH,
            strength_from: StrengthFrom::Bigger,
            muscle_speed: DEFAULT_MUSCLE_SPEED,
            max_speed: 5.0,
            drop_height: 0.05,
            explosion_distance: 2.0,
            speed_limit: 100.0,
            energy_tolerance: ENERGY_TOLERANCE,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_check_names_the_key_and_its_range() {
        // A default with one value changed.
        let with = |change: fn(&mut SimOptions)| {
            let mut options = SimOptions::default();
            change(&mut options);
            options
        };
        let cases: [(SimOptions, &str); 8] = [
            (with(|o| o.substeps = 0), "substeps must be 1 to 64, not 0"),
            (
                with(|o| o.substeps = 4_000_000_000),
                "substeps must be 1 to 64, not 4000000000",
            ),
            (
                with(|o| o.solver_iterations = 1_000_000_000),
                "solver_iterations must be 1 to 256, not 1000000000",
            ),
            (
                with(|o| o.control_step = 1e-9),
                "control_step must be in [0.001, 0.1] seconds, not 0.000000001",
            ),
            (
                with(|o| o.control_step = f64::NAN),
                "control_step must be in [0.001, 0.1] seconds, not NaN",
            ),
            (
                with(|o| o.friction = -1.0),
                "friction must be finite and not negative, not -1",
            ),
            (
                with(|o| o.muscle_speed = f64::INFINITY),
                "muscle_speed must be finite and positive, not inf",
            ),
            (
                with(|o| o.energy_tolerance = -2.0),
                "energy_tolerance must be finite and not negative (0 turns the audit off), not -2",
            ),
        ];
        for (options, message) in cases {
            let e = options.check().unwrap_err();
            assert_eq!(e.to_string(), message);
            assert_eq!(
                e.within("sim").within("task").to_string(),
                format!("[task.sim] {message}")
            );
        }
        let e = SimOptions {
            rest_substeps: 65,
            ..SimOptions::default()
        }
        .check()
        .unwrap_err();
        assert_eq!(
            e.for_flag("--rest-substeps"),
            "--rest-substeps must be 1 to 64, not 65"
        );
    }
}
