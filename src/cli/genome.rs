//! `ontogeny genome`: inspect genome files.

use std::path::PathBuf;

use anyhow::Context;
use clap::{Args, Subcommand};
use ontogeny::creature::Severity;
use ontogeny::encoding::{GraphGenome, GraphLimits};

/// Subcommands of `ontogeny genome`.
#[derive(Subcommand)]
pub enum GenomeVerb {
    /// Print a graph genome (a run's `best.json`) readably: its nodes with their
    /// connections and local neurons, its global neurons, and the creature it develops into.
    Show {
        /// The graph genome (JSON).
        file: PathBuf,
    },
}

/// Flags of `ontogeny genome`.
#[derive(Args)]
pub struct GenomeArgs {
    #[command(subcommand)]
    verb: GenomeVerb,
}

/// Reads a graph genome from `file`, checked against the default limits.
pub(super) fn read_graph(file: &std::path::Path) -> anyhow::Result<GraphGenome> {
    let text =
        std::fs::read_to_string(file).with_context(|| format!("cannot read {}", file.display()))?;
    GraphGenome::from_text(&text, &GraphLimits::default())
        .map_err(|e| super::bad(format!("{}: {e}", file.display())))
}

/// Runs `ontogeny genome`.
pub fn run(args: &GenomeArgs) -> anyhow::Result<()> {
    match &args.verb {
        GenomeVerb::Show { file } => {
            let genome = read_graph(file)?;
            say!("{}", genome.describe().trim_end());
            let creature = genome.creature(GraphLimits::default().max_parts);
            let mut kinds = std::collections::BTreeMap::<String, usize>::new();
            for j in &creature.joints {
                let name = serde_json::to_value(j.kind)?
                    .as_str()
                    .unwrap_or("?")
                    .to_string();
                *kinds.entry(name).or_default() += 1;
            }
            say!(
                "develops into {} parts, {} joints ({}), {} neurons, {} links; {}",
                creature.parts.len(),
                creature.joints.len(),
                kinds
                    .iter()
                    .map(|(k, n)| format!("{n} {k}"))
                    .collect::<Vec<_>>()
                    .join(", "),
                creature.brain.neurons.len(),
                creature.brain.links.len(),
                if creature.is_valid() {
                    "valid"
                } else {
                    "invalid"
                }
            );
            for p in &creature.problems {
                let level = match p.severity {
                    Severity::Warning => "warning",
                    Severity::Error => "error",
                };
                say!("{level}: {}", p.message);
            }
            Ok(())
        }
    }
}
