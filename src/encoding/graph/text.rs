//! The graph genome as text: its JSON form (read with its sizes checked first) and the
//! readable description `ontogeny genome show` prints.

use super::*;
use crate::lang::{self, Diagnostic, DiagnosticKind, Span};

/// `at_most` of the limit `limits.FIELD`, named by its key, the field's name.
macro_rules! at_most {
    ($count:expr, $limits:ident . $field:ident, $what:expr $(,)?) => {
        at_most($count, $limits.$field, stringify!($field), $what)
    };
}

/// What is wrong at the place of a JSON error `e` in `text`, in words: a number JSON cannot
/// hold (`NaN`, `Infinity`), text after the genome's end, else serde's message without its
/// place.
fn json_error_in_words(text: &str, e: &serde_json::Error) -> String {
    let source = lang::Source::new("genome", text);
    let rest = &text[json_error_offset(&source, e)..];
    for word in ["NaN", "-NaN", "Infinity", "-Infinity", "inf", "-inf"] {
        if rest.starts_with(word) {
            return format!("{word} is not a number JSON can hold (a genome's numbers are finite)");
        }
    }
    let message = e.to_string();
    let message = message
        .rsplit_once(" at line ")
        .map_or(message.as_str(), |(m, _)| m);
    match message {
        "trailing characters" => "text after the end of the genome".to_string(),
        other => other.to_string(),
    }
}

/// The byte offset in `source` of the place serde reports `e` at (its line and column,
/// both from 1), on a character boundary.
fn json_error_offset(source: &lang::Source, e: &serde_json::Error) -> usize {
    let text = source.text();
    let line_start: usize = text
        .split_inclusive('\n')
        .take(e.line().saturating_sub(1))
        .map(str::len)
        .sum();
    let mut at = (line_start + e.column().saturating_sub(1)).min(text.len());
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    at
}

/// The member of a run's `best.json` that records its champion's evaluation, beside the
/// genome.
pub const CHAMPION_KEY: &str = "champion";

/// `text` without a JSON object's `"champion"` member (a text without one, or that is no
/// JSON object, is returned as it is), so that the genome's reading sees only the genome.
pub fn without_champion(text: &str) -> std::borrow::Cow<'_, str> {
    if !text.contains(&format!("\"{CHAMPION_KEY}\"")) {
        return std::borrow::Cow::Borrowed(text);
    }
    match serde_json::from_str::<serde_json::Value>(text) {
        Ok(serde_json::Value::Object(mut map)) if map.contains_key(CHAMPION_KEY) => {
            map.remove(CHAMPION_KEY);
            let mut out =
                serde_json::to_string_pretty(&serde_json::Value::Object(map)).unwrap_or_default();
            out.push('\n');
            std::borrow::Cow::Owned(out)
        }
        _ => std::borrow::Cow::Borrowed(text),
    }
}

impl GraphGenome {
    /// The genome read from its JSON text form, checked against `limits`. Its sizes (nodes,
    /// connections, neurons, inputs) are checked first, on a reading that keeps nothing but
    /// counts, so that a file far beyond the limits is refused before it is built.
    pub fn from_text(text: &str, limits: &GraphLimits) -> Result<GraphGenome, DevelopError> {
        GraphGenome::read_json(text, limits).map_err(|e| match e {
            Err(e) => DevelopError(format!(
                "not a graph genome: line {}, column {}: {}",
                e.line(),
                e.column(),
                json_error_in_words(text, &e)
            )),
            Ok(problem) => DevelopError(problem),
        })
    }

    /// [`GraphGenome::from_text`] for the file `name`: an error in the JSON itself (a `NaN`,
    /// text after the genome, a missing comma) is pointed at in the file, at its line and
    /// column; a genome beyond the limits names its file.
    pub fn from_file_text(
        name: &str,
        text: &str,
        limits: &GraphLimits,
    ) -> Result<GraphGenome, Diagnostic> {
        GraphGenome::read_json(text, limits).map_err(|e| match e {
            Err(e) => {
                let source = lang::Source::new(name, text);
                let at = json_error_offset(&source, &e);
                Diagnostic::at(
                    DiagnosticKind::Syntax,
                    &source,
                    Span::new(at, at + 1),
                    format!("not a graph genome: {}", json_error_in_words(text, &e)),
                )
            }
            Ok(problem) => {
                Diagnostic::without_location(DiagnosticKind::Semantic, format!("{name}: {problem}"))
            }
        })
    }

    /// The genome in `text`, checked against `limits`: `Err(Err(e))` when the text is no
    /// genome's JSON, `Err(Ok(problem))` when the genome is beyond the limits or malformed.
    fn read_json(
        text: &str,
        limits: &GraphLimits,
    ) -> Result<GraphGenome, Result<String, serde_json::Error>> {
        // A champion's record (`"champion"`, written by a run) is not the genome's.
        let text = &*without_champion(text);
        // A text that is not even shaped like a genome gets the full reading's message.
        if let Ok(shape) = serde_json::from_str::<GenomeShape>(text) {
            shape.check(limits).map_err(Ok)?;
        }
        let g: GraphGenome = serde_json::from_str(text).map_err(Err)?;
        g.check(limits).map_err(Ok)?;
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
        at_most!(self.neurons.len(), limits.max_global_neurons, |n| format!(
            "{n} global neurons"
        ))?;
        let inputs = |where_: &str, neurons: &[NeuronShape]| -> Result<(), String> {
            for (k, g) in neurons.iter().enumerate() {
                at_most!(g.inputs.len(), limits.max_inputs, |n| {
                    format!("{where_} neuron {k} has {n} inputs")
                })?;
            }
            Ok(())
        };
        inputs("global", &self.neurons)?;
        for (i, node) in self.nodes.iter().enumerate() {
            at_most!(node.neurons.len(), limits.max_local_neurons, |n| format!(
                "node {i}: {n} neurons"
            ))?;
            inputs(&format!("node {i}"), &node.neurons)?;
            at_most!(node.connections.len(), limits.max_connections, |n| format!(
                "node {i}: {n} connections"
            ))?;
        }
        Ok(())
    }
}

/// `Err` saying "`what(count)`; at most `limit` allowed (`knob`)" when `count` is over `limit`.
fn at_most(
    count: usize,
    limit: usize,
    knob: &str,
    what: impl FnOnce(usize) -> String,
) -> Result<(), String> {
    if count > limit {
        return Err(format!("{}; at most {limit} allowed ({knob})", what(count)));
    }
    Ok(())
}
