//! The noisy trials of an evaluation (`[task.trials]`): how many, the ranges their noise is
//! drawn from (heading, start offset, muscle strength, friction and roughness), how their
//! fitnesses combine ([`Aggregate`]), and one trial's draw ([`Perturbation`]), a pure function
//! of the creature's evaluation key, so identical creatures get identical trials wherever they
//! run. The habitats the trials run in are `habitat`'s.

use nalgebra::{UnitQuaternion, Vector3};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use crate::creature::Creature;
use crate::sim::SettingError;

/// The most trials per habitat (`[task.trials] count`).
pub const MAX_TRIALS: u32 = 64;

/// The widest heading noise (degrees, ±): half a turn either way.
pub const MAX_HEADING: f64 = 180.0;

/// The widest start offset noise (m, ±, along x and along z).
pub const MAX_OFFSET: f64 = 100.0;

/// The widest noise on strength, friction and roughness (%, ±): below 100, so a factor stays
/// positive.
pub const MAX_PERCENT: f64 = 99.0;

/// How the fitnesses of an individual's units combine into its fitness.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Aggregate {
    /// The arithmetic mean.
    #[default]
    Mean,
    /// The smallest.
    Min,
    /// The middle value; of an even number, the mean of the two middle values.
    Median,
}

impl Aggregate {
    /// Every aggregate, in the order the reference lists them.
    pub const ALL: [Aggregate; 3] = [Aggregate::Mean, Aggregate::Min, Aggregate::Median];

    /// The name configs and reports spell.
    pub fn name(self) -> &'static str {
        match self {
            Aggregate::Mean => "mean",
            Aggregate::Min => "min",
            Aggregate::Median => "median",
        }
    }

    /// `values` combined (NaN for none): the mean, the smallest, or the median (of an even
    /// count, the mean of the two middle values).
    pub fn of(self, values: &[f64]) -> f64 {
        if values.is_empty() {
            return f64::NAN;
        }
        match self {
            Aggregate::Mean => values.iter().sum::<f64>() / values.len() as f64,
            Aggregate::Min => values.iter().copied().fold(f64::INFINITY, f64::min),
            Aggregate::Median => {
                let mut sorted = values.to_vec();
                sorted.sort_by(f64::total_cmp);
                let n = sorted.len();
                if n % 2 == 1 {
                    sorted[n / 2]
                } else {
                    (sorted[n / 2 - 1] + sorted[n / 2]) / 2.0
                }
            }
        }
    }
}

/// The trials of every habitat (`[task.trials]`): how many, how they combine, and the ranges
/// their noise is drawn from (each uniformly in [−range, +range]; 0: no noise).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Trials {
    /// Trials per habitat, K (1 to [`MAX_TRIALS`]).
    pub count: u32,
    /// How the fitnesses of every habitat's trials combine.
    pub aggregate: Aggregate,
    /// Whether the elite are walked again each generation on fresh draws (the generation
    /// joins the draw's seed), so no lucky draw is kept for ever.
    pub fresh: bool,
    /// The creature's initial heading, degrees (±), turned about the vertical through its
    /// centre.
    pub heading: f64,
    /// Its start offset, metres (±, along x and along z independently).
    pub offset: f64,
    /// The muscles' strength, percent (±).
    pub strength: f64,
    /// The friction of the ground and the parts, percent (±).
    pub friction: f64,
    /// The amplitude of a rough world's heightfield, percent (±).
    pub roughness: f64,
}

impl Default for Trials {
    fn default() -> Self {
        Trials {
            count: 1,
            aggregate: Aggregate::Mean,
            fresh: false,
            heading: 0.0,
            offset: 0.0,
            strength: 0.0,
            friction: 0.0,
            roughness: 0.0,
        }
    }
}

impl Trials {
    /// Whether these are the default trials (one, no noise): not written to a config.
    pub fn is_default(&self) -> bool {
        *self == Trials::default()
    }

