//! From text to [`LsysFile`] with pest: the grammar lives in `grammar/lsystem.pest`.

use std::sync::OnceLock;

use pest::Parser;
use pest::iterators::Pair;
use pest::pratt_parser::{Assoc, Op, PrattParser};

use super::ast::{
    BinaryOp, Define, Derivative, Expr, Heading, LsysFile, ModuleCall, PatternModule, RuleOf,
    Section, Timing, UnaryOp,
};
use super::source::{Diagnostic, DiagnosticKind, Source, Span};

#[derive(pest_derive::Parser)]
#[grammar = "../grammar/lsystem.pest"]
struct LsysParser;

/// Most operators one expression may hold.
const MAX_OPERATORS: usize = 1000;
/// Deepest an expression tree may be (keeps evaluation's recursion bounded).
const MAX_EXPR_DEPTH: usize = 256;

/// A module before its word is split: a call (in an axiom or successor) or a pattern.
pub(super) struct RawModule<M> {
    pub module: M,
    /// Where the name alone stands.
    pub name_span: Span,
    /// Whether the name is a word (splittable) rather than a special character.
    pub is_word: bool,
}

/// A module in an axiom or successor before its word is split.
pub(super) type RawCall = RawModule<ModuleCall>;

/// A module in a pattern before its word is split.
pub(super) type RawPattern = RawModule<PatternModule>;

/// A rule whose module lists are still raw words.
pub(super) type RawRule = RuleOf<RawPattern, RawCall>;

/// The file before words are split.
#[derive(Default)]
pub(super) struct RawFile {
    pub file: LsysFile,
    pub axiom: Option<(Vec<RawCall>, Span)>,
    pub rules: Vec<RawRule>,
}

fn human_rule_name(grammar_rule: &Rule) -> String {
    match grammar_rule {
        Rule::EOI => "end of line",
        Rule::file | Rule::statement | Rule::section => "a statement",
        Rule::define => "'define NAME = value'",
        Rule::module_decl => "'module' and names",
        Rule::seed_stmt => "'seed: N'",
        Rule::axiom_stmt => "'axiom: ...'",
        Rule::length_stmt => "'derivation length: N'",
        Rule::ignore_stmt => "'ignore: ...'",
        Rule::productions_header => "'productions:'",
        Rule::interpretation_header => "'interpretation:'",
        Rule::rule => "a rule ('predecessor --> successor')",
        Rule::arrow => "'-->'",
        Rule::left_context | Rule::right_context => "a context module",
        Rule::predecessor => "a predecessor module",
        Rule::guard => "a condition",
        Rule::probability => "a probability",
        Rule::successor => "successor modules",
        Rule::pattern_module => "a module",
        Rule::formal_params => "parameter names in parentheses",
        Rule::formal => "a parameter name or a number",
        Rule::module_list => "modules",
        Rule::module_call => "a module",
        Rule::actual_params => "parameter values in parentheses",
        Rule::symbol_name | Rule::word | Rule::query | Rule::special => "a module name",
        Rule::expr | Rule::expression => "an expression",
        Rule::infix => "an operator",
        Rule::or => "'||'",
        Rule::and => "'&&'",
        Rule::eq => "'=='",
        Rule::ne => "'!='",
        Rule::le => "'<='",
        Rule::ge => "'>='",
        Rule::lt => "'<'",
        Rule::gt => "'>'",
        Rule::add => "'+'",
        Rule::sub => "'-'",
        Rule::mul => "'*'",
        Rule::div => "'/'",
        Rule::rem => "'%'",
        Rule::pow => "'^'",
        Rule::prefix | Rule::neg | Rule::not => "a sign",
        Rule::primary => "a value",
        Rule::call => "a function call",
        Rule::name => "a name",
        Rule::number => "a number",
        Rule::integer => "a whole number",
        Rule::eol => "end of line",
        Rule::time_stmt => "'time: T'",
        Rule::dt_stmt => "'dt: D'",
        Rule::timing_stmt => "'timing: exact' or 'timing: iterative'",
        Rule::timing_mode => "'exact' or 'iterative'",
        Rule::environment_stmt => "'environment:' and numbers",
        Rule::angle_stmt => "'angle: degrees'",
        Rule::step_stmt => "'step: length'",
        Rule::heading_stmt => "'heading: up' or 'heading: ground'",
        Rule::heading_value => "'up' or 'ground'",
        Rule::signed_number => "a number",
        Rule::solve => "'solve' and ODEs",
        Rule::kw_solve => "'solve'",
        Rule::derivative => "an ODE 'dx/dt = expr'",
        Rule::d_name => "'d' and a parameter name, as in 'dx/dt'",
        Rule::kw_define => "'define'",
        Rule::kw_module => "'module'",
        Rule::ident_char => "a letter, digit or '_'",
        Rule::WHITESPACE => "white space",
        Rule::COMMENT => "a comment",
    }
    .to_string()
}

