//! Static analysis of an L-system for `ontogeny check`: symbols, rules that can never fire,
//! parameters and constants never used.

use std::collections::{BTreeSet, HashSet};

use serde::Serialize;

use super::LSystem;
use super::compile::{CompiledRule, PatternEl, RuleSet};
use crate::lang::ast::{self, Expr, Section, SplitWord};
use crate::lang::{Diagnostic, DiagnosticKind, Span};

/// What kind of finding a [`Finding`] is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum FindingKind {
    /// A rule that no derivation can apply.
    NeverFires,
    /// A formal parameter that the rule's guard, successor and probability never read.
    UnusedParameter,
    /// A constant no expression reads.
    UnusedConstant,
    /// A word read as several modules, all of them known names (`FF` as `F F`).
    SplitWord,
    /// A word read as several modules that are not all known names (`Tial` as `T i a l`):
    /// most likely a typo. Every verb that reads the grammar shows it ([`LSystem::findings`]).
    UnknownWord,
    /// A successor or the axiom whose `[` and `]` do not pair up: the derived string is
    /// balanced only if other rules close (or open) the branch.
    UnbalancedBrackets,
}

/// One thing `check` has to say about a place in the file.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Finding {
    /// What kind of finding.
    pub kind: FindingKind,
    /// In words.
    pub message: String,
    /// 1-based line.
    pub line: usize,
    /// 1-based column.
    pub column: usize,
}

/// A module name and the parameter counts it appears with.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SymbolSummary {
    /// The name.
    pub name: String,
    /// Every parameter count it is written with.
    pub arities: Vec<usize>,
    /// Whether some production rewrites it.
    pub rewritten: bool,
}

/// The result of checking an L-system.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Report {
    /// The file checked.
    pub file: String,
    /// Every module name used.
    pub symbols: Vec<SymbolSummary>,
    /// Number of productions.
    pub productions: usize,
    /// Number of interpretation rules.
    pub interpretation_rules: usize,
    /// Named constants and their values.
    pub constants: Vec<(String, f64)>,
    /// The axiom, written readably.
    pub axiom: String,
    /// The file's derivation length.
    pub derivation_length: Option<u64>,
    /// Continuous development's end time, when the file has `time:`.
    pub time: Option<f64>,
    /// The observation step.
    pub dt: f64,
    /// `exact` or `iterative`.
    pub timing: String,
    /// Number of differential (`solve`) rules.
    pub differential_rules: usize,
    /// The environment's initial values.
    pub environment: Vec<f64>,
    /// Rules that never fire, unused parameters and constants, split words.
    pub findings: Vec<Finding>,
}

/// `n` and `word`, with an `s` unless `n` is 1 (`1 production`, `2 productions`).
fn count(n: usize, word: &str) -> String {
    format!("{n} {word}{}", if n == 1 { "" } else { "s" })
}