    /// Whether any noise range is set.
    pub fn noisy(&self) -> bool {
        [
            self.heading,
            self.offset,
            self.strength,
            self.friction,
            self.roughness,
        ]
        .iter()
        .any(|&r| r != 0.0)
    }

    pub(super) fn check(&self) -> Result<(), SettingError> {
        if !(1..=MAX_TRIALS).contains(&self.count) {
            return Err(SettingError::out_of_range(
                "count",
                &format!("1 to {MAX_TRIALS}"),
                self.count,
            ));
        }
        self.check_ranges()
    }

    pub(super) fn check_ranges(&self) -> Result<(), SettingError> {
        for (key, value, most) in [
            ("heading", self.heading, MAX_HEADING),
            ("offset", self.offset, MAX_OFFSET),
            ("strength", self.strength, MAX_PERCENT),
            ("friction", self.friction, MAX_PERCENT),
            ("roughness", self.roughness, MAX_PERCENT),
        ] {
            if !(0.0..=most).contains(&value) {
                return Err(SettingError::out_of_range(
                    key,
                    &format!("in [0, {most}]"),
                    value,
                ));
            }
        }
        Ok(())
    }
}

/// One trial's draw: what changes from the habitat as written.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Perturbation {
    /// The turn of the creature about the vertical through its centre (degrees).
    pub heading: f64,
    /// Its start offset along x and z (m).
    pub offset: [f64; 2],
    /// The factor on the muscles' strength.
    pub strength: f64,
    /// The factor on the friction of the ground and the parts.
    pub friction: f64,
    /// The factor on a rough world's amplitude.
    pub roughness: f64,
}

impl Default for Perturbation {
    fn default() -> Self {
        Perturbation {
            heading: 0.0,
            offset: [0.0; 2],
            strength: 1.0,
            friction: 1.0,
            roughness: 1.0,
        }
    }
}

impl Perturbation {
    /// The draw of trial `trial` in habitat `habitat` for the individual whose evaluation key
    /// is `key`, from the ranges of `trials`; `generation` joins the seed when the trials are
    /// fresh. ChaCha8 seeded from the key, its stream the habitat and trial: identical
    /// creatures get identical trials wherever and in whatever order they run.
    pub fn draw(
        trials: &Trials,
        key: [u8; 32],
        habitat: u32,
        trial: u32,
        generation: Option<u32>,
    ) -> Perturbation {
        let mut seed = key;
        if let Some(g) = generation {
            for (b, x) in seed.iter_mut().zip((u64::from(g) + 1).to_le_bytes()) {
                *b ^= x;
            }
        }
        let mut rng = ChaCha8Rng::from_seed(seed);
        rng.set_stream((u64::from(habitat) << 32) | u64::from(trial));
        let mut within = |range: f64| -> f64 {
            // Drawn even for a zero range, so a range does not move another's draw.
            let u: f64 = rng.random_range(-1.0..=1.0);
            u * range
        };
        let heading = within(trials.heading);
        let offset = [within(trials.offset), within(trials.offset)];
        let strength = 1.0 + within(trials.strength) / 100.0;
        let friction = 1.0 + within(trials.friction) / 100.0;
        let roughness = 1.0 + within(trials.roughness) / 100.0;
        Perturbation {
            heading,
            offset,
            strength,
            friction,
            roughness,
        }
    }

