//! A fitness the user writes: an expression of a task's terms (`D_w - 0.5 * drag`) in the
//! grammar's own expression language (parsed by [`crate::lang::parse_expression`] and
//! evaluated as a rule's parameters are), checked against the terms its task declares
//! ([`super::Task::TERMS`]) when a configuration is read, its value the fitness of every
//! evaluation that succeeds ([`FitnessExpression::score`]). A task whose `fitness` also names
//! formulas (the walker's) holds a [`Fitness`]: a formula or an expression.

use std::collections::BTreeMap;
use std::str::FromStr;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::{Evaluation, FAILURE_FITNESS, Status};
use crate::lang::ast::Expr;
use crate::lang::{Source, suggest};
use crate::lsystem::expr::{EvalEnv, ExprError, Resolved, compile};

/// The terms every task's evaluation gives besides its own, from the protocol they share:
/// `joint_gap`, how far the solver let any joint come apart (m).
pub const PROTOCOL_TERMS: &[&str] = &["joint_gap"];

/// The names an expression knows without a term: the constants `pi` and `e`.
const CONSTANTS: [&str; 2] = ["pi", "e"];

/// A fitness written as an expression of the task's terms: `"D_w - 0.5 * drag"`. It is kept
/// as written (so it is stored, shown and hashed into evaluation keys as the user wrote it),
/// with its syntax tree, or its syntax error, which its check reports.
#[derive(Clone, Debug)]
pub struct FitnessExpression {
    source: String,
    parsed: Result<Expr, String>,
}

impl PartialEq for FitnessExpression {
    /// Two expressions are one when they are written alike.
    fn eq(&self, other: &FitnessExpression) -> bool {
        self.source == other.source
    }
}

impl FitnessExpression {
    /// `text` read as an expression; a syntax error is kept, for [`FitnessExpression::check`]
    /// to report.
    pub fn new(text: &str) -> FitnessExpression {
        let source = Source::new("fitness", text);
        let parsed = crate::lang::parse_expression(&source).map_err(|d| match d.location {
            Some(at) => format!("{} at column {}", d.message, at.column),
            None => d.message,
        });
        FitnessExpression {
            source: text.to_string(),
            parsed,
        }
    }

    /// The expression as written.
    pub fn source(&self) -> &str {
        &self.source
    }

    /// Whether it reads the term `name`.
    pub fn reads(&self, name: &str) -> bool {
        let mut found = false;
        if let Ok(expr) = &self.parsed {
            expr.visit_names(&mut |n, _| found |= n == name);
        }
        found
    }

    /// Checks it as the fitness of the task `task`, whose evaluations give the terms `terms`
    /// (and [`PROTOCOL_TERMS`]) and whose formulas are `formulas`: its syntax, every name a
    /// term or a constant (`pi`, `e`), every function known and given as many arguments as
    /// it takes, none random. The error is what is wrong, as a message says it after the key
    /// (`reads D_x, which is not a term of the walker task (did you mean D_w?); ...`).
    pub fn check(&self, task: &str, terms: &[&str], formulas: &[&str]) -> Result<(), String> {
        let known = || terms.iter().chain(PROTOCOL_TERMS).copied();
        // Meant as a formula's name, but misspelt: `hornby-polack`.
        let formula = suggest::closest(&self.source, formulas.iter().copied()).map(|name| {
            format!(
                "\"{}\" is not one of the {task} task's formulas (did you mean {name}?) nor an \
                 expression of its terms",
                self.source
            )
        });
        let expr = match &self.parsed {
            Ok(expr) => expr,
            Err(problem) => {
                return Err(formula.unwrap_or_else(|| {
                    format!(
                        "\"{}\" is not an expression of the {task} task's terms: {problem}",
                        self.source
                    )
                }));
            }
        };
        let mut unknown: Option<String> = None;
        expr.visit_names(&mut |name, _| {
            let is_known = known().any(|t| t == name) || CONSTANTS.contains(&name);
            if !is_known && unknown.is_none() {
                unknown = Some(name.to_string());
            }
        });
        if let Some(name) = unknown {
            return Err(formula.unwrap_or_else(|| {
                format!(
                    "reads {name}, which is not a term of the {task} task{}; its terms are {}",
                    suggest::did_you_mean(&name, known()),
                    known().collect::<Vec<_>>().join(", ")
                )
            }));
        }
        let slots: Vec<&str> = known().collect();
        let compiled = compile(expr, &|name| {
            slots.iter().position(|t| *t == name).map(Resolved::Arg)
        })
        .map_err(|e| format!("\"{}\": {}", self.source, self.at(e)))?;
        if compiled.uses_random() {
            return Err(format!(
                "\"{}\" draws random numbers (uniform, normal): a fitness is a function of the \
                 terms",
                self.source
            ));
        }
        Ok(())
    }

