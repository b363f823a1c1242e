//! What a creature's world is made of besides the creature: the ground's shape (a slope, steps,
//! a rough heightfield), fixed obstacles, free objects, the ground's friction and its patches,
//! and the medium (air, or water with no ground and no gravity). Plain serialisable data, read
//! from a config's `[task.world]` table; [`WorldSpec::default`] is today's world: flat ground
//! of the simulator's friction, in air. Every world is deterministic given its seeds.
//!
//! Axes: y is up; the creature is dropped above the origin; directions in the horizontal
//! plane are angles in degrees about +y, measured from +x towards +z (0 = +x, 90 = +z).

use serde::{Deserialize, Serialize};

use super::knobs::{SettingError, check_real};
use super::water::MAX_VISCOSITY;

/// The most obstacles, and the most free objects, a world may hold.
pub const MAX_BODIES: usize = 1000;

/// The most friction patches a world may hold.
pub const MAX_PATCHES: usize = 1000;

/// The most steps in a flight.
pub const MAX_STEPS: u32 = 1000;

/// How far the level ground round a heightfield, and the steps' sides and last tread, reach
/// from the origin (m).
pub const FAR: f64 = 500.0;

/// The most samples along each side of a heightfield.
pub const MAX_SAMPLES: usize = 513;

/// The most a length in a world may be (m): the ground reaches [`FAR`].
pub const MAX_LENGTH: f64 = 400.0;

/// A creature's world besides the creature (the `[task.world]` table).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct WorldSpec {
    /// A plane ground tilted by an angle (none: level ground).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub slope: Option<Slope>,
    /// A flight of steps (none: no steps).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub steps: Option<Steps>,
    /// A rough ground: a seeded heightfield (none: smooth ground).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rough: Option<Rough>,
    /// Fixed boxes (none: no obstacles).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub obstacles: Option<Obstacles>,
    /// Free bodies: balls and boxes, with a starting velocity.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub objects: Vec<Object>,
    /// The ground's friction and its patches (none: the simulator's `friction`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction: Option<GroundFriction>,
    /// The medium the creature is in.
    #[serde(skip_serializing_if = "Medium::is_air")]
    pub medium: Medium,
}

impl WorldSpec {
    /// Whether this is today's world: flat ground of the simulator's friction, in air, nothing
    /// else in it. A flat world changes no evaluation key and writes no `[task.world]` table.
    pub fn is_flat(&self) -> bool {
        *self == WorldSpec::default()
    }

    /// Checks every key against its range; the error names the key in its table, from inside
    /// `[task.world]` (`slope`'s `degrees` is in table `slope`). At most one of `slope`,
    /// `steps` and `rough` shapes the ground. Water is alone in its world (it has no ground:
    /// no terrain, obstacles, objects or ground friction), its viscosity in
    /// (0, [`MAX_VISCOSITY`]].
    pub fn check(&self) -> Result<(), SettingError> {
        if let Medium::Water { viscosity } = self.medium {
            let rest = WorldSpec {
                medium: Medium::Air,
                ..self.clone()
            };
            if !rest.is_flat() {
                return Err(SettingError::out_of_range(
                    "medium",
                    "alone: water has no ground, so no slope, steps, rough, obstacles, objects or \
                     friction",
                    "water in a world with them",
                ));
            }
            if !(viscosity > 0.0 && viscosity <= MAX_VISCOSITY) {
                return Err(SettingError::out_of_range(
                    "viscosity",
                    &format!("in (0, {MAX_VISCOSITY}] N·s/m³"),
                    viscosity,
                )
                .within("medium"));
            }
        }
        let shapes = [
            self.slope.is_some(),
            self.steps.is_some(),
            self.rough.is_some(),
        ];
        if shapes.iter().filter(|&&s| s).count() > 1 {
            return Err(SettingError::out_of_range(
                "slope",
                "alone: slope, steps and rough each shape the whole ground, give one",
                "given with steps or rough",
            ));
        }
        if let Some(slope) = &self.slope {
            slope.check().map_err(|e| e.within("slope"))?;
        }
        if let Some(steps) = &self.steps {
            steps.check().map_err(|e| e.within("steps"))?;
        }
        if let Some(rough) = &self.rough {
            rough.check().map_err(|e| e.within("rough"))?;
        }
        if let Some(obstacles) = &self.obstacles {
            obstacles.check().map_err(|e| e.within("obstacles"))?;
        }
        if self.objects.len() > MAX_BODIES {
            return Err(SettingError::out_of_range(
                "objects",
                &format!("at most {MAX_BODIES} objects"),
                self.objects.len(),
            ));
        }
        for object in &self.objects {
            object.check().map_err(|e| e.within("objects"))?;
        }
        if let Some(friction) = &self.friction {
            friction.check().map_err(|e| e.within("friction"))?;
        }
        Ok(())
    }
}

