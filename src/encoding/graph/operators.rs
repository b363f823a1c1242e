//! The graph genome's operators (Sims 1994): random genomes, mutation of nodes, connections
//! and neurons, crossover and grafting, and the garbage collection and regeneration that
//! keep a newborn well formed.

use super::*;
use crate::encoding::draw::{perturb_gaussian, uniform_on_grid};

// ---------------------------------------------------------------------------------------------
// Random values.

fn uniform(rng: &mut Rng, range: (f64, f64)) -> f64 {
    uniform_on_grid(rng, range, GRID)
}

fn perturb(x: f64, range: (f64, f64), rng: &mut Rng) -> f64 {
    perturb_gaussian(x, range, GRID, rng)
}

/// Chaumont et al.'s Table I functions (besides sensors and effectors).
pub(super) const CHAUMONT: [NeuronFunction; 7] = [
    NeuronFunction::Threshold,
    NeuronFunction::Divide,
    NeuronFunction::Memory,
    NeuronFunction::Wave,
    NeuronFunction::Product,
    NeuronFunction::Sum,
    NeuronFunction::Constant,
];

/// A random function: half the time one of Chaumont's Table I, else any of the brain's.
pub(super) fn random_function(rng: &mut Rng) -> NeuronFunction {
    if rng.random_bool(0.5) {
        CHAUMONT[rng.random_range(0..CHAUMONT.len())]
    } else {
        NeuronFunction::ALL[rng.random_range(0..NeuronFunction::ALL.len())]
    }
}

/// Random parameters for `function`: the threshold, delay or constant it reads.
pub(super) fn random_params(function: NeuronFunction, rng: &mut Rng) -> Vec<f64> {
    match function {
        NeuronFunction::Threshold | NeuronFunction::Constant => vec![uniform(rng, BIAS_RANGE)],
        NeuronFunction::Memory => vec![uniform(rng, DELAY_RANGE).round()],
        _ => Vec::new(),
    }
}

pub(super) fn param_range(function: NeuronFunction) -> (f64, f64) {
    if function == NeuronFunction::Memory {
        DELAY_RANGE
    } else {
        BIAS_RANGE
    }
}

