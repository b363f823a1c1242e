//! Creatures: plain, serialisable data that every encoding produces and every task consumes.
//!
//! A [`Creature`] is a body — box [`Part`]s joined by [`Joint`]s of zero to three degrees of
//! freedom — and a [`Brain`], a directed graph of [`Neuron`]s joined by weighted [`Link`]s,
//! some of which read sensors and some of which drive actuators. Positions and orientations
//! are in world coordinates: Y is up, the ground is the plane y = 0, lengths are in metres.

mod chain;
mod differences;
mod geometry;
mod ids;
mod regularity;
pub mod repeats;
mod summary;

pub use differences::{PhenotypeDifferences, phenotype_differences};
pub use geometry::{boxes_intersect, interpenetration_messages, overlap_beyond_joints};
pub use ids::{JointId, PartId};
pub use regularity::{
    LENGTH_STEP, MIRROR_AXIS_COSINE, MIRROR_TOLERANCE, Regularity, canonical_description,
    regularity,
};
pub use summary::{Summary, counted};

use nalgebra::{UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};

/// The default density of a part (kg/m³): water's, and MuJoCo's default.
pub const DEFAULT_DENSITY: f64 = 1000.0;

/// The range of every edge (m) of a projectile that evolves with its thrower (the genomes'
/// projectile genes, `evolve_projectile`): Chaumont et al. give none; from a 5 cm tile to a
/// 1 m block, 0.125 kg to 1 t at water's density.
pub const PROJECTILE_EDGE: (f64, f64) = (0.05, 1.0);

/// A creature: body, brain, and what development had to say about it.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Creature {
    /// Box parts; part 0 is the root.
    pub parts: Vec<Part>,
    /// Joints, each joining a parent part to a child part.
    pub joints: Vec<Joint>,
    /// The neural controller.
    pub brain: Brain,
    /// The chemical environment the creature grew in (its controller reads and writes it).
    pub environment: Vec<f64>,
    /// Problems found while building it; a creature with an error-level problem is invalid.
    pub problems: Vec<Problem>,
    /// The edge lengths (m) of the projectile it throws, when it has one of its own: its
    /// genome carries one (a run whose `[task.catapult]` sets `evolve_projectile`) or its
    /// file names one (a grammar's `# projectile: X Y Z` line, `creature.json`'s
    /// `projectile`). The catapult and aim tasks throw this box in place of their
    /// `projectile_size`. None for every other creature.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub projectile: Option<[f64; 3]>,
}

/// A rigid box.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Part {
    /// Edge lengths along the part's own axes: x is its length (the direction it grew in),
    /// y its thickness, z its width.
    pub size: Vector3<f64>,
    /// The centre, in world coordinates.
    pub position: Vector3<f64>,
    /// Rotation from the part's axes to the world's.
    pub orientation: UnitQuaternion<f64>,
    /// Density (kg/m³; [`DEFAULT_DENSITY`] unless an encoding says otherwise).
    pub density: f64,
    /// Whether the part is still growing (made by a maturing command such as `mforward`).
    pub growing: bool,
}

impl Part {
    /// The volume.
    pub fn volume(&self) -> f64 {
        self.size.x * self.size.y * self.size.z
    }

    /// The mass (volume × density).
    pub fn mass(&self) -> f64 {
        self.volume() * self.density
    }

    /// The eight corners in world coordinates.
    pub fn corners(&self) -> [Vector3<f64>; 8] {
        let h = self.size / 2.0;
        let mut out = [Vector3::zeros(); 8];
        for (i, c) in out.iter_mut().enumerate() {
            let local = Vector3::new(
                if i & 1 == 0 { -h.x } else { h.x },
                if i & 2 == 0 { -h.y } else { h.y },
                if i & 4 == 0 { -h.z } else { h.z },
            );
            *c = self.position + self.orientation * local;
        }
        out
    }
}

