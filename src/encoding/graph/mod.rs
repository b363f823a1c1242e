//! Sims' (1994) directed-graph encoding as Chaumont, Egli & Adami (2007, sections 3.1, 4.1,
//! 5.5–5.7) reimplemented it.
//!
//! A genome is a list of **nodes** (node 0 is the root) and a list of **global neurons**. A
//! node describes one part: its size, the joint that attaches it to its parent (any
//! [`JointKind`], with limits per degree of freedom), a recursive limit, its **local neurons**
//! and its **connections**. A connection says where a child part grows: on which face of the
//! parent and where on it, turned how, scaled by how much, whether it is reflected and whether
//! it applies only at the end of a recursive chain (terminal-only).
//!
//! Development ([`GraphGenome::creature`]) walks the graph depth-first from the root: every
//! visit of a node makes a part, a node appearing on the path from the root at most its
//! recursive limit times, and development stops making parts at `max_parts` (Chaumont's
//! n_max). Every part gets its own copy of its node's local neurons; global neurons exist
//! once. Unconnected neurons are kept (Chaumont section 5.6: no garbage collection of the
//! controller).
//!
//! The operators are Sims': node and connection parameters mutate, a new random node is added
//! (initially unconnected), connections are added, removed and redirected, unreachable nodes
//! are removed; crossover lines the two parents' nodes up and switches from one to the other at
//! a crossover point; grafting redirects a connection of the first parent to a node of the
//! second, copying the nodes reachable from it. For the throwing tasks ([`Purpose::Throwing`])
//! the root node is the arm and always comes from the first parent (Chaumont's Figures 5 and
//! 6). A newborn whose parts interpenetrate is made again (Chaumont section 5.5), at most
//! `regenerate_tries` times.

use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};
use rand::RngExt;
use serde::{Deserialize, Serialize};

use super::draw::clamp_rate;
use super::{DevelopError, Genome, Purpose, Rng};
use crate::creature::{
    Actuator, Creature, DEFAULT_DENSITY, Face, Joint, JointKind, Link, Neuron, NeuronFunction,
    Part, Problem, Role, Sensor, Severity,
};

mod develop;
mod mirror;
mod operators;
mod text;

pub use develop::face_frame;
use operators::param_range;
pub use text::{CHAMPION_KEY, without_champion};
use text::{GenomeShape, kind_name};

/// Random values are rounded to this many parts of a unit, so that genomes stay readable.
const GRID: f64 = 1000.0;

/// Range of a node's part size along each axis (metres), before a connection's scale.
pub const SIZE_RANGE: (f64, f64) = (0.1, 1.0);
/// Range of a part's size along each axis (metres) after the scales along its path.
pub const PART_SIZE_RANGE: (f64, f64) = (0.05, 2.0);
/// Range of a connection's scale factor.
pub const SCALE_RANGE: (f64, f64) = (0.5, 1.5);
/// Range of a connection's two bend angles (radians): a child leaves its face within 45° of
/// the face's normal in each of two directions (the range's ends on the 0.001 grid).
pub const BEND_RANGE: (f64, f64) = (-0.785, 0.785);
/// Range of a connection's roll about the child's length (radians, ±90°: a box is the same
/// after a half turn).
pub const ROLL_RANGE: (f64, f64) = (-1.571, 1.571);
/// Range of a joint's lower limit per degree of freedom (radians, −90° to −5.7°); the upper
/// limit is in the mirror range.
pub const LOWER_LIMIT_RANGE: (f64, f64) = (-1.571, -0.1);
/// Range of a link's weight.
pub const WEIGHT_RANGE: (f64, f64) = (-2.0, 2.0);
/// Range of a neuron's bias, and of the threshold and constant parameters.
pub const BIAS_RANGE: (f64, f64) = (-1.0, 1.0);
/// Range of a memory neuron's delay (steps).
pub const DELAY_RANGE: (f64, f64) = (1.0, 30.0);

