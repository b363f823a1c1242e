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
use rand_distr::{Distribution, StandardNormal};
use serde::{Deserialize, Serialize};

use super::{DevelopError, Genome, Purpose, Rng};
use crate::creature::{
    Actuator, Creature, DEFAULT_DENSITY, Face, Joint, JointKind, Link, Neuron, NeuronFunction,
    Part, Problem, Role, Sensor, Severity,
};

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
    /// What the creatures are for: set from the task when a run is assembled, never written.
    #[serde(skip)]
    pub purpose: Purpose,
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
            purpose: Purpose::Locomotion,
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
    /// thickness and width for the end faces; see the README).
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

// ---------------------------------------------------------------------------------------------
// Random values.

fn round(x: f64) -> f64 {
    (x * GRID).round() / GRID
}

fn uniform(rng: &mut Rng, (lo, hi): (f64, f64)) -> f64 {
    round(lo + rng.random::<f64>() * (hi - lo)).clamp(lo, hi)
}

/// Sims' scalar mutation: a Gaussian step relative to the value's magnitude (at least a tenth
/// of the range), kept in range and on the grid.
fn perturb(x: f64, (lo, hi): (f64, f64), rng: &mut Rng) -> f64 {
    let z: f64 = StandardNormal.sample(rng);
    let scale = x.abs().max(0.1 * (hi - lo));
    round((x + 0.25 * scale * z).clamp(lo, hi)).clamp(lo, hi)
}