/// The kinds of joint, by their degrees of freedom (Sims 1994; Chaumont et al. 2007).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum JointKind {
    /// No freedom: the parts are fused.
    Rigid,
    /// One hinge axis perpendicular to the parent's length (Hornby's `revolute`).
    Revolute,
    /// One axis along the length (Hornby's `twist`).
    Twist,
    /// Two perpendicular hinge axes.
    Universal,
    /// A bend axis, then a twist axis.
    BendTwist,
    /// A twist axis, then a bend axis.
    TwistBend,
    /// Three axes.
    Spherical,
}

impl JointKind {
    /// Degrees of freedom.
    pub fn dof(self) -> usize {
        match self {
            JointKind::Rigid => 0,
            JointKind::Revolute | JointKind::Twist => 1,
            JointKind::Universal | JointKind::BendTwist | JointKind::TwistBend => 2,
            JointKind::Spherical => 3,
        }
    }
}

/// A joint between a parent part and a child part.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Joint {
    /// The parent part's index.
    pub parent: usize,
    /// The child part's index.
    pub child: usize,
    /// The kind of joint.
    pub kind: JointKind,
    /// Where the parts are joined, in world coordinates.
    pub anchor: Vector3<f64>,
    /// One unit axis per degree of freedom, in world coordinates.
    pub axes: Vec<Vector3<f64>>,
    /// Angle limits (radians) per degree of freedom: (lower, upper).
    pub limits: Vec<(f64, f64)>,
    /// Strength of the joint's motor (scaled by the simulator, e.g. by cross-section).
    pub strength: f64,
    /// Whether the joint is still growing (made by a maturing command).
    pub growing: bool,
}

/// A neuron's transfer function.
///
/// `x` is the neuron's **bias** plus the weighted sum of its inputs (Σ wᵢ·oᵢ + bias);
/// `a, b, c` are its first three weighted inputs, in link order, with the bias added to `a`
/// (`a` = w₀·o₀ + bias, or the bias alone when the neuron has no input); a missing `b` or `c`
/// takes the value that leaves the result unchanged, given with each function. Functions
/// that ignore their inputs (`constant`, `step-wave`, `saw`) ignore the bias too, and a
/// sensor's output is its reading.
///
/// Every function gives a number for every finite input: sums saturate at ±`f64::MAX`
/// instead of overflowing, the power function has a real fallback for a negative base, and
/// the output is clipped to [−1, 1] — so an overflow to ±∞ becomes ±1 — and any result that is
/// still not a number becomes 0 (a safety net: no function above produces one).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum NeuronFunction {
    /// `x` (Hornby & Pollack; Matos & Arita).
    Linear,
    /// tanh(`x`) (Hornby & Pollack; Matos & Arita).
    Sigmoid,
    /// sin(phase), the phase advancing at a frequency of π(1 + clamp(`x`, −1, 1)), i.e. the
    /// weighted input sum mapped into [0, 2π] rad/s (Matos & Arita section 2).
    Oscillator,
    /// Chaumont's `sumT`: `a + b` if it is at least the threshold `params[0]` (default 0),
    /// else 0 (missing `b`: 0).
    Threshold,
    /// Chaumont's `div`: 1 if `b` ≤ ε (1e-6), else `a / b` (missing `b`: 1).
    Divide,
    /// Chaumont's `mem`: `a` as it was `params[0]` steps ago (default 1, at most 10,000).
    Memory,
    /// Chaumont's `wav`: `b · sin(a · t + c)`, t the simulated time (missing `b`: 1, `c`: 0).
    Wave,
    /// Chaumont's `cst`: the constant V = `params[0]` (0 when absent), whatever the inputs;
    /// also Walking with Dinosaurs' "constant value node".
    Constant,
    /// WWD `sum`: `a + b` (missing `b`: 0).
    Sum,
    /// WWD `product`: `a · b` (missing `b`: 1).
    Product,
    /// WWD `divide`: `a / b`, 0 when `b` is 0 (missing `b`: 1).
    Quotient,
    /// WWD `sum threshold`: 1 if `a + b > c`, else 0 (missing `b`, `c`: 0).
    SumGreater,
    /// WWD `greater than`: 1 if `a > b`, else 0 (missing `b`: 0).
    GreaterThan,
    /// WWD `sign of`: the sign of `a` (0 for 0).
    Sign,
    /// WWD `minimum` of `a` and the `b, c` present.
    Min,
    /// WWD `maximum` of `a` and the `b, c` present.
    Max,
    /// WWD `absolute value` of `a`.
    Abs,
    /// WWD `if`: `a` if `b` ≠ 0, else 0 (missing `b`: 1).
    If,
    /// WWD `interpolate`: the mean of `a` and the `b, c` present.
    Interpolate,
    /// WWD `sine` of `a`.
    Sin,
    /// WWD `cosine` of `a`.
    Cos,
    /// WWD `inverse tangent` of `a`.
    Atan,
    /// WWD `logarithmic`: ln `a` if `a` > 0, else `a`.
    Log,
    /// WWD `exponential`: `a` to the power `b` (missing `b`: 1). Where `a^b` is not a real
    /// number — a negative `a` with a non-integer `b` — it is −|`a`|^`b` (the signed power: the
    /// real root for odd roots such as `b` = 1/3, and continuous in `a`); 0 to a negative
    /// power is +∞, so 1 after clipping.
    Power,
    /// WWD `sigmoidal`: 1 / (1 + e^(−`a`)).
    Logistic,
    /// WWD `wave`: sin(steps · 2π / 360), steps counting this neuron's updates.
    StepWave,
    /// WWD `saw`: sin(steps · 2π / 4).
    Saw,
}