pub(super) fn random_limits(dof: usize, rng: &mut Rng) -> Vec<(f64, f64)> {
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
pub(super) struct Context {
    /// Local neurons of the node (None for a global neuron).
    locals: Option<usize>,
    /// Neurons a parent node may have (the limit).
    parents: usize,
    globals: usize,
    /// Degrees of freedom of the node's joint.
    dof: usize,
}

pub(super) fn random_source(ctx: Context, rng: &mut Rng) -> Source {
    source_of_kind(ctx, rng.random_range(0..5), rng)
}

/// The source of kind `k` (0 local, 1 parent, 2 global, 3 touch, 4 angle), or a touch sensor
/// when that kind is not available.
pub(super) fn source_of_kind(ctx: Context, k: u32, rng: &mut Rng) -> Source {
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

pub(super) fn random_input(ctx: Context, rng: &mut Rng) -> Input {
    Input {
        source: random_source(ctx, rng),
        weight: uniform(rng, WEIGHT_RANGE),
    }
}

pub(super) fn random_neuron(
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

pub(super) fn random_connection(
    nodes: usize,
    limits: &GraphLimits,
    root: bool,
    rng: &mut Rng,
) -> Connection {
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
pub(super) fn random_node(globals: usize, limits: &GraphLimits, rng: &mut Rng) -> Node {
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

pub(super) fn random_global(globals: usize, limits: &GraphLimits, rng: &mut Rng) -> NeuronGene {
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

pub(super) fn mutate_neuron(
    n: &mut NeuronGene,
    ctx: Context,
    limits: &GraphLimits,
    rate: f64,
    rng: &mut Rng,
) {
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

pub(super) fn mutate_neurons(
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

pub(super) fn mutate_connection(
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
    /// Removes the nodes the root cannot reach (Sims' garbage collection of the graph) and
    /// renumbers the connections.
    pub(super) fn collect_garbage(&mut self) {
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
    pub(super) fn regenerate(
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

    pub(super) fn random_once(limits: &GraphLimits, rng: &mut Rng) -> GraphGenome {
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
        let mut g = GraphGenome {
            nodes,
            neurons,
            projectile: limits.projectile,
        };
        g.collect_garbage();
        g
    }

    pub(super) fn mutate_once(
        &self,
        limits: &GraphLimits,
        rate: f64,
        rng: &mut Rng,
    ) -> GraphGenome {
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

    pub(super) fn crossover_once(
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
        // The first parent's projectile, whole (Chaumont 4.1: "one projectile only").
        let mut g = GraphGenome {
            nodes,
            neurons,
            projectile: self.projectile,
        };
        g.collect_garbage();
        g
    }

    pub(super) fn graft_once(
        &self,
        other: &GraphGenome,
        limits: &GraphLimits,
        rng: &mut Rng,
    ) -> Option<GraphGenome> {
        let mut g = self.clone();
        // No connection to redirect: a new one from the root.
        let (_, keep, room) = graft_site(&mut g, limits, rng, |rng| {
            random_connection(1, limits, true, rng)
        })?;
        let candidates: Vec<(usize, Vec<usize>)> = (0..other.nodes.len())
            .map(|b| (b, reachable_list(&other.nodes, b)))
            .filter(|(_, list)| list.len() <= room)
            .collect();
        if candidates.is_empty() {
            return None;
        }
        let (_, list) = &candidates[rng.random_range(0..candidates.len())];
        Some(GraphGenome {
            nodes: joined(&g.nodes, &keep, other, list),
            neurons: g.neurons,
            projectile: g.projectile,
        })
    }
}

/// Where a graft (or a mirroring copy) goes in `g`: one of its connections drawn uniformly,
/// or, when it has none, a new one on its root that `new_root` makes (`None` when the root has
/// no room for one: `max_connections` is 0). That connection is marked to lead to `usize::MAX`
/// (what [`joined`] hangs the grafted nodes from). Returns its place (node, index), which of
/// `g`'s nodes the root still reaches, and the room `max_nodes` leaves for grafted nodes.
pub(super) fn graft_site(
    g: &mut GraphGenome,
    limits: &GraphLimits,
    rng: &mut Rng,
    new_root: impl FnOnce(&mut Rng) -> Connection,
) -> Option<((usize, usize), Vec<bool>, usize)> {
    let sites = crate::encoding::index_pairs(&g.nodes, |n| n.connections.len());
    let (i, j) = if sites.is_empty() {
        if limits.max_connections == 0 || g.nodes.is_empty() {
            return None;
        }
        let c = new_root(rng);
        g.nodes[0].connections.push(c);
        (0, 0)
    } else {
        sites[rng.random_range(0..sites.len())]
    };
    g.nodes[i].connections[j].to = usize::MAX;
    let keep = reachable_from(&g.nodes, 0);
    let kept = keep.iter().filter(|k| **k).count();
    let room = limits.nodes().saturating_sub(kept);
    Some(((i, j), keep, room))
}

/// The nodes of a graft: the `keep` nodes of `nodes`, then `other`'s nodes `list` (the first
/// the one grafted on), renumbered; the one connection of `nodes` that leads to `usize::MAX`
/// leads to the first grafted node.
pub(super) fn joined(
    nodes: &[Node],
    keep: &[bool],
    other: &GraphGenome,
    list: &[usize],
) -> Vec<Node> {
    const MARK: usize = usize::MAX;
    let kept = keep.iter().filter(|k| **k).count();
    let mut index1 = vec![MARK; nodes.len()];
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
    let mut joined: Vec<Node> = Vec::with_capacity(kept + list.len());
    for (a, node) in nodes.iter().enumerate() {
        if keep[a] {
            let mut node = node.clone();
            for c in &mut node.connections {
                c.to = if c.to == MARK { kept } else { index1[c.to] };
            }
            joined.push(node);
        }
    }
    for b in list {
        let mut node = other.nodes[*b].clone();
        for c in &mut node.connections {
            c.to = index2[c.to];
        }
        joined.push(node);
    }
    joined
}