impl Report {
    /// The report for people, as `ontogeny check` prints it: the file, its axiom, its
    /// development (derivation length or continuous time), environment, symbols, rules,
    /// constants and findings, a line each (no final newline).
    pub fn text(&self) -> String {
        let mut lines = vec![
            format!("{}: ok", self.file),
            format!("axiom: {}", self.axiom),
        ];
        lines.push(match (self.time, self.derivation_length) {
            (Some(time), _) => format!(
                "continuous time: 0 to {time}, dt = {}, timing {}, {}",
                self.dt,
                self.timing,
                count(self.differential_rules, "differential rule")
            ),
            (None, Some(n)) => format!("derivation length: {n}"),
            (None, None) => {
                "derivation length: not given (derive prints the axiom only unless --steps)".into()
            }
        });
        if self.time.is_none() && self.differential_rules > 0 {
            lines.push(format!(
                "note: {} differential rule(s) but no 'time:': derive them with --time T",
                self.differential_rules
            ));
        }
        if !self.environment.is_empty() {
            let values: Vec<String> = self.environment.iter().map(f64::to_string).collect();
            lines.push(format!("environment: {}", values.join(" ")));
        }
        let symbols: Vec<String> = self
            .symbols
            .iter()
            .map(|s| {
                let arities: Vec<String> = s.arities.iter().map(usize::to_string).collect();
                let arity = match s.arities.as_slice() {
                    [0] => String::new(),
                    _ => format!("({})", arities.join("|")),
                };
                let mark = if s.rewritten { "*" } else { "" };
                format!("{}{arity}{mark}", s.name)
            })
            .collect();
        lines.push(format!(
            "symbols ({}, * = rewritten by a production): {}",
            symbols.len(),
            symbols.join(" ")
        ));
        lines.push(format!(
            "rules: {}, {}",
            count(self.productions, "production"),
            count(self.interpretation_rules, "interpretation rule")
        ));
        if !self.constants.is_empty() {
            let constants: Vec<String> = self
                .constants
                .iter()
                .map(|(n, v)| format!("{n} = {v}"))
                .collect();
            lines.push(format!("constants: {}", constants.join(", ")));
        }
        if self.findings.is_empty() {
            lines.push("findings: none".into());
        } else {
            lines.push(format!("findings ({}):", self.findings.len()));
            for f in &self.findings {
                lines.push(format!(
                    "  {}:{}:{}: {}",
                    self.file, f.line, f.column, f.message
                ));
            }
        }
        lines.join("\n")
    }
}

/// The checks `check` runs, in order: each adds its findings (the report sorts them by place).
const PASSES: [fn(&LSystem, &mut Findings); 5] = [
    rules_that_never_fire,
    unused_parameters,
    unused_constants,
    unbalanced_brackets,
    split_words,
];

/// The findings of the passes so far, located in the system's source.
struct Findings<'a> {
    system: &'a LSystem,
    list: Vec<Finding>,
}

impl Findings<'_> {
    /// The 1-based line and column where `span` starts.
    fn at(&self, span: Span) -> (usize, usize) {
        self.system.source.line_col(span.start)
    }

    fn push(&mut self, kind: FindingKind, span: Span, message: String) {
        let (line, column) = self.at(span);
        self.list.push(Finding {
            kind,
            message,
            line,
            column,
        });
    }
}

/// Every rule of both sections (productions, then interpretation) with its section's rules,
/// its index there and its syntax.
fn rules_with_syntax(
    system: &LSystem,
) -> impl Iterator<Item = (&RuleSet, usize, &CompiledRule, &ast::Rule)> {
    [
        (Section::Productions, &system.productions),
        (Section::Interpretation, &system.interpretation),
    ]
    .into_iter()
    .flat_map(move |(section, set)| {
        let asts = system
            .file
            .rules
            .iter()
            .filter(move |r| r.section == section);
        set.rules
            .iter()
            .zip(asts)
            .enumerate()
            .map(move |(index, (rule, ast))| (set, index, rule, ast))
    })
}

/// The symbols that can ever appear: the axiom's, then successors of reachable rules.
fn reachable_symbols(system: &LSystem) -> HashSet<u32> {
    let mut reachable: HashSet<u32> = system.axiom.symbols().iter().copied().collect();
    loop {
        let before = reachable.len();
        for rule in &system.productions.rules {
            if reachable.contains(&rule.pred) {
                reachable.extend(rule.successor.iter().map(|(s, _)| *s));
            }
        }
        if reachable.len() == before {
            return reachable;
        }
    }
}