impl NeuronFunction {
    /// Every neuron function, in the order of the enum.
    pub const ALL: [NeuronFunction; 27] = [
        NeuronFunction::Linear,
        NeuronFunction::Sigmoid,
        NeuronFunction::Oscillator,
        NeuronFunction::Threshold,
        NeuronFunction::Divide,
        NeuronFunction::Memory,
        NeuronFunction::Wave,
        NeuronFunction::Constant,
        NeuronFunction::Sum,
        NeuronFunction::Product,
        NeuronFunction::Quotient,
        NeuronFunction::SumGreater,
        NeuronFunction::GreaterThan,
        NeuronFunction::Sign,
        NeuronFunction::Min,
        NeuronFunction::Max,
        NeuronFunction::Abs,
        NeuronFunction::If,
        NeuronFunction::Interpolate,
        NeuronFunction::Sin,
        NeuronFunction::Cos,
        NeuronFunction::Atan,
        NeuronFunction::Log,
        NeuronFunction::Power,
        NeuronFunction::Logistic,
        NeuronFunction::StepWave,
        NeuronFunction::Saw,
    ];

    /// The functions the edge encoding's `setfunc(n)` chooses from, by n (rounded, modulo
    /// their number): Hornby & Pollack's and Matos & Arita's three.
    pub const SETFUNC: [NeuronFunction; 3] = [
        NeuronFunction::Linear,
        NeuronFunction::Sigmoid,
        NeuronFunction::Oscillator,
    ];
}

/// What a neuron is for.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "kind")]
pub enum Role {
    /// An internal neuron.
    Hidden,
    /// Reads a sensor.
    Sensor {
        /// Which sensor.
        sensor: Sensor,
    },
    /// Drives an actuator.
    Actuator {
        /// Which actuator.
        actuator: Actuator,
    },
}

/// A sensor a neuron reads.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "type")]
pub enum Sensor {
    /// Contact of a part with anything: 1 touching, −1 not. With a `face`, only contacts on
    /// that face count (Chaumont et al.'s Table I: "the block's face the sensor is attached
    /// to"); without, any face does (the turtle's `touch`, Hornby & Pollack's per-part sensor).
    Touch {
        /// The part.
        part: usize,
        /// The face, if the sensor is on one face only.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        face: Option<Face>,
    },
    /// A joint's angle, scaled to [−1, 1] over its limits.
    Angle {
        /// The joint.
        joint: usize,
        /// Which degree of freedom.
        dof: usize,
    },
    /// An environment slot's concentration.
    Chemical {
        /// The slot.
        slot: usize,
    },
    /// The direction to the task's target, when it has one.
    Target,
}

