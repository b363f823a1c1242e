//! Source text, byte spans into it, and source-located diagnostics.

use std::fmt;
use std::sync::Arc;

/// A byte range `[start, end)` into a [`Source`]'s text.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Span {
    /// First byte of the range.
    pub start: usize,
    /// One past the last byte of the range.
    pub end: usize,
}

impl Span {
    /// A span from `start` to `end` (bytes).
    pub fn new(start: usize, end: usize) -> Self {
        Span { start, end }
    }

    /// The smallest span covering both `self` and `other`.
    pub fn join(self, other: Span) -> Span {
        Span::new(self.start.min(other.start), self.end.max(other.end))
    }
}

/// The text of one L-system file and the name it is reported under.
#[derive(Debug)]
pub struct Source {
    name: String,
    text: String,
    line_starts: Vec<usize>,
}

impl Source {
    /// Wraps `text`, reported in diagnostics as coming from `name` (usually its path).
    pub fn new(name: impl Into<String>, text: impl Into<String>) -> Arc<Source> {
        let text = text.into();
        // Lines end at "\n", "\r\n" or a lone "\r", as the grammar's NEWLINE does.
        let bytes = text.as_bytes();
        let line_starts = std::iter::once(0)
            .chain(bytes.iter().enumerate().filter_map(|(i, &b)| match b {
                b'\n' => Some(i + 1),
                b'\r' if bytes.get(i + 1) != Some(&b'\n') => Some(i + 1),
                _ => None,
            }))
            .collect();
        Arc::new(Source {
            name: name.into(),
            text,
            line_starts,
        })
    }

    /// Reads a file ([`crate::input::read`]: within the cap on an input's size, a byte-order
    /// mark left out); the path becomes the source's name. The path `-` reads standard input,
    /// named `<stdin>`.
    pub fn read(path: &std::path::Path) -> std::io::Result<Arc<Source>> {
        Source::from_bytes(path, Source::read_bytes(path)?)
    }

    /// The bytes of the file at `path` (`-`: standard input), as [`crate::input::read`] reads
    /// them.
    pub fn read_bytes(path: &std::path::Path) -> std::io::Result<Vec<u8>> {
        crate::input::read(path)
    }

    /// The source of `bytes` read from `path` (`-`: standard input, named `<stdin>`), which
    /// must be UTF-8 text.
    pub fn from_bytes(path: &std::path::Path, bytes: Vec<u8>) -> std::io::Result<Arc<Source>> {
        let text = crate::input::text(bytes)?;
        let name = if path.as_os_str() == "-" {
            "<stdin>".to_string()
        } else {
            path.display().to_string()
        };
        Ok(Source::new(name, text))
    }

    /// The name diagnostics report (a path, or `<string>`).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The whole text.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// 1-based line and column (in characters) of a byte offset.
    pub fn line_col(&self, offset: usize) -> (usize, usize) {
        let offset = self.floor_char_boundary(offset.min(self.text.len()));
        let line = match self.line_starts.binary_search(&offset) {
            Ok(i) => i,
            Err(i) => i - 1,
        };
        let column = self.text[self.line_starts[line]..offset].chars().count() + 1;
        (line + 1, column)
    }

    /// The byte offset where a 1-based line starts.
    pub fn line_start(&self, line: usize) -> usize {
        self.line_starts[line - 1]
    }

    /// The text of a 1-based line, without its line ending.
    pub fn line_text(&self, line: usize) -> &str {
        let start = self.line_starts[line - 1];
        let end = self
            .line_starts
            .get(line)
            .map_or(self.text.len(), |&next| next);
        self.text[start..end].trim_end_matches(['\r', '\n'])
    }

    fn floor_char_boundary(&self, mut offset: usize) -> usize {
        while !self.text.is_char_boundary(offset) {
            offset -= 1;
        }
        offset
    }
}

/// What stage found a problem.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DiagnosticKind {
    /// The text does not follow the grammar.
    Syntax,
    /// The text parses but means nothing sensible (unknown name, wrong arity, ...).
    Semantic,
    /// Something went wrong while deriving (division by zero, runaway growth, ...).
    Runtime,
    /// The work was stopped by its caller's [`Cancel`](crate::cancel::Cancel) token, not by
    /// anything in the text.
    Interrupted,
}

