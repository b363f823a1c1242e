//! From syntax tree to a ready-to-derive [`LSystem`]: names resolved, arities checked,
//! constants folded.

use std::collections::HashMap;
use std::sync::Arc;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use super::LSystem;
use super::defines::{DefineOverride, override_of, unknown_define};
use super::expr::{self, CExpr, EvalEnv, ExprError, Resolved};
use super::string::{ModuleString, POP, PUSH, SymbolId, SymbolTable};
use crate::environment::Environment;
use crate::lang::ast::{
    Expr, LsysFile, ModuleCall, PatternModule, Rule, Section, Timing, is_constant_formal,
};
use crate::lang::{Diagnostic, DiagnosticKind, Source, Span};

/// One element of a context pattern.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum PatternEl {
    /// `[`: the context enters a branch.
    Push,
    /// `]`: the context skips to the end of the current branch.
    Pop,
    /// A module, binding its parameters to slots `slot..slot + arity`.
    Module {
        sym: SymbolId,
        arity: usize,
        slot: usize,
    },
}

/// A rule ready to apply.
#[derive(Clone, Debug)]
pub(crate) struct CompiledRule {
    pub pred: SymbolId,
    pub arity: usize,
    pub left: Vec<PatternEl>,
    pub right: Vec<PatternEl>,
    /// Parameters bound when matching: predecessor's, then left context's, then right's.
    pub slots: usize,
    pub guard: Option<CExpr>,
    pub successor: Vec<(SymbolId, Vec<CExpr>)>,
    /// For a differential rule: (parameter index, rate) for each ODE.
    pub solve: Option<Vec<(usize, CExpr)>>,
    /// Whether the successor holds `?E` modules.
    pub emits_query: bool,
    /// The successor, when none of its parameters depends on the match.
    pub constant: Option<ModuleString>,
    pub probability: Option<f64>,
    /// Argument slots that must hold a given value (numbers written in a pattern).
    pub constraints: Vec<(usize, f64)>,
    pub span: Span,
}

impl CompiledRule {
    /// Whether the rule applies to every module with its predecessor, whatever the string.
    pub fn unconditional(&self) -> bool {
        self.left.is_empty()
            && self.right.is_empty()
            && self.constraints.is_empty()
            && self.probability.is_none()
            && self
                .guard
                .as_ref()
                .is_none_or(|g| g.as_const().is_some_and(|v| v != 0.0))
    }
}

/// The rules of one section, indexed by predecessor.
#[derive(Clone, Debug, Default)]
pub(crate) struct RuleSet {
    pub rules: Vec<CompiledRule>,
    /// For each symbol, its rules in file order.
    pub by_symbol: Vec<Vec<u32>>,
    /// For each symbol, the rule that always applies with a constant successor, if any:
    /// derivation copies that successor without evaluating anything.
    pub always: Vec<Option<u32>>,
    /// Whether any rule has a context (then derivation needs the bracket table).
    pub has_context: bool,
    /// The id of `?E`, if the system has it.
    pub query: Option<SymbolId>,
    /// Whether some rule's choice can depend on other modules or on the time (context, or
    /// a guard that reads `t`): continuous time must then watch every module for events.
    pub guards_see_outside: bool,
}

impl RuleSet {
    fn index(&mut self, symbols: usize) {
        self.by_symbol = vec![Vec::new(); symbols];
        for (i, rule) in self.rules.iter().enumerate() {
            self.by_symbol[rule.pred as usize].push(i as u32);
        }
        self.always = self
            .by_symbol
            .iter()
            .map(|ids| {
                let &first = ids.first()?;
                let rule = &self.rules[first as usize];
                (rule.unconditional() && rule.constant.is_some() && rule.solve.is_none())
                    .then_some(first)
            })
            .collect();
        self.has_context = self
            .rules
            .iter()
            .any(|r| !r.left.is_empty() || !r.right.is_empty());
        self.guards_see_outside = self.has_context
            || self.rules.iter().any(|r| {
                r.guard
                    .as_ref()
                    .is_some_and(|g| g.uses_time() || g.uses_random())
            });
    }
}