/// A face of a box part, named in the part's own axes: x is its length (the direction it
/// grew in), y its thickness (the turtle's up), z its width (the turtle's right).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Face {
    /// +x: the far end.
    Front,
    /// −x: the near end.
    Back,
    /// +y.
    Top,
    /// −y.
    Bottom,
    /// +z.
    Right,
    /// −z.
    Left,
}

impl Face {
    /// The face whose outward normal is closest to `normal` (in the part's axes).
    pub fn facing(normal: &Vector3<f64>) -> Face {
        let k = normal.iamax();
        match (k, normal[k] >= 0.0) {
            (0, true) => Face::Front,
            (0, false) => Face::Back,
            (1, true) => Face::Top,
            (1, false) => Face::Bottom,
            (_, true) => Face::Right,
            (_, false) => Face::Left,
        }
    }
}

/// An actuator a neuron drives.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "type")]
pub enum Actuator {
    /// A joint's motor on one degree of freedom.
    Joint {
        /// The joint.
        joint: usize,
        /// Which degree of freedom.
        dof: usize,
    },
    /// Writes an environment slot.
    Secrete {
        /// The slot.
        slot: usize,
    },
    /// The catapult task's early-release signal.
    Release,
}

/// A neuron.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Neuron {
    /// Its transfer function.
    pub function: NeuronFunction,
    /// The function's parameters (a threshold, a delay, a constant, ...), empty when it has
    /// none.
    #[serde(default)]
    pub params: Vec<f64>,
    /// Added to the weighted input sum `x` and to the first input `a` (see
    /// [`NeuronFunction`]); 0 by default.
    #[serde(default)]
    pub bias: f64,
    /// What it is for.
    pub role: Role,
    /// The part it belongs to (Sims' local neurons), or `None` for the whole creature.
    pub part: Option<usize>,
}

/// A weighted connection from one neuron's output to another's input.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Link {
    /// The source neuron.
    pub from: usize,
    /// The destination neuron.
    pub to: usize,
    /// The weight.
    pub weight: f64,
}

/// The neural controller.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Brain {
    /// The neurons.
    pub neurons: Vec<Neuron>,
    /// The links.
    pub links: Vec<Link>,
}

/// How serious a [`Problem`] is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Severity {
    /// Worth knowing; the creature can still be evaluated.
    Warning,
    /// The creature is invalid: the evaluator will not simulate it.
    Error,
}

/// Something development found wrong with the creature.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Problem {
    /// How serious (a picture's warning about what physics refuses ends in
    /// [`Problem::PICTURE_ONLY`]).
    pub severity: Severity,
    /// In words.
    pub message: String,
    /// The module it concerns, written readably, if any.
    pub module: Option<String>,
    /// The developmental time, if any.
    pub t: Option<f64>,
}

impl Problem {
    /// The end of a warning about what is fine in a picture and an error where physics needs
    /// the creature (parts that overlap, a body in pieces).
    pub const PICTURE_ONLY: &str = " (fine for a picture; an error for eval and evolve)";

    /// Whether this is a picture's warning about what physics refuses.
    pub fn is_picture_only(&self) -> bool {
        self.message.ends_with(Self::PICTURE_ONLY)
    }
}

impl std::fmt::Display for Problem {
    /// The problem as `grow` and `eval` print it: `warning: MESSAGE [MODULE] at t = T`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let level = match self.severity {
            Severity::Warning => "warning",
            Severity::Error => "error",
        };
        write!(f, "{level}: {}", self.message)?;
        if let Some(module) = &self.module {
            write!(f, " [{module}]")?;
        }
        if let Some(t) = self.t {
            write!(f, " at t = {t}")?;
        }
        Ok(())
    }
}