/// The limits of the graph genome: every operator keeps a genome within them. They are part
/// of a run's configuration (`config.toml`); unknown keys are refused.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct GraphLimits {
    /// Most nodes (genes): Chaumont's n_max = 20 (section 5.5). At least 1.
    pub max_nodes: usize,
    /// Most parts development makes; the rest of the graph is not built (a warning). 20, as
    /// the task's n_max. At least 1.
    pub max_parts: usize,
    /// Most connections leaving one node (4).
    pub max_connections: usize,
    /// Highest recursive limit of a node (4): how many times a node may appear on one path
    /// from the root. At least 1.
    pub max_recursion: u32,
    /// Most local neurons per node (4).
    pub max_local_neurons: usize,
    /// Most global neurons (4).
    pub max_global_neurons: usize,
    /// Most inputs per neuron (3: a, b, c of Chaumont's Table I).
    pub max_inputs: usize,
    /// How many times an operator makes a newborn again while its parts interpenetrate
    /// (Chaumont section 5.5); the last try is kept (and evaluated as `self-intersecting`).
    /// At least 1.
    pub regenerate_tries: usize,
    /// The joint kinds of new nodes and joint mutations: `one-axis` (default, Chaumont 5.1)
    /// or `sims` (all seven). A genome that holds other kinds still loads and keeps them.
    pub joint_kinds: JointSet,
    /// A creature with more neurons than this (sensors and actuators included, as the run
    /// store's `neurons` column counts them) is invalid. Absent (the default): no limit. Not
    /// written when absent, so that a run's stored configuration stays as it was.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_neurons: Option<usize>,
    /// A creature whose body has a longer unbranched row of parts than this
    /// ([`Creature::longest_chain`](crate::creature::Creature::longest_chain); Hornby &
    /// Pollack's bars in a row) is invalid. Absent (the default): no limit. Not written when
    /// absent.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_chain: Option<usize>,
    /// What the creatures are for: set from the task when a run is assembled, never written.
    #[serde(skip)]
    pub purpose: Purpose,
    /// The projectile newborns carry when the run evolves it (set by
    /// [`Genome::evolve_projectile`]; not a key of the limits). None: no genome carries one.
    #[serde(skip)]
    pub projectile: Option<[f64; 3]>,
}

impl Default for GraphLimits {
    fn default() -> Self {
        GraphLimits {
            max_nodes: 20,
            max_parts: 20,
            max_connections: 4,
            max_recursion: 4,
            max_local_neurons: 4,
            max_global_neurons: 4,
            max_inputs: 3,
            regenerate_tries: 10,
            joint_kinds: JointSet::OneAxis,
            max_neurons: None,
            max_chain: None,
            purpose: Purpose::Locomotion,
            projectile: None,
        }
    }
}

impl GraphLimits {
    fn nodes(&self) -> usize {
        self.max_nodes.max(1)
    }
    fn recursion(&self) -> u32 {
        self.max_recursion.max(1)
    }
    fn throwing(&self) -> bool {
        self.purpose == Purpose::Throwing
    }
}

/// A graph genome: nodes (node 0 is the root) and the creature's global neurons.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GraphGenome {
    /// The nodes; node 0 is the root (the arm, for the throwing tasks).
    pub nodes: Vec<Node>,
    /// Neurons that exist once for the whole creature.
    #[serde(default)]
    pub neurons: Vec<NeuronGene>,
    /// The edge lengths (m) of the projectile it throws, when its run evolves the projectile
    /// (Chaumont et al. 4.1, Figure 3: the projectile is a gene of its own; see
    /// [`Genome::evolve_projectile`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub projectile: Option<[f64; 3]>,
}

/// A node: one part, its joint to its parent, its local neurons and its connections.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Node {
    /// The part's size: length (x), thickness (y), width (z), in metres, in [`SIZE_RANGE`].
    pub size: [f64; 3],
    /// The joint attaching the part to its parent (unused for the root's first instance).
    pub joint: JointKind,
    /// Angle limits (radians) per degree of freedom of `joint`: (lower, upper).
    pub limits: Vec<(f64, f64)>,
    /// How many times the node may appear on one path from the root (1 to `max_recursion`).
    pub recursive_limit: u32,
    /// Local neurons, copied into every part the node makes.
    #[serde(default)]
    pub neurons: Vec<NeuronGene>,
    /// Where children grow.
    #[serde(default)]
    pub connections: Vec<Connection>,
}