/// Rules that no derivation can apply: a predecessor or context that never appears, a
/// condition always false, or an earlier rule that always rewrites the same symbol first.
fn rules_that_never_fire(system: &LSystem, findings: &mut Findings) {
    let reachable = reachable_symbols(system);
    for (set, index, rule, ast) in rules_with_syntax(system) {
        let name = system.symbols.name(rule.pred);
        let reason = if !reachable.contains(&rule.pred) {
            Some(format!(
                "'{name}' never appears in the axiom or in a successor that can be produced"
            ))
        } else if let Some(missing) = rule
            .left
            .iter()
            .chain(&rule.right)
            .filter_map(|el| match el {
                PatternEl::Module { sym, .. } => Some(*sym),
                _ => None,
            })
            .find(|s| !reachable.contains(s))
        {
            Some(format!(
                "its context needs '{}', which never appears",
                system.symbols.name(missing)
            ))
        } else if rule.guard.as_ref().and_then(|g| g.as_const()) == Some(0.0) {
            Some("its condition is always false".to_string())
        } else {
            set.by_symbol[rule.pred as usize]
                .iter()
                .take_while(|&&r| r as usize != index)
                .map(|&r| &set.rules[r as usize])
                .find(|earlier| earlier.unconditional())
                .map(|earlier| {
                    let (line, _) = findings.at(earlier.span);
                    format!("the rule on line {line} always rewrites '{name}' first")
                })
        };
        if let Some(reason) = reason {
            findings.push(
                FindingKind::NeverFires,
                ast.span,
                format!("rule never fires: {reason}"),
            );
        }
    }
}

/// Formal parameters that a rule's guard, probability, successor and ODEs never read.
fn unused_parameters(system: &LSystem, findings: &mut Findings) {
    for (_, _, _, ast) in rules_with_syntax(system) {
        let mut used = HashSet::new();
        let mut note = |n: &str, _| {
            used.insert(n.to_string());
        };
        for e in ast.guard.iter().chain(&ast.probability) {
            e.visit_names(&mut note);
        }
        for call in &ast.successor {
            call.args.iter().for_each(|a| a.visit_names(&mut note));
        }
        for ode in ast.solve.iter().flatten() {
            ode.rhs.visit_names(&mut note);
        }
        let formals = ast
            .left
            .iter()
            .chain(std::iter::once(&ast.predecessor))
            .chain(&ast.right)
            .flat_map(|p| &p.params);
        for (param, span) in formals {
            if !used.contains(param) && !ast::is_constant_formal(param) {
                findings.push(
                    FindingKind::UnusedParameter,
                    *span,
                    format!("parameter '{param}' is never used"),
                );
            }
        }
    }
}

/// Constants no expression of the file reads.
fn unused_constants(system: &LSystem, findings: &mut Findings) {
    let mut used = HashSet::new();
    let mut note = |n: &str, _| {
        used.insert(n.to_string());
    };
    let file = &system.file;
    let exprs = file
        .defines
        .iter()
        .map(|d| &d.value)
        .chain(&file.derivation_length)
        .chain(&file.time)
        .chain(&file.dt)
        .chain(
            file.axiom
                .iter()
                .flat_map(|(calls, _)| calls.iter().flat_map(|c| &c.args)),
        )
        .chain(file.rules.iter().flat_map(|r| {
            r.guard
                .iter()
                .chain(&r.probability)
                .chain(r.successor.iter().flat_map(|c| &c.args))
                .chain(r.solve.iter().flatten().map(|ode| &ode.rhs))
        }));
    exprs.for_each(|e: &Expr| e.visit_names(&mut note));
    for (name, _, span) in &system.constants {
        if !used.contains(name) {
            findings.push(
                FindingKind::UnusedConstant,
                *span,
                format!("constant '{name}' is never used"),
            );
        }
    }
}

/// Branches a successor (or the axiom) opens and does not close, or closes unopened.
fn unbalanced_brackets(system: &LSystem, findings: &mut Findings) {
    let file = &system.file;
    let successors = file
        .axiom
        .iter()
        .map(|(calls, _)| ("the axiom", calls))
        .chain(file.rules.iter().map(|r| ("this successor", &r.successor)));
    for (whose, calls) in successors {
        let mut open = Vec::new();
        for call in calls {
            match call.name.as_str() {
                "[" => open.push(call.span),
                "]" if open.pop().is_none() => findings.push(
                    FindingKind::UnbalancedBrackets,
                    call.span,
                    format!(
                        "']' closes a branch {whose} did not open (the builder ignores it, with a warning, unless a module before it opened one)"
                    ),
                ),
                _ => {}
            }
        }
        for span in open {
            findings.push(
                FindingKind::UnbalancedBrackets,
                span,
                format!(
                    "'[' is not closed in {whose} (unless a later module closes it, the branch runs to the end of the string, and the builder warns)"
                ),
            );
        }
    }
}

