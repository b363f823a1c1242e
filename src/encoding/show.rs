//! A genome file shown for people (`ontogeny genome show`): which encoding's text it is,
//! recognised by its extension (the registry's [`EncodingInfo::text_extension`]) and then by
//! its content (the first encoding, in the registry's order, that reads it back), what it
//! holds ([`Genome::show`]) and what it develops into.

use std::path::Path;

use super::{DevelopError, ENCODINGS, EncodingInfo, Genome};
use crate::creature::{Creature, Summary, counted};
use crate::lang::Diagnostic;
use crate::lsystem::LSystem;

/// The extension of a grammar's text (the L-system genomes' files).
const GRAMMAR_EXTENSION: &str = "lsys";

/// Why a file was not shown as a genome.
#[derive(Debug, thiserror::Error)]
pub enum ShowError {
    /// A grammar file that does not compile: its located error.
    #[error(transparent)]
    Grammar(#[from] Diagnostic),
    /// No encoding reads the file: the file, what was expected, and why each encoding its
    /// extension names refused it.
    #[error("{0}")]
    NotAGenome(String),
}

/// A genome file read for showing: which encoding's it is, the genome as [`Genome::show`]
/// writes it, and what it develops into.
#[derive(Clone, Debug)]
pub struct ShownGenome {
    /// The file, as named.
    pub file: String,
    /// The encoding that reads it.
    pub encoding: &'static str,
    /// The encoding's description.
    pub description: &'static str,
    /// The genome, shown ([`Genome::show`]).
    pub genome: String,
    /// The creature it develops into with the encoding's default limits and development
    /// seed 0, or why it does not develop.
    pub creature: Result<Creature, String>,
}

impl ShownGenome {
    /// As `ontogeny genome show` prints it: a line naming the file and its encoding, the
    /// genome, and what it develops into.
    pub fn text(&self) -> String {
        let development = match &self.creature {
            Ok(creature) => develops_into(creature),
            Err(e) => format!("does not develop: {e}"),
        };
        format!(
            "{}: {} genome ({})\n{}\n{development}",
            self.file, self.encoding, self.description, self.genome
        )
    }

    /// As `ontogeny genome show --json` prints it: `{"file", "encoding", "description",
    /// "genome" (the text above), "develops" (whether it does), "creature"` (what it develops
    /// into, as `grow --json` summarises a creature, without the growth's file, time and
    /// frames; null when it does not develop)`, "error"` (why not, or null)`}`.
    pub fn json(&self) -> serde_json::Value {
        let creature = self.creature.as_ref().ok().map(|c| {
            let mut summary =
                serde_json::to_value(Summary::of("", 0.0, 1, c)).expect("a summary is plain data");
            if let Some(map) = summary.as_object_mut() {
                for key in ["file", "t", "frames"] {
                    map.remove(key);
                }
            }
            summary
        });
        serde_json::json!({
            "file": self.file,
            "encoding": self.encoding,
            "description": self.description,
            "genome": self.genome,
            "develops": self.creature.is_ok(),
            "creature": creature,
            "error": self.creature.as_ref().err(),
        })
    }
}

/// The genome file `path` holding `text`, shown ([`ShownGenome::text`]).
pub fn show_genome_file(path: &Path, text: &str) -> Result<String, ShowError> {
    read_genome_file(path, text).map(|shown| shown.text())
}

/// The genome file `path` holding `text`, read for showing: its encoding, the genome
/// ([`Genome::show`]), and what it develops into with the encoding's default limits and
/// development seed 0. An extension no encoding writes (or none) is tried with every encoding.
pub fn read_genome_file(path: &Path, text: &str) -> Result<ShownGenome, ShowError> {
    let extension = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    let named: Vec<&EncodingInfo> = ENCODINGS
        .iter()
        .filter(|e| e.text_extension == extension)
        .collect();
    if extension == GRAMMAR_EXTENSION {
        // A grammar that does not compile gets its located error once, not once per encoding.
        LSystem::from_text(&path.display().to_string(), text)?;
    }
    let candidates = if named.is_empty() {
        ENCODINGS.iter().collect()
    } else {
        named.clone()
    };
    let mut refusals = Vec::new();
    for e in candidates {
        let shown = crate::with_genome!(e.name, G => shown::<G>(text), |other| Err(
            DevelopError(format!("unknown encoding '{other}'"))
        ));
        match shown {
            Ok((genome, creature)) => {
                return Ok(ShownGenome {
                    file: path.display().to_string(),
                    encoding: e.name,
                    description: e.description,
                    genome,
                    creature,
                });
            }
            Err(why) => refusals.push(format!("as {}: {why}", e.name)),
        }
    }
    let mut message = format!(
        "{}: not a genome file: expected {}",
        path.display(),
        expected()
    );
    if !named.is_empty() {
        message.push_str(&format!("; read {}", refusals.join("; ")));
    }
    Err(ShowError::NotAGenome(message))
}

/// What a genome file is, from the registry: `.lsys (lsystem, ...) or .json (graph)`.
fn expected() -> String {
    let mut extensions: Vec<&str> = ENCODINGS.iter().map(|e| e.text_extension).collect();
    extensions.dedup();
    let groups: Vec<String> = extensions
        .iter()
        .map(|x| {
            let names: Vec<&str> = ENCODINGS
                .iter()
                .filter(|e| e.text_extension == *x)
                .map(|e| e.name)
                .collect();
            format!(".{x} ({})", names.join(", "))
        })
        .collect();
    format!("the text of a genome, {}", groups.join(" or "))
}

/// A genome of type `G` read from `text` with the default limits: shown, and the creature it
/// develops into (or why it does not).
fn shown<G: Genome>(text: &str) -> Result<(String, Result<Creature, String>), DevelopError> {
    let limits = G::Limits::default();
    let genome = G::read_text(text, &limits)?;
    let creature = genome.develop(&limits, 0).map_err(|e| e.to_string());
    Ok((genome.show(), creature))
}

/// What a genome develops into, in a line (parts, joints by kind, neurons, links, validity),
/// then its problems, a line each.
pub(super) fn develops_into(creature: &Creature) -> String {
    let s = Summary::of("", 0.0, 1, creature);
    let kinds: Vec<String> = s.joints.iter().map(|(k, n)| format!("{n} {k}")).collect();
    let mut lines = vec![format!(
        "develops into {}, {} ({}), {}, {}; {}",
        counted(s.parts, "part"),
        counted(creature.joints.len(), "joint"),
        kinds.join(", "),
        counted(s.neurons, "neuron"),
        counted(s.links, "link"),
        if s.valid { "valid" } else { "invalid" }
    )];
    lines.extend(creature.problems.iter().map(ToString::to_string));
    lines.join("\n")
}
