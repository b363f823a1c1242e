//! Parallel rewriting: one derivation step, context matching, stochastic choice.

use rand::RngExt;
use rand_chacha::ChaCha8Rng;

use super::compile::{CompiledRule, PatternEl, RuleSet};
use super::expr::{EvalEnv, ExprError};
use super::string::{ModuleString, POP, PUSH};
use crate::lang::Span;

const NO_MATCH: u32 = u32::MAX;

/// Why a rewriting pass failed.
#[derive(Debug)]
pub(crate) enum Failure {
    /// An expression failed (division by zero, NaN, ...).
    Expr(ExprError),
    /// The string grew past the module limit; the span is the rule that crossed it.
    TooLong { span: Option<Span>, limit: usize },
    /// A `solve` rule matched in discrete mode.
    SolveInDiscreteMode { span: Span },
    /// An `?E` module could not be processed; the span is the rule that made it, if known.
    Query { span: Option<Span>, message: String },
    /// A module kept being rewritten at one instant of continuous time.
    NoSettling { span: Option<Span>, passes: usize },
}

/// What a pass did.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct PassStats {
    /// How many modules a discrete rule rewrote.
    pub rewritten: usize,
    /// The last discrete rule applied.
    pub last_rule: Option<Span>,
}

impl From<ExprError> for Failure {
    fn from(e: ExprError) -> Self {
        Failure::Expr(e)
    }
}

/// Scratch space reused across passes so that rewriting does not allocate per module.
#[derive(Debug, Default)]
pub(crate) struct Workspace {
    args: Vec<f64>,
    /// For each bracket, the index of its partner (or `NO_MATCH`).
    brackets: Vec<u32>,
    candidates: Vec<(u32, f64)>,
    open: Vec<usize>,
    /// Output indices of `?E` modules made by the last pass, with the rule that made them.
    pub query_origins: Vec<(u32, Span)>,
    /// The context modules bound by the last successful match: (first slot, module index).
    pub bound: Vec<(u32, u32)>,
    /// Arguments for evaluating ODE right-hand sides.
    pub scratch_args: Vec<f64>,
}

/// What one pass reads besides the string.
pub(crate) struct Pass<'a> {
    pub rules: &'a RuleSet,
    pub ignored: &'a [bool],
    pub t: f64,
    pub max_modules: usize,
    /// In continuous mode a `solve` rule keeps its module (the ODE grows it); in discrete
    /// mode it is an error.
    pub continuous: bool,
}

