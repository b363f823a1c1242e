//! Running a creature's brain: synchronous updates of every neuron from the previous step's
//! outputs, with no allocation per step.

use crate::creature::{Brain, NeuronFunction, Role};

/// Below this a divisor counts as zero for Chaumont's `div`.
const EPSILON: f64 = 1e-6;

/// The state of a running brain.
#[derive(Clone, Debug)]
pub struct BrainRuntime {
    functions: Vec<NeuronFunction>,
    params: Vec<Vec<f64>>,
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
                let len = if neuron.function == NeuronFunction::Memory {
                    neuron
                        .params
                        .first()
                        .copied()
                        .unwrap_or(1.0)
                        .clamp(1.0, 10_000.0) as usize
                } else {
                    0
                };
                let start = memory.len();
                memory.resize(start + len, 0.0);
                (start, len, 0)
            })
            .collect();
        BrainRuntime {
            functions: brain.neurons.iter().map(|n| n.function).collect(),
            params: brain.neurons.iter().map(|n| n.params.clone()).collect(),
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

    /// Every neuron's current output.
    pub fn outputs(&self) -> &[f64] {
        &self.outputs
    }

    /// Sets a sensor neuron's output (its reading) for the next update.
    pub fn set_sensor(&mut self, neuron: usize, value: f64) {
        self.outputs[neuron] = value.clamp(-1.0, 1.0);
    }

    /// Updates every non-sensor neuron at once from the previous outputs. `t` is the
    /// simulated time and `dt` the control step. Returns false if any output was not a
    /// number (the outputs are then left as they were).
    pub fn step(&mut self, t: f64, dt: f64) -> bool {
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
            let sum: f64 = range
                .clone()
                .map(|j| self.weights[j] * self.outputs[self.sources[j]])
                .sum();
            let a = input(0).unwrap_or(0.0);
            let param = |k: usize, default: f64| self.params[i].get(k).copied().unwrap_or(default);
            let value = match self.functions[i] {
                NeuronFunction::Linear => sum,
                NeuronFunction::Sigmoid => sum.tanh(),
                NeuronFunction::Oscillator => {
                    let frequency = std::f64::consts::PI * (1.0 + sum.clamp(-1.0, 1.0));
                    self.phases[i] += frequency * dt;
                    self.phases[i].sin()
                }
                NeuronFunction::Threshold => {
                    let s = a + input(1).unwrap_or(0.0);
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
                    b * (a * t + c).sin()
                }
                NeuronFunction::Sum => a + input(1).unwrap_or(0.0),
                NeuronFunction::Product => a * input(1).unwrap_or(1.0),
                NeuronFunction::Quotient => {
                    let b = input(1).unwrap_or(1.0);
                    if b == 0.0 { 0.0 } else { a / b }
                }
                NeuronFunction::SumGreater => {
                    let s = a + input(1).unwrap_or(0.0);
                    if s > input(2).unwrap_or(0.0) {
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
                NeuronFunction::Min => (0..3).filter_map(input).fold(f64::INFINITY, f64::min),
                NeuronFunction::Max => (0..3).filter_map(input).fold(f64::NEG_INFINITY, f64::max),
                NeuronFunction::Abs => a.abs(),
                NeuronFunction::If => {
                    if input(1).unwrap_or(1.0) != 0.0 {
                        a
                    } else {
                        0.0
                    }
                }
                NeuronFunction::Interpolate => {
                    let (n, total) = (0..3)
                        .filter_map(input)
                        .fold((0.0, 0.0), |(n, s), v| (n + 1.0, s + v));
                    if n > 0.0 { total / n } else { 0.0 }
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
                NeuronFunction::Power => a.powf(input(1).unwrap_or(1.0)),
                NeuronFunction::Logistic => 1.0 / (1.0 + (-a).exp()),
                NeuronFunction::StepWave => {
                    (self.steps as f64 * std::f64::consts::TAU / 360.0).sin()
                }
                NeuronFunction::Saw => (self.steps as f64 * std::f64::consts::TAU / 4.0).sin(),
            };
            // Min and Max of no inputs give infinities: a neuron with no input outputs 0.
            let value = if value.is_infinite() && range.is_empty() {
                0.0
            } else {
                value
            };
            if value.is_nan() {
                return false;
            }
            self.next[i] = value.clamp(-1.0, 1.0);
        }
        std::mem::swap(&mut self.outputs, &mut self.next);
        true
    }
}