/// `value` is finite and within [−[`MAX_LENGTH`], [`MAX_LENGTH`]].
fn check_place(key: &'static str, value: f64) -> Result<(), SettingError> {
    if value.is_finite() && value.abs() <= MAX_LENGTH {
        return Ok(());
    }
    Err(SettingError::out_of_range(
        key,
        &format!("within {MAX_LENGTH} m of the origin"),
        value,
    ))
}

/// `value` is above 0 and at most [`MAX_LENGTH`].
fn check_length(key: &'static str, value: f64) -> Result<(), SettingError> {
    check_real(key, value, 0.0, true)?;
    check_place(key, value)
}

/// `value` is a finite direction in degrees.
fn check_direction(value: f64) -> Result<(), SettingError> {
    if value.is_finite() && value.abs() <= 360.0 {
        return Ok(());
    }
    Err(SettingError::out_of_range(
        "direction",
        "in [-360, 360] (degrees)",
        value,
    ))
}

impl Slope {
    fn check(&self) -> Result<(), SettingError> {
        if !(self.degrees.is_finite() && (0.0..MAX_SLOPE).contains(&self.degrees)) {
            return Err(SettingError::out_of_range(
                "degrees",
                &format!("at least 0 and below {MAX_SLOPE}"),
                self.degrees,
            ));
        }
        check_direction(self.direction)
    }
}

/// The steepest slope (degrees, exclusive): steeper ground is a wall.
pub const MAX_SLOPE: f64 = 80.0;

impl Steps {
    fn check(&self) -> Result<(), SettingError> {
        check_length("height", self.height)?;
        check_length("depth", self.depth)?;
        if !(1..=MAX_STEPS).contains(&self.count) {
            return Err(SettingError::out_of_range(
                "count",
                &format!("1 to {MAX_STEPS}"),
                self.count,
            ));
        }
        check_real("start", self.start, 0.0, false)?;
        check_place("start", self.start)?;
        check_direction(self.direction)?;
        let reach = self.start + self.count as f64 * self.depth;
        if reach > MAX_LENGTH {
            return Err(SettingError::out_of_range(
                "count",
                &format!("few enough that the flight ends within {MAX_LENGTH} m"),
                format!("{} steps ending at {reach} m", self.count),
            ));
        }
        Ok(())
    }
}

impl Rough {
    fn check(&self) -> Result<(), SettingError> {
        check_length("amplitude", self.amplitude)?;
        check_length("wavelength", self.wavelength)?;
        check_length("size", self.size)?;
        let most = ((MAX_SAMPLES - 1) / 4) as f64;
        if self.size / self.wavelength > most {
            return Err(SettingError::out_of_range(
                "wavelength",
                &format!("at least size / {most} (the heightfield's samples are bounded)"),
                self.wavelength,
            ));
        }
        Ok(())
    }
}

impl Obstacles {
    fn check(&self) -> Result<(), SettingError> {
        for &side in &self.size {
            check_length("size", side)?;
        }
        if self.count as usize > MAX_BODIES || self.at.len() > MAX_BODIES {
            return Err(SettingError::out_of_range(
                "count",
                &format!("at most {MAX_BODIES}"),
                self.count.max(self.at.len() as u32),
            ));
        }
        check_real("raised", self.raised, 0.0, false)?;
        check_place("raised", self.raised)?;
        check_real("clear", self.clear, 0.0, false)?;
        check_place("clear", self.clear)?;
        check_length("reach", self.reach)?;
        for &[x, z] in &self.at {
            check_place("at", x)?;
            check_place("at", z)?;
        }
        let keep_out = self.clear + 0.5 * self.size[0].hypot(self.size[2]);
        if self.at.is_empty() && self.count > 0 && self.reach <= keep_out {
            return Err(SettingError::out_of_range(
                "reach",
                &format!(
                    "more than clear plus half the box's diagonal ({keep_out} m), so the boxes fit"
                ),
                self.reach,
            ));
        }
        Ok(())
    }
}

