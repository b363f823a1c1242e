//! Running a creature's brain: synchronous updates of every neuron from the previous step's
//! outputs, with no allocation per step; neurons and links can be added while it runs.

use crate::creature::{Brain, Link, Neuron, NeuronFunction, Role};

/// Below this a divisor counts as zero for Chaumont's `div`.
const EPSILON: f64 = 1e-6;

/// The state of a running brain.
#[derive(Clone, Debug)]
pub struct BrainRuntime {
    functions: Vec<NeuronFunction>,
    params: Vec<Vec<f64>>,
    biases: Vec<f64>,
    sensor: Vec<bool>,
    /// Inputs of neuron i are `sources[starts[i]..starts[i + 1]]` with `weights[...]`.
    starts: Vec<usize>,
    sources: Vec<usize>,
    weights: Vec<f64>,
    outputs: Vec<f64>,
    next: Vec<f64>,
    phases: Vec<f64>,
    /// Ring buffers of `Memory` neurons: (start in `memory`, length, position).
    rings: Vec<(usize, usize, usize)>,
    memory: Vec<f64>,
    steps: u64,
}

impl BrainRuntime {
    /// Prepares `brain` to run; every output starts at 0.
    pub fn new(brain: &Brain) -> Self {
        let n = brain.neurons.len();
        let mut order: Vec<usize> = (0..brain.links.len()).collect();
        order.sort_by_key(|&l| brain.links[l].to); // stable: link order kept per neuron
        let mut starts = vec![0; n + 1];
        for link in &brain.links {
            starts[link.to + 1] += 1;
        }
        for i in 0..n {
            starts[i + 1] += starts[i];
        }
        let sources = order.iter().map(|&l| brain.links[l].from).collect();
        let weights = order.iter().map(|&l| brain.links[l].weight).collect();
        let mut memory = Vec::new();
        let rings = brain
            .neurons
            .iter()
            .map(|neuron| {
                let len = ring_length(neuron);
                let start = memory.len();
                memory.resize(start + len, 0.0);
                (start, len, 0)
            })
            .collect();
        BrainRuntime {
            functions: brain.neurons.iter().map(|n| n.function).collect(),
            params: brain.neurons.iter().map(|n| n.params.clone()).collect(),
            biases: brain.neurons.iter().map(|n| n.bias).collect(),
            sensor: brain
                .neurons
                .iter()
                .map(|n| matches!(n.role, Role::Sensor { .. }))
                .collect(),
            starts,
            sources,
            weights,
            outputs: vec![0.0; n],
            next: vec![0.0; n],
            phases: vec![0.0; n],
            rings,
            memory,
            steps: 0,
        }
    }

    /// Adds `neuron`, with no input yet and an output of 0, while the brain runs; returns its
    /// index, the next one. It is updated from the next [`step`](Self::step) on.
    pub fn add_neuron(&mut self, neuron: &Neuron) -> usize {
        let len = ring_length(neuron);
        let start = self.memory.len();
        self.memory.resize(start + len, 0.0);
        self.rings.push((start, len, 0));
        self.functions.push(neuron.function);
        self.params.push(neuron.params.clone());
        self.biases.push(neuron.bias);
        self.sensor.push(matches!(neuron.role, Role::Sensor { .. }));
        self.starts.push(*self.starts.last().unwrap_or(&0));
        self.outputs.push(0.0);
        self.next.push(0.0);
        self.phases.push(0.0);
        self.outputs.len() - 1
    }

    /// Adds `link` while the brain runs: its weighted source becomes its destination's last
    /// input (after the inputs it had, as links made together are in link order), from the
    /// next [`step`](Self::step) on.
    ///
    /// # Panics
    ///
    /// If either end names no neuron.
    pub fn add_link(&mut self, link: &Link) {
        let n = self.outputs.len();
        assert!(
            link.from < n && link.to < n,
            "a link from neuron {} to neuron {} in a brain of {n} neurons",
            link.from,
            link.to
        );
        let at = self.starts[link.to + 1];
        self.sources.insert(at, link.from);
        self.weights.insert(at, link.weight);
        for start in &mut self.starts[link.to + 1..] {
            *start += 1;
        }
    }

    /// How many neurons.
    pub fn neuron_count(&self) -> usize {
        self.outputs.len()
    }

    /// Every neuron's current output.
    pub fn outputs(&self) -> &[f64] {
        &self.outputs
    }

    /// Sets a sensor neuron's output (its reading) for the next update, clipped to [−1, 1]
    /// (a reading that is not a number counts as 0).
    pub fn set_sensor(&mut self, neuron: usize, value: f64) {
        self.outputs[neuron] = if value.is_nan() {
            0.0
        } else {
            value.clamp(-1.0, 1.0)
        };
    }

