//! What a file given to a verb is, told from its first bytes and its name before it is parsed:
//! a grammar, or one of the other files Ontogeny writes or a user may pick up by mistake (a
//! MuJoCo model, a growth's frames, a recording, a creature, a graph genome, a run's store, a
//! picture, a configuration), so that a message can say what it is and which command takes it
//! instead of reporting the grammar's syntax error at its first character.

use std::path::Path;
use std::sync::Arc;

use super::{Diagnostic, DiagnosticKind, Source};

/// What a file is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FileKind {
    /// An L-system (`.lsys`), or a file nothing else was recognised in.
    Grammar,
    /// A MuJoCo model (an XML file whose root is `<mujoco>`).
    Mjcf,
    /// Another XML file (SVG pictures included).
    Xml,
    /// The frames of a growth (`frames.jsonl`, written by `grow --out`): one JSON object
    /// per line, a step, its time and the creature.
    GrowthFrames,
    /// A recording of an evaluation (`recording.json`, written by `eval --record`).
    Recording,
    /// A creature (`creature.json`).
    Creature,
    /// A graph genome (a graph run's `best.json`).
    GraphGenome,
    /// Other JSON.
    Json,
    /// A run's store (`run.sqlite`).
    RunStore,
    /// A PNG picture.
    Png,
    /// A GIF animation.
    Gif,
    /// A configuration of `evolve` or `compare` (TOML).
    Config,
}

impl FileKind {
    /// Tells what the file `path`, whose content is `bytes`, is. Only a positive sign counts
    /// (a magic number, a document that parses as JSON, an `<` where a grammar cannot start,
    /// a `.toml` name): anything else is a [`FileKind::Grammar`], for the parser to judge.
    pub fn of(path: &Path, bytes: &[u8]) -> FileKind {
        let extension = path.extension().and_then(|e| e.to_str()).unwrap_or("");
        if bytes.starts_with(b"SQLite format 3\0") {
            return FileKind::RunStore;
        }
        if bytes.starts_with(b"\x89PNG") {
            return FileKind::Png;
        }
        if bytes.starts_with(b"GIF87a") || bytes.starts_with(b"GIF89a") {
            return FileKind::Gif;
        }
        let Ok(text) = std::str::from_utf8(bytes) else {
            return FileKind::Grammar;
        };
        let text = text.trim_start_matches('\u{feff}').trim_start();
        if text.starts_with('<') {
            // No statement of the language starts with `<`.
            return if text.contains("<mujoco") {
                FileKind::Mjcf
            } else {
                FileKind::Xml
            };
        }
        if text.starts_with(['{', '['])
            && let Some(kind) = json_kind(text, extension == "jsonl")
        {
            return kind;
        }
        if extension == "toml" {
            return FileKind::Config;
        }
        FileKind::Grammar
    }

    /// What the file is, in words ("a MuJoCo model (MJCF)").
    pub fn describe(self) -> &'static str {
        match self {
            FileKind::Grammar => "a grammar",
            FileKind::Mjcf => "a MuJoCo model (MJCF)",
            FileKind::Xml => "an XML file",
            FileKind::GrowthFrames => {
                "the frames of a growth (written by `ontogeny grow --out DIR`)"
            }
            FileKind::Recording => "a recording (written by `ontogeny eval --record DIR`)",
            FileKind::Creature => "a creature",
            FileKind::GraphGenome => "a graph genome",
            FileKind::Json => "a JSON file",
            FileKind::RunStore => "a run's store (SQLite, written by `ontogeny evolve`)",
            FileKind::Png => "a PNG picture",
            FileKind::Gif => "a GIF animation",
            FileKind::Config => "a configuration (TOML)",
        }
    }

    /// Which command takes the file (`path`), when one does.
    pub fn advice(self, path: &Path) -> String {
        let dir = path
            .parent()
            .map(Path::display)
            .map(|d| d.to_string())
            .filter(|d| !d.is_empty())
            .unwrap_or_else(|| ".".to_string());
        let path = path.display();
        match self {
            FileKind::Grammar => {
                format!(
                    "to start a run from its mutants: `ontogeny evolve --init {path} --out DIR`"
                )
            }
            FileKind::Mjcf => {
                "Ontogeny writes MJCF (`ontogeny export`) but does not read it".into()
            }
            FileKind::Png | FileKind::Gif => "open it with an image viewer or a browser".into(),
            FileKind::Xml | FileKind::Json => "no command of Ontogeny reads it".into(),
            FileKind::GrowthFrames => format!("show the growth with `ontogeny view {dir}`"),
            FileKind::Recording => format!(
                "play it with `ontogeny view {dir}`, or draw it again with `ontogeny replay {dir}`"
            ),
            FileKind::Creature => {
                format!("`ontogeny eval {path} --task walker`, `export` and `bench` take it")
            }
            FileKind::GraphGenome => format!(
                "`ontogeny eval {path} --task walker`, `export` and `bench` take it, and \
                 `ontogeny genome show {path}` prints it"
            ),
            FileKind::RunStore => format!(
                "`ontogeny runs show {dir}` prints the run's generations, `ontogeny view {dir}` \
                 shows them"
            ),
            FileKind::Config => {
                format!("`ontogeny evolve --config {path}` (or `compare --config`) reads it")
            }
        }
    }

    /// The refusal of a file of this kind (`path`) where `wanted` is expected: what it is, and
    /// which command takes it.
    pub fn refusal(self, path: &Path, wanted: &str) -> Diagnostic {
        Diagnostic::without_location(
            DiagnosticKind::Semantic,
            format!(
                "{} is {}, not {wanted}: {}",
                path.display(),
                self.describe(),
                self.advice(path)
            ),
        )
    }
}