impl Object {
    fn check(&self) -> Result<(), SettingError> {
        check_length("size", self.size)?;
        check_real("mass", self.mass, 0.0, true)?;
        if self.mass > 1e6 {
            return Err(SettingError::out_of_range(
                "mass",
                "at most 10^6 kg",
                self.mass,
            ));
        }
        for &p in &self.position {
            check_place("position", p)?;
        }
        for &v in &self.velocity {
            if !(v.is_finite() && v.abs() <= 100.0) {
                return Err(SettingError::out_of_range(
                    "velocity",
                    "within 100 m/s on each axis",
                    v,
                ));
            }
        }
        Ok(())
    }
}

impl GroundFriction {
    fn check(&self) -> Result<(), SettingError> {
        check_coefficient(self.coefficient)?;
        if self.patches.len() > MAX_PATCHES {
            return Err(SettingError::out_of_range(
                "patches",
                &format!("at most {MAX_PATCHES}"),
                self.patches.len(),
            ));
        }
        for patch in &self.patches {
            check_coefficient(patch.coefficient).map_err(|e| e.within("patches"))?;
            for (key, [from, to]) in [("x", patch.x), ("z", patch.z)] {
                check_place(key, from).map_err(|e| e.within("patches"))?;
                check_place(key, to).map_err(|e| e.within("patches"))?;
                if from > to {
                    return Err(SettingError::out_of_range(
                        key,
                        "[from, to] with from at most to",
                        format!("[{from}, {to}]"),
                    )
                    .within("patches"));
                }
            }
        }
        Ok(())
    }
}

/// A friction coefficient: finite, 0 to 10.
fn check_coefficient(value: f64) -> Result<(), SettingError> {
    if value.is_finite() && (0.0..=10.0).contains(&value) {
        return Ok(());
    }
    Err(SettingError::out_of_range(
        "coefficient",
        "in [0, 10]",
        value,
    ))
}

/// A plane ground tilted by `degrees`, rising towards `direction`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Slope {
    /// The angle between the ground and the horizontal, in degrees (0 to below 90).
    pub degrees: f64,
    /// The horizontal direction in which the ground rises, in degrees about +y from +x
    /// (default 0: uphill is +x).
    #[serde(default)]
    pub direction: f64,
}

/// Which way a flight of steps goes from the start.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum StepsWay {
    /// Each step higher than the one before.
    #[default]
    Up,
    /// Each step lower than the one before.
    Down,
}

/// A flight of `count` steps, each `height` high and `depth` deep, starting `start` metres
/// from the origin towards `direction`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Steps {
    /// Each step's rise (m).
    pub height: f64,
    /// Each step's tread, along the direction (m).
    pub depth: f64,
    /// How many steps.
    pub count: u32,
    /// Up or down.
    #[serde(default)]
    pub way: StepsWay,
    /// The distance from the origin to the first step's edge (m, default 1).
    #[serde(default = "default_steps_start")]
    pub start: f64,
    /// The horizontal direction the flight runs in, degrees about +y from +x (default 0).
    #[serde(default)]
    pub direction: f64,
}

fn default_steps_start() -> f64 {
    1.0
}

/// A rough ground: a heightfield of smooth random bumps.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rough {
    /// The bumps' largest height above or below the mean ground (m).
    pub amplitude: f64,
    /// The bumps' typical horizontal spacing (m).
    pub wavelength: f64,
    /// The heightfield's seed: one seed, one ground.
    #[serde(default)]
    pub seed: u64,
    /// The side of the square of ground the heightfield covers, centred on the origin (m,
    /// default 40); level ground beyond.
    #[serde(default = "default_rough_size")]
    pub size: f64,
}

fn default_rough_size() -> f64 {
    40.0
}