fn pratt() -> &'static PrattParser<Rule> {
    static PRATT: OnceLock<PrattParser<Rule>> = OnceLock::new();
    PRATT.get_or_init(|| {
        PrattParser::new()
            .op(Op::infix(Rule::or, Assoc::Left))
            .op(Op::infix(Rule::and, Assoc::Left))
            .op(Op::infix(Rule::eq, Assoc::Left) | Op::infix(Rule::ne, Assoc::Left))
            .op(Op::infix(Rule::lt, Assoc::Left)
                | Op::infix(Rule::le, Assoc::Left)
                | Op::infix(Rule::gt, Assoc::Left)
                | Op::infix(Rule::ge, Assoc::Left))
            .op(Op::infix(Rule::add, Assoc::Left) | Op::infix(Rule::sub, Assoc::Left))
            .op(Op::infix(Rule::mul, Assoc::Left)
                | Op::infix(Rule::div, Assoc::Left)
                | Op::infix(Rule::rem, Assoc::Left))
            .op(Op::prefix(Rule::neg) | Op::prefix(Rule::not))
            .op(Op::infix(Rule::pow, Assoc::Right))
    })
}

fn span_of(pair: &Pair<'_, Rule>) -> Span {
    let s = pair.as_span();
    Span::new(s.start(), s.end())
}

/// Parses `source` into the raw file, before word splitting.
pub(super) fn parse_raw(source: &Source) -> Result<RawFile, Diagnostic> {
    let pairs =
        LsysParser::parse(Rule::file, source.text()).map_err(|e| syntax_error(source, e))?;
    let mut builder = Builder {
        source,
        raw: RawFile::default(),
        section: Section::Productions,
    };
    for pair in pairs.flatten().filter(|p| p.as_rule() == Rule::file) {
        for statement in pair.into_inner() {
            builder.statement(statement)?;
        }
    }
    Ok(builder.raw)
}

/// Parses `source` as one expression and nothing else (the grammar's `expression`): the
/// language's own expressions, outside a file.
pub(super) fn parse_expression(source: &Source) -> Result<Expr, Diagnostic> {
    let pairs = LsysParser::parse(Rule::expression, source.text())
        .map_err(|e| expression_syntax_error(source, e))?;
    let builder = Builder {
        source,
        raw: RawFile::default(),
        section: Section::Productions,
    };
    let expr = pairs
        .flatten()
        .find(|p| p.as_rule() == Rule::expr)
        .expect("grammar: an expression holds an expr");
    builder.expr(expr, 0)
}

/// The syntax error of an expression on its own: what was expected and found, at its place
/// ("expected an operator or the end, found 'drag'").
fn expression_syntax_error(source: &Source, error: pest::error::Error<Rule>) -> Diagnostic {
    let (start, end) = error_span(&error);
    let message = expected_and_found(source, &error, start)
        .replace("end of line", "the end")
        .replace("end of file", "the end");
    Diagnostic::at(
        DiagnosticKind::Syntax,
        source,
        Span::new(start, end),
        message,
    )
}

/// A syntax error's message, without its place: what was expected at byte `start` (pest's
/// message, its rules in human words, where it names none) and what was found there.
fn expected_and_found(source: &Source, error: &pest::error::Error<Rule>, start: usize) -> String {
    let message = match &error.variant {
        pest::error::ErrorVariant::ParsingError { positives, .. } if !positives.is_empty() => {
            format!("expected {}", expected(source.text(), start, positives))
        }
        _ => error
            .clone()
            .renamed_rules(human_rule_name)
            .variant
            .message()
            .into_owned(),
    };
    format!("{message}, found {}", found_token(source.text(), start))
}

