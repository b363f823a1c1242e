//! Static analysis of an L-system for `ontogeny check`: symbols, rules that can never fire,
//! parameters and constants never used.

use std::collections::{BTreeSet, HashSet};

use serde::Serialize;

use super::LSystem;
use super::compile::PatternEl;
use crate::lang::Span;
use crate::lang::ast::{Expr, Section};

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
    /// A word read as several modules.
    SplitWord,
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

impl LSystem {
    /// Analyses the system without deriving it.
    pub fn check(&self) -> Report {
        let mut findings = Vec::new();
        let at = |span: Span| self.source.line_col(span.start);
        let mut push = |kind, span: Span, message: String| {
            let (line, column) = at(span);
            findings.push(Finding {
                kind,
                message,
                line,
                column,
            });
        };

        // Which symbols can ever appear: the axiom's, then successors of reachable rules.
        let mut reachable: HashSet<u32> = self.axiom.symbols().iter().copied().collect();
        loop {
            let before = reachable.len();
            for rule in &self.productions.rules {
                if reachable.contains(&rule.pred) {
                    reachable.extend(rule.successor.iter().map(|(s, _)| *s));
                }
            }
            if reachable.len() == before {
                break;
            }
        }

        for (section, set) in [
            (Section::Productions, &self.productions),
            (Section::Interpretation, &self.interpretation),
        ] {
            let asts = self.file.rules.iter().filter(|r| r.section == section);
            for (index, (rule, ast)) in set.rules.iter().zip(asts).enumerate() {
                let name = self.symbols.name(rule.pred);
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
                        self.symbols.name(missing)
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
                            let (line, _) = at(earlier.span);
                            format!("the rule on line {line} always rewrites '{name}' first")
                        })
                };
                if let Some(reason) = reason {
                    push(
                        FindingKind::NeverFires,
                        ast.span,
                        format!("rule never fires: {reason}"),
                    );
                }

                // Parameters never read.
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
                    if !used.contains(param) && !crate::lang::ast::is_constant_formal(param) {
                        push(
                            FindingKind::UnusedParameter,
                            *span,
                            format!("parameter '{param}' is never used"),
                        );
                    }
                }
            }
        }

        // Constants never read.
        let mut used = HashSet::new();
        let mut note = |n: &str, _| {
            used.insert(n.to_string());
        };
        let file = &self.file;
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
        for (name, _, span) in &self.constants {
            if !used.contains(name) {
                push(
                    FindingKind::UnusedConstant,
                    *span,
                    format!("constant '{name}' is never used"),
                );
            }
        }

        // Branches a successor (or the axiom) opens and does not close, or closes unopened.
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
                    "]" if open.pop().is_none() => push(
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
                push(
                    FindingKind::UnbalancedBrackets,
                    span,
                    format!(
                        "'[' is not closed in {whose} (unless a later module closes it, the branch runs to the end of the string, and the builder warns)"
                    ),
                );
            }
        }

        for (word, pieces, span) in &file.split_words {
            push(
                FindingKind::SplitWord,
                *span,
                format!("'{word}' is read as the modules {}", pieces.join(" ")),
            );
        }
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
                crate::lang::ast::Timing::Exact => "exact".to_string(),
                crate::lang::ast::Timing::Iterative => "iterative".to_string(),
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
