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

/// The genome file `path` holding `text`, shown: a line naming the file and its encoding,
/// the genome ([`Genome::show`]), and what it develops into with the encoding's default
/// limits and development seed 0. An extension no encoding writes (or none) is tried with
/// every encoding.
pub fn show_genome_file(path: &Path, text: &str) -> Result<String, ShowError> {
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
            Ok(shown) => {
                return Ok(format!(
                    "{}: {} genome ({})\n{shown}",
                    path.display(),
                    e.name,
                    e.description
                ));
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

/// A genome of type `G` read from `text` with the default limits, shown with what it
/// develops into.
fn shown<G: Genome>(text: &str) -> Result<String, DevelopError> {
    let limits = G::Limits::default();
    let genome = G::read_text(text, &limits)?;
    let development = match genome.develop(&limits, 0) {
        Ok(creature) => develops_into(&creature),
        Err(e) => format!("does not develop: {e}"),
    };
    Ok(format!("{}\n{development}", genome.show()))
}

/// What a genome develops into, in a line (parts, joints by kind, neurons, links, validity),
/// then its problems, a line each.
fn develops_into(creature: &Creature) -> String {
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
