//! Reading the creature a file describes, whatever its kind: an L-system (`.lsys`, a grammar
//! or a direct genome, grown to its last frame), a `creature.json`, or a graph genome's JSON
//! (a run's `best.json`), each checked before use. `ontogeny eval`, `export` and `bench` and
//! the Python package read their creature through [`load_creature`].

use std::path::{Path, PathBuf};

use crate::creature::repeats::said_once;
use crate::creature::{Creature, Severity};
use crate::develop::{BuildOptions, grow_last};
use crate::lang::{Diagnostic, DiagnosticKind, FileKind};
use crate::lsystem::{DefineOverride, DeriveOptions, LSystem, Overrides, print};

use super::{GraphGenome, GraphLimits};

/// How an L-system file is grown into its creature (a JSON file ignores all but `max_parts`).
#[derive(Clone, Debug)]
pub struct LoadOptions {
    /// The derivation's options (seed, environment, continuous time, most modules).
    pub derive: DeriveOptions,
    /// Values in place of the grammar's defines ([`LSystem::parse_with`]); the seed in
    /// place of its `seed:` is `derive.seed` (the grammar is compiled with it).
    pub defines: Vec<DefineOverride>,
    /// Discrete derivation steps (default: the file's `derivation length:`).
    pub steps: Option<u64>,
    /// Most parts: a creature grown from an L-system with more is invalid, a
    /// `creature.json` with more is refused.
    pub max_parts: usize,
    /// Set, it stops the growth of an L-system before its next frame (see
    /// [`BuildOptions::cancel`]).
    pub cancel: crate::cancel::Cancel,
    /// A habitat's chemical array: an L-system whose `environment:` has as many slots grows
    /// from it (`derive.env` still applies over it), and a JSON creature whose controller's
    /// array has as many slots gets it, as [`super::Genome::develop_in`] does; another length
    /// leaves the creature's own array.
    pub habitat_environment: Option<Vec<f64>>,
}

impl Default for LoadOptions {
    fn default() -> Self {
        LoadOptions {
            derive: DeriveOptions::default(),
            defines: Vec::new(),
            steps: None,
            max_parts: BuildOptions::default().max_parts,
            cancel: crate::cancel::Cancel::default(),
            habitat_environment: None,
        }
    }
}

/// A creature read from a file, with the notes and warnings to show its reader (a grammar
/// without a derivation length, the builder's warnings).
#[derive(Clone, Debug)]
pub struct Loaded {
    /// The creature (an L-system's may be invalid: its problems say why).
    pub creature: Creature,
    /// Notes and warnings, one line each, in the order they arose.
    pub notes: Vec<String>,
}

/// Why a file gave no creature.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    /// The file could not be read.
    #[error("cannot read {}: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        source: std::io::Error,
    },
    /// The file is not a usable creature: a malformed grammar (with its line and column), a
    /// file of another kind, a creature out of bounds.
    #[error("{0}")]
    Bad(Diagnostic),
}

impl From<Diagnostic> for LoadError {
    fn from(d: Diagnostic) -> Self {
        LoadError::Bad(d)
    }
}

fn bad(message: String) -> LoadError {
    LoadError::Bad(Diagnostic::without_location(
        DiagnosticKind::Semantic,
        message,
    ))
}

/// Reads the creature `file` describes: an L-system grown to its last frame with `options`
/// (invalid beyond `max_parts` parts; `progress` sees the growth's fraction done), a
/// `creature.json`, which must be well formed and have at most `max_parts` parts, or a graph
/// genome's JSON (checked against the default limits before it develops, and developed with
/// them). A file is a JSON file by its `.json` extension.
pub fn load_creature(
    file: &Path,
    options: &LoadOptions,
    progress: &mut dyn FnMut(f64),
) -> Result<Loaded, LoadError> {
    if file.extension().is_some_and(|e| e == "json") {
        let text = crate::input::read_to_string(file).map_err(|source| LoadError::Read {
            path: file.to_path_buf(),
            source,
        })?;
        return creature_json(file, &text, options.max_parts).map(|mut creature| {
            if let Some(values) = options
                .habitat_environment
                .as_ref()
                .filter(|v| v.len() == creature.environment.len())
            {
                creature.environment = values.clone();
            }
            Loaded {
                creature,
                notes: Vec::new(),
            }
        });
    }
    let overrides = Overrides {
        defines: options.defines.clone(),
        seed: options.derive.seed,
    };
    let lsys = LSystem::from_path_with(file, &overrides)?;
    grow_grammar(&lsys, options, progress)
}