/// Compiles `file`, read from `source`, with `overrides` in place of the values its defines
/// give (see [`super::defines`]).
pub(crate) fn compile(
    source: Arc<Source>,
    file: LsysFile,
    overrides: &[DefineOverride],
) -> Result<LSystem, Diagnostic> {
    let mut c = Compiler {
        source: &source,
        symbols: SymbolTable::default(),
        constants: Vec::new(),
        arity: HashMap::new(),
        environment_len: 0,
    };
    let seed = file.seed.map_or(0, |(s, _)| s);

    if let Some(unknown) = overrides
        .iter()
        .find(|o| !file.defines.iter().any(|d| d.name == o.name))
    {
        return Err(unknown_define(&source, &unknown.name, &file.defines));
    }

    // Constants, in order; each may use the ones before it. An overridden one is still
    // evaluated, so that the random draws of those after it do not change.
    let mut define_rng = ChaCha8Rng::seed_from_u64(seed);
    define_rng.set_stream(2);
    for define in &file.defines {
        if let Some((_, _, first)) = c.constants.iter().find(|(n, ..)| *n == define.name) {
            let (line, _) = source.line_col(first.start);
            return Err(c.error(
                define.name_span,
                format!(
                    "constant '{}' is defined twice (first on line {line})",
                    define.name
                ),
            ));
        }
        let value = c.constant_expr(&define.value, &mut define_rng)?;
        let value = override_of(overrides, &define.name).unwrap_or(value);
        c.constants
            .push((define.name.clone(), value, define.name_span));
    }

    // Predecessor arities: a symbol rewritten by rules has one arity everywhere.
    for rule in &file.rules {
        let p = &rule.predecessor;
        if p.name == "[" || p.name == "]" {
            return Err(c.error(p.span, "a bracket cannot be a predecessor"));
        }
        c.check_arity(&p.name, p.params.len(), p.span)?;
    }

    let mut axiom = ModuleString::new();
    let axiom_span = match &file.axiom {
        Some((calls, span)) => {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            rng.set_stream(3);
            for call in calls {
                let sym = c.module_symbol(call)?;
                let mut params = Vec::with_capacity(call.args.len());
                for arg in &call.args {
                    params.push(c.constant_expr(arg, &mut rng)?);
                }
                axiom.push(sym, &params);
            }
            *span
        }
        None => {
            return Err(Diagnostic::without_location(
                DiagnosticKind::Semantic,
                format!("{}: no 'axiom:' line", source.name()),
            )
            .with_note("every L-system needs a starting string, e.g. 'axiom: F'"));
        }
    };

    let derivation_length = match &file.derivation_length {
        Some(e) => {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            let v = c.constant_expr(e, &mut rng)?;
            if v < 0.0 || v.fract() != 0.0 || v > 1e9 {
                return Err(c.error(
                    e.span(),
                    format!("derivation length must be a whole number from 0 to 10^9, not {v}"),
                ));
            }
            Some(v as u64)
        }
        None => None,
    };

    let environment = Environment::new(
        file.environment
            .as_ref()
            .map_or_else(Vec::new, |(values, _)| values.clone()),
    );
    let mut settings_rng = ChaCha8Rng::seed_from_u64(seed);
    let time = match &file.time {
        Some(e) => {
            let v = c.constant_expr(e, &mut settings_rng)?;
            if v < 0.0 {
                return Err(c.error(e.span(), format!("time must be 0 or more, not {v}")));
            }
            Some(v)
        }
        None => None,
    };
    let dt = match &file.dt {
        Some(e) => {
            let v = c.constant_expr(e, &mut settings_rng)?;
            if v <= 0.0 {
                return Err(c.error(e.span(), format!("dt must be more than 0, not {v}")));
            }
            Some(v)
        }
        None => None,
    };
    let timing = file.timing.map(|(t, _)| t).unwrap_or(Timing::Exact);
    let mut turtle = super::TurtleHeaders {
        heading: file.heading.map(|(h, _)| h).unwrap_or_default(),
        ..Default::default()
    };
    if let Some(e) = &file.angle {
        let v = c.constant_expr(e, &mut settings_rng)?;
        if !v.is_finite() {
            return Err(c.error(
                e.span(),
                format!("angle must be a finite number of degrees, not {v}"),
            ));
        }
        turtle.angle = Some(v);
    }
    if let Some(e) = &file.step {
        let v = c.constant_expr(e, &mut settings_rng)?;
        if !(v.is_finite() && v > 0.0) {
            return Err(c.error(e.span(), format!("step must be more than 0, not {v}")));
        }
        turtle.step = Some(v);
    }
    crate::lang::textbook::check_supported(&file, &source)?;
    c.environment_len = environment.len();
    c.check_queries(axiom_calls(&file))?;

    let mut ignored = Vec::new();
    for (name, span) in &file.ignore {
        if name == "[" || name == "]" {
            return Err(c.error(*span, "brackets cannot be ignored: they shape the branches"));
        }
        ignored.push(c.symbols.intern(name));
    }

    let mut productions = RuleSet::default();
    let mut interpretation = RuleSet::default();
    for rule in &file.rules {
        let compiled = c.rule(rule)?;
        match rule.section {
            Section::Productions => productions.rules.push(compiled),
            Section::Interpretation => interpretation.rules.push(compiled),
        }
    }
    let n = c.symbols.len();
    productions.index(n);
    interpretation.index(n);
    productions.query = c.symbols.id(QUERY);
    interpretation.query = productions.query;
    let mut ignored_by_symbol = vec![false; n];
    for id in ignored {
        ignored_by_symbol[id as usize] = true;
    }

    let query = c.symbols.id(QUERY);
    Ok(LSystem {
        symbols: c.symbols,
        constants: c.constants,
        axiom,
        axiom_span,
        seed,
        derivation_length,
        productions,
        interpretation,
        ignored: ignored_by_symbol,
        query,
        environment,
        time,
        dt,
        timing,
        turtle,
        file,
        source,
    })
}

