//! The textbook symbols Ontogeny's turtle leaves out: the symbols of *The Algorithmic
//! Beauty of Plants* that it does not support (polygons, colours, surfaces), reported by
//! name at their place. The symbols it supports are rows of the command table
//! ([`super::commands`]).

use super::ast::{LsysFile, ModuleCall};
use super::source::{Diagnostic, DiagnosticKind, Source};

/// The textbook's symbols that Ontogeny does not support, with what they mean there.
pub const UNSUPPORTED: [(&str, &str); 5] = [
    ("'", "the colour index"),
    ("%", "cutting the branch off"),
    (".", "a polygon's vertex"),
    ("~", "a predefined surface"),
    ("$", "rolling the turtle to the horizontal"),
];

/// What a module call that Ontogeny does not support means in the textbook; `None` for any
/// other call. A `}` with no count closes the textbook's polygon `{ … }` when a `{` is open
/// before it in its list (`open`), and is a stray brace otherwise; Ontogeny's `{ … }(n)` is a
/// repeat block.
pub fn unsupported(call: &ModuleCall, open: bool) -> Option<String> {
    if call.name == "}" && call.args.is_empty() {
        return Some(if open {
            "'{ … }' without a count is the textbook's polygon, which Ontogeny does not \
             support; a repeat block is written '{ … }(n)'"
                .to_string()
        } else {
            "'}' closes no '{': a repeat block is written '{ … }(n)'".to_string()
        });
    }
    UNSUPPORTED
        .iter()
        .find(|(name, _)| *name == call.name)
        .map(|(name, meaning)| {
            format!(
                "'{name}' is the textbook's symbol for {meaning}, which Ontogeny does not support"
            )
        })
}

/// The first module of the axiom or a successor that Ontogeny does not support, as an
/// error at its place.
pub fn check_supported(file: &LsysFile, source: &Source) -> Result<(), Diagnostic> {
    let axiom = file.axiom.iter().map(|(calls, _)| calls);
    let successors = file.rules.iter().map(|r| &r.successor);
    for calls in axiom.chain(successors) {
        // How many `{` are open before each call of the list.
        let mut open = 0usize;
        for call in calls {
            if let Some(message) = unsupported(call, open > 0) {
                return Err(Diagnostic::at(
                    DiagnosticKind::Semantic,
                    source,
                    call.span,
                    message,
                ));
            }
            match call.name.as_str() {
                "{" => open += 1,
                "}" => open = open.saturating_sub(1),
                _ => {}
            }
        }
    }
    Ok(())
}