/// The creature of a JSON file's `text`: a graph genome (developed with the default limits),
/// or a creature, well formed and with at most `max_parts` parts; a file that is neither (a
/// recording, ...) is refused with what it is.
fn creature_json(file: &Path, text: &str, max_parts: usize) -> Result<Creature, LoadError> {
    match FileKind::of(file, text.as_bytes()) {
        FileKind::GraphGenome => {
            return graph_genome(file, text);
        }
        // A graph genome broken as JSON (a NaN, text after its end) is no JSON file: it is
        // read as the graph genome it names itself, for its error's place.
        FileKind::Json | FileKind::Grammar if looks_like_graph_genome(text) => {
            return graph_genome(file, text);
        }
        FileKind::Creature | FileKind::Json | FileKind::Grammar => {}
        other => return Err(other.refusal(file, "a creature").into()),
    }
    let creature: Creature = serde_json::from_str(text)
        .map_err(|e| bad(format!("{}: not a creature: {e}", file.display())))?;
    creature.check_file(max_parts).map_err(|problem| {
        bad(format!(
            "{}: not a usable creature: {problem}",
            file.display()
        ))
    })?;
    Ok(creature)
}

/// The creature of a graph genome's JSON `text` (read from `file`), developed with the
/// default limits; an error in the JSON is placed at its line and column.
fn graph_genome(file: &Path, text: &str) -> Result<Creature, LoadError> {
    let limits = GraphLimits::default();
    let genome = GraphGenome::from_file_text(&file.display().to_string(), text, &limits)?;
    Ok(Creature {
        projectile: genome.projectile,
        ..genome.creature(limits.max_parts)
    })
}

/// Whether a text that does not read as JSON is a graph genome all the same: it has the
/// genome's `"nodes"` and not a creature's `"parts"`.
fn looks_like_graph_genome(text: &str) -> bool {
    text.contains("\"nodes\"") && !text.contains("\"parts\"")
}

/// Grows `lsys` to its last frame with `options`, as `ontogeny grow` does, cut short where
/// the creature is decided ([`grow_last`]); the notes are the grammar's findings
/// ([`LSystem::findings`]), the mode's ([`print::check_mode`]), the shortcut taken, if any,
/// and the builder's warnings, each once (its errors make the creature invalid, which an
/// evaluation reports).
pub fn grow_grammar(
    lsys: &LSystem,
    options: &LoadOptions,
    progress: &mut dyn FnMut(f64),
) -> Result<Loaded, LoadError> {
    let mut notes: Vec<String> = lsys.findings().iter().map(|d| d.warning()).collect();
    let in_habitat;
    let options = match &options.habitat_environment {
        Some(values) if values.len() == lsys.environment().len() => {
            let mut derive = options.derive.clone();
            derive.env = values
                .iter()
                .copied()
                .enumerate()
                .chain(derive.env)
                .collect();
            in_habitat = LoadOptions {
                derive,
                ..options.clone()
            };
            &in_habitat
        }
        _ => options,
    };
    notes.extend(print::check_mode(
        lsys,
        &options.derive,
        options.steps,
        "building",
    )?);
    let build_options = BuildOptions {
        max_parts: options.max_parts,
        cancel: options.cancel.clone(),
        ..BuildOptions::default()
    };
    let last = grow_last(
        lsys,
        &options.derive,
        options.steps,
        &build_options,
        progress,
    )?;
    notes.extend(last.shortcut.map(|s| format!("note: {s}")));
    // A genome's `# projectile:` line (or a hand-written one) names the projectile it throws.
    let projectile = super::projectile::read_line(lsys.source().text())
        .map_err(|e| bad(format!("{}: {}", lsys.source().name(), e.0)))?;
    let creature = Creature {
        projectile,
        ..last.frame.creature
    };
    notes.extend(said_once(
        creature
            .problems
            .iter()
            .filter(|p| p.severity == Severity::Warning)
            .map(|p| p.to_string()),
    ));
    Ok(Loaded { creature, notes })
}