/// Words the parser read as several modules, but for the textbook's one-letter notation: a
/// word of one-letter names that are all known (`FF`, `FX` with a rule for `X`).
fn split_words(system: &LSystem, findings: &mut Findings) {
    for word in &system.file.split_words {
        // The classic one-letter notation (`FF`, or `FX` where `X` has a rule) says nothing.
        if word.all_known() && word.pieces.iter().all(|p| p.chars().count() == 1) {
            continue;
        }
        let kind = match word.all_known() {
            true => FindingKind::SplitWord,
            false => FindingKind::UnknownWord,
        };
        findings.push(kind, word.span, split_word_message(word));
    }
}

/// What is said of a word read as several modules: `'Tial' is read as the modules T i a l
/// (did you mean `Tail`?)`.
fn split_word_message(word: &SplitWord) -> String {
    format!(
        "'{}' is read as the modules {}{}",
        word.word,
        word.pieces.join(" "),
        crate::lang::did_you_mean(word.suggestion.as_deref())
    )
}

impl LSystem {
    /// The findings every verb that reads the grammar shows, as warnings located in its
    /// source (`grow`, `eval`, `derive`, `export`, the viewer's page; `check` lists them with
    /// the rest): the words read as several modules that are not all known names, most
    /// likely typos (`Tial` for `Tail`, `foward` for `forward`). In a file that declares its
    /// modules these are errors instead, and the file does not parse.
    pub fn findings(&self) -> Vec<Diagnostic> {
        self.file
            .split_words
            .iter()
            .filter(|w| !w.all_known())
            .map(|w| {
                Diagnostic::at(
                    DiagnosticKind::Semantic,
                    &self.source,
                    w.span,
                    split_word_message(w),
                )
            })
            .collect()
    }

    /// Analyses the system without deriving it: the named passes in order, their findings
    /// sorted by place.
    pub fn check(&self) -> Report {
        let mut findings = Findings {
            system: self,
            list: Vec::new(),
        };
        for pass in PASSES {
            pass(self, &mut findings);
        }
        let mut findings = findings.list;
        findings.sort_by_key(|f| (f.line, f.column));

        Report {
            file: self.source.name().to_string(),
            symbols: self.symbol_summaries(),
            productions: self.productions.rules.len(),
            interpretation_rules: self.interpretation.rules.len(),
            constants: self.constants().map(|(n, v)| (n.to_string(), v)).collect(),
            axiom: self.display(&self.axiom),
            derivation_length: self.derivation_length,
            time: self.time,
            dt: self.dt(),
            timing: match self.timing {
                ast::Timing::Exact => "exact".to_string(),
                ast::Timing::Iterative => "iterative".to_string(),
            },
            differential_rules: self
                .productions
                .rules
                .iter()
                .filter(|r| r.solve.is_some())
                .count(),
            environment: self.environment.values().to_vec(),
            findings,
        }
    }

    fn symbol_summaries(&self) -> Vec<SymbolSummary> {
        let mut arities: Vec<BTreeSet<usize>> = vec![BTreeSet::new(); self.symbols.len()];
        for m in self.axiom.iter() {
            arities[m.sym as usize].insert(m.params.len());
        }
        for set in [&self.productions, &self.interpretation] {
            for rule in &set.rules {
                arities[rule.pred as usize].insert(rule.arity);
                for (sym, args) in &rule.successor {
                    arities[*sym as usize].insert(args.len());
                }
                for el in rule.left.iter().chain(&rule.right) {
                    if let PatternEl::Module { sym, arity, .. } = el {
                        arities[*sym as usize].insert(*arity);
                    }
                }
            }
        }
        (0..self.symbols.len() as u32)
            .map(|id| SymbolSummary {
                name: self.symbols.name(id).to_string(),
                arities: arities[id as usize].iter().copied().collect(),
                rewritten: !self.productions.by_symbol[id as usize].is_empty(),
            })
            .filter(|s| !s.arities.is_empty())
            .collect()
    }
}