    /// `creature` turned by the heading about the vertical through its centre (the mean of
    /// its parts' centres), then moved by the offset; unchanged, bit for bit, when both are 0.
    pub fn place(&self, creature: &Creature) -> Creature {
        let mut placed = creature.clone();
        if self.heading == 0.0 && self.offset == [0.0; 2] {
            return placed;
        }
        let n = creature.parts.len().max(1) as f64;
        let sum = creature
            .parts
            .iter()
            .fold(Vector3::zeros(), |s, p| s + p.position);
        let centre = Vector3::new(sum.x / n, 0.0, sum.z / n);
        let turn = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), self.heading.to_radians());
        let shift = Vector3::new(self.offset[0], 0.0, self.offset[1]);
        let moved = |p: Vector3<f64>| turn * (p - centre) + centre + shift;
        for part in &mut placed.parts {
            part.position = moved(part.position);
            part.orientation = turn * part.orientation;
        }
        for joint in &mut placed.joints {
            joint.anchor = moved(joint.anchor);
            for axis in &mut joint.axes {
                *axis = turn * *axis;
            }
        }
        placed
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_aggregates_match_values_computed_by_hand() {
        let trials = [3.0, -1.0, 4.0, 1.5];
        assert_eq!(Aggregate::Mean.of(&trials), 7.5 / 4.0);
        assert_eq!(Aggregate::Min.of(&trials), -1.0);
        // Even count: sorted -1, 1.5, 3, 4; the mean of 1.5 and 3.
        assert_eq!(Aggregate::Median.of(&trials), 2.25);
        assert_eq!(Aggregate::Median.of(&[3.0, -1.0, 4.0]), 3.0);
        assert_eq!(Aggregate::Median.of(&[2.0]), 2.0);
        assert!(Aggregate::Mean.of(&[]).is_nan());
    }

    #[test]
    fn a_draw_depends_on_the_key_habitat_trial_and_fresh_generation_only() {
        let trials = Trials {
            heading: 30.0,
            offset: 0.5,
            strength: 10.0,
            friction: 20.0,
            roughness: 50.0,
            ..Trials::default()
        };
        let a = Perturbation::draw(&trials, [1; 32], 0, 1, None);
        assert_eq!(a, Perturbation::draw(&trials, [1; 32], 0, 1, None));
        for other in [
            Perturbation::draw(&trials, [2; 32], 0, 1, None),
            Perturbation::draw(&trials, [1; 32], 1, 1, None),
            Perturbation::draw(&trials, [1; 32], 0, 0, None),
            Perturbation::draw(&trials, [1; 32], 0, 1, Some(0)),
        ] {
            assert_ne!(a, other);
        }
        assert!(a.heading.abs() <= 30.0 && a.offset.iter().all(|o| o.abs() <= 0.5));
        assert!((0.9..=1.1).contains(&a.strength));
        assert!((0.8..=1.2).contains(&a.friction));
        assert!((0.5..=1.5).contains(&a.roughness));
    }

    #[test]
    fn a_quarter_turn_turns_parts_and_joints_about_the_centre() {
        use crate::creature::{Joint, JointKind, Part};
        let part = |x: f64| Part {
            size: Vector3::new(1.0, 0.2, 0.2),
            position: Vector3::new(x, 0.5, 0.0),
            orientation: UnitQuaternion::identity(),
            density: 1000.0,
            growing: false,
        };
        let creature = Creature {
            parts: vec![part(0.0), part(2.0)],
            joints: vec![Joint {
                parent: 0,
                child: 1,
                kind: JointKind::Revolute,
                anchor: Vector3::new(1.0, 0.5, 0.0),
                axes: vec![Vector3::z()],
                limits: vec![(-1.0, 1.0)],
                strength: 1.0,
                growing: false,
            }],
            ..Creature::default()
        };
        let p = Perturbation {
            heading: 90.0,
            offset: [0.0, 3.0],
            ..Perturbation::default()
        };
        let placed = p.place(&creature);
        // About the centre (1, _, 0): (0, 0.5, 0) goes to (1, 0.5, 1), then 3 m along z.
        let close = |a: Vector3<f64>, b: Vector3<f64>| (a - b).norm() < 1e-12;
        assert!(close(placed.parts[0].position, Vector3::new(1.0, 0.5, 4.0)));
        assert!(close(placed.parts[1].position, Vector3::new(1.0, 0.5, 2.0)));
        assert!(close(placed.joints[0].anchor, Vector3::new(1.0, 0.5, 3.0)));
        assert!(close(placed.joints[0].axes[0], Vector3::new(1.0, 0.0, 0.0)));
        assert_eq!(Perturbation::default().place(&creature), creature);
    }
}