impl Creature {
    /// Checks that the creature is well formed: finite, positive sizes; finite poses and
    /// densities; finite weights, neuron parameters and biases; joints, links, sensors and
    /// actuators that point at parts, joints and neurons that exist; limits in order.
    /// Creatures read from files must pass this before anything uses them.
    pub fn check_consistency(&self) -> Result<(), String> {
        let finite3 = |v: &Vector3<f64>| v.iter().all(|x| x.is_finite());
        for (i, p) in self.parts.iter().enumerate() {
            if !p.size.iter().all(|x| x.is_finite() && *x > 0.0) {
                return Err(format!(
                    "part {i} has a size that is not positive and finite"
                ));
            }
            if !finite3(&p.position)
                || !p.orientation.coords.iter().all(|x| x.is_finite())
                || (p.orientation.coords.norm() - 1.0).abs() > 1e-6
            {
                return Err(format!(
                    "part {i} has a position that is not finite or an orientation that is not a unit quaternion"
                ));
            }
            if !(p.density.is_finite() && p.density > 0.0) {
                return Err(format!(
                    "part {i} has a density that is not positive and finite"
                ));
            }
        }
        let n = self.parts.len();
        for (j, joint) in self.joints.iter().enumerate() {
            if joint.parent >= n || joint.child >= n || joint.parent == joint.child {
                return Err(format!("joint {j} does not join two of the {n} parts"));
            }
            if joint.axes.len() < joint.kind.dof() || joint.limits.len() < joint.kind.dof() {
                return Err(format!(
                    "joint {j} needs an axis and limits per degree of freedom"
                ));
            }
            if !finite3(&joint.anchor)
                || joint.axes.iter().any(|a| !finite3(a) || a.norm() < 1e-9)
                || joint
                    .limits
                    .iter()
                    .any(|(lo, hi)| !(lo.is_finite() && hi.is_finite() && lo <= hi))
                || !(joint.strength.is_finite() && joint.strength >= 0.0)
            {
                return Err(format!(
                    "joint {j} has a non-finite anchor, axis, limit or strength, or limits out of order"
                ));
            }
        }
        let neurons = self.brain.neurons.len();
        for (k, link) in self.brain.links.iter().enumerate() {
            if link.from >= neurons || link.to >= neurons || !link.weight.is_finite() {
                return Err(format!(
                    "link {k} does not join two of the {neurons} neurons with a finite weight"
                ));
            }
        }
        for (k, neuron) in self.brain.neurons.iter().enumerate() {
            if neuron.params.iter().any(|p| !p.is_finite()) || !neuron.bias.is_finite() {
                return Err(format!("neuron {k} has a non-finite parameter or bias"));
            }
            if neuron.part.is_some_and(|p| p >= n) {
                return Err(format!(
                    "neuron {k} belongs to a part the creature does not have"
                ));
            }
            let joint_ok = |joint: usize, dof: usize| {
                self.joints.get(joint).is_some_and(|j| dof < j.kind.dof())
            };
            let ok = match neuron.role {
                Role::Hidden => true,
                Role::Sensor { sensor } => match sensor {
                    Sensor::Touch { part, .. } => part < n,
                    Sensor::Angle { joint, dof } => joint_ok(joint, dof),
                    Sensor::Chemical { slot } => slot < self.environment.len(),
                    Sensor::Target => true,
                },
                Role::Actuator { actuator } => match actuator {
                    Actuator::Joint { joint, dof } => joint_ok(joint, dof),
                    Actuator::Secrete { slot } => slot < self.environment.len(),
                    Actuator::Release => true,
                },
            };
            if !ok {
                return Err(format!(
                    "neuron {k} senses or drives something the creature does not have"
                ));
            }
        }
        if self.environment.iter().any(|v| !v.is_finite()) {
            return Err("the environment holds a value that is not finite".to_string());
        }
        if let Some(size) = self.projectile
            && !size.iter().all(|x| x.is_finite() && *x > 0.0)
        {
            return Err("its projectile has a size that is not positive and finite".to_string());
        }
        Ok(())
    }

    /// Checks a creature read from a file before anything uses it: at most `max_parts` parts
    /// (the limit development obeys; a file may come from anywhere), then
    /// [`check_consistency`](Self::check_consistency).
    pub fn check_file(&self, max_parts: usize) -> Result<(), String> {
        if self.parts.len() > max_parts {
            return Err(format!(
                "{} parts, more than the {max_parts} allowed (--max-parts)",
                self.parts.len()
            ));
        }
        self.check_consistency()
    }