fn syntax_error(source: &Source, error: pest::error::Error<Rule>) -> Diagnostic {
    let (start, end) = error_span(&error);
    let (line, _) = source.line_col(start);
    let line_text = source.line_text(line);
    let header = HEADERS.iter().find(|(h, _)| {
        line_text.trim_start().strip_prefix(*h).is_some_and(|rest| {
            (rest.is_empty() || rest.starts_with(char::is_whitespace))
                && !rest.trim_start().starts_with(':')
        })
    });
    // A header line that fails is also tried as a rule (`axiom: A (2)` reads as the module
    // `axiom` with a guard), which reaches further and so names the rule's tokens. Parse such
    // a line again as the header it starts with, and report that error.
    let header_error = header_with_colon(line_text).and_then(|header_rule| {
        let line_start = source.line_start(line);
        LsysParser::parse(header_rule, line_text).err().map(|e| {
            let (s, e2) = error_span(&e);
            (e, line_start + s, line_start + e2)
        })
    });
    let (error, start, end) = match header_error {
        Some(found) => found,
        None => (error, start, end),
    };
    let diagnostic = Diagnostic::at(
        DiagnosticKind::Syntax,
        source,
        Span::new(start, end),
        expected_and_found(source, &error, start),
    );
    let before = &source.text()[..start.min(source.text().len())];
    let word_before_space = before
        .strip_suffix([' ', '\t'])
        .map(|b| b.trim_end_matches([' ', '\t']))
        .and_then(|b| {
            let word: String = b
                .chars()
                .rev()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            (!word.is_empty()).then(|| word.chars().rev().collect::<String>())
        });
    let found_paren = found_token(source.text(), start) == "'('";
    if line_text.contains("->") && !line_text.contains("-->") {
        diagnostic.with_note("a rule's arrow is '-->'")
    } else if let Some(header) = miscased_header(line_text) {
        diagnostic.with_note(format!(
            "headers are written in lower case: '{header}:' (a capitalised word is a module)"
        ))
    } else if let Some((header, _)) = header {
        diagnostic.with_note(format!("a header ends with a colon: '{header}: ...'"))
    } else if let (Some(word), true) = (word_before_space, found_paren) {
        diagnostic.with_note(format!(
            "parameters follow a module's name with no space between: '{word}(...)'"
        ))
    } else {
        diagnostic
    }
}

/// The header `line` starts with when it is written in other letter case (`Axiom: A`), and is
/// followed by a colon; `None` when it is written right or is no header.
fn miscased_header(line: &str) -> Option<&'static str> {
    let line = line.trim_start();
    HEADERS.iter().map(|(h, _)| *h).find(|h| {
        line.get(..h.len()).is_some_and(|start| {
            start.eq_ignore_ascii_case(h)
                && start != *h
                && line[h.len()..].trim_start().starts_with(':')
        })
    })
}

/// The byte range a pest error points at.
fn error_span(error: &pest::error::Error<Rule>) -> (usize, usize) {
    match error.location {
        pest::error::InputLocation::Pos(p) => (p, p),
        pest::error::InputLocation::Span((s, e)) => (s, e),
    }
}

/// The grammar rule of the header `line` starts with, colon included; `None` for a line
/// holding a rule's arrow (a module may be named like a header).
fn header_with_colon(line: &str) -> Option<Rule> {
    if line.contains("-->") || line.contains('→') {
        return None;
    }
    HEADERS.iter().find_map(|(h, rule)| {
        let rest = line.trim_start().strip_prefix(*h)?;
        rest.trim_start().starts_with(':').then_some(*rule)
    })
}

/// What pest expected at `at`, in plain words, each once: the binary operators are "an
/// operator", the ways to start a value are "a value", and where an argument list or a
/// parenthesis is open, ',' and ')' (or ')' alone) are named too.
fn expected(text: &str, at: usize, positives: &[Rule]) -> String {
    let mut names: Vec<String> = Vec::new();
    let mut operator = false;
    for expected in positives {
        let name = if is_binary_operator(*expected) {
            operator = true;
            "an operator".to_string()
        } else if matches!(
            expected,
            Rule::neg | Rule::not | Rule::number | Rule::name | Rule::call | Rule::primary
        ) {
            "a value".to_string()
        } else {
            human_rule_name(expected)
        };
        if !names.contains(&name) {
            names.push(name);
        }
    }
    if operator {
        match open_parenthesis(text, at) {
            Some(true) => names.extend(["','".to_string(), "')'".to_string()]),
            Some(false) => names.push("')'".to_string()),
            None => {}
        }
    }
    one_of(&names)
}

