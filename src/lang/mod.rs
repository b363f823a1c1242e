//! The L-system language: parsing text (`*.lsys`) into a syntax tree, with source-located
//! errors.
//!
//! # Tokenising words
//!
//! In axioms, successors and contexts a *word* (letters, digits and `_`, starting with a
//! letter) may stand for one module or for several written together, as in the classic
//! one-letter notation `F-F+F+FF-F-F+F`. A word is split like this:
//!
//! 1. If the whole word is a **known name**, it is one module. Known names are the names
//!    declared with `module`, every rule's predecessor, and the built-in commands
//!    ([`BUILTIN_COMMANDS`] and their maturing twins prefixed `m`).
//! 2. Otherwise it is cut from the left: at each place take the **longest known name** that
//!    starts there; if none does, take **one character** as a module of its own.
//! 3. A parameter list written after the word belongs to the last module of the split.
//!
//! White space always separates modules, and a predecessor is always one module. So with
//! predecessors `a` and `b`, `ab` is `a b`; with `module forward`, `forward(1)` is one module;
//! and `F2` with no known name `F2` is the two modules `F` and `2`.

pub mod ast;
pub mod commands;
pub mod file_kind;
mod parser;
pub mod source;
pub mod suggest;
pub mod textbook;

use std::collections::HashSet;

pub use ast::LsysFile;
pub use file_kind::{FileKind, read_as, read_grammar};
pub use source::{Diagnostic, DiagnosticKind, Location, Source, Span};

use ast::{Expr, ModuleCall, PatternModule, Rule};
use parser::RawModule;

/// The builder's commands (Hornby & Pollack; Matos & Arita; the textbook turtle's symbols),
/// known names for word splitting: the names of [`commands::COMMANDS`]. Each but the
/// textbook's symbols also has a maturing twin prefixed `m` (`mforward`, `mrevolute1`, ...).
pub const BUILTIN_COMMANDS: &[&str] = &commands::NAMES;

/// Whether `name` is a built-in command or its maturing twin.
pub fn is_builtin_command(name: &str) -> bool {
    BUILTIN_COMMANDS.contains(&name)
        || name
            .strip_prefix('m')
            .and_then(commands::Command::from_name)
            .is_some_and(commands::Command::has_maturing_twin)
}

/// Parses an L-system file into its syntax tree, splitting words into modules.
pub fn parse(source: &Source) -> Result<LsysFile, Diagnostic> {
    let raw = parser::parse_raw(source)?;
    let mut file = raw.file;

    let mut known: HashSet<String> = file
        .declared_modules
        .iter()
        .map(|(n, _)| n.clone())
        .collect();
    known.extend(raw.rules.iter().map(|r| r.predecessor.name.clone()));
    let longest_known = known
        .iter()
        .map(String::len)
        .chain(BUILTIN_COMMANDS.iter().map(|c| c.len() + 1))
        .max()
        .unwrap_or(1);
    let splitter = Splitter {
        known: &known,
        longest_known,
    };

    if let Some((calls, span)) = raw.axiom {
        let modules = splitter.modules(calls, &mut file.split_words);
        file.axiom = Some((modules, span));
    }
    for rule in raw.rules {
        let left = splitter.modules(rule.left, &mut file.split_words);
        let right = splitter.modules(rule.right, &mut file.split_words);
        let successor = splitter.modules(rule.successor, &mut file.split_words);
        file.rules.push(Rule {
            left,
            predecessor: rule.predecessor,
            right,
            guard: rule.guard,
            successor,
            solve: rule.solve,
            probability: rule.probability,
            section: rule.section,
            span: rule.span,
        });
    }
    Ok(file)
}

struct Splitter<'k> {
    known: &'k HashSet<String>,
    /// Length in bytes of the longest known name: no longer prefix need be tried.
    longest_known: usize,
}