/// Fixed boxes: `count` scattered with a seed, or placed at given points.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Obstacles {
    /// Each box's size (m): along x, up, along z.
    pub size: [f64; 3],
    /// How many boxes to scatter (ignored when `at` is given).
    #[serde(default)]
    pub count: u32,
    /// The scattering's seed.
    #[serde(default)]
    pub seed: u64,
    /// The scattering's reach: boxes fall in the square of this half-side round the origin,
    /// but not within `clear` of it (m, default 5).
    #[serde(default = "default_obstacles_reach")]
    pub reach: f64,
    /// The radius round the origin kept free of boxes, so the creature is not dropped on one
    /// (m, default 1).
    #[serde(default = "default_obstacles_clear")]
    pub clear: f64,
    /// The boxes' centres in the horizontal plane, [x, z] (m); when given, `count` is unused.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub at: Vec<[f64; 2]>,
    /// The height of each box's underside above the ground (m, default 0: on the ground); a
    /// raised box is a bar a tall creature strikes and a low one passes under.
    #[serde(default)]
    pub raised: f64,
}

fn default_obstacles_reach() -> f64 {
    5.0
}

fn default_obstacles_clear() -> f64 {
    1.0
}

/// The shape of a free object.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ObjectShape {
    /// A ball; `size` is its radius.
    #[default]
    Ball,
    /// A box; `size` is its side.
    Box,
}

/// A free body in the world: it falls, rolls and strikes the creature.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Object {
    /// Ball or box.
    #[serde(default)]
    pub shape: ObjectShape,
    /// A ball's radius, a box's side (m).
    pub size: f64,
    /// Its mass (kg).
    pub mass: f64,
    /// Where its centre starts, [x, y, z] (m; y above the ground beneath it).
    pub position: [f64; 3],
    /// Its velocity when the creature's walk starts, [x, y, z] (m/s).
    #[serde(default)]
    pub velocity: [f64; 3],
}

/// The ground's friction coefficient, and patches of another.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroundFriction {
    /// The ground's coefficient.
    pub coefficient: f64,
    /// Rectangles of ground with another coefficient.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub patches: Vec<FrictionPatch>,
}

/// A rectangle of ground, `[x0, x1]` by `[z0, z1]`, with its own friction coefficient.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FrictionPatch {
    /// Its extent along x (m): [from, to].
    pub x: [f64; 2],
    /// Its extent along z (m): [from, to].
    pub z: [f64; 2],
    /// Its coefficient.
    pub coefficient: f64,
}

/// The medium a creature is in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "kind", deny_unknown_fields)]
pub enum Medium {
    /// Air: ground and gravity, no resistance.
    #[default]
    Air,
    /// Water: no ground, no gravity; every face of every part feels a viscous resistance
    /// −k·A·(v·n)·n, A the face's area, n its outward normal, v its velocity.
    Water {
        /// k, in N·s/m³ (newtons per square metre of face per metre per second).
        viscosity: f64,
    },
}

impl Medium {
    /// Whether the medium is air.
    pub fn is_air(&self) -> bool {
        matches!(self, Medium::Air)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_empty_world_table_is_the_flat_world_and_every_part_reads() {
        let flat: WorldSpec = toml::from_str("").unwrap();
        assert!(flat.is_flat());
        let world: WorldSpec = toml::from_str(
            "slope = { degrees = 10 }\n\
             steps = { height = 0.1, depth = 0.5, count = 3, way = \"down\" }\n\
             rough = { amplitude = 0.05, wavelength = 1.0, seed = 7 }\n\
             obstacles = { size = [0.2, 0.3, 2.0], count = 4, raised = 0.5 }\n\
             objects = [{ shape = \"box\", size = 0.5, mass = 20, position = [3, 0.25, 0], velocity = [-2, 0, 0] }]\n\
             friction = { coefficient = 0.8, patches = [{ x = [1, 2], z = [-1, 1], coefficient = 0.1 }] }\n\
             medium = { kind = \"water\", viscosity = 40 }\n",
        )
        .unwrap();
        assert!(!world.is_flat());
        assert_eq!(world.steps.as_ref().unwrap().way, StepsWay::Down);
        assert_eq!(world.steps.as_ref().unwrap().start, 1.0);
        assert_eq!(world.medium, Medium::Water { viscosity: 40.0 });
        let back: WorldSpec = toml::from_str(&toml::to_string(&world).unwrap()).unwrap();
        assert_eq!(back, world);
        assert!(toml::from_str::<WorldSpec>("hills = 3").is_err());
    }
}