    /// Its value over the terms `terms` of an evaluation; an error says why there is none
    /// (a term the evaluation lacks, a division by zero, a value that is NaN or infinite).
    pub fn value(&self, terms: &BTreeMap<String, f64>) -> Result<f64, String> {
        let expr = self.parsed.as_ref().map_err(Clone::clone)?;
        let mut names: Vec<String> = Vec::new();
        expr.visit_names(&mut |name, _| {
            if terms.contains_key(name) && !names.iter().any(|n| n == name) {
                names.push(name.to_string());
            }
        });
        let compiled = compile(expr, &|name| {
            names.iter().position(|n| n == name).map(Resolved::Arg)
        })
        .map_err(|e| self.at(e))?;
        let args: Vec<f64> = names.iter().map(|n| terms[n]).collect();
        // No draw is made: the check refuses random functions.
        let mut rng = ChaCha8Rng::seed_from_u64(0);
        compiled
            .eval(&mut EvalEnv {
                args: &args,
                t: 0.0,
                rng: &mut rng,
            })
            .map_err(|e| self.at(e))
    }

    /// `evaluation` scored by the expression: when it succeeded, its fitness is the
    /// expression's value over its terms; a value that cannot be had (NaN, infinite, a
    /// division by zero) or that is at or below [`FAILURE_FITNESS`] makes it a failure
    /// (`invalid`, the failure floor, its terms and recording kept, the message saying why).
    /// A failed evaluation stays as it is.
    pub fn score(&self, mut evaluation: Evaluation) -> Evaluation {
        if evaluation.status != Status::Ok {
            return evaluation;
        }
        let problem = match self.value(&evaluation.terms) {
            Ok(value) if value > FAILURE_FITNESS => {
                evaluation.fitness = value;
                return evaluation;
            }
            Ok(value) => format!("gives {value}, at or below the failure floor {FAILURE_FITNESS}"),
            Err(problem) => problem,
        };
        evaluation.status = Status::Invalid;
        evaluation.fitness = FAILURE_FITNESS;
        evaluation.message = Some(format!(
            "the fitness expression \"{}\": {problem}",
            self.source
        ));
        evaluation
    }

    /// An error of the expression in words, with the column it starts at.
    fn at(&self, error: ExprError) -> String {
        let column = self.source[..error.span.start.min(self.source.len())]
            .chars()
            .count()
            + 1;
        format!("{} at column {column}", error.message)
    }
}

impl Serialize for FitnessExpression {
    /// As written.
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(&self.source)
    }
}

impl<'de> Deserialize<'de> for FitnessExpression {
    /// Any string: its check says whether it is an expression of the task's terms.
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        String::deserialize(deserializer).map(|text| FitnessExpression::new(&text))
    }
}

/// The fitness of a task that has named formulas (`F`, the walker's [`super::WalkerFitness`]):
/// one of them, or an expression of its terms. A config writes either as a string
/// (`fitness = "hornby-pollack"`, `fitness = "D_w - 0.5 * drag"`): a formula's name is the
/// formula, anything else an expression. A formula is stored, and hashed into evaluation
/// keys, as it was before expressions existed.
#[derive(Clone, Debug, PartialEq)]
pub enum Fitness<F> {
    /// A named formula.
    Formula(F),
    /// An expression of the task's terms.
    Expression(FitnessExpression),
}

impl<F: FromStr> Fitness<F> {
    /// The formula named `text`, else `text` as an expression.
    pub fn new(text: &str) -> Fitness<F> {
        match text.parse() {
            Ok(formula) => Fitness::Formula(formula),
            Err(_) => Fitness::Expression(FitnessExpression::new(text)),
        }
    }
}

impl<F> Fitness<F> {
    /// The expression, when it is one.
    pub fn expression(&self) -> Option<&FitnessExpression> {
        match self {
            Fitness::Formula(_) => None,
            Fitness::Expression(e) => Some(e),
        }
    }
}

impl<F> From<F> for Fitness<F> {
    fn from(formula: F) -> Fitness<F> {
        Fitness::Formula(formula)
    }
}