impl Splitter<'_> {
    fn is_known(&self, name: &str) -> bool {
        self.known.contains(name) || is_builtin_command(name)
    }

    /// Cuts `word` into module names (byte ranges into the word).
    fn split(&self, word: &str) -> Vec<(usize, usize)> {
        if self.is_known(word) {
            return vec![(0, word.len())];
        }
        let mut pieces = Vec::new();
        let mut start = 0;
        while start < word.len() {
            let rest = &word[start..];
            let longest = (1..=rest.len().min(self.longest_known))
                .rev()
                .find(|&len| rest.is_char_boundary(len) && self.is_known(&rest[..len]))
                .unwrap_or_else(|| rest.chars().next().map_or(1, char::len_utf8));
            pieces.push((start, start + longest));
            start += longest;
        }
        pieces
    }

    /// Splits one written module (a word with its parameter list) into modules. `make`
    /// builds a module from a name, its span and the parameters (the last piece gets them).
    /// Returns `None` when the module stays whole.
    fn split_module<T, P>(
        &self,
        word: &str,
        name_span: Span,
        end: usize,
        params: P,
        split_words: &mut Vec<(String, Vec<String>, Span)>,
        make: impl Fn(String, Span, P) -> T,
    ) -> Result<Vec<T>, P>
    where
        P: Default,
    {
        let pieces = self.split(word);
        if pieces.len() == 1 {
            return Err(params);
        }
        split_words.push((
            word.to_string(),
            pieces
                .iter()
                .map(|&(a, b)| word[a..b].to_string())
                .collect(),
            name_span,
        ));
        let last = pieces.len() - 1;
        let mut params = Some(params);
        Ok(pieces
            .iter()
            .enumerate()
            .map(|(i, &(a, b))| {
                let stop = if i == last { end } else { name_span.start + b };
                let span = Span::new(name_span.start + a, stop);
                let own = if i == last {
                    params.take().unwrap_or_default()
                } else {
                    P::default()
                };
                make(word[a..b].to_string(), span, own)
            })
            .collect())
    }

    /// Every module of `raw` with its word split into the modules it names.
    fn modules<M: Splittable>(
        &self,
        raw: Vec<RawModule<M>>,
        split_words: &mut Vec<(String, Vec<String>, Span)>,
    ) -> Vec<M> {
        let mut out = Vec::with_capacity(raw.len());
        for raw in raw {
            if !raw.is_word {
                out.push(raw.module);
                continue;
            }
            let (name, params, span) = raw.module.into_parts();
            match self.split_module(&name, raw.name_span, span.end, params, split_words, M::new) {
                Ok(pieces) => out.extend(pieces),
                Err(params) => out.push(M::new(name, span, params)),
            }
        }
        out
    }
}

/// A module whose written word may name several modules: a call or a pattern, taken apart
/// into its name, parameters and span and made again from them.
trait Splittable: Sized {
    /// Its arguments (a call's) or formal parameters (a pattern's).
    type Params: Default;
    /// Its name, parameters and span.
    fn into_parts(self) -> (String, Self::Params, Span);
    /// The module of this name, span and parameters.
    fn new(name: String, span: Span, params: Self::Params) -> Self;
}

impl Splittable for ModuleCall {
    type Params = Vec<Expr>;
    fn into_parts(self) -> (String, Vec<Expr>, Span) {
        (self.name, self.args, self.span)
    }
    fn new(name: String, span: Span, args: Vec<Expr>) -> Self {
        ModuleCall { name, args, span }
    }
}

impl Splittable for PatternModule {
    type Params = Vec<(String, Span)>;
    fn into_parts(self) -> (String, Vec<(String, Span)>, Span) {
        (self.name, self.params, self.span)
    }
    fn new(name: String, span: Span, params: Vec<(String, Span)>) -> Self {
        PatternModule { name, params, span }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(calls: &[ModuleCall]) -> Vec<&str> {
        calls.iter().map(|c| c.name.as_str()).collect()
    }

    #[test]
    fn one_letter_notation_splits_into_fourteen_modules() {
        let src = Source::new("t", "axiom: F\nF --> F-F+F+FF-F-F+F\n");
        let file = parse(&src).unwrap();
        assert_eq!(file.rules[0].successor.len(), 14);
    }

    #[test]
    fn known_words_are_one_module_and_others_split_by_longest_prefix() {
        let src = Source::new(
            "t",
            "module ar, al\naxiom: forward(1) revolute2 aral Fx(2)\nF --> F\n",
        );
        let file = parse(&src).unwrap();
        let (axiom, _) = file.axiom.unwrap();
        assert_eq!(
            names(&axiom),
            ["forward", "revolute2", "ar", "al", "F", "x"]
        );
        assert!(axiom[5].args.len() == 1 && axiom[4].args.is_empty());
    }

    #[test]
    fn syntax_error_points_at_line_and_column() {
        let src = Source::new("bad.lsys", "axiom: A\nA --> B(1,\n");
        let err = parse(&src).unwrap_err();
        let loc = err.location.clone().unwrap();
        assert_eq!((loc.file.as_str(), loc.line), ("bad.lsys", 2));
        assert!(err.to_string().contains("bad.lsys:2:"), "{err}");
        assert!(err.to_string().contains("expected"), "{err}");
    }
}