fn clamp_rate(rate: f64) -> f64 {
    if rate.is_nan() {
        0.0
    } else {
        rate.clamp(0.0, 1.0)
    }
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
    /// into exploits of the impulse solver (see the README's *Speed and fidelity*).
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

/// Chaumont et al.'s Table I functions (besides sensors and effectors).
const CHAUMONT: [NeuronFunction; 7] = [
    NeuronFunction::Threshold,
    NeuronFunction::Divide,
    NeuronFunction::Memory,
    NeuronFunction::Wave,
    NeuronFunction::Product,
    NeuronFunction::Sum,
    NeuronFunction::Constant,
];

/// A random function: half the time one of Chaumont's Table I, else any of the brain's.
fn random_function(rng: &mut Rng) -> NeuronFunction {
    if rng.random_bool(0.5) {
        CHAUMONT[rng.random_range(0..CHAUMONT.len())]
    } else {
        NeuronFunction::ALL[rng.random_range(0..NeuronFunction::ALL.len())]
    }
}

/// Random parameters for `function`: the threshold, delay or constant it reads.
fn random_params(function: NeuronFunction, rng: &mut Rng) -> Vec<f64> {
    match function {
        NeuronFunction::Threshold | NeuronFunction::Constant => vec![uniform(rng, BIAS_RANGE)],
        NeuronFunction::Memory => vec![uniform(rng, DELAY_RANGE).round()],
        _ => Vec::new(),
    }
}

fn param_range(function: NeuronFunction) -> (f64, f64) {
    if function == NeuronFunction::Memory {
        DELAY_RANGE
    } else {
        BIAS_RANGE
    }
}

fn random_limits(dof: usize, rng: &mut Rng) -> Vec<(f64, f64)> {
    (0..dof)
        .map(|_| {
            let lo = uniform(rng, LOWER_LIMIT_RANGE);
            let hi = -uniform(rng, LOWER_LIMIT_RANGE);
            (lo, hi)
        })
        .collect()
}

/// What a neuron may read: its node's neurons, the parent's, the globals, its part's faces
/// and its joint's angles (locals); the globals and the root part's faces (globals).
#[derive(Clone, Copy)]
struct Context {
    /// Local neurons of the node (None for a global neuron).
    locals: Option<usize>,
    /// Neurons a parent node may have (the limit).
    parents: usize,
    globals: usize,
    /// Degrees of freedom of the node's joint.
    dof: usize,
}

fn random_source(ctx: Context, rng: &mut Rng) -> Source {
    source_of_kind(ctx, rng.random_range(0..5), rng)
}

/// The source of kind `k` (0 local, 1 parent, 2 global, 3 touch, 4 angle), or a touch sensor
/// when that kind is not available.
fn source_of_kind(ctx: Context, k: u32, rng: &mut Rng) -> Source {
    let touch = |rng: &mut Rng| Source::Touch {
        face: FACES[rng.random_range(0..6)],
    };
    match (k, ctx.locals) {
        (0, Some(n)) if n > 0 => Source::Local {
            neuron: rng.random_range(0..n),
        },
        (1, Some(_)) if ctx.parents > 0 => Source::Parent {
            neuron: rng.random_range(0..ctx.parents),
        },
        (2, _) if ctx.globals > 0 => Source::Global {
            neuron: rng.random_range(0..ctx.globals),
        },
        (4, Some(_)) if ctx.dof > 0 => Source::Angle {
            dof: rng.random_range(0..ctx.dof),
        },
        _ => touch(rng),
    }
}

fn random_input(ctx: Context, rng: &mut Rng) -> Input {
    Input {
        source: random_source(ctx, rng),
        weight: uniform(rng, WEIGHT_RANGE),
    }
}

fn random_neuron(
    ctx: Context,
    effector: Option<Effector>,
    limits: &GraphLimits,
    rng: &mut Rng,
) -> NeuronGene {
    let function = random_function(rng);
    let inputs = if limits.max_inputs == 0 {
        0
    } else {
        rng.random_range(1..=limits.max_inputs)
    };
    NeuronGene {
        function,
        params: random_params(function, rng),
        bias: uniform(rng, BIAS_RANGE),
        inputs: (0..inputs).map(|_| random_input(ctx, rng)).collect(),
        effector,
    }
}

fn random_connection(nodes: usize, limits: &GraphLimits, root: bool, rng: &mut Rng) -> Connection {
    let mut face = FACES[rng.random_range(0..6)];
    if root && limits.throwing() && face == Face::Back {
        face = Face::Front; // the projectile is held at the arm's back face
    }
    Connection {
        to: rng.random_range(0..nodes.max(1)),
        face,
        position: [uniform(rng, (-1.0, 1.0)), uniform(rng, (-1.0, 1.0))],
        orientation: [
            uniform(rng, BEND_RANGE),
            uniform(rng, BEND_RANGE),
            uniform(rng, ROLL_RANGE),
        ],
        scale: uniform(rng, SCALE_RANGE),
        reflection: rng.random_bool(0.3),
        terminal_only: rng.random_bool(0.1),
    }
}

/// A random node with no connections: one effector neuron per degree of freedom (as room
/// allows), perhaps a hidden neuron.
fn random_node(globals: usize, limits: &GraphLimits, rng: &mut Rng) -> Node {
    let joint = limits.joint_kinds.random(rng);
    let dof = joint.dof();
    let recursive_limit = if rng.random_bool(0.5) {
        1
    } else {
        rng.random_range(1..=limits.recursion())
    };
    let count = (dof + usize::from(rng.random_bool(0.5))).min(limits.max_local_neurons);
    let ctx = Context {
        locals: Some(count),
        parents: limits.max_local_neurons,
        globals,
        dof,
    };
    let neurons = (0..count)
        .map(|k| {
            let effector = (k < dof).then_some(Effector::Joint { dof: k });
            random_neuron(ctx, effector, limits, rng)
        })
        .collect();
    Node {
        size: [
            uniform(rng, SIZE_RANGE),
            uniform(rng, SIZE_RANGE),
            uniform(rng, SIZE_RANGE),
        ],
        joint,
        limits: random_limits(dof, rng),
        recursive_limit,
        neurons,
        connections: Vec::new(),
    }
}

fn random_global(globals: usize, limits: &GraphLimits, rng: &mut Rng) -> NeuronGene {
    let ctx = Context {
        locals: None,
        parents: 0,
        globals,
        dof: 0,
    };
    let effector = (limits.throwing() && rng.random_bool(0.5)).then_some(Effector::Release);
    random_neuron(ctx, effector, limits, rng)
}

// ---------------------------------------------------------------------------------------------
// Mutation.

fn mutate_neuron(n: &mut NeuronGene, ctx: Context, limits: &GraphLimits, rate: f64, rng: &mut Rng) {
    if rng.random_bool(rate) {
        n.function = random_function(rng);
        n.params = random_params(n.function, rng);
    }
    let range = param_range(n.function);
    for p in &mut n.params {
        if rng.random_bool(rate) {
            *p = perturb(*p, range, rng);
            if n.function == NeuronFunction::Memory {
                *p = p.round().clamp(DELAY_RANGE.0, DELAY_RANGE.1);
            }
        }
    }
    if rng.random_bool(rate) {
        n.bias = perturb(n.bias, BIAS_RANGE, rng);
    }
    for input in &mut n.inputs {
        if rng.random_bool(rate) {
            input.weight = perturb(input.weight, WEIGHT_RANGE, rng);
        }
        if rng.random_bool(rate) {
            input.source = random_source(ctx, rng);
        }
    }
    if !n.inputs.is_empty() && rng.random_bool(rate) {
        let k = rng.random_range(0..n.inputs.len());
        n.inputs.remove(k);
    }
    if n.inputs.len() < limits.max_inputs && rng.random_bool(rate) {
        n.inputs.push(random_input(ctx, rng));
    }
    if rng.random_bool(rate) {
        n.effector = match (n.effector, ctx.locals) {
            (Some(_), _) => None,
            (None, Some(_)) if ctx.dof > 0 => Some(Effector::Joint {
                dof: rng.random_range(0..ctx.dof),
            }),
            (None, None) if limits.throwing() => Some(Effector::Release),
            (None, _) => None,
        };
    }
}

fn mutate_neurons(
    neurons: &mut Vec<NeuronGene>,
    mut ctx: Context,
    max: usize,
    limits: &GraphLimits,
    rate: f64,
    rng: &mut Rng,
) {
    for n in neurons.iter_mut() {
        mutate_neuron(n, ctx, limits, rate, rng);
    }
    if !neurons.is_empty() && rng.random_bool(rate) {
        let k = rng.random_range(0..neurons.len());
        neurons.remove(k);
    }
    if neurons.len() < max && rng.random_bool(rate) {
        if ctx.locals.is_some() {
            ctx.locals = Some(neurons.len() + 1);
        } else {
            ctx.globals = neurons.len() + 1;
        }
        neurons.push(random_neuron(ctx, None, limits, rng));
    }
}

fn mutate_connection(
    c: &mut Connection,
    nodes: usize,
    root: bool,
    limits: &GraphLimits,
    rate: f64,
    rng: &mut Rng,
) {
    if rng.random_bool(rate) {
        c.to = rng.random_range(0..nodes);
    }
    if rng.random_bool(rate) {
        c.face = FACES[rng.random_range(0..6)];
    }
    if root && limits.throwing() && c.face == Face::Back {
        c.face = Face::Front;
    }
    for v in &mut c.position {
        if rng.random_bool(rate) {
            *v = perturb(*v, (-1.0, 1.0), rng);
        }
    }
    for (k, v) in c.orientation.iter_mut().enumerate() {
        if rng.random_bool(rate) {
            *v = perturb(*v, if k < 2 { BEND_RANGE } else { ROLL_RANGE }, rng);
        }
    }
    if rng.random_bool(rate) {
        c.scale = perturb(c.scale, SCALE_RANGE, rng);
    }
    if rng.random_bool(rate) {
        c.reflection = !c.reflection;
    }
    if rng.random_bool(rate) {
        c.terminal_only = !c.terminal_only;
    }
}

impl GraphGenome {
    /// Checks that the genome is within `limits` and well formed (connections to nodes that
    /// exist, limits per degree of freedom, values in their ranges); `Err` says what is not.
    pub fn check(&self, limits: &GraphLimits) -> Result<(), String> {
        GenomeShape::of(self).check(limits)?;
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

    /// Removes the nodes the root cannot reach (Sims' garbage collection of the graph) and
    /// renumbers the connections.
    fn collect_garbage(&mut self) {
        let keep = self.reachable();
        let mut new_index = vec![usize::MAX; self.nodes.len()];
        let mut next = 0;
        for (i, k) in keep.iter().enumerate() {
            if *k {
                new_index[i] = next;
                next += 1;
            }
        }
        let nodes = std::mem::take(&mut self.nodes);
        self.nodes = nodes
            .into_iter()
            .zip(keep)
            .filter_map(|(n, k)| k.then_some(n))
            .collect();
        for node in &mut self.nodes {
            for c in &mut node.connections {
                c.to = new_index[c.to];
            }
        }
    }

    /// Makes genomes with `make` until one develops without interpenetrating parts, at most
    /// `regenerate_tries` times; the last is kept.
    fn regenerate(
        limits: &GraphLimits,
        rng: &mut Rng,
        mut make: impl FnMut(&mut Rng) -> Option<GraphGenome>,
    ) -> Option<GraphGenome> {
        let mut last = None;
        for _ in 0..limits.regenerate_tries.max(1) {
            let g = make(rng)?;
            let clean = g
                .creature(limits.max_parts)
                .interpenetrating_pairs()
                .is_empty();
            last = Some(g);
            if clean {
                break;
            }
        }
        last
    }

    fn random_once(limits: &GraphLimits, rng: &mut Rng) -> GraphGenome {
        let globals = rng.random_range(0..=limits.max_global_neurons.min(2));
        let neurons = (0..globals)
            .map(|_| random_global(globals, limits, rng))
            .collect();
        let count = rng.random_range(1..=limits.nodes().min(4));
        let mut nodes: Vec<Node> = (0..count)
            .map(|_| random_node(globals, limits, rng))
            .collect();
        // Connect every node to an earlier one (as room allows), then add a few more.
        if limits.max_connections > 0 {
            for i in 1..count {
                let from = rng.random_range(0..i);
                if nodes[from].connections.len() < limits.max_connections {
                    let mut c = random_connection(count, limits, from == 0, rng);
                    c.to = i;
                    nodes[from].connections.push(c);
                }
            }
            for (from, node) in nodes.iter_mut().enumerate() {
                if node.connections.len() < limits.max_connections && rng.random_bool(0.3) {
                    node.connections
                        .push(random_connection(count, limits, from == 0, rng));
                }
            }
        }
        let mut g = GraphGenome { nodes, neurons };
        g.collect_garbage();
        g
    }

    fn mutate_once(&self, limits: &GraphLimits, rate: f64, rng: &mut Rng) -> GraphGenome {
        let mut g = self.clone();
        let globals = g.neurons.len();
        // (1) Node parameters and local neurons.
        for node in &mut g.nodes {
            for s in &mut node.size {
                if rng.random_bool(rate) {
                    *s = perturb(*s, SIZE_RANGE, rng);
                }
            }
            if rng.random_bool(rate) {
                node.joint = limits.joint_kinds.random(rng);
                let dof = node.joint.dof();
                node.limits.truncate(dof);
                let more = random_limits(dof - node.limits.len(), rng);
                node.limits.extend(more);
            }
            for (lo, hi) in &mut node.limits {
                if rng.random_bool(rate) {
                    *lo = perturb(*lo, LOWER_LIMIT_RANGE, rng);
                }
                if rng.random_bool(rate) {
                    *hi = -perturb(-*hi, LOWER_LIMIT_RANGE, rng);
                }
            }
            if rng.random_bool(rate) {
                let up = rng.random_bool(0.5);
                node.recursive_limit = if up {
                    (node.recursive_limit + 1).min(limits.recursion())
                } else {
                    node.recursive_limit.saturating_sub(1).max(1)
                };
            }
            let ctx = Context {
                locals: Some(node.neurons.len()),
                parents: limits.max_local_neurons,
                globals,
                dof: node.joint.dof(),
            };
            mutate_neurons(
                &mut node.neurons,
                ctx,
                limits.max_local_neurons,
                limits,
                rate,
                rng,
            );
        }
        // (2) A new random node, initially unconnected.
        if g.nodes.len() < limits.nodes() && rng.random_bool(rate) {
            g.nodes.push(random_node(globals, limits, rng));
        }
        // (3) Connection parameters, (4) connections removed and added.
        let n = g.nodes.len();
        for (i, node) in g.nodes.iter_mut().enumerate() {
            for c in &mut node.connections {
                mutate_connection(c, n, i == 0, limits, rate, rng);
            }
            if !node.connections.is_empty() && rng.random_bool(rate) {
                let k = rng.random_range(0..node.connections.len());
                node.connections.remove(k);
            }
            if node.connections.len() < limits.max_connections && rng.random_bool(rate) {
                node.connections
                    .push(random_connection(n, limits, i == 0, rng));
            }
        }
        // Global neurons.
        let ctx = Context {
            locals: None,
            parents: 0,
            globals,
            dof: 0,
        };
        mutate_neurons(
            &mut g.neurons,
            ctx,
            limits.max_global_neurons,
            limits,
            rate,
            rng,
        );
        // (5) Unreachable nodes go.
        g.collect_garbage();
        g
    }

    fn crossover_once(
        &self,
        other: &GraphGenome,
        limits: &GraphLimits,
        rng: &mut Rng,
    ) -> GraphGenome {
        let (n1, n2) = (self.nodes.len(), other.nodes.len());
        let k = rng.random_range(1..=n1.min(n2).max(1));
        let mut nodes: Vec<Node> = self.nodes[..k.min(n1)].to_vec();
        nodes.extend(other.nodes.iter().skip(k).cloned());
        nodes.truncate(limits.nodes());
        let n = nodes.len();
        for node in &mut nodes {
            for c in &mut node.connections {
                if c.to >= n {
                    c.to = rng.random_range(0..n);
                }
            }
        }
        let (g1, g2) = (self.neurons.len(), other.neurons.len());
        let kg = rng.random_range(0..=g1.min(g2));
        let mut neurons: Vec<NeuronGene> = self.neurons[..kg].to_vec();
        neurons.extend(other.neurons.iter().skip(kg).cloned());
        neurons.truncate(limits.max_global_neurons);
        let mut g = GraphGenome { nodes, neurons };
        g.collect_garbage();
        g
    }

    fn graft_once(
        &self,
        other: &GraphGenome,
        limits: &GraphLimits,
        rng: &mut Rng,
    ) -> Option<GraphGenome> {
        const MARK: usize = usize::MAX;
        let mut g = self.clone();
        let sites: Vec<(usize, usize)> = g
            .nodes
            .iter()
            .enumerate()
            .flat_map(|(i, n)| (0..n.connections.len()).map(move |j| (i, j)))
            .collect();
        let (i, j) = if sites.is_empty() {
            // No connection to redirect: a new one from the root, if it has room.
            if limits.max_connections == 0 {
                return None;
            }
            let c = random_connection(1, limits, true, rng);
            g.nodes[0].connections.push(c);
            (0, 0)
        } else {
            sites[rng.random_range(0..sites.len())]
        };
        g.nodes[i].connections[j].to = MARK;
        let keep = reachable_from(&g.nodes, 0);
        let kept = keep.iter().filter(|k| **k).count();
        let room = limits.nodes().saturating_sub(kept);
        let candidates: Vec<(usize, Vec<usize>)> = (0..other.nodes.len())
            .map(|b| (b, reachable_list(&other.nodes, b)))
            .filter(|(_, list)| list.len() <= room)
            .collect();
        if candidates.is_empty() {
            return None;
        }
        let (_, list) = &candidates[rng.random_range(0..candidates.len())];
        // Renumber: the kept nodes of the first parent, then the grafted ones.
        let mut index1 = vec![MARK; g.nodes.len()];
        let mut next = 0;
        for (a, k) in keep.iter().enumerate() {
            if *k {
                index1[a] = next;
                next += 1;
            }
        }
        let mut index2 = vec![MARK; other.nodes.len()];
        for (k, b) in list.iter().enumerate() {
            index2[*b] = kept + k;
        }
        let mut nodes: Vec<Node> = Vec::with_capacity(kept + list.len());
        for (a, node) in g.nodes.iter().enumerate() {
            if keep[a] {
                let mut node = node.clone();
                for c in &mut node.connections {
                    c.to = if c.to == MARK { kept } else { index1[c.to] };
                }
                nodes.push(node);
            }
        }
        for b in list {
            let mut node = other.nodes[*b].clone();
            for c in &mut node.connections {
                c.to = index2[c.to];
            }
            nodes.push(node);
        }
        Some(GraphGenome {
            nodes,
            neurons: g.neurons,
        })
    }

    /// The creature the genome develops into, with at most `max_parts` parts (see the module
    /// documentation). Never panics; the genome should pass [`GraphGenome::check`] (values out
    /// of range are used as they are, connections to missing nodes are skipped).
    pub fn creature(&self, max_parts: usize) -> Creature {
        let mut d = Development {
            genome: self,
            max_parts: max_parts.max(1),
            creature: Creature::default(),
            on_cycle: on_cycle(&self.nodes),
            counts: vec![0; self.nodes.len()],
            instances: Vec::new(),
            links: Vec::new(),
            capped: false,
        };
        for g in &self.neurons {
            let role = match g.effector {
                Some(Effector::Release) => Role::Actuator {
                    actuator: Actuator::Release,
                },
                _ => Role::Hidden,
            };
            d.creature.brain.neurons.push(neuron_of(g, role, None));
        }
        if let Some(root) = self.nodes.first() {
            let size = clamp_size(Vector3::from(root.size));
            d.grow(
                0,
                None,
                Vector3::zeros(),
                Rotation3::identity(),
                size,
                1.0,
                false,
            );
        }
        // Global neurons' inputs: other globals and the root part's touch sensors.
        for (k, g) in self.neurons.iter().enumerate() {
            for input in &g.inputs {
                let from = match input.source {
                    Source::Global { neuron } if neuron < self.neurons.len() => Some(neuron),
                    Source::Touch { face } if !d.instances.is_empty() => Some(d.sensor(
                        0,
                        Sensor::Touch {
                            part: 0,
                            face: Some(face),
                        },
                    )),
                    _ => None,
                };
                if let Some(from) = from {
                    d.links.push((
                        k,
                        Link {
                            from,
                            to: k,
                            weight: input.weight,
                        },
                    ));
                }
            }
        }
        if d.capped {
            d.creature.problems.push(Problem {
                severity: Severity::Warning,
                message: format!(
                    "the graph makes more than {} parts (max_parts): the rest is not built",
                    d.max_parts
                ),
                module: None,
                t: None,
            });
        }
        // Links grouped by destination, each neuron's inputs in order.
        d.links.sort_by_key(|(to, _)| *to);
        d.creature.brain.links = d.links.into_iter().map(|(_, l)| l).collect();
        for (a, b) in d.creature.interpenetrating_pairs() {
            d.creature.problems.push(Problem {
                severity: Severity::Error,
                message: format!("parts {a} and {b} interpenetrate"),
                module: None,
                t: None,
            });
        }
        d.creature
    }

    /// The genome read from its JSON text form, checked against `limits`. Its sizes (nodes,
    /// connections, neurons, inputs) are checked first, on a reading that keeps nothing but
    /// counts, so that a file far beyond the limits is refused before it is built.
    pub fn from_text(text: &str, limits: &GraphLimits) -> Result<GraphGenome, DevelopError> {
        // A text that is not even shaped like a genome gets the full reading's message.
        if let Ok(shape) = serde_json::from_str::<GenomeShape>(text) {
            shape.check(limits).map_err(DevelopError)?;
        }
        let g: GraphGenome = serde_json::from_str(text)
            .map_err(|e| DevelopError(format!("not a graph genome: {e}")))?;
        g.check(limits).map_err(DevelopError)?;
        Ok(g)
    }

    /// The genome for people: nodes with their connections and neurons, then the global
    /// neurons (what `ontogeny genome show` prints).
    pub fn describe(&self) -> String {
        use std::fmt::Write;
        let mut out = String::new();
        let reach = self.reachable();
        let _ = writeln!(
            out,
            "graph genome: {} nodes, {} global neurons",
            self.nodes.len(),
            self.neurons.len()
        );
        for (i, node) in self.nodes.iter().enumerate() {
            let _ = writeln!(
                out,
                "node {i}{}: part {} x {} x {} m, {} joint{}, recursive limit {}{}",
                if i == 0 { " (root)" } else { "" },
                node.size[0],
                node.size[1],
                node.size[2],
                kind_name(node.joint),
                if node.limits.is_empty() {
                    String::new()
                } else {
                    format!(
                        " limits {}",
                        node.limits
                            .iter()
                            .map(|(lo, hi)| format!("[{lo}, {hi}]"))
                            .collect::<Vec<_>>()
                            .join(" ")
                    )
                },
                node.recursive_limit,
                if reach[i] { "" } else { " (unreachable)" }
            );
            for c in &node.connections {
                let _ = writeln!(
                    out,
                    "  -> node {} on the {} face at ({}, {}), turned ({}, {}, {}) rad, scale {}{}{}",
                    c.to,
                    face_name(c.face),
                    c.position[0],
                    c.position[1],
                    c.orientation[0],
                    c.orientation[1],
                    c.orientation[2],
                    c.scale,
                    if c.reflection { ", reflected" } else { "" },
                    if c.terminal_only {
                        ", terminal only"
                    } else {
                        ""
                    }
                );
            }
            for (k, g) in node.neurons.iter().enumerate() {
                let _ = writeln!(out, "  neuron {k}: {}", describe_neuron(g));
            }
        }
        for (k, g) in self.neurons.iter().enumerate() {
            let _ = writeln!(out, "global neuron {k}: {}", describe_neuron(g));
        }
        out
    }
}

fn kind_name(kind: JointKind) -> String {
    serde_json::to_value(kind)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default()
}

fn face_name(face: Face) -> String {
    serde_json::to_value(face)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default()
}

fn describe_neuron(g: &NeuronGene) -> String {
    let name = serde_json::to_value(g.function)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default();
    let params = if g.params.is_empty() {
        String::new()
    } else {
        format!(
            "({})",
            g.params
                .iter()
                .map(f64::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        )
    };
    let inputs = g
        .inputs
        .iter()
        .map(|i| {
            let from = match i.source {
                Source::Local { neuron } => format!("neuron {neuron}"),
                Source::Parent { neuron } => format!("parent neuron {neuron}"),
                Source::Global { neuron } => format!("global neuron {neuron}"),
                Source::Touch { face } => format!("touch {}", face_name(face)),
                Source::Angle { dof } => format!("angle {dof}"),
            };
            format!("{} × {from}", i.weight)
        })
        .collect::<Vec<_>>();
    let effector = match g.effector {
        Some(Effector::Joint { dof }) => format!(" -> joint dof {dof}"),
        Some(Effector::Release) => " -> release".to_string(),
        None => String::new(),
    };
    format!(
        "{name}{params} bias {} inputs [{}]{effector}",
        g.bias,
        inputs.join(", ")
    )
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

fn clamp_size(v: Vector3<f64>) -> Vector3<f64> {
    v.map(|x| {
        if x.is_finite() {
            x.clamp(PART_SIZE_RANGE.0, PART_SIZE_RANGE.1)
        } else {
            PART_SIZE_RANGE.0
        }
    })
}

/// The rotation from a face's frame to the part's: its x is the face's outward normal; its y
/// and z span the face (the `position` coordinates).
pub fn face_frame(face: Face) -> Matrix3<f64> {
    let (x, y, z) = (Vector3::x(), Vector3::y(), Vector3::z());
    let cols = match face {
        Face::Front => [x, y, z],
        Face::Back => [-x, y, -z],
        Face::Top => [y, -x, z],
        Face::Bottom => [-y, x, z],
        Face::Right => [z, y, -x],
        Face::Left => [-z, y, x],
    };
    Matrix3::from_columns(&cols)
}

/// The face a mirrored part calls `face` (the mirror flips its width axis).
fn mirrored_face(face: Face) -> Face {
    match face {
        Face::Right => Face::Left,
        Face::Left => Face::Right,
        f => f,
    }
}

/// The rotation of a connection's turn: bends about the face's y and z axes, then a roll
/// about the child's length.
fn turn(o: &[f64; 3]) -> Matrix3<f64> {
    let r = Rotation3::from_axis_angle(&Vector3::y_axis(), o[0])
        * Rotation3::from_axis_angle(&Vector3::z_axis(), o[1])
        * Rotation3::from_axis_angle(&Vector3::x_axis(), o[2]);
    *r.matrix()
}

/// One part made by development.
struct Instance {
    node: usize,
    /// Brain index of the node's first local neuron in this part.
    first_neuron: usize,
    /// The joint to the parent part.
    joint: Option<usize>,
    /// Sensors made for this part so far.
    sensors: Vec<(Sensor, usize)>,
}

/// The sizes of a genome's JSON text, read without building the genome: every list is
/// skipped over and counted (see [`GraphGenome::from_text`]).
#[derive(Deserialize)]
struct GenomeShape {
    #[serde(default)]
    nodes: Vec<NodeShape>,
    #[serde(default)]
    neurons: Vec<NeuronShape>,
}

/// A node's sizes (see [`GenomeShape`]).
#[derive(Deserialize)]
struct NodeShape {
    #[serde(default)]
    connections: Vec<serde::de::IgnoredAny>,
    #[serde(default)]
    neurons: Vec<NeuronShape>,
}

/// A neuron gene's sizes (see [`GenomeShape`]).
#[derive(Deserialize)]
struct NeuronShape {
    #[serde(default)]
    inputs: Vec<serde::de::IgnoredAny>,
}

impl NeuronShape {
    fn of(g: &NeuronGene) -> NeuronShape {
        NeuronShape {
            inputs: vec![serde::de::IgnoredAny; g.inputs.len()],
        }
    }
}

impl GenomeShape {
    /// The sizes of a genome already read.
    fn of(genome: &GraphGenome) -> GenomeShape {
        GenomeShape {
            nodes: genome
                .nodes
                .iter()
                .map(|node| NodeShape {
                    connections: vec![serde::de::IgnoredAny; node.connections.len()],
                    neurons: node.neurons.iter().map(NeuronShape::of).collect(),
                })
                .collect(),
            neurons: genome.neurons.iter().map(NeuronShape::of).collect(),
        }
    }

    /// The size limits of [`GraphGenome::check`] (its first checks), each message naming
    /// the limit.
    fn check(&self, limits: &GraphLimits) -> Result<(), String> {
        let n = self.nodes.len();
        if n == 0 || n > limits.nodes() {
            return Err(format!(
                "{n} nodes; 1 to {} allowed (max_nodes)",
                limits.nodes()
            ));
        }
        if self.neurons.len() > limits.max_global_neurons {
            return Err(format!(
                "{} global neurons; at most {} allowed (max_global_neurons)",
                self.neurons.len(),
                limits.max_global_neurons
            ));
        }
        let inputs = |where_: &str, neurons: &[NeuronShape]| -> Result<(), String> {
            for (k, g) in neurons.iter().enumerate() {
                if g.inputs.len() > limits.max_inputs {
                    return Err(format!(
                        "{where_} neuron {k} has {} inputs; at most {} allowed (max_inputs)",
                        g.inputs.len(),
                        limits.max_inputs
                    ));
                }
            }
            Ok(())
        };
        inputs("global", &self.neurons)?;
        for (i, node) in self.nodes.iter().enumerate() {
            if node.neurons.len() > limits.max_local_neurons {
                return Err(format!(
                    "node {i}: {} neurons; at most {} allowed (max_local_neurons)",
                    node.neurons.len(),
                    limits.max_local_neurons
                ));
            }
            inputs(&format!("node {i}"), &node.neurons)?;
            if node.connections.len() > limits.max_connections {
                return Err(format!(
                    "node {i}: {} connections; at most {} allowed (max_connections)",
                    node.connections.len(),
                    limits.max_connections
                ));
            }
        }
        Ok(())
    }
}

struct Development<'a> {
    genome: &'a GraphGenome,
    max_parts: usize,
    creature: Creature,
    on_cycle: Vec<bool>,
    /// How many times each node is on the current path from the root.
    counts: Vec<u32>,
    instances: Vec<Instance>,
    /// (destination, link), collected in input order.
    links: Vec<(usize, Link)>,
    capped: bool,
}

impl Development<'_> {
    /// The brain index of part `part`'s sensor `sensor`, made on first use.
    fn sensor(&mut self, part: usize, sensor: Sensor) -> usize {
        if let Some((_, i)) = self.instances[part]
            .sensors
            .iter()
            .find(|(s, _)| *s == sensor)
        {
            return *i;
        }
        let i = self.creature.brain.neurons.len();
        self.creature.brain.neurons.push(Neuron {
            function: NeuronFunction::Linear,
            params: Vec::new(),
            bias: 0.0,
            role: Role::Sensor { sensor },
            part: Some(part),
        });
        self.instances[part].sensors.push((sensor, i));
        i
    }

    /// Makes a part of node `node` (and, recursively, its children): `parent` is the parent
    /// part and the joint's anchor, `centre`, `rotation` and `size` the part's pose and size,
    /// `scale` the product of the scales on its path, `mirrored` whether it is reflected.
    #[allow(clippy::too_many_arguments)]
    fn grow(
        &mut self,
        node: usize,
        parent: Option<(usize, Vector3<f64>)>,
        centre: Vector3<f64>,
        rotation: Rotation3<f64>,
        size: Vector3<f64>,
        scale: f64,
        mirrored: bool,
    ) {
        let gene = &self.genome.nodes[node];
        let part = self.creature.parts.len();
        self.creature.parts.push(Part {
            size,
            position: centre,
            orientation: UnitQuaternion::from_rotation_matrix(&rotation),
            density: DEFAULT_DENSITY,
            growing: false,
        });
        let joint = parent.map(|(parent, anchor)| {
            let m = rotation.matrix();
            let (x, y, z) = (
                m.column(0).into_owned(),
                m.column(1).into_owned(),
                m.column(2).into_owned(),
            );
            let axes = match gene.joint {
                JointKind::Rigid => vec![],
                JointKind::Revolute => vec![z],
                JointKind::Twist => vec![x],
                JointKind::Universal => vec![z, y],
                JointKind::BendTwist => vec![z, x],
                JointKind::TwistBend => vec![x, z],
                JointKind::Spherical => vec![x, y, z],
            };
            let dof = gene.joint.dof();
            let mut limits: Vec<(f64, f64)> = gene
                .limits
                .iter()
                .take(dof)
                .map(|&(lo, hi)| {
                    let (lo, hi) = (lo.min(0.0), hi.max(0.0));
                    (lo.max(-std::f64::consts::PI), hi.min(std::f64::consts::PI))
                })
                .collect();
            limits.resize(dof, (0.0, 0.0));
            let j = self.creature.joints.len();
            self.creature.joints.push(Joint {
                parent,
                child: part,
                kind: gene.joint,
                anchor,
                axes,
                limits,
                strength: 1.0,
                growing: false,
            });
            j
        });
        let dof = joint.map_or(0, |j| self.creature.joints[j].kind.dof());
        // Local neurons: a copy per part.
        let first_neuron = self.creature.brain.neurons.len();
        for g in &gene.neurons {
            let role = match g.effector {
                Some(Effector::Joint { dof: k }) if k < dof => Role::Actuator {
                    actuator: Actuator::Joint {
                        joint: joint.expect("dof > 0 needs a joint"),
                        dof: k,
                    },
                },
                Some(Effector::Release) => Role::Actuator {
                    actuator: Actuator::Release,
                },
                _ => Role::Hidden,
            };
            self.creature
                .brain
                .neurons
                .push(neuron_of(g, role, Some(part)));
        }
        let parent_instance = parent.map(|(p, _)| p);
        self.instances.push(Instance {
            node,
            first_neuron,
            joint,
            sensors: Vec::new(),
        });
        for (k, g) in gene.neurons.iter().enumerate() {
            let to = first_neuron + k;
            for input in &g.inputs {
                let from = match input.source {
                    Source::Local { neuron } if neuron < gene.neurons.len() => {
                        Some(first_neuron + neuron)
                    }
                    Source::Parent { neuron } => parent_instance.and_then(|p| {
                        let inst = &self.instances[p];
                        (neuron < self.genome.nodes[inst.node].neurons.len())
                            .then_some(inst.first_neuron + neuron)
                    }),
                    Source::Global { neuron } if neuron < self.genome.neurons.len() => Some(neuron),
                    Source::Touch { face } => {
                        let face = if mirrored { mirrored_face(face) } else { face };
                        Some(self.sensor(
                            part,
                            Sensor::Touch {
                                part,
                                face: Some(face),
                            },
                        ))
                    }
                    Source::Angle { dof: k } if k < dof => {
                        let joint = self.instances[part].joint.expect("dof > 0 needs a joint");
                        Some(self.sensor(part, Sensor::Angle { joint, dof: k }))
                    }
                    _ => None,
                };
                if let Some(from) = from {
                    self.links.push((
                        to,
                        Link {
                            from,
                            to,
                            weight: input.weight,
                        },
                    ));
                }
            }
        }
        // Children.
        self.counts[node] += 1;
        let terminal = self.counts[node] >= gene.recursive_limit || !self.on_cycle[node];
        let half = size / 2.0;
        for c in &gene.connections {
            if c.to >= self.genome.nodes.len()
                || (c.terminal_only && !terminal)
                || self.counts[c.to] >= self.genome.nodes[c.to].recursive_limit.max(1)
            {
                continue;
            }
            if self.creature.parts.len() >= self.max_parts {
                self.capped = true;
                break;
            }
            let child = &self.genome.nodes[c.to];
            let child_scale = scale * c.scale;
            let child_size = clamp_size(Vector3::from(child.size) * child_scale);
            let f = face_frame(c.face);
            let extent = |col: usize| f.column(col).abs().dot(&half);
            let mut anchor = f.column(0) * extent(0)
                + f.column(1) * (c.position[0].clamp(-1.0, 1.0) * extent(1))
                + f.column(2) * (c.position[1].clamp(-1.0, 1.0) * extent(2));
            let mut q = f * turn(&c.orientation);
            let child_mirrored = mirrored ^ c.reflection;
            if child_mirrored {
                let p = Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, -1.0));
                anchor = p * anchor;
                q = p * q * p;
            }
            let local_centre = anchor + q.column(0) * (child_size.x / 2.0);
            let child_rotation = rotation * Rotation3::from_matrix_unchecked(q);
            let world_anchor = centre + rotation * anchor;
            let child_centre = centre + rotation * local_centre;
            self.grow(
                c.to,
                Some((part, world_anchor)),
                child_centre,
                child_rotation,
                child_size,
                child_scale,
                child_mirrored,
            );
        }
        self.counts[node] -= 1;
    }
}