/// A connection from a node to a child node.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Connection {
    /// The child node's index.
    pub to: usize,
    /// The face of the parent part the child grows from.
    pub face: Face,
    /// Where on the face, each coordinate in [−1, 1] across the face's two other axes (its
    /// thickness and width for the end faces; see docs/reference/genomes.md).
    pub position: [f64; 2],
    /// The child's turn relative to the face's normal: two bends in [`BEND_RANGE`] and a roll
    /// about its length in [`ROLL_RANGE`] (radians).
    pub orientation: [f64; 3],
    /// The child's scale (in [`SCALE_RANGE`]); scales multiply down the path.
    pub scale: f64,
    /// Whether the child and everything below it are mirrored across the parent's length–
    /// thickness plane (Sims' reflection: symmetric limbs from one node).
    pub reflection: bool,
    /// Whether the connection applies only where its node's recursion ends.
    pub terminal_only: bool,
}

/// A neuron of a node (local) or of the whole creature (global).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NeuronGene {
    /// Its transfer function.
    pub function: NeuronFunction,
    /// The function's parameters: a threshold, a delay, a constant (see [`NeuronFunction`]).
    #[serde(default)]
    pub params: Vec<f64>,
    /// Its bias.
    #[serde(default)]
    pub bias: f64,
    /// Weighted inputs, in order (a, b, c).
    #[serde(default)]
    pub inputs: Vec<Input>,
    /// What it drives, if anything.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub effector: Option<Effector>,
}

/// A neuron's weighted input.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Input {
    /// Where it comes from.
    pub source: Source,
    /// The weight.
    pub weight: f64,
}

/// Where a neuron's input comes from. A source that does not exist in a part (a parent neuron
/// of the root, the angle of a degree of freedom its joint lacks, a neuron a mutation removed)
/// is left out when the part is built.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "from")]
pub enum Source {
    /// A local neuron of the same part.
    Local {
        /// Its index among the node's neurons.
        neuron: usize,
    },
    /// A local neuron of the parent part.
    Parent {
        /// Its index among the parent node's neurons.
        neuron: usize,
    },
    /// A global neuron.
    Global {
        /// Its index among the global neurons.
        neuron: usize,
    },
    /// The touch sensor on one face of the part (of the root part, for a global neuron).
    Touch {
        /// The face.
        face: Face,
    },
    /// The angle of one degree of freedom of the part's joint.
    Angle {
        /// The degree of freedom.
        dof: usize,
    },
}

/// What a neuron drives.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "type")]
pub enum Effector {
    /// One degree of freedom of the part's joint (ignored where the joint lacks it).
    Joint {
        /// The degree of freedom.
        dof: usize,
    },
    /// The catapult's early release of the projectile (global neurons).
    Release,
}

const FACES: [Face; 6] = [
    Face::Front,
    Face::Back,
    Face::Top,
    Face::Bottom,
    Face::Right,
    Face::Left,
];

/// Sims' seven joint kinds.
const SIMS_KINDS: [JointKind; 7] = [
    JointKind::Rigid,
    JointKind::Revolute,
    JointKind::Twist,
    JointKind::Universal,
    JointKind::BendTwist,
    JointKind::TwistBend,
    JointKind::Spherical,
];

/// The kinds with at most one degree of freedom.
const ONE_AXIS_KINDS: [JointKind; 3] = [JointKind::Rigid, JointKind::Revolute, JointKind::Twist];

/// Which joint kinds new nodes and joint mutations draw from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum JointSet {
    /// `rigid`, `revolute` and `twist`: at most one degree of freedom, as Chaumont et al.
    /// built their creatures (section 5.1: "To ensure a maximum of stability, each (ball and
    /// socket) joint has only one degree of freedom"). Evolution turns the multi-axis joints
    /// into exploits of the impulse solver (see docs/results/speed.md).
    #[default]
    OneAxis,
    /// Sims' seven kinds, `universal`, `bend-twist`, `twist-bend` and `spherical` included.
    Sims,
}

impl JointSet {
    /// The kinds this set draws from.
    pub fn kinds(self) -> &'static [JointKind] {
        match self {
            JointSet::OneAxis => &ONE_AXIS_KINDS,
            JointSet::Sims => &SIMS_KINDS,
        }
    }

    /// A random kind of this set.
    fn random(self, rng: &mut Rng) -> JointKind {
        let kinds = self.kinds();
        kinds[rng.random_range(0..kinds.len())]
    }
}