impl Pass<'_> {
    /// Rewrites `input` into `out` in parallel: every module by the first rule that matches,
    /// or copied when none does.
    pub fn rewrite(
        &self,
        input: &ModuleString,
        out: &mut ModuleString,
        ws: &mut Workspace,
        rng: &mut ChaCha8Rng,
    ) -> Result<PassStats, Failure> {
        out.clear();
        ws.query_origins.clear();
        let mut stats = PassStats::default();
        if self.rules.has_context {
            match_brackets(&input.syms, &mut ws.brackets, &mut ws.open);
        }
        let limit = self.max_modules;
        for i in 0..input.len() {
            let sym = input.syms[i] as usize;
            if let Some(Some(r)) = self.rules.always.get(sym) {
                let rule = &self.rules.rules[*r as usize];
                let start = out.len();
                append(
                    out,
                    rule.constant.as_ref().expect("'always' rules are constant"),
                );
                stats.rewritten += 1;
                stats.last_rule = Some(rule.span);
                if rule.emits_query {
                    self.note_queries(out, start, rule.span, ws);
                }
                if out.len() > limit {
                    return Err(Failure::TooLong {
                        span: Some(rule.span),
                        limit,
                    });
                }
                continue;
            }
            let ids = self.rules.by_symbol.get(sym).map_or(&[][..], |v| &v[..]);
            let mut applied = None;
            for (k, &r) in ids.iter().enumerate() {
                let rule = &self.rules.rules[r as usize];
                if !self.matches(rule, input, i, ws, rng)? {
                    continue;
                }
                let chosen = if rule.probability.is_some() {
                    self.choose(&ids[k..], input, i, ws, rng)?
                } else {
                    rule
                };
                if chosen.solve.is_some() {
                    if !self.continuous {
                        return Err(Failure::SolveInDiscreteMode { span: chosen.span });
                    }
                    out.push_from(input, i);
                } else {
                    let start = out.len();
                    self.apply(chosen, out, ws, rng)?;
                    stats.rewritten += 1;
                    stats.last_rule = Some(chosen.span);
                    if chosen.emits_query {
                        self.note_queries(out, start, chosen.span, ws);
                    }
                }
                applied = Some(chosen.span);
                break;
            }
            if applied.is_none() {
                out.push_from(input, i);
            }
            if out.len() > limit {
                return Err(Failure::TooLong {
                    span: applied,
                    limit,
                });
            }
        }
        Ok(stats)
    }

    /// Records where the `?E` modules just appended from `start` came from.
    fn note_queries(&self, out: &ModuleString, start: usize, span: Span, ws: &mut Workspace) {
        for j in start..out.len() {
            if self.rules.query == Some(out.syms[j]) {
                ws.query_origins.push((j as u32, span));
            }
        }
    }

    /// The index of the first rule that matches module `i`, if any (for continuous time:
    /// which rule a module lives under). Binds nothing the caller may use.
    pub fn first_match(
        &self,
        input: &ModuleString,
        i: usize,
        ws: &mut Workspace,
        rng: &mut ChaCha8Rng,
    ) -> Result<Option<u32>, Failure> {
        let sym = input.syms[i] as usize;
        if let Some(Some(r)) = self.rules.always.get(sym) {
            return Ok(Some(*r));
        }
        let ids = self.rules.by_symbol.get(sym).map_or(&[][..], |v| &v[..]);
        for &r in ids {
            if self.matches(&self.rules.rules[r as usize], input, i, ws, rng)? {
                return Ok(Some(r));
            }
        }
        Ok(None)
    }

    /// Prepares the bracket table for [`first_match`](Self::first_match) on `input`.
    pub fn prepare(&self, input: &ModuleString, ws: &mut Workspace) {
        if self.rules.has_context {
            match_brackets(&input.syms, &mut ws.brackets, &mut ws.open);
        }
    }

    /// Draws one of the stochastic rules in `ids` that match, by weight, and binds its
    /// parameters.
    fn choose<'r>(
        &'r self,
        ids: &[u32],
        input: &ModuleString,
        i: usize,
        ws: &mut Workspace,
        rng: &mut ChaCha8Rng,
    ) -> Result<&'r CompiledRule, Failure> {
        let mut candidates = std::mem::take(&mut ws.candidates);
        candidates.clear();
        let mut total = 0.0;
        for &r in ids {
            let rule = &self.rules.rules[r as usize];
            if let Some(p) = rule.probability
                && self.matches(rule, input, i, ws, rng)?
            {
                total += p;
                candidates.push((r, total));
            }
        }
        let draw = rng.random::<f64>() * total;
        let chosen = candidates
            .iter()
            .find(|&&(_, cumulative)| draw < cumulative)
            .or(candidates.last())
            .map(|&(r, _)| r)
            .expect("the first matching rule is a candidate");
        ws.candidates = candidates;
        let rule = &self.rules.rules[chosen as usize];
        // Bind the chosen rule's parameters again (the last match bound another's).
        self.matches(rule, input, i, ws, rng)?;
        Ok(rule)
    }

    /// Whether `rule` matches module `i`, binding its parameters into `ws.args`.
    fn matches(
        &self,
        rule: &CompiledRule,
        input: &ModuleString,
        i: usize,
        ws: &mut Workspace,
        rng: &mut ChaCha8Rng,
    ) -> Result<bool, Failure> {
        let params = input.params(i);
        if params.len() != rule.arity {
            return Ok(false);
        }
        ws.args.clear();
        ws.args.resize(rule.slots, 0.0);
        ws.bound.clear();
        ws.args[..rule.arity].copy_from_slice(params);
        if !rule.left.is_empty() && !self.context_matches(Side::Left, rule, input, i, ws) {
            return Ok(false);
        }
        if !rule.right.is_empty() && !self.context_matches(Side::Right, rule, input, i, ws) {
            return Ok(false);
        }
        if rule
            .constraints
            .iter()
            .any(|&(slot, value)| ws.args[slot] != value)
        {
            return Ok(false);
        }
        match &rule.guard {
            None => Ok(true),
            Some(guard) => {
                let mut env = EvalEnv {
                    args: &ws.args,
                    t: self.t,
                    rng,
                };
                Ok(guard.eval(&mut env)? != 0.0)
            }
        }
    }

    /// Whether the rule's context on `side` of module `i` matches (cpfg), its parameters bound
    /// in `ws`. The left context, walking back: `[` is skipped (to the parent), a whole
    /// preceding branch `[...]` is skipped at its `]`, and ignored modules are skipped. The
    /// right context: lateral branches the pattern does not ask for are skipped, the end of the
    /// current branch stops the match, a `]` in the pattern skips to the end of the current
    /// branch, and ignored modules are skipped.
    #[inline]
    fn context_matches(
        &self,
        side: Side,
        rule: &CompiledRule,
        input: &ModuleString,
        i: usize,
        ws: &mut Workspace,
    ) -> bool {
        let syms = &input.syms;
        match side {
            Side::Left => {
                let mut j = i; // the next module to look at is j - 1
                for el in rule.left.iter().rev() {
                    let PatternEl::Module { sym, arity, slot } = *el else {
                        unreachable!("left contexts hold no brackets (checked when compiled)")
                    };
                    loop {
                        if j == 0 {
                            return false;
                        }
                        let s = syms[j - 1];
                        if s == sym {
                            break;
                        } else if s == POP {
                            let open = ws.brackets[j - 1];
                            if open == NO_MATCH {
                                return false;
                            }
                            j = open as usize;
                        } else if s == PUSH || self.ignored[s as usize] {
                            j -= 1;
                        } else {
                            return false;
                        }
                    }
                    if !bind(input, j - 1, arity, slot, ws) {
                        return false;
                    }
                    j -= 1;
                }
            }
            Side::Right => {
                let n = syms.len();
                let mut j = i + 1;
                for el in &rule.right {
                    match *el {
                        PatternEl::Push => {
                            while j < n && syms[j] != PUSH && self.ignored[syms[j] as usize] {
                                j += 1;
                            }
                            if j < n && syms[j] == PUSH {
                                j += 1;
                            } else {
                                return false;
                            }
                        }
                        PatternEl::Pop => loop {
                            if j >= n {
                                return false;
                            }
                            match syms[j] {
                                POP => {
                                    j += 1;
                                    break;
                                }
                                PUSH => {
                                    let close = ws.brackets[j];
                                    if close == NO_MATCH {
                                        return false;
                                    }
                                    j = close as usize + 1;
                                }
                                _ => j += 1,
                            }
                        },
                        PatternEl::Module { sym, arity, slot } => {
                            loop {
                                if j >= n {
                                    return false;
                                }
                                let s = syms[j];
                                if s == sym {
                                    break;
                                } else if s == PUSH {
                                    let close = ws.brackets[j];
                                    if close == NO_MATCH {
                                        return false;
                                    }
                                    j = close as usize + 1;
                                } else if s != POP && self.ignored[s as usize] {
                                    j += 1;
                                } else {
                                    return false;
                                }
                            }
                            if !bind(input, j, arity, slot, ws) {
                                return false;
                            }
                            j += 1;
                        }
                    }
                }
            }
        }
        true
    }

    fn apply(
        &self,
        rule: &CompiledRule,
        out: &mut ModuleString,
        ws: &Workspace,
        rng: &mut ChaCha8Rng,
    ) -> Result<(), ExprError> {
        if let Some(constant) = &rule.constant {
            append(out, constant);
            return Ok(());
        }
        let mut env = EvalEnv {
            args: &ws.args,
            t: self.t,
            rng,
        };
        for (sym, args) in &rule.successor {
            out.syms.push(*sym);
            for a in args {
                let v = a.eval(&mut env)?;
                out.params.push(v);
            }
            out.bounds.push(out.params_len());
        }
        Ok(())
    }
}