fn neuron_of(g: &NeuronGene, role: Role, part: Option<usize>) -> Neuron {
    Neuron {
        function: g.function,
        params: g.params.clone(),
        bias: g.bias,
        role,
        part,
    }
}

impl Genome for GraphGenome {
    type Limits = GraphLimits;

    const NAME: &'static str = "graph";

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
        GraphGenome::regenerate(limits, rng, |rng| Some(self.mutate_once(limits, rate, rng)))
            .expect("mutation always makes a genome")
    }

    fn crossover(&self, other: &Self, limits: &GraphLimits, rng: &mut Rng) -> Option<Self> {
        GraphGenome::regenerate(limits, rng, |rng| {
            Some(self.crossover_once(other, limits, rng))
        })
    }

    fn graft(&self, other: &Self, limits: &GraphLimits, rng: &mut Rng) -> Option<Self> {
        GraphGenome::regenerate(limits, rng, |rng| self.graft_once(other, limits, rng))
    }

    fn develop(&self, limits: &GraphLimits, _seed: u64) -> Result<Creature, DevelopError> {
        self.check(limits).map_err(DevelopError)?;
        Ok(self.creature(limits.max_parts))
    }

    fn to_text(&self) -> String {
        let mut text = serde_json::to_string_pretty(self).unwrap_or_default();
        text.push('\n');
        text
    }

    fn annotated_text(&self, _note: &str) -> String {
        self.to_text() // JSON has no comments
    }
}