    /// Updates every non-sensor neuron at once from the previous outputs. `t` is the
    /// simulated time and `dt` the control step. Every output is a number in [−1, 1]: sums
    /// saturate at ±`f64::MAX`, the output is clipped (±∞ gives ±1), and a result that is not a
    /// number gives 0 (see [`NeuronFunction`]).
    pub fn step(&mut self, t: f64, dt: f64) {
        self.steps += 1;
        for i in 0..self.outputs.len() {
            if self.sensor[i] {
                self.next[i] = self.outputs[i];
                continue;
            }
            let range = self.starts[i]..self.starts[i + 1];
            let input = |k: usize| -> Option<f64> {
                let j = self.starts[i] + k;
                (j < self.starts[i + 1]).then(|| self.weights[j] * self.outputs[self.sources[j]])
            };
            let bias = self.biases[i];
            let x = add(
                range
                    .map(|j| self.weights[j] * self.outputs[self.sources[j]])
                    .fold(0.0, add),
                bias,
            );
            let a = add(input(0).unwrap_or(0.0), bias);
            // a and the b, c present: for min, max and interpolate.
            let present = || std::iter::once(a).chain((1..3).filter_map(input));
            let param = |k: usize, default: f64| self.params[i].get(k).copied().unwrap_or(default);
            let value = match self.functions[i] {
                NeuronFunction::Linear => x,
                NeuronFunction::Sigmoid => x.tanh(),
                NeuronFunction::Oscillator => {
                    let frequency = std::f64::consts::PI * (1.0 + x.clamp(-1.0, 1.0));
                    self.phases[i] += frequency * dt;
                    self.phases[i].sin()
                }
                NeuronFunction::Threshold => {
                    let s = add(a, input(1).unwrap_or(0.0));
                    if s >= param(0, 0.0) { s } else { 0.0 }
                }
                NeuronFunction::Divide => {
                    let b = input(1).unwrap_or(1.0);
                    if b <= EPSILON { 1.0 } else { a / b }
                }
                NeuronFunction::Memory => {
                    let (start, len, pos) = self.rings[i];
                    let old = self.memory[start + pos];
                    self.memory[start + pos] = a;
                    self.rings[i].2 = (pos + 1) % len;
                    old
                }
                NeuronFunction::Wave => {
                    let b = input(1).unwrap_or(1.0);
                    let c = input(2).unwrap_or(0.0);
                    b * add(saturate(a * t), c).sin()
                }
                NeuronFunction::Constant => param(0, 0.0),
                NeuronFunction::Sum => add(a, input(1).unwrap_or(0.0)),
                NeuronFunction::Product => a * input(1).unwrap_or(1.0),
                NeuronFunction::Quotient => {
                    let b = input(1).unwrap_or(1.0);
                    if b == 0.0 { 0.0 } else { a / b }
                }
                NeuronFunction::SumGreater => {
                    if add(a, input(1).unwrap_or(0.0)) > input(2).unwrap_or(0.0) {
                        1.0
                    } else {
                        0.0
                    }
                }
                NeuronFunction::GreaterThan => {
                    if a > input(1).unwrap_or(0.0) {
                        1.0
                    } else {
                        0.0
                    }
                }
                NeuronFunction::Sign => {
                    if a > 0.0 {
                        1.0
                    } else if a < 0.0 {
                        -1.0
                    } else {
                        0.0
                    }
                }
                NeuronFunction::Min => present().fold(f64::INFINITY, f64::min),
                NeuronFunction::Max => present().fold(f64::NEG_INFINITY, f64::max),
                NeuronFunction::Abs => a.abs(),
                NeuronFunction::If => {
                    if input(1).unwrap_or(1.0) != 0.0 {
                        a
                    } else {
                        0.0
                    }
                }
                NeuronFunction::Interpolate => {
                    let (n, total) = present().fold((0.0, 0.0), |(n, s), v| (n + 1.0, add(s, v)));
                    total / n
                }
                NeuronFunction::Sin => a.sin(),
                NeuronFunction::Cos => a.cos(),
                NeuronFunction::Atan => a.atan(),
                NeuronFunction::Log => {
                    if a > 0.0 {
                        a.ln()
                    } else {
                        a
                    }
                }
                NeuronFunction::Power => power(a, input(1).unwrap_or(1.0)),
                NeuronFunction::Logistic => 1.0 / (1.0 + (-a).exp()),
                NeuronFunction::StepWave => {
                    (self.steps as f64 * std::f64::consts::TAU / 360.0).sin()
                }
                NeuronFunction::Saw => (self.steps as f64 * std::f64::consts::TAU / 4.0).sin(),
            };
            // The safety net: ±∞ clips to ±1, and nothing that is not a number gets through.
            self.next[i] = if value.is_nan() {
                0.0
            } else {
                value.clamp(-1.0, 1.0)
            };
        }
        std::mem::swap(&mut self.outputs, &mut self.next);
    }
}

/// The length of a neuron's ring buffer: its delay for a `Memory` neuron (a NaN delay counts
/// as 1, and it is kept within 1 to 10,000 steps), else 0.
fn ring_length(neuron: &Neuron) -> usize {
    if neuron.function == NeuronFunction::Memory {
        neuron
            .params
            .first()
            .copied()
            .filter(|d| !d.is_nan())
            .unwrap_or(1.0)
            .clamp(1.0, 10_000.0) as usize
    } else {
        0
    }
}

/// `x` clamped to the finite range (±∞ become ±`f64::MAX`).
fn saturate(x: f64) -> f64 {
    x.clamp(-f64::MAX, f64::MAX)
}

/// `x + y` for finite `x` and `y`, saturating at ±`f64::MAX` instead of overflowing (so it
/// is never ±∞, and never ∞ − ∞ = NaN further on).
fn add(x: f64, y: f64) -> f64 {
    saturate(x + y)
}

/// `a` to the power `b` as a real number: `a^b` where that is real; −|`a`|^`b` for a negative
/// `a` and a non-integer `b` (the signed power); +∞ for 0 to a negative power.
fn power(a: f64, b: f64) -> f64 {
    if a == 0.0 && b < 0.0 {
        f64::INFINITY
    } else if a < 0.0 && b.fract() != 0.0 {
        -(-a).powf(b)
    } else {
        a.powf(b)
    }
}