/// A side of a rule's predecessor: its left or its right context.
#[derive(Clone, Copy)]
enum Side {
    Left,
    Right,
}

/// Binds the parameters of module `k` of `input` to the rule's slots from `slot` on, as its
/// context pattern's module of `arity` parameters; false when the module has another number.
#[inline]
fn bind(input: &ModuleString, k: usize, arity: usize, slot: usize, ws: &mut Workspace) -> bool {
    let params = input.params(k);
    if params.len() != arity {
        return false;
    }
    ws.args[slot..slot + arity].copy_from_slice(params);
    ws.bound.push((slot as u32, k as u32));
    true
}

/// Appends a whole string.
#[inline]
fn append(out: &mut ModuleString, tail: &ModuleString) {
    let base = out.params_len();
    out.syms.extend_from_slice(&tail.syms);
    if tail.params.is_empty() {
        out.bounds
            .extend(std::iter::repeat_n(base, tail.syms.len()));
    } else {
        out.params.extend_from_slice(&tail.params);
        out.bounds.extend(tail.bounds[1..].iter().map(|b| b + base));
    }
}

/// Pairs every bracket with its partner; unmatched ones get `NO_MATCH`.
fn match_brackets(syms: &[u32], table: &mut Vec<u32>, open: &mut Vec<usize>) {
    table.clear();
    table.resize(syms.len(), NO_MATCH);
    open.clear();
    for (i, &s) in syms.iter().enumerate() {
        if s == PUSH {
            open.push(i);
        } else if s == POP
            && let Some(j) = open.pop()
        {
            table[i] = j as u32;
            table[j] = i as u32;
        }
    }
}