impl GraphGenome {
    /// Checks that the genome is within `limits` and well formed (connections to nodes that
    /// exist, limits per degree of freedom, values in their ranges); `Err` says what is not.
    pub fn check(&self, limits: &GraphLimits) -> Result<(), String> {
        GenomeShape::of(self).check(limits)?;
        super::projectile::check(self.projectile)?;
        let n = self.nodes.len();
        let within = |x: f64, (lo, hi): (f64, f64)| x.is_finite() && x >= lo && x <= hi;
        let check_neuron = |where_: &str, g: &NeuronGene| -> Result<(), String> {
            if !within(g.bias, BIAS_RANGE)
                || g.params.len() > 1
                || g.params
                    .iter()
                    .any(|p| !within(*p, param_range(g.function)))
                || g.inputs.iter().any(|i| !within(i.weight, WEIGHT_RANGE))
            {
                return Err(format!(
                    "{where_} has a bias, parameter or weight out of range (bias and weights in [{}, {}] and [{}, {}], at most one parameter)",
                    BIAS_RANGE.0, BIAS_RANGE.1, WEIGHT_RANGE.0, WEIGHT_RANGE.1
                ));
            }
            Ok(())
        };
        for (k, g) in self.neurons.iter().enumerate() {
            check_neuron(&format!("global neuron {k}"), g)?;
        }
        for (i, node) in self.nodes.iter().enumerate() {
            if !node.size.iter().all(|s| within(*s, SIZE_RANGE)) {
                return Err(format!(
                    "node {i}: sizes must be {} to {} m",
                    SIZE_RANGE.0, SIZE_RANGE.1
                ));
            }
            if node.limits.len() != node.joint.dof() {
                return Err(format!(
                    "node {i}: a {} joint needs {} pairs of limits, not {}",
                    kind_name(node.joint),
                    node.joint.dof(),
                    node.limits.len()
                ));
            }
            if node
                .limits
                .iter()
                .any(|&(lo, hi)| !within(lo, LOWER_LIMIT_RANGE) || !within(-hi, LOWER_LIMIT_RANGE))
            {
                return Err(format!(
                    "node {i}: joint limits must be {} to {} (lower) and {} to {} (upper)",
                    LOWER_LIMIT_RANGE.0,
                    LOWER_LIMIT_RANGE.1,
                    -LOWER_LIMIT_RANGE.1,
                    -LOWER_LIMIT_RANGE.0
                ));
            }
            if node.recursive_limit == 0 || node.recursive_limit > limits.recursion() {
                return Err(format!(
                    "node {i}: recursive limit {}; 1 to {} allowed",
                    node.recursive_limit,
                    limits.recursion()
                ));
            }
            for (k, g) in node.neurons.iter().enumerate() {
                check_neuron(&format!("node {i} neuron {k}"), g)?;
            }
            for (k, c) in node.connections.iter().enumerate() {
                if c.to >= n {
                    return Err(format!(
                        "node {i} connection {k} leads to node {}, which does not exist",
                        c.to
                    ));
                }
                if !c.position.iter().all(|v| within(*v, (-1.0, 1.0)))
                    || !within(c.orientation[0], BEND_RANGE)
                    || !within(c.orientation[1], BEND_RANGE)
                    || !within(c.orientation[2], ROLL_RANGE)
                    || !within(c.scale, SCALE_RANGE)
                {
                    return Err(format!(
                        "node {i} connection {k}: position, orientation or scale out of range"
                    ));
                }
            }
        }
        Ok(())
    }

    /// The nodes reachable from the root, in order of index.
    fn reachable(&self) -> Vec<bool> {
        reachable_from(&self.nodes, 0)
    }
}

/// Which nodes are reachable from `start`.
fn reachable_from(nodes: &[Node], start: usize) -> Vec<bool> {
    let mut seen = vec![false; nodes.len()];
    let mut stack = vec![start];
    while let Some(i) = stack.pop() {
        if i >= nodes.len() || seen[i] {
            continue;
        }
        seen[i] = true;
        stack.extend(nodes[i].connections.iter().map(|c| c.to));
    }
    seen
}