impl<F: Serialize> Serialize for Fitness<F> {
    /// A formula as the formula serialises; an expression as written.
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Fitness::Formula(formula) => formula.serialize(serializer),
            Fitness::Expression(expression) => expression.serialize(serializer),
        }
    }
}

impl<'de, F: FromStr> Deserialize<'de> for Fitness<F> {
    /// A string: a formula's name, or an expression.
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        String::deserialize(deserializer).map(|text| Fitness::new(&text))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn terms(pairs: &[(&str, f64)]) -> BTreeMap<String, f64> {
        pairs.iter().map(|&(n, v)| (n.to_string(), v)).collect()
    }

    #[test]
    fn an_expression_of_terms_is_evaluated_as_the_language_evaluates_it() {
        let e = FitnessExpression::new("D_w - 0.5 * drag");
        assert_eq!(e.value(&terms(&[("D_w", 3.0), ("drag", 1.5)])), Ok(2.25));
        let e = FitnessExpression::new("max(D_w, 1) ^ 2 * (N >= 3) + pi * 0");
        assert_eq!(e.value(&terms(&[("D_w", 0.5), ("N", 3.0)])), Ok(1.0));
        assert!(e.reads("N") && !e.reads("drag"));
    }

    #[test]
    fn a_value_that_cannot_be_had_says_why_and_where() {
        let e = FitnessExpression::new("D_w / (N - 2)");
        assert_eq!(
            e.value(&terms(&[("D_w", 1.0), ("N", 2.0)])),
            Err("division by zero at column 1".to_string())
        );
        let e = FitnessExpression::new("1 + sqrt(D_w)");
        assert_eq!(
            e.value(&terms(&[("D_w", -1.0)])),
            Err("expression gives NaN (not a number) at column 5".to_string())
        );
    }

    #[test]
    fn the_check_names_an_unknown_term_and_the_closest() {
        let walker = ["D_w", "N", "drag"];
        let e = FitnessExpression::new("D_x - 0.5 * drag");
        assert_eq!(
            e.check("walker", &walker, &[]),
            Err(
                "reads D_x, which is not a term of the walker task (did you mean D_w?); its \
                 terms are D_w, N, drag, joint_gap"
                    .to_string()
            )
        );
        assert_eq!(
            FitnessExpression::new("D_w - pi * joint_gap").check("walker", &walker, &[]),
            Ok(())
        );
        assert_eq!(
            FitnessExpression::new("hornby-polack").check("walker", &walker, &["hornby-pollack"]),
            Err(
                "\"hornby-polack\" is not one of the walker task's formulas (did you mean \
                 hornby-pollack?) nor an expression of its terms"
                    .to_string()
            )
        );
    }

    #[test]
    fn the_check_refuses_bad_syntax_unknown_functions_and_chance() {
        let walker = ["D_w"];
        assert_eq!(
            FitnessExpression::new("D_w -").check("walker", &walker, &[]),
            Err(
                "\"D_w -\" is not an expression of the walker task's terms: expected a value, \
                 found the end at column 6"
                    .to_string()
            )
        );
        assert_eq!(
            FitnessExpression::new("sqr(D_w)").check("walker", &walker, &[]),
            Err(
                "\"sqr(D_w)\": unknown function 'sqr' (known: sin, cos, tan, asin, acos, atan, \
                 atan2, sqrt, exp, ln, log, abs, floor, ceil, round, min, max, clamp, pow, \
                 uniform, normal) at column 1"
                    .to_string()
            )
        );
        assert!(
            FitnessExpression::new("D_w + uniform(0, 1)")
                .check("walker", &walker, &[])
                .unwrap_err()
                .contains("draws random numbers")
        );
    }

    #[test]
    fn a_formula_keeps_its_form_and_anything_else_is_an_expression() {
        use crate::task::WalkerFitness;
        let f: Fitness<WalkerFitness> = Fitness::new("hornby-pollack");
        assert_eq!(f, Fitness::Formula(WalkerFitness::HornbyPollack));
        assert_eq!(
            serde_json::to_value(&f).unwrap(),
            serde_json::to_value(WalkerFitness::HornbyPollack).unwrap()
        );
        let f: Fitness<WalkerFitness> = serde_json::from_str("\"D_w - 0.5 * drag\"").unwrap();
        assert_eq!(
            f.expression().map(FitnessExpression::source),
            Some("D_w - 0.5 * drag")
        );
        assert_eq!(serde_json::to_string(&f).unwrap(), "\"D_w - 0.5 * drag\"");
    }
}
