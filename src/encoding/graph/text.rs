//! The graph genome as text: its JSON form (read with its sizes checked first) and the
//! readable description `ontogeny genome show` prints.

use super::*;

impl GraphGenome {
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

pub(super) fn kind_name(kind: JointKind) -> String {
    serde_json::to_value(kind)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default()
}

pub(super) fn face_name(face: Face) -> String {
    serde_json::to_value(face)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default()
}

pub(super) fn describe_neuron(g: &NeuronGene) -> String {
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

/// The sizes of a genome's JSON text, read without building the genome: every list is
/// skipped over and counted (see [`GraphGenome::from_text`]).
#[derive(Deserialize)]
pub(super) struct GenomeShape {
    #[serde(default)]
    nodes: Vec<NodeShape>,
    #[serde(default)]
    neurons: Vec<NeuronShape>,
}

/// A node's sizes (see [`GenomeShape`]).
#[derive(Deserialize)]
pub(super) struct NodeShape {
    #[serde(default)]
    connections: Vec<serde::de::IgnoredAny>,
    #[serde(default)]
    neurons: Vec<NeuronShape>,
}

/// A neuron gene's sizes (see [`GenomeShape`]).
#[derive(Deserialize)]
pub(super) struct NeuronShape {
    #[serde(default)]
    inputs: Vec<serde::de::IgnoredAny>,
}

impl NeuronShape {
    pub(super) fn of(g: &NeuronGene) -> NeuronShape {
        NeuronShape {
            inputs: vec![serde::de::IgnoredAny; g.inputs.len()],
        }
    }
}

impl GenomeShape {
    /// The sizes of a genome already read.
    pub(super) fn of(genome: &GraphGenome) -> GenomeShape {
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
    pub(super) fn check(&self, limits: &GraphLimits) -> Result<(), String> {
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