/// What a text that starts like JSON is, when it is JSON: a document, or lines of documents
/// (JSON Lines, as is a `lines` file of one line) of which only the first is looked at.
fn json_kind(text: &str, lines: bool) -> Option<FileKind> {
    #[derive(serde::Deserialize)]
    struct Probe {
        nodes: Option<serde::de::IgnoredAny>,
        parts: Option<serde::de::IgnoredAny>,
        creature: Option<serde::de::IgnoredAny>,
        frames: Option<serde::de::IgnoredAny>,
    }
    let kind = |probe: Probe, lines: bool| match probe {
        Probe { nodes: Some(_), .. } => FileKind::GraphGenome,
        Probe {
            creature: Some(_),
            frames: None,
            ..
        } if lines => FileKind::GrowthFrames,
        Probe { parts: Some(_), .. } => FileKind::Creature,
        Probe {
            creature: Some(_),
            frames: Some(_),
            ..
        } => FileKind::Recording,
        _ => FileKind::Json,
    };
    if serde_json::from_str::<serde::de::IgnoredAny>(text).is_ok() {
        return Some(serde_json::from_str(text).map_or(FileKind::Json, |p| kind(p, lines)));
    }
    let first = text.lines().next()?;
    serde_json::from_str::<serde::de::IgnoredAny>(first).ok()?;
    Some(serde_json::from_str(first).map_or(FileKind::Json, |p| kind(p, true)))
}

/// Reads the grammar at `path` (`-`: standard input), refusing, with what it is and which
/// command takes it, a file that is something else ([`FileKind::of`]).
pub fn read_grammar(path: &Path) -> Result<Arc<Source>, Diagnostic> {
    read_as(path, &[FileKind::Grammar], "a grammar")
}

/// Reads the file at `path` (`-`: standard input) as a source when it is of one of the
/// `accepted` kinds; any other is refused with what it is, which command takes it, and that
/// `expected` (e.g. "a grammar") was expected.
pub fn read_as(
    path: &Path,
    accepted: &[FileKind],
    expected: &str,
) -> Result<Arc<Source>, Diagnostic> {
    let cannot = |e: std::io::Error| {
        Diagnostic::without_location(
            DiagnosticKind::Semantic,
            format!("cannot read {}: {e}", path.display()),
        )
    };
    let bytes = Source::read_bytes(path).map_err(cannot)?;
    let kind = FileKind::of(path, &bytes);
    if !accepted.contains(&kind) {
        return Err(kind.refusal(path, expected));
    }
    Source::from_bytes(path, bytes).map_err(cannot)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kind(name: &str, text: &str) -> FileKind {
        FileKind::of(Path::new(name), text.as_bytes())
    }

    #[test]
    fn files_are_told_apart_by_their_content() {
        assert_eq!(
            kind("q.xml", "<?xml version=\"1.0\"?>\n<mujoco model=\"q\">"),
            FileKind::Mjcf
        );
        assert_eq!(kind("f.svg", "<svg></svg>"), FileKind::Xml);
        let frame = "{\"step\": 0, \"t\": 0.0, \"creature\": {\"parts\": []}}\n";
        assert_eq!(
            kind("frames.jsonl", &frame.repeat(2)),
            FileKind::GrowthFrames
        );
        assert_eq!(kind("frames.jsonl", frame), FileKind::GrowthFrames);
        assert_eq!(
            kind("c.json", "{\"parts\": [], \"joints\": []}"),
            FileKind::Creature
        );
        assert_eq!(
            kind("r.json", "{\"creature\": {}, \"frames\": []}"),
            FileKind::Recording
        );
        assert_eq!(kind("best.json", "{\"nodes\": []}"), FileKind::GraphGenome);
        assert_eq!(kind("x", "[1, 2]"), FileKind::Json);
        assert_eq!(
            kind("run.sqlite", "SQLite format 3\0..."),
            FileKind::RunStore
        );
        assert_eq!(kind("w.toml", "seed = 1\n"), FileKind::Config);
    }

    #[test]
    fn grammars_are_grammars_even_when_they_start_with_a_bracket() {
        assert_eq!(kind("a.lsys", "axiom: A\nA --> A B\n"), FileKind::Grammar);
        assert_eq!(kind("b.lsys", "[ --> [ A\n"), FileKind::Grammar);
        assert_eq!(kind("c.txt", "{ --> }\n"), FileKind::Grammar);
    }
}