/// The name of the open L-system's environment module.
pub(crate) const QUERY: &str = "?E";

fn axiom_calls(file: &LsysFile) -> &[ModuleCall] {
    file.axiom
        .as_ref()
        .map_or(&[], |(calls, _)| calls.as_slice())
}

struct Compiler<'s> {
    source: &'s Arc<Source>,
    symbols: SymbolTable,
    constants: Vec<(String, f64, Span)>,
    /// Arity of every predecessor symbol, with the place that fixed it.
    arity: HashMap<String, (usize, Span)>,
    /// Size of the environment array.
    environment_len: usize,
}

impl Compiler<'_> {
    fn error(&self, span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic::at(DiagnosticKind::Semantic, self.source, span, message)
    }

    fn expr_error(&self, e: ExprError) -> Diagnostic {
        self.error(e.span, e.message)
    }

    fn constant(&self, name: &str) -> Option<f64> {
        self.constants
            .iter()
            .rev()
            .find(|(n, ..)| n == name)
            .map(|(_, v, _)| *v)
    }

    /// An expression that may use only constants (defines, axiom, derivation length).
    fn constant_expr(&self, e: &Expr, rng: &mut ChaCha8Rng) -> Result<f64, Diagnostic> {
        let resolve = |name: &str| self.constant(name).map(Resolved::Const);
        let compiled = expr::compile(e, &resolve).map_err(|err| self.expr_error(err))?;
        let mut env = EvalEnv {
            args: &[],
            t: 0.0,
            rng,
        };
        compiled.eval(&mut env).map_err(|err| self.expr_error(err))
    }

    /// `?E(mode, index, value)` modules: three parameters; constant modes and indices are
    /// checked against the environment now.
    fn check_queries(&self, calls: &[ModuleCall]) -> Result<(), Diagnostic> {
        for call in calls.iter().filter(|c| c.name == QUERY) {
            if call.args.len() != 3 {
                return Err(self.error(
                    call.span,
                    format!(
                        "?E takes 3 parameters (mode, index, value), not {}",
                        call.args.len()
                    ),
                ));
            }
            // A value known before deriving: literals, constants and what folds from them.
            let constant = |e: &Expr| {
                let resolve = |name: &str| self.constant(name).map(Resolved::Const);
                expr::compile(e, &resolve).ok().and_then(|c| c.as_const())
            };
            if let Some(mode) = constant(&call.args[0])
                && mode != 0.0
                && mode != 1.0
            {
                return Err(self.error(
                    call.args[0].span(),
                    format!("?E's mode is 0 (write) or 1 (read), not {mode}"),
                ));
            }
            if let Some(index) = constant(&call.args[1])
                && (index < 0.0 || index.fract() != 0.0 || index >= self.environment_len as f64)
            {
                return Err(self.error(
                    call.args[1].span(),
                    format!(
                        "?E's index {index} is outside the environment of {} slot(s) (see 'environment:')",
                        self.environment_len
                    ),
                ));
            }
        }
        Ok(())
    }

    fn check_arity(&mut self, name: &str, arity: usize, span: Span) -> Result<(), Diagnostic> {
        match self.arity.get(name) {
            Some(&(expected, first)) if expected != arity => {
                let (line, _) = self.source.line_col(first.start);
                Err(self.error(
                    span,
                    format!(
                        "'{name}' has {arity} parameter{} here, but its rule on line {line} takes {expected}",
                        plural(arity)
                    ),
                ))
            }
            Some(_) => Ok(()),
            None => {
                self.arity.insert(name.to_string(), (arity, span));
                Ok(())
            }
        }
    }

    /// The error for `call` given other parameters than `takes` says it takes.
    fn given_wrong_count(&self, call: &ModuleCall, takes: &str) -> Diagnostic {
        let n = call.args.len();
        self.error(
            call.span,
            format!(
                "'{}' is given {n} parameter{}, but {takes}",
                call.name,
                plural(n)
            ),
        )
    }

    /// Checks a module's arity against its predecessor's (if it has one) and interns it.
    fn module_symbol(&mut self, call: &ModuleCall) -> Result<SymbolId, Diagnostic> {
        if let Some(&(expected, first)) = self.arity.get(&call.name)
            && expected != call.args.len()
        {
            let (line, _) = self.source.line_col(first.start);
            return Err(
                self.given_wrong_count(call, &format!("the rule on line {line} takes {expected}"))
            );
        }
        if (call.name == "[" || call.name == "]") && !call.args.is_empty() {
            return Err(self.error(call.span, "brackets take no parameters"));
        }
        // A built-in command a rule rewrites takes what its rule takes (checked above): the
        // builder reads its first parameters (`mforward(x, l)`, a limb growing to l).
        if let Some((takes, what)) = crate::lang::builtin_parameters(&call.name)
            && call.args.len() > takes
            && !self.arity.contains_key(&call.name)
        {
            let takes = match takes {
                0 => "none".to_string(),
                n => format!("{n} ({what})"),
            };
            return Err(
                self.given_wrong_count(call, &format!("the built-in command takes {takes}"))
            );
        }
        Ok(self.symbols.intern(&call.name))
    }

    fn pattern_symbol(&mut self, p: &PatternModule) -> Result<SymbolId, Diagnostic> {
        if p.name == QUERY && p.params.len() != 3 {
            return Err(self.error(
                p.span,
                format!(
                    "?E takes 3 parameters (mode, index, value), not {}",
                    p.params.len()
                ),
            ));
        }
        let call = ModuleCall {
            name: p.name.clone(),
            args: vec![Expr::Number(0.0, p.span); p.params.len()],
            span: p.span,
        };
        self.module_symbol(&call)
    }

    fn rule(&mut self, rule: &Rule) -> Result<CompiledRule, Diagnostic> {
        // Formal parameters: predecessor, then left context, then right context.
        let mut names: Vec<(String, Span)> = Vec::new();
        let mut constraints = Vec::new();
        let mut bind = |params: &[(String, Span)], c: &Compiler<'_>| -> Result<usize, Diagnostic> {
            let slot = names.len();
            for (name, span) in params {
                if is_constant_formal(name) {
                    let value: f64 = name
                        .parse()
                        .map_err(|_| c.error(*span, format!("'{name}' is not a number")))?;
                    constraints.push((names.len(), value));
                    // A slot no expression can name.
                    names.push((format!("#{}", names.len()), *span));
                    continue;
                }
                if names.iter().any(|(n, _)| n == name) {
                    return Err(c.error(
                        *span,
                        format!("parameter '{name}' is named twice in this rule"),
                    ));
                }
                names.push((name.clone(), *span));
            }
            Ok(slot)
        };
        let pred = self.pattern_symbol(&rule.predecessor)?;
        let arity = rule.predecessor.params.len();
        bind(&rule.predecessor.params, self)?;

        let mut left = Vec::new();
        for p in &rule.left {
            if p.name == "[" || p.name == "]" {
                return Err(self.error(
                    p.span,
                    "brackets are not allowed in a left context (it already skips branches)",
                ));
            }
            let sym = self.pattern_symbol(p)?;
            let slot = bind(&p.params, self)?;
            left.push(PatternEl::Module {
                sym,
                arity: p.params.len(),
                slot,
            });
        }
        let mut right = Vec::new();
        for p in &rule.right {
            let el = match p.name.as_str() {
                "[" | "]" if !p.params.is_empty() => {
                    return Err(self.error(p.span, "brackets take no parameters"));
                }
                "[" => PatternEl::Push,
                "]" => PatternEl::Pop,
                _ => {
                    let sym = self.pattern_symbol(p)?;
                    let slot = bind(&p.params, self)?;
                    PatternEl::Module {
                        sym,
                        arity: p.params.len(),
                        slot,
                    }
                }
            };
            right.push(el);
        }
        let slots = names.len();

        let resolve = |name: &str| {
            if let Some(i) = names.iter().position(|(n, _)| n == name) {
                Some(Resolved::Arg(i))
            } else if let Some(v) = self.constant(name) {
                Some(Resolved::Const(v))
            } else if name == "t" {
                Some(Resolved::Time)
            } else {
                None
            }
        };
        let compile = |e: &Expr| expr::compile(e, &resolve).map_err(|err| self.expr_error(err));

        let guard = rule.guard.as_ref().map(compile).transpose()?;
        let solve = match &rule.solve {
            None => None,
            Some(odes) => {
                if rule.section == Section::Interpretation {
                    return Err(self.error(
                        rule.span,
                        "interpretation rules cannot 'solve': they only rewrite for the builder",
                    ));
                }
                if arity == 0 {
                    return Err(self.error(
                        rule.predecessor.span,
                        format!(
                            "'solve' needs parameters to change, but '{}' has none",
                            rule.predecessor.name
                        ),
                    ));
                }
                if let Some(p) = &rule.probability {
                    return Err(self.error(p.span(), "a 'solve' rule cannot be stochastic"));
                }
                let mut compiled = Vec::with_capacity(odes.len());
                for ode in odes {
                    let Some(index) = rule
                        .predecessor
                        .params
                        .iter()
                        .position(|(n, _)| *n == ode.param)
                    else {
                        let params: Vec<&str> = rule
                            .predecessor
                            .params
                            .iter()
                            .map(|(n, _)| n.as_str())
                            .collect();
                        return Err(self.error(
                            ode.span,
                            format!(
                                "'{}' is not a parameter of the predecessor {}({})",
                                ode.param,
                                rule.predecessor.name,
                                params.join(", ")
                            ),
                        ));
                    };
                    if compiled.iter().any(|(i, _)| *i == index) {
                        return Err(
                            self.error(ode.span, format!("d{}/dt is given twice", ode.param))
                        );
                    }
                    let rate = compile(&ode.rhs)?;
                    if rate.uses_random() {
                        return Err(self.error(
                            ode.rhs.span(),
                            "random functions cannot be used in an ODE (its value must not depend on the solver's steps)",
                        ));
                    }
                    compiled.push((index, rate));
                }
                Some(compiled)
            }
        };
        self.check_queries(&rule.successor)?;
        let mut successor = Vec::with_capacity(rule.successor.len());
        for call in &rule.successor {
            let args = call
                .args
                .iter()
                .map(compile)
                .collect::<Result<Vec<_>, _>>()?;
            successor.push((call.name.as_str(), args, call));
        }
        let probability = match &rule.probability {
            Some(e) => {
                let value = compile(e)?.as_const().ok_or_else(|| {
                    self.error(e.span(), "a probability must be a constant number")
                })?;
                if !(value > 0.0 && value <= 1.0) {
                    return Err(
                        self.error(e.span(), format!("probability {value} is not in (0, 1]"))
                    );
                }
                Some(value)
            }
            None => None,
        };

        let mut resolved = Vec::with_capacity(successor.len());
        for (_, args, call) in successor {
            let sym = self.module_symbol(call)?;
            resolved.push((sym, args));
        }
        let constant = resolved
            .iter()
            .all(|(_, args)| args.iter().all(|a| a.as_const().is_some()))
            .then(|| {
                let mut s = ModuleString::with_capacity(resolved.len(), 0);
                for (sym, args) in &resolved {
                    let params: Vec<f64> = args.iter().filter_map(CExpr::as_const).collect();
                    s.push(*sym, &params);
                }
                s
            });
        debug_assert!(pred != PUSH && pred != POP);
        Ok(CompiledRule {
            pred,
            arity,
            left,
            right,
            slots,
            guard,
            emits_query: resolved
                .iter()
                .any(|(sym, _)| self.symbols.name(*sym) == QUERY),
            successor: resolved,
            solve,
            constant,
            probability,
            constraints,
            span: rule.span,
        })
    }
}

fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}