    /// The number of neurons of its brain, sensors and actuators included: the count the run
    /// store keeps in its `neurons` column and the one `[limits] max_neurons` bounds.
    pub fn neuron_count(&self) -> usize {
        self.brain.neurons.len()
    }

    /// Whether the evaluator may simulate it (no error-level problem, at least one part).
    pub fn is_valid(&self) -> bool {
        !self.parts.is_empty() && self.problems.iter().all(|p| p.severity != Severity::Error)
    }

    /// Total mass of the parts.
    pub fn mass(&self) -> f64 {
        // Folded from +0.0: an empty sum of f64 is −0.0, which prints as "-0.0000".
        self.parts
            .iter()
            .fold(0.0, |total, part| total + part.mass())
    }

    /// The axis-aligned bounding box of all parts: (min, max); zeros for no parts.
    pub fn bounding_box(&self) -> (Vector3<f64>, Vector3<f64>) {
        let mut corners = self.parts.iter().flat_map(|p| p.corners());
        let Some(first) = corners.next() else {
            return (Vector3::zeros(), Vector3::zeros());
        };
        corners.fold((first, first), |(lo, hi), c| (lo.inf(&c), hi.sup(&c)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The variant names serde's derive knows, caught by a deserializer that only records
    /// them: the enum itself, not a hand-written list.
    fn serde_variants() -> &'static [&'static str] {
        use serde::de::{self, Deserializer, Visitor};
        struct Catch(Option<&'static [&'static str]>);
        impl<'de> Deserializer<'de> for &mut Catch {
            type Error = de::value::Error;
            fn deserialize_any<V: Visitor<'de>>(self, _: V) -> Result<V::Value, Self::Error> {
                Err(de::Error::custom("only enums"))
            }
            fn deserialize_enum<V: Visitor<'de>>(
                self,
                _: &'static str,
                variants: &'static [&'static str],
                _: V,
            ) -> Result<V::Value, Self::Error> {
                self.0 = Some(variants);
                Err(de::Error::custom("caught"))
            }
            serde::forward_to_deserialize_any! {
                bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes
                byte_buf option unit unit_struct newtype_struct seq tuple tuple_struct map
                struct identifier ignored_any
            }
        }
        let mut catch = Catch(None);
        let _ = NeuronFunction::deserialize(&mut catch);
        catch.0.expect("NeuronFunction deserialises as an enum")
    }

    #[test]
    fn all_lists_every_neuron_function_in_order() {
        let names: Vec<String> = NeuronFunction::ALL
            .iter()
            .map(|f| {
                serde_json::to_value(f)
                    .unwrap()
                    .as_str()
                    .unwrap()
                    .to_string()
            })
            .collect();
        assert_eq!(names, serde_variants());
        assert!(
            NeuronFunction::SETFUNC
                .iter()
                .all(|f| NeuronFunction::ALL.contains(f))
        );
    }

    #[test]
    fn a_non_finite_bias_is_rejected_and_a_missing_one_is_zero() {
        let json = r#"{"function":"linear","role":{"kind":"hidden"},"part":null}"#;
        let neuron: Neuron = serde_json::from_str(json).unwrap();
        assert_eq!(neuron.bias, 0.0);
        assert!(neuron.params.is_empty());
        let mut c = Creature {
            brain: Brain {
                neurons: vec![neuron],
                links: vec![],
            },
            ..Creature::default()
        };
        assert_eq!(c.check_consistency(), Ok(()));
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            c.brain.neurons[0].bias = bad;
            let err = c.check_consistency().unwrap_err();
            assert!(err.contains("neuron 0") && err.contains("bias"), "{err}");
        }
    }

    #[test]
    fn a_problem_is_written_with_its_level_module_and_time() {
        let problem = Problem {
            severity: Severity::Warning,
            message: "a joint without axes".into(),
            module: Some("revolute1".into()),
            t: Some(0.5),
        };
        assert_eq!(
            problem.to_string(),
            "warning: a joint without axes [revolute1] at t = 0.5"
        );
        let bare = Problem {
            severity: Severity::Error,
            module: None,
            t: None,
            ..problem
        };
        assert_eq!(bare.to_string(), "error: a joint without axes");
    }
}
