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
//!
//! A word that step 2 cuts into pieces that are not all known names (`Tial` read as `T i a
//! l`, `foward` as `f o w a r d`) is most likely a typo: it is recorded in
//! [`LsysFile::split_words`] with the known name it is closest to, and every verb shows it
//! (see `LSystem::findings`). In a file that declares its modules with `module`, such a word
//! is an error. The textbook turtle's letters `F` and `f` are known names too.

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

use ast::{Expr, ModuleCall, PatternModule, Rule, SplitWord};
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

/// How many parameters the built-in command (or maturing twin) `name` takes, and what the
/// one it takes means; `None` when `name` is not a built-in command. A maturing twin takes
/// one: the command's own (`mforward(l)`), or its age when the command takes none
/// (`mrevolute1(x)`).
pub fn builtin_parameters(name: &str) -> Option<(usize, &'static str)> {
    use commands::Command;
    if let Some(command) = Command::from_name(name) {
        return Some((command.parameters(), command.argument().describe()));
    }
    let twin = name.strip_prefix('m').and_then(Command::from_name)?;
    let what = match twin.argument() {
        commands::Argument::None => "its age",
        argument => argument.describe(),
    };
    Some((1, what))
}

/// The letters of the textbook turtle (*The Algorithmic Beauty of Plants*): `F` builds a part,
/// `f` moves without building. Known names for word splitting, as the built-in commands are.
pub const TEXTBOOK_LETTERS: &[&str] = &["F", "f"];

/// Parses `source` as one expression of the language and nothing else (`D_w - 0.5 * drag`):
/// its numbers, names, operators and functions, as a rule's parameters and guards write them.
pub fn parse_expression(source: &Source) -> Result<Expr, Diagnostic> {
    parser::parse_expression(source)
}

/// Parses an L-system file into its syntax tree, splitting words into modules. In a file that
/// declares its modules, a word that is not made of known names is an error
/// (`undeclared_word`).
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
    file.split_words.sort_by_key(|w| w.span.start);
    if let Some(diagnostic) = undeclared_word(source, &file) {
        return Err(diagnostic);
    }
    Ok(file)
}

/// The error for the first word of a file that declares its modules (`module Torso, Legs`)
/// that is not made entirely of known names (declared modules, rules' predecessors, built-in
/// commands, the textbook letters): `None` when there is none, or the file declares nothing.
/// A word made of known names (`FF` as `F F`) and a word of one character stay allowed.
fn undeclared_word(source: &Source, file: &LsysFile) -> Option<Diagnostic> {
    let (_, declared_at) = file.declared_modules.first()?;
    let word = file.split_words.iter().find(|w| !w.all_known())?;
    let (line, _) = source.line_col(declared_at.start);
    Some(
        Diagnostic::at(
            DiagnosticKind::Semantic,
            source,
            word.span,
            format!(
                "'{}' is not a declared module: it would be read as the modules {}{}",
                word.word,
                word.pieces.join(" "),
                did_you_mean(word.suggestion.as_deref())
            ),
        )
        .with_note(format!(
            "this file declares its modules (line {line}): a word must be a declared module, a \
             rule's predecessor or a built-in command, or be written of them ('FF' is 'F F')"
        )),
    )
}

/// ` (did you mean `NAME`?)`, or nothing.
pub fn did_you_mean(name: Option<&str>) -> String {
    name.map_or(String::new(), |n| format!(" (did you mean `{n}`?)"))
}

struct Splitter<'k> {
    known: &'k HashSet<String>,
    /// Length in bytes of the longest known name: no longer prefix need be tried.
    longest_known: usize,
}

impl Splitter<'_> {
    fn is_known(&self, name: &str) -> bool {
        self.known.contains(name) || is_builtin_command(name) || TEXTBOOK_LETTERS.contains(&name)
    }

    /// The known name of two or more characters closest to `word` ([`suggest::closest`]):
    /// what a word that is not made of known names was probably meant to be. Of names
    /// equally close, the file's own (in alphabetical order) come before the built-in
    /// commands, so that the answer never depends on the order of a set.
    fn suggestion(&self, word: &str) -> Option<String> {
        let mut own: Vec<&str> = self.known.iter().map(String::as_str).collect();
        own.sort_unstable();
        let twins: Vec<String> = BUILTIN_COMMANDS.iter().map(|c| format!("m{c}")).collect();
        let names = own
            .into_iter()
            .chain(BUILTIN_COMMANDS.iter().copied())
            .chain(twins.iter().map(String::as_str))
            .filter(|n| n.chars().count() > 1);
        suggest::closest(word, names).map(str::to_string)
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
        split_words: &mut Vec<SplitWord>,
        make: impl Fn(String, Span, P) -> T,
    ) -> Result<Vec<T>, P>
    where
        P: Default,
    {
        let pieces = self.split(word);
        if pieces.len() == 1 {
            return Err(params);
        }
        let names: Vec<String> = pieces
            .iter()
            .map(|&(a, b)| word[a..b].to_string())
            .collect();
        let known: Vec<bool> = names.iter().map(|n| self.is_known(n)).collect();
        let suggestion = match known.iter().all(|&k| k) {
            true => None,
            false => self.suggestion(word),
        };
        split_words.push(SplitWord {
            word: word.to_string(),
            pieces: names,
            known,
            suggestion,
            span: name_span,
        });
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
        split_words: &mut Vec<SplitWord>,
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
            "axiom: forward(1) revolute2 aral Fx(2)\nar --> ar\nal --> al\n",
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
    fn a_file_that_declares_its_modules_refuses_a_word_not_made_of_known_names() {
        let src = Source::new("t", "module ar, al\naxiom: aral FF x Fx(2)\n");
        let err = parse(&src).unwrap_err();
        assert_eq!(
            err.message,
            "'Fx' is not a declared module: it would be read as the modules F x"
        );
        assert_eq!(err.location.unwrap().column, 18);
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