fn is_binary_operator(grammar_rule: Rule) -> bool {
    matches!(
        grammar_rule,
        Rule::infix
            | Rule::or
            | Rule::and
            | Rule::eq
            | Rule::ne
            | Rule::le
            | Rule::ge
            | Rule::lt
            | Rule::gt
            | Rule::add
            | Rule::sub
            | Rule::mul
            | Rule::div
            | Rule::rem
            | Rule::pow
    )
}

/// Whether a parenthesis is open at `at` on its line: `Some(true)` when the innermost one
/// follows a name (a module's parameters or a function call, where ',' may come next),
/// `Some(false)` for a bracketing parenthesis, `None` when none is open.
fn open_parenthesis(text: &str, at: usize) -> Option<bool> {
    let at = at.min(text.len());
    let line_start = text[..at].rfind(['\n', '\r']).map_or(0, |i| i + 1);
    let mut open: Vec<usize> = Vec::new();
    for (i, c) in text[line_start..at].char_indices() {
        match c {
            '(' => open.push(line_start + i),
            ')' => {
                open.pop();
            }
            '#' => break,
            _ => {}
        }
    }
    let paren = *open.last()?;
    let before = text[..paren].trim_end_matches([' ', '\t']);
    Some(
        before
            .chars()
            .next_back()
            .is_some_and(|c| c.is_alphanumeric() || c == '_'),
    )
}

/// The token at `at`, quoted, for "found ...": a whole word or number, an arrow, a
/// two-character operator, or one character; "end of line" or "end of file" at the end.
fn found_token(text: &str, at: usize) -> String {
    if at >= text.trim_end().len() {
        return "end of file".to_string();
    }
    let rest = &text[at..];
    let word_len = rest
        .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == '.'))
        .unwrap_or(rest.len());
    let token = if word_len > 0 {
        &rest[..word_len]
    } else if let Some(t) = ["-->", "→", "||", "&&", "==", "!=", "<=", ">="]
        .into_iter()
        .find(|t| rest.starts_with(t))
    {
        t
    } else {
        match rest.chars().next() {
            Some('\n' | '\r') => return "end of line".to_string(),
            Some(c) => &rest[..c.len_utf8()],
            None => return "end of file".to_string(),
        }
    };
    format!("'{token}'")
}

/// The headers a line may start with, each followed by a colon.
const HEADERS: [(&str, Rule); 11] = [
    ("axiom", Rule::axiom_stmt),
    ("derivation length", Rule::length_stmt),
    ("seed", Rule::seed_stmt),
    ("ignore", Rule::ignore_stmt),
    ("time", Rule::time_stmt),
    ("dt", Rule::dt_stmt),
    ("timing", Rule::timing_stmt),
    ("environment", Rule::environment_stmt),
    ("angle", Rule::angle_stmt),
    ("step", Rule::step_stmt),
    ("heading", Rule::heading_stmt),
];

/// "a", "a or b", "a, b, or c".
fn one_of(names: &[String]) -> String {
    match names {
        [] => String::new(),
        [one] => one.clone(),
        [a, b] => format!("{a} or {b}"),
        [init @ .., last] => format!("{}, or {last}", init.join(", ")),
    }
}

struct Builder<'s> {
    source: &'s Source,
    raw: RawFile,
    section: Section,
}

