//! Cutting a derivation short once its result is decided, and bounding the rest of its work.
//!
//! - A **fixed point**: when every step is a pure function of the string (no stochastic
//!   rule, no random function, no rule that reads the time, no `?E`), a step that leaves the
//!   string as it was leaves it so at every later step: no more steps need deriving
//!   ([`LSystem::steps_are_pure`]).
//! - A **settled prefix**: the modules before the first one that any rule (production or
//!   interpretation) or `?E` could change are never changed again, in discrete or continuous
//!   time ([`LSystem::settled_prefix`]); the builder, which reads a string left to right,
//!   uses it to stop at the part limit as soon as the prefix alone passes it.
//! - A **work budget** ([`WorkBudget`]): the modules that all the rewriting passes read
//!   together (about modules × steps), refused past [`DeriveOptions::max_work`] with a
//!   message naming `--max-work`, so that a derivation that is decided by nothing above
//!   cannot run for minutes.

use super::{DeriveOptions, LSystem, ModuleString};
use crate::lang::{Diagnostic, DiagnosticKind};

/// The default work budget of a derivation ([`DeriveOptions::max_work`]): the modules all
/// its rewriting passes may read together: under a second of rewriting.
pub const DEFAULT_MAX_WORK: u64 = 20_000_000;

/// The work a derivation has done, against its budget.
#[derive(Clone, Copy, Debug)]
pub(crate) struct WorkBudget {
    done: u64,
    most: u64,
}

impl WorkBudget {
    /// A fresh budget of `options.max_work`.
    pub(crate) fn new(options: &DeriveOptions) -> WorkBudget {
        WorkBudget {
            done: 0,
            most: options.max_work,
        }
    }

    /// Spends the work of a pass over `modules` modules (at least 1: a pass over an empty
    /// string still costs a step); `Err` when the budget would be passed, saying `when`.
    pub(crate) fn spend(&mut self, modules: usize, when: &str) -> Result<(), Diagnostic> {
        let cost = (modules as u64).max(1);
        if self.done.saturating_add(cost) > self.most {
            return Err(Diagnostic::without_location(
                DiagnosticKind::Runtime,
                format!(
                    "{when}, the derivation would rewrite more than {} modules in all \
                     (modules × steps, the work budget): raise it with --max-work, or lower \
                     the steps or the time",
                    self.most
                ),
            ));
        }
        self.done += cost;
        Ok(())
    }
}

impl LSystem {
    /// Whether a discrete step is a pure function of the string: no production is
    /// stochastic or reads the time or a random function (in its guard or its successor),
    /// and there is no `?E`. Then a step that changes nothing is a fixed point.
    pub fn steps_are_pure(&self) -> bool {
        self.query.is_none()
            && self.productions.rules.iter().all(|rule| {
                rule.probability.is_none()
                    && rule
                        .guard
                        .iter()
                        .chain(rule.successor.iter().flat_map(|(_, args)| args))
                        .all(|e| !e.uses_time() && !e.uses_random())
            })
    }

    /// Whether the system has `?E` modules, through which the environment can change.
    pub fn queries_environment(&self) -> bool {
        self.query.is_some()
    }

    /// How many modules at the start of `s` no later step can change: those before the
    /// first module whose symbol has a rule (of the productions or the interpretation) or is
    /// `?E`. Every later string, in discrete or continuous time, and its interpretation,
    /// starts with these modules as they are.
    pub fn settled_prefix(&self, s: &ModuleString) -> usize {
        let has_rules = |sym: u32| {
            let sym = sym as usize;
            let rules =
                |set: &super::RuleSet| set.by_symbol.get(sym).is_some_and(|r| !r.is_empty());
            rules(&self.productions) || rules(&self.interpretation)
        };
        s.syms
            .iter()
            .position(|&sym| Some(sym) == self.query || has_rules(sym))
            .unwrap_or(s.len())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_budget_refuses_the_pass_that_would_pass_it_and_names_the_flag() {
        let options = DeriveOptions {
            max_work: 10,
            ..DeriveOptions::default()
        };
        let mut budget = WorkBudget::new(&options);
        budget.spend(6, "at step 1").unwrap();
        budget.spend(4, "at step 2").unwrap();
        let e = budget.spend(0, "at step 3").unwrap_err().to_string();
        assert!(
            e.contains("at step 3, the derivation would rewrite more than 10 modules"),
            "{e}"
        );
        assert!(e.contains("--max-work"), "{e}");
    }

    #[test]
    fn steps_are_pure_without_chance_time_or_the_environment() {
        let pure = |text: &str| LSystem::from_text("t", text).unwrap().steps_are_pure();
        assert!(pure("axiom: A\nA --> A B\n"));
        assert!(pure("axiom: A(1)\nA(x) : x < 3 --> A(x + 1)\n"));
        assert!(!pure("axiom: A\nA --> A : 0.5\nA --> B : 0.5\n"));
        assert!(!pure("axiom: A(0)\nA(x) : t < 3 --> A(x)\n"));
        assert!(!pure("axiom: A(0)\nA(x) --> A(uniform(0, 1))\n"));
    }

    #[test]
    fn the_settled_prefix_ends_at_the_first_module_a_rule_could_change() {
        let lsys = LSystem::from_text(
            "t",
            "axiom: forward(1) [ left forward(1) ] A forward(1)\nA --> forward(1) A\n",
        )
        .unwrap();
        assert_eq!(lsys.settled_prefix(lsys.axiom()), 5);
        let lsys = LSystem::from_text(
            "t",
            "axiom: forward(1) B\nB --> B\ninterpretation:\nforward(x) --> forward(x)\n",
        )
        .unwrap();
        assert_eq!(lsys.settled_prefix(lsys.axiom()), 0);
    }
}