/// The nodes reachable from `start`, `start` first, then in order of index.
fn reachable_list(nodes: &[Node], start: usize) -> Vec<usize> {
    let seen = reachable_from(nodes, start);
    std::iter::once(start)
        .chain((0..nodes.len()).filter(|&i| seen[i] && i != start))
        .collect()
}

/// For each node, whether a path of connections leads from it back to it.
fn on_cycle(nodes: &[Node]) -> Vec<bool> {
    (0..nodes.len())
        .map(|i| {
            nodes[i]
                .connections
                .iter()
                .any(|c| c.to < nodes.len() && reachable_from(nodes, c.to)[i])
        })
        .collect()
}

impl Genome for GraphGenome {
    type Limits = GraphLimits;

    const NAME: &'static str = "graph";

    const DESCRIPTION: &'static str = "Sims' directed graph, as Chaumont et al. reimplemented it";

    /// A run begun before `joint_kinds` existed drew all of Sims' joint kinds.
    const LIMITS_OF_OLDER_RUNS: &'static [(&'static str, &'static str)] =
        &[("joint_kinds", "sims")];

    const TEXT_EXTENSION: &'static str = "json";

    fn adapt_limits(limits: &mut GraphLimits, purpose: Purpose) {
        limits.purpose = purpose;
    }

    fn random(limits: &GraphLimits, rng: &mut Rng) -> Self {
        GraphGenome::regenerate(limits, rng, |rng| {
            Some(GraphGenome::random_once(limits, rng))
        })
        .expect("random always makes a genome")
    }

    fn mutate(&self, limits: &GraphLimits, rate: f64, rng: &mut Rng) -> Self {
        let rate = clamp_rate(rate);
        let mut g =
            GraphGenome::regenerate(limits, rng, |rng| Some(self.mutate_once(limits, rate, rng)))
                .expect("mutation always makes a genome");
        // Last, so that a run whose projectile does not evolve draws as it always has.
        g.projectile = super::projectile::mutated(
            self.projectile,
            limits.projectile,
            rate,
            super::projectile::Step::Gaussian,
            rng,
        );
        g
    }

    fn evolve_projectile(limits: &mut GraphLimits, start: [f64; 3]) {
        limits.projectile = Some(start);
    }

    fn projectile(&self) -> Option<[f64; 3]> {
        self.projectile
    }

    fn crossover(&self, other: &Self, limits: &GraphLimits, rng: &mut Rng) -> Option<Self> {
        GraphGenome::regenerate(limits, rng, |rng| {
            Some(self.crossover_once(other, limits, rng))
        })
    }

    fn graft(&self, other: &Self, limits: &GraphLimits, rng: &mut Rng) -> Option<Self> {
        GraphGenome::regenerate(limits, rng, |rng| self.graft_once(other, limits, rng))
    }

    /// A part of `other` (a node, the nodes it reaches and the connection that places it),
    /// its connection half turned about the parent's up axis, replaces what one of `self`'s
    /// connections grew (see `graph::mirror`); made again while its parts interpenetrate, as
    /// every newborn is.
    fn mirroring_crossover(
        &self,
        other: &Self,
        limits: &GraphLimits,
        rng: &mut Rng,
    ) -> Option<Self> {
        GraphGenome::regenerate(limits, rng, |rng| self.mirror_once(other, limits, rng))
    }

    fn develop(&self, limits: &GraphLimits, _seed: u64) -> Result<Creature, DevelopError> {
        self.check(limits).map_err(DevelopError)?;
        Ok(Creature {
            projectile: self.projectile,
            ..self.creature(limits.max_parts)
        })
    }

    fn to_text(&self) -> String {
        let mut text = serde_json::to_string_pretty(self).unwrap_or_default();
        text.push('\n');
        text
    }

    fn annotated_text(&self, _note: &str) -> String {
        self.to_text() // JSON has no comments
    }

    fn read_text(text: &str, limits: &GraphLimits) -> Result<Self, DevelopError> {
        GraphGenome::from_text(text, limits)
    }

    fn show(&self) -> String {
        self.describe().trim_end().to_string()
    }
}