impl Builder<'_> {
    fn error(&self, span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic::at(DiagnosticKind::Semantic, self.source, span, message)
    }

    fn statement(&mut self, pair: Pair<'_, Rule>) -> Result<(), Diagnostic> {
        let span = span_of(&pair);
        match pair.as_rule() {
            Rule::define => {
                let mut inner = pair.into_inner();
                inner.next(); // keyword
                let name = inner.next().expect("grammar: define has a name");
                let value = self.expr(inner.next().expect("grammar: define has a value"), 0)?;
                self.raw.file.defines.push(Define {
                    name: name.as_str().to_string(),
                    name_span: span_of(&name),
                    value,
                });
            }
            Rule::module_decl => {
                for word in pair.into_inner().filter(|p| p.as_rule() == Rule::word) {
                    self.raw
                        .file
                        .declared_modules
                        .push((word.as_str().to_string(), span_of(&word)));
                }
            }
            Rule::seed_stmt => {
                let digits = pair.into_inner().next().expect("grammar: seed has digits");
                let seed: u64 = digits.as_str().parse().map_err(|_| {
                    self.error(
                        span_of(&digits),
                        "the seed must fit in 64 bits (0 to 18446744073709551615)",
                    )
                })?;
                if let Some((_, first)) = self.raw.file.seed {
                    return Err(self.twice("seed", span, first));
                }
                self.raw.file.seed = Some((seed, span));
            }
            Rule::axiom_stmt => {
                if let Some((_, first)) = &self.raw.axiom {
                    return Err(self.twice("axiom", span, *first));
                }
                let list = pair
                    .into_inner()
                    .next()
                    .expect("grammar: axiom has modules");
                let calls = self.module_list(list.into_inner())?;
                self.raw.axiom = Some((calls, span));
            }
            Rule::length_stmt => {
                if let Some(first) = &self.raw.file.derivation_length {
                    return Err(self.twice("derivation length", span, first.span()));
                }
                let value = self.expr(pair.into_inner().next().expect("grammar: length"), 0)?;
                self.raw.file.derivation_length = Some(value);
            }
            Rule::time_stmt | Rule::dt_stmt | Rule::angle_stmt | Rule::step_stmt => {
                let header = pair.as_rule();
                let value = self.expr(pair.into_inner().next().expect("grammar: value"), 0)?;
                let file = &mut self.raw.file;
                let (slot, what) = match header {
                    Rule::time_stmt => (&mut file.time, "time"),
                    Rule::dt_stmt => (&mut file.dt, "dt"),
                    Rule::angle_stmt => (&mut file.angle, "angle"),
                    _ => (&mut file.step, "step"),
                };
                if let Some(first) = slot {
                    let first = first.span();
                    return Err(self.twice(what, span, first));
                }
                *slot = Some(value);
            }
            Rule::heading_stmt | Rule::timing_stmt => {
                let is_heading = pair.as_rule() == Rule::heading_stmt;
                let word = pair.into_inner().next().expect("grammar: a header's word");
                let file = &mut self.raw.file;
                let (first, what) = if is_heading {
                    (file.heading.map(|(_, s)| s), "heading")
                } else {
                    (file.timing.map(|(_, s)| s), "timing")
                };
                if let Some(first) = first {
                    return Err(self.twice(what, span, first));
                }
                match (is_heading, word.as_str()) {
                    (true, "up") => file.heading = Some((Heading::Up, span)),
                    (true, _) => file.heading = Some((Heading::Ground, span)),
                    (false, "exact") => file.timing = Some((Timing::Exact, span)),
                    (false, _) => file.timing = Some((Timing::Iterative, span)),
                }
            }
            Rule::environment_stmt => {
                if let Some((_, first)) = &self.raw.file.environment {
                    return Err(self.twice("environment", span, *first));
                }
                let mut values = Vec::new();
                for number in pair.into_inner() {
                    let v: f64 = number
                        .as_str()
                        .parse()
                        .map_err(|_| self.error(span_of(&number), "not a number"))?;
                    if !v.is_finite() {
                        return Err(
                            self.error(span_of(&number), "number too large for a 64-bit float")
                        );
                    }
                    values.push(v);
                }
                self.raw.file.environment = Some((values, span));
            }
            Rule::ignore_stmt => {
                for sym in pair.into_inner() {
                    self.raw
                        .file
                        .ignore
                        .push((sym.as_str().to_string(), span_of(&sym)));
                }
            }
            Rule::productions_header => self.section = Section::Productions,
            Rule::interpretation_header => self.section = Section::Interpretation,
            Rule::rule => {
                let rule = self.rule(pair)?;
                self.raw.rules.push(rule);
            }
            Rule::EOI => {}
            other => unreachable!("grammar: unexpected statement {other:?}"),
        }
        Ok(())
    }

    fn twice(&self, what: &str, span: Span, first: Span) -> Diagnostic {
        let (line, _) = self.source.line_col(first.start);
        self.error(
            span,
            format!("'{what}' is given twice (first on line {line})"),
        )
    }

    fn rule(&self, pair: Pair<'_, Rule>) -> Result<RawRule, Diagnostic> {
        let span = span_of(&pair);
        let mut rule = RawRule {
            left: Vec::new(),
            predecessor: PatternModule {
                name: String::new(),
                params: Vec::new(),
                span,
            },
            right: Vec::new(),
            guard: None,
            successor: Vec::new(),
            solve: None,
            probability: None,
            section: self.section,
            span,
        };
        for part in pair.into_inner() {
            match part.as_rule() {
                Rule::left_context => {
                    rule.left = part.into_inner().map(|p| self.pattern(p)).collect()
                }
                Rule::predecessor => {
                    let p = part
                        .into_inner()
                        .next()
                        .expect("grammar: predecessor module");
                    rule.predecessor = self.pattern(p).module;
                }
                Rule::right_context => {
                    rule.right = part.into_inner().map(|p| self.pattern(p)).collect()
                }
                Rule::guard => {
                    rule.guard = Some(self.expr(part.into_inner().next().expect("guard"), 0)?)
                }
                Rule::successor => {
                    let mut inner = part.into_inner().peekable();
                    if inner.peek().is_some_and(|p| p.as_rule() == Rule::solve) {
                        let solve = inner.next().expect("peeked");
                        let mut odes = Vec::new();
                        for d in solve
                            .into_inner()
                            .filter(|p| p.as_rule() == Rule::derivative)
                        {
                            let mut parts = d.into_inner();
                            let name = parts.next().expect("grammar: d_name");
                            let rhs = self.expr(parts.next().expect("grammar: rhs"), 0)?;
                            odes.push(Derivative {
                                param: name.as_str()[1..].to_string(),
                                span: span_of(&name),
                                rhs,
                            });
                        }
                        rule.solve = Some(odes);
                    } else {
                        rule.successor = self.module_list(inner)?;
                    }
                }
                Rule::probability => {
                    rule.probability =
                        Some(self.expr(part.into_inner().next().expect("probability"), 0)?)
                }
                Rule::arrow => {}
                other => unreachable!("grammar: unexpected rule part {other:?}"),
            }
        }
        Ok(rule)
    }

    fn pattern(&self, pair: Pair<'_, Rule>) -> RawPattern {
        let span = span_of(&pair);
        let mut inner = pair.into_inner();
        let name = inner.next().expect("grammar: pattern has a name");
        let is_word = name.as_rule() == Rule::word;
        let name_span = span_of(&name);
        let params = inner
            .next()
            .map(|formal| {
                formal
                    .into_inner()
                    .map(|n| (n.as_str().to_string(), span_of(&n)))
                    .collect()
            })
            .unwrap_or_default();
        RawPattern {
            module: PatternModule {
                name: name.as_str().to_string(),
                params,
                span,
            },
            name_span,
            is_word,
        }
    }

    fn module_list<'i>(
        &self,
        pairs: impl Iterator<Item = Pair<'i, Rule>>,
    ) -> Result<Vec<RawCall>, Diagnostic> {
        pairs.map(|p| self.module_call(p)).collect()
    }

    fn module_call(&self, pair: Pair<'_, Rule>) -> Result<RawCall, Diagnostic> {
        let span = span_of(&pair);
        let mut inner = pair.into_inner();
        let name = inner.next().expect("grammar: module has a name");
        let is_word = name.as_rule() == Rule::word;
        let name_span = span_of(&name);
        let args = match inner.next() {
            Some(actual) => actual
                .into_inner()
                .map(|e| self.expr(e, 0))
                .collect::<Result<_, _>>()?,
            None => Vec::new(),
        };
        Ok(RawCall {
            module: ModuleCall {
                name: name.as_str().to_string(),
                args,
                span,
            },
            name_span,
            is_word,
        })
    }

    /// Builds an expression; `nesting` counts enclosing parentheses and calls.
    fn expr(&self, pair: Pair<'_, Rule>, nesting: usize) -> Result<Expr, Diagnostic> {
        let span = span_of(&pair);
        if nesting > 64 {
            return Err(self.error(span, "expression nested too deeply (more than 64 levels)"));
        }
        let operators = pair
            .clone()
            .into_inner()
            .filter(|p| {
                !matches!(
                    p.as_rule(),
                    Rule::number | Rule::name | Rule::call | Rule::expr
                )
            })
            .count();
        if operators > MAX_OPERATORS {
            return Err(self.error(
                span,
                format!("expression too long (more than {MAX_OPERATORS} operators)"),
            ));
        }
        let (expr, depth) = pratt()
            .map_primary(|p| self.primary(p, nesting))
            .map_prefix(|op, operand| {
                let (operand, depth) = operand?;
                let op_span = span_of(&op);
                let span = op_span.join(operand.span());
                let op = if op.as_rule() == Rule::neg {
                    UnaryOp::Neg
                } else {
                    UnaryOp::Not
                };
                Ok((
                    Expr::Unary {
                        op,
                        operand: Box::new(operand),
                        span,
                    },
                    depth + 1,
                ))
            })
            .map_infix(|lhs, op, rhs| {
                let (lhs, dl) = lhs?;
                let (rhs, dr) = rhs?;
                let op = match op.as_rule() {
                    Rule::or => BinaryOp::Or,
                    Rule::and => BinaryOp::And,
                    Rule::eq => BinaryOp::Eq,
                    Rule::ne => BinaryOp::Ne,
                    Rule::le => BinaryOp::Le,
                    Rule::ge => BinaryOp::Ge,
                    Rule::lt => BinaryOp::Lt,
                    Rule::gt => BinaryOp::Gt,
                    Rule::add => BinaryOp::Add,
                    Rule::sub => BinaryOp::Sub,
                    Rule::mul => BinaryOp::Mul,
                    Rule::div => BinaryOp::Div,
                    Rule::rem => BinaryOp::Rem,
                    Rule::pow => BinaryOp::Pow,
                    other => unreachable!("grammar: unexpected operator {other:?}"),
                };
                let span = lhs.span().join(rhs.span());
                Ok((
                    Expr::Binary {
                        op,
                        lhs: Box::new(lhs),
                        rhs: Box::new(rhs),
                        span,
                    },
                    dl.max(dr) + 1,
                ))
            })
            .parse(pair.into_inner())?;
        if depth > MAX_EXPR_DEPTH {
            return Err(self.error(
                span,
                format!("expression nested too deeply (more than {MAX_EXPR_DEPTH} levels)"),
            ));
        }
        Ok(expr)
    }

    fn primary(&self, pair: Pair<'_, Rule>, nesting: usize) -> Result<(Expr, usize), Diagnostic> {
        let span = span_of(&pair);
        match pair.as_rule() {
            Rule::number => {
                let value: f64 = pair.as_str().parse().map_err(|_| {
                    self.error(span, format!("'{}' is not a number", pair.as_str()))
                })?;
                if !value.is_finite() {
                    return Err(self.error(span, "number too large for a 64-bit float"));
                }
                Ok((Expr::Number(value, span), 1))
            }
            Rule::name => Ok((Expr::Name(pair.as_str().to_string(), span), 1)),
            Rule::call => {
                let mut inner = pair.into_inner();
                let name = inner.next().expect("grammar: call has a name");
                let args = inner
                    .map(|a| self.expr(a, nesting + 1))
                    .collect::<Result<Vec<_>, _>>()?;
                let depth = 1 + args.iter().map(expr_depth).max().unwrap_or(0);
                Ok((
                    Expr::Call {
                        name: name.as_str().to_string(),
                        args,
                        span,
                    },
                    depth,
                ))
            }
            Rule::expr => {
                let e = self.expr(pair, nesting + 1)?;
                let depth = expr_depth(&e);
                Ok((e, depth))
            }
            other => unreachable!("grammar: unexpected primary {other:?}"),
        }
    }
}

/// Depth of an expression tree (already bounded by the builder, so recursion is safe).
fn expr_depth(e: &Expr) -> usize {
    match e {
        Expr::Number(..) | Expr::Name(..) => 1,
        Expr::Unary { operand, .. } => 1 + expr_depth(operand),
        Expr::Binary { lhs, rhs, .. } => 1 + expr_depth(lhs).max(expr_depth(rhs)),
        Expr::Call { args, .. } => 1 + args.iter().map(expr_depth).max().unwrap_or(0),
    }
}