/// Where in a file a diagnostic points.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Location {
    /// The file's name.
    pub file: String,
    /// 1-based line.
    pub line: usize,
    /// 1-based column, in characters.
    pub column: usize,
    /// The text of that line.
    pub line_text: String,
    /// How many characters to underline (at least 1).
    pub width: usize,
}

/// A problem with an L-system, with the place in the file it comes from.
///
/// Its `Display` shows the message, `file:line:column`, the line, and a caret under the spot:
///
/// ```text
/// error: unknown name 'GROWHT'
///  --> plant.lsys:4:22
///   |
/// 4 | A(x) --> A(x * GROWHT)
///   |                ^^^^^^
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    /// Which stage found it.
    pub kind: DiagnosticKind,
    /// What is wrong, in words.
    pub message: String,
    /// Where, when there is a place in a source to point at.
    pub location: Option<Box<Location>>,
    /// Extra lines of explanation.
    pub notes: Vec<String>,
}

impl Diagnostic {
    /// A diagnostic pointing at `span` in `source`.
    pub fn at(
        kind: DiagnosticKind,
        source: &Source,
        span: Span,
        message: impl Into<String>,
    ) -> Self {
        let (line, column) = source.line_col(span.start);
        let line_text = source.line_text(line).to_string();
        let (end_line, end_column) = source.line_col(span.end);
        let width = if end_line == line && end_column > column {
            end_column - column
        } else {
            1
        };
        Diagnostic {
            kind,
            message: message.into(),
            location: Some(Box::new(Location {
                file: source.name().to_string(),
                line,
                column,
                line_text,
                width,
            })),
            notes: Vec::new(),
        }
    }

    /// A diagnostic with no place to point at.
    pub fn without_location(kind: DiagnosticKind, message: impl Into<String>) -> Self {
        Diagnostic {
            kind,
            message: message.into(),
            location: None,
            notes: Vec::new(),
        }
    }

    /// Adds a line of explanation.
    pub fn with_note(mut self, note: impl Into<String>) -> Self {
        self.notes.push(note.into());
        self
    }
}

impl Diagnostic {
    /// The diagnostic shown as a warning: as its `Display`, headed `warning:` instead of
    /// `error:` (for findings that do not stop the work, such as a word read as modules that
    /// are not known names).
    pub fn warning(&self) -> String {
        struct Warning<'a>(&'a Diagnostic);
        impl fmt::Display for Warning<'_> {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                self.0.render(f, "warning")
            }
        }
        Warning(self).to_string()
    }

    /// The message headed by `level`, then the place with a caret under it, then the notes.
    fn render(&self, f: &mut fmt::Formatter<'_>, level: &str) -> fmt::Result {
        write!(f, "{level}: {}", self.message)?;
        if let Some(loc) = &self.location {
            let gutter = loc.line.to_string().len();
            let pad = " ".repeat(gutter);
            writeln!(f)?;
            writeln!(f, "{pad}--> {}:{}:{}", loc.file, loc.line, loc.column)?;
            writeln!(f, "{pad} |")?;
            writeln!(f, "{} | {}", loc.line, loc.line_text)?;
            // Tabs before the spot keep the caret aligned.
            let lead: String = loc
                .line_text
                .chars()
                .take(loc.column - 1)
                .map(|c| if c == '\t' { '\t' } else { ' ' })
                .collect();
            write!(f, "{pad} | {lead}{}", "^".repeat(loc.width.max(1)))?;
        }
        for note in &self.notes {
            write!(f, "\n  = {note}")?;
        }
        Ok(())
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.render(f, "error")
    }
}

impl std::error::Error for Diagnostic {}

/// Interrupted work as a diagnostic of kind [`DiagnosticKind::Interrupted`], for the loops
/// whose error is a [`Diagnostic`] (growth).
impl From<crate::cancel::Interrupted> for Diagnostic {
    fn from(interrupted: crate::cancel::Interrupted) -> Self {
        Diagnostic::without_location(DiagnosticKind::Interrupted, interrupted.to_string())
    }
}
