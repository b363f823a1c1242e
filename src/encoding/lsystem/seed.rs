//! A hand-written grammar as the L-system genome that seeds a run (`evolve --init`): its
//! rules kept as the genome's productions where they fit, rewritten into the genome's
//! forms where an equivalent exists (`-s` is `s * -1`, `2 * 0.5` is `1`, an axiom of several
//! modules becomes a first production, one derivation step more), else the string it
//! derives as one production (the same creature); the run's limits widened to fit the seed;
//! what cannot be represented listed all at once, each with its line and column.

use super::*;
use crate::encoding::Seed;
use crate::encoding::direct::{LSYSTEM_NOT_USED, derived_items, textbook_items, without_flags};
use crate::encoding::limits::{CheckedLimits, MOST_MODULES};
use crate::lsystem::TurtleHeaders;

/// The module through which a grammar reads the environment.
const QUERY: &str = "?E";

/// The most items a successor may hold under any limits (`max_successor`'s range).
const MOST_SUCCESSOR: usize = 256;

pub(super) fn refuse(message: impl Into<String>) -> DevelopError {
    DevelopError(format!(
        "this file does not fit the lsystem genome: {}",
        message.into()
    ))
}

/// Writes every named constant (`define`) of `file` into its axiom, guards and successors as
/// its value, where a rule's own parameter of that name does not hide it: the genome keeps
/// numbers, not names.
fn inline_constants(file: &mut lang::ast::LsysFile, constants: &[(&str, f64)]) {
    fn inline(e: &mut Expr, constants: &[(&str, f64)], formals: &[String]) {
        match e {
            Expr::Name(n, span) => {
                if !formals.contains(n)
                    && let Some((_, v)) = constants.iter().find(|(c, _)| c == n)
                {
                    *e = Expr::Number(*v, *span);
                }
            }
            Expr::Number(..) => {}
            Expr::Unary { operand, .. } => inline(operand, constants, formals),
            Expr::Binary { lhs, rhs, .. } => {
                inline(lhs, constants, formals);
                inline(rhs, constants, formals);
            }
            Expr::Call { args, .. } => {
                for a in args {
                    inline(a, constants, formals);
                }
            }
        }
    }
    if constants.is_empty() {
        return;
    }
    if let Some((axiom, _)) = &mut file.axiom {
        for a in axiom.iter_mut().flat_map(|call| call.args.iter_mut()) {
            inline(a, constants, &[]);
        }
    }
    for rule in &mut file.rules {
        let formals: Vec<String> = rule.predecessor.formals();
        if let Some(g) = &mut rule.guard {
            inline(g, constants, &formals);
        }
        for a in rule
            .successor
            .iter_mut()
            .flat_map(|call| call.args.iter_mut())
        {
            inline(a, constants, &formals);
        }
    }
}

/// The value of an expression without names (`2 * 0.5`, `-(1)`), computed as the language
/// computes it; `None` when it names anything or is not finite.
fn constant(e: &Expr) -> Option<f64> {
    let v = match e {
        Expr::Number(v, _) => *v,
        Expr::Unary {
            op: lang::ast::UnaryOp::Neg,
            operand,
            ..
        } => -constant(operand)?,
        Expr::Binary { op, lhs, rhs, .. } => {
            let (a, b) = (constant(lhs)?, constant(rhs)?);
            match op {
                BinaryOp::Add => a + b,
                BinaryOp::Sub => a - b,
                BinaryOp::Mul => a * b,
                BinaryOp::Div => a / b,
                _ => return None,
            }
        }
        _ => return None,
    };
    v.is_finite().then_some(v)
}

/// An argument in the genome's forms, exactly equal to `e` for every value of the
/// parameters (`formals`): a number, `s`, `s ± c`, `c + s`, `s * c`, `c * s`, `-s` (as
/// `s * -1`).
fn argument(e: &Expr, formals: &[String]) -> Option<Arg> {
    if let Some(v) = constant(e) {
        return Some(Arg::Const(v));
    }
    let param = |e: &Expr| match e {
        Expr::Name(n, _) => formals.iter().position(|f| f == n),
        _ => None,
    };
    match e {
        Expr::Name(..) => param(e).map(|i| Arg::Plus(i, 0.0)),
        Expr::Unary {
            op: lang::ast::UnaryOp::Neg,
            operand,
            ..
        } => param(operand).map(|i| Arg::Times(i, -1.0)),
        Expr::Binary { op, lhs, rhs, .. } => {
            let (i, c, swapped) = match (param(lhs), constant(rhs), param(rhs), constant(lhs)) {
                (Some(i), Some(c), _, _) => (i, c, false),
                (_, _, Some(i), Some(c)) => (i, c, true),
                _ => return None,
            };
            match op {
                BinaryOp::Add => Some(Arg::Plus(i, c)),
                BinaryOp::Sub if !swapped => Some(Arg::Plus(i, -c)),
                BinaryOp::Mul => Some(Arg::Times(i, c)),
                _ => None,
            }
        }
        _ => None,
    }
}

/// The slot of a read as a genome writes it before a call, `?E(1, SLOT, 0)`.
fn read_slot(call: &ModuleCall) -> Option<usize> {
    if call.name != QUERY {
        return None;
    }
    match call.args.as_slice() {
        [mode, slot, value] => {
            let (mode, slot, value) = (constant(mode)?, constant(slot)?, constant(value)?);
            (mode == 1.0 && value == 0.0 && slot >= 0.0 && slot.fract() == 0.0)
                .then_some(slot as usize)
        }
        _ => None,
    }
}

/// The slot and the value's name of a read as a production's left context,
/// `?E(1, SLOT, c)`.
fn read_pattern(pattern: &lang::ast::PatternModule) -> Option<(usize, String)> {
    let [(mode, _), (slot, _), (value, _)] = pattern.params.as_slice() else {
        return None;
    };
    let number = |s: &str| s.parse::<f64>().ok();
    if number(mode) != Some(1.0) || number(value).is_some() {
        return None;
    }
    let slot = number(slot).filter(|s| *s >= 0.0 && s.fract() == 0.0)?;
    Some((slot as usize, value.clone()))
}

/// The file's rules as the genome's productions, with notes on what was rewritten; `Err`
/// lists every reason they cannot be (each with its line and column).
fn structural(
    name: &str,
    text: &str,
    lsys: &LSystem,
) -> Result<(LSystemGenome, Vec<String>), Vec<String>> {
    let source = Source::new(name, text);
    let mut file = lang::parse(&source).map_err(|d| vec![d.to_string()])?;
    inline_constants(&mut file, &lsys.constants().collect::<Vec<_>>());
    let snippet = |span: lang::Span| text.get(span.start..span.end).unwrap_or("?").to_string();
    let place = |span: lang::Span| {
        let (line, column) = source.line_col(span.start);
        format!("line {line}, column {column}")
    };
    let mut reasons: Vec<String> = Vec::new();
    let mut notes: Vec<String> = Vec::new();
    if lsys.is_continuous() {
        reasons.push("it develops in continuous time; the genome derives discrete steps".into());
    }
    let environment = lsys.environment().values().to_vec();
    if let Some((lang::ast::Heading::Up, span)) = &file.heading {
        reasons.push(format!(
            "{}: its turtle starts heading up ('heading: up'); the genome's starts on the ground",
            place(*span)
        ));
    }
    let turtle = lsys.turtle();
    let Some((axiom, axiom_span)) = &file.axiom else {
        return Err(vec!["it has no axiom".into()]);
    };
    let rewritten_names: Vec<&String> = file
        .rules
        .iter()
        .filter(|r| r.section == Section::Productions)
        .map(|r| &r.predecessor.name)
        .collect();
    // The axiom is kept as P0's starting values when it is one call of a production with
    // numbers; else it becomes the successor of a new first production.
    // A read written before the start call is the start production's, as the genome
    // writes it: `axiom: ?E(1, 0, 0) P0(1, 2)`.
    let (axiom_read, axiom_call) = match axiom.as_slice() {
        [read, start] => match read_slot(read) {
            Some(slot) => (Some((slot, read.span)), std::slice::from_ref(start)),
            None => (None, axiom.as_slice()),
        },
        _ => (None, axiom.as_slice()),
    };
    let kept_axiom = match axiom_call {
        [start] if rewritten_names.contains(&&start.name) => {
            let values: Option<Vec<f64>> = start.args.iter().map(constant).collect();
            let arity = file
                .rules
                .iter()
                .find(|r| r.predecessor.name == start.name)
                .map(|r| r.predecessor.params.len());
            values.filter(|v| Some(v.len()) == arity)
        }
        _ => None,
    };
    let mut names: Vec<String> = Vec::new();
    match &kept_axiom {
        Some(_) => names.push(axiom_call[0].name.clone()),
        None => {
            names.push(String::new()); // the new first production
            notes.push(format!(
                "the axiom '{}' becomes the successor of a first production P0, derived one step more",
                snippet(*axiom_span)
            ));
        }
    }
    for name in rewritten_names {
        if !names.contains(name) {
            names.push(name.clone());
        }
    }
    let mut params = 0usize;
    let mut productions: Vec<Production> = vec![
        Production {
            pairs: Vec::new(),
            read: None,
        };
        names.len()
    ];
    // The reads written before calls: (production called, slot read or none, where).
    let mut calls: Vec<(usize, Option<usize>, lang::Span)> = Vec::new();
    if let (Some((slot, span)), Some(_)) = (axiom_read, &kept_axiom) {
        calls.push((0, Some(slot), span));
    }
    let successors = Successors {
        names: &names,
        turtle: &turtle,
        place: &place,
        snippet: &snippet,
        slots: environment.len(),
    };
    for rule in &file.rules {
        let at = place(rule.span);
        if rule.section == Section::Interpretation {
            reasons.push(format!(
                "{at}: interpretation rules are not part of the genome"
            ));
            continue;
        }
        // A production that reads: `?E(1, SLOT, c) < P1(n0, n1)`, the value read named by
        // its last formal.
        let mut read_name: Option<String> = None;
        match (rule.left.as_slice(), rule.right.is_empty()) {
            ([], true) => {}
            ([read], true) if read.name == QUERY => match read_pattern(read) {
                Some((slot, name)) => {
                    let k = names.iter().position(|n| *n == rule.predecessor.name);
                    if let Some(k) = k {
                        match productions[k].read {
                            Some(other) if other != slot => reasons.push(format!(
                                "{at}: {} reads slot {other} in another rule; a production reads one slot",
                                rule.predecessor.name
                            )),
                            _ => productions[k].read = Some(slot),
                        }
                    }
                    read_name = Some(name);
                }
                None => reasons.push(format!(
                    "{at}: a production's read is written as its left context ?E(1, SLOT, {READ_VALUE}), with a whole slot and a name for the value read"
                )),
            },
            _ => reasons.push(format!(
                "{at}: context-sensitive rules are not part of the genome (but a read of the environment, ?E(1, SLOT, {READ_VALUE}) <)"
            )),
        }
        if rule.probability.is_some() {
            reasons.push(format!("{at}: stochastic rules are not part of the genome"));
        }
        if rule.solve.is_some() {
            reasons.push(format!(
                "{at}: differential rules are not part of the genome"
            ));
        }
        let name = &rule.predecessor.name;
        if Command::building_from_name(name).is_some() || lang::is_builtin_command(name) {
            reasons.push(format!(
                "{at}: a rule rewrites the building command '{name}'; productions must be control symbols"
            ));
            continue;
        }
        let k = names.iter().position(|n| n == name).expect("collected");
        let formals: Vec<String> = rule.predecessor.formals();
        params = params.max(formals.len());
        if let Some(f) = formals.iter().find(|f| lang::ast::is_constant_formal(f)) {
            reasons.push(format!(
                "{at}: the predecessor matches the number {f}; write a condition instead"
            ));
        }
        let condition = match &rule.guard {
            None => None,
            Some(g) => {
                let read = || {
                    let Expr::Binary { op, lhs, rhs, .. } = g else {
                        return None;
                    };
                    let compare = match op {
                        BinaryOp::Lt => Compare::Less,
                        BinaryOp::Le => Compare::LessEqual,
                        BinaryOp::Gt => Compare::Greater,
                        BinaryOp::Ge => Compare::GreaterEqual,
                        _ => return None,
                    };
                    // A parameter (Some(index)), or the value read (Some(None)).
                    let param = |e: &Expr| match e {
                        Expr::Name(n, _) if read_name.as_ref() == Some(n) => Some(None),
                        Expr::Name(n, _) => formals.iter().position(|f| f == n).map(Some),
                        _ => None,
                    };
                    match (param(lhs), constant(rhs), param(rhs), constant(lhs)) {
                        (Some(p), Some(c), _, _) => Some((p, c, compare)),
                        (_, _, Some(p), Some(c)) => Some((p, c, compare.flipped())),
                        _ => None,
                    }
                };
                match read() {
                    Some((param, value, compare)) => Some(Condition {
                        param: param.unwrap_or(0),
                        compare,
                        value,
                        read: param.is_none(),
                    }),
                    None => {
                        reasons.push(format!(
                            "{}: the condition '{}' is not a parameter (or the value read) compared with a number",
                            place(g.span()),
                            snippet(g.span())
                        ));
                        None
                    }
                }
            }
        };
        let successor = items(
            &successors,
            &rule.successor,
            &formals,
            &mut reasons,
            &mut calls,
        );
        productions[k].pairs.push(Pair {
            condition,
            successor,
        });
    }
    let axiom_kept = kept_axiom.is_some();
    let start = match kept_axiom {
        Some(values) => values,
        None => {
            productions[0].pairs.push(Pair {
                condition: None,
                successor: items(&successors, axiom, &[], &mut reasons, &mut calls),
            });
            Vec::new()
        }
    };
    // A production that reads has its read written right before every call of it, and no
    // other production has one.
    if axiom_kept && axiom_read.is_none() {
        calls.push((0, None, axiom_call[0].span));
    }
    for (k, slot, span) in calls {
        let name = if names[k].is_empty() { "P0" } else { &names[k] };
        match (productions[k].read, slot) {
            (Some(want), Some(got)) if want == got => {}
            (Some(want), _) => reasons.push(format!(
                "{}: {name} reads slot {want}: write ?E(1, {want}, 0) right before every call of it",
                place(span)
            )),
            (None, Some(_)) => reasons.push(format!(
                "{}: a read ?E(1, SLOT, 0) stands before a call of {name}, whose rules read nothing",
                place(span)
            )),
            (None, None) => {}
        }
    }
    if !reasons.is_empty() {
        return Err(reasons);
    }
    // Every production takes the most parameters any takes; calls and the start are padded
    // with 0 (a parameter a rule does not name is never read).
    let params = params.max(start.len());
    for pair in productions.iter_mut().flat_map(|p| p.pairs.iter_mut()) {
        for item in &mut pair.successor {
            if let Item::Call(_, args) = item {
                args.resize(params, Arg::Const(0.0));
            }
        }
    }
    // A production without a rule (a module that only the axiom rewrites into) keeps
    // itself, as the file's module does.
    let mut start = start;
    start.resize(params, 0.0);
    let derivation_length = lsys.derivation_length().unwrap_or(0) + u64::from(names[0].is_empty());
    let genome = LSystemGenome {
        start,
        derivation_length,
        productions,
        environment,
        projectile: None,
    };
    Ok((genome, notes))
}

/// What reading a file's successors as the genome's items needs of the file: the
/// productions' names, the turtle's headers, where a span is and the text there (for
/// messages), and how many slots the environment has.
struct Successors<'a> {
    names: &'a [String],
    turtle: &'a TurtleHeaders,
    place: &'a dyn Fn(lang::Span) -> String,
    snippet: &'a dyn Fn(lang::Span) -> String,
    slots: usize,
}

/// The successor `modules`, in a rule with the parameters `formals`, as the genome's items;
/// a module that is neither a production, a building command of the genome's nor a bracket,
/// and has no rule, builds nothing and is dropped; the textbook's symbols become their exact
/// equivalents ([`textbook_items`]); what cannot be represented goes to `reasons`, and the
/// calls of productions, with the slot read before each, to `calls`.
fn items(
    successors: &Successors<'_>,
    modules: &[ModuleCall],
    formals: &[String],
    reasons: &mut Vec<String>,
    calls: &mut Vec<(usize, Option<usize>, lang::Span)>,
) -> Vec<Item> {
    let Successors {
        names,
        turtle,
        place,
        snippet,
        slots,
    } = *successors;
    let mut out = Vec::new();
    // A read just written, waiting for the call it stands before.
    let mut read: Option<(usize, lang::Span)> = None;
    let arg = |e: &Expr, reasons: &mut Vec<String>| {
        argument(e, formals).unwrap_or_else(|| {
            reasons.push(format!(
                "{}: the argument '{}' is not a number, a parameter, or a parameter plus, minus or times a number",
                place(e.span()),
                snippet(e.span())
            ));
            Arg::Const(0.0)
        })
    };
    for call in modules {
        if let Some((_, span)) = read
            && !names.contains(&call.name)
        {
            reasons.push(format!(
                "{}: a read ?E(1, SLOT, 0) stands right before a call of a production, not before '{}'",
                place(span),
                call.name
            ));
            read = None;
        }
        if call.name == QUERY {
            match read_slot(call) {
                Some(slot) => read = Some((slot, call.span)),
                None => reasons.push(format!(
                    "{}: a genome's read of the environment is written ?E(1, SLOT, 0), right before a call of a production",
                    place(call.span)
                )),
            }
            continue;
        }
        match call.name.as_str() {
            "[" => out.push(Item::Push),
            "]" => out.push(Item::Pop),
            "{" => out.push(Item::RepeatOpen),
            "}" => match call.args.as_slice() {
                [n] => match constant(n) {
                    Some(v) if v.fract() == 0.0 && (2.0..=MOST_REPEAT as f64).contains(&v) => {
                        out.push(Item::RepeatClose(v as usize));
                    }
                    _ => reasons.push(format!(
                        "{}: a repeat block's count in the genome is a whole number of 2 to {MOST_REPEAT}, not '{}'",
                        place(n.span()),
                        snippet(n.span())
                    )),
                },
                _ => reasons.push(format!(
                    "{}: a repeat block ends with its count, '}}(n)'",
                    place(call.span)
                )),
            },
            name => {
                if let Some(c) =
                    Command::from_name(name).filter(|c| ENVIRONMENT_COMMANDS.contains(c))
                {
                    match call.args.as_slice() {
                        _ if slots == 0 => reasons.push(format!(
                            "{}: '{}' reads or writes the environment, and the file has none ('environment:')",
                            place(call.span),
                            c.name()
                        )),
                        [a] => out.push(Item::Command(c, Some(arg(a, reasons)))),
                        _ => reasons.push(format!(
                            "{}: write '{}' with the slot it reads or writes, as {}(0)",
                            place(call.span),
                            c.name(),
                            c.name()
                        )),
                    }
                } else if let Some(c) = Command::building_from_name(name) {
                    match call.args.as_slice() {
                        [] => out.push(Item::Command(c, None)),
                        [a] if c.argument() != Argument::None => {
                            out.push(Item::Command(c, Some(arg(a, reasons))));
                        }
                        _ => reasons.push(format!(
                            "{}: '{}' takes {} argument",
                            place(call.span),
                            c.name(),
                            if c.argument() == Argument::None {
                                "no"
                            } else {
                                "at most one"
                            }
                        )),
                    }
                } else if let Some(c) = Command::from_name(name).filter(|c| c.is_textbook()) {
                    let argument = match call.args.as_slice() {
                        [] => None,
                        [a, ..] => Some(arg(a, reasons)),
                    };
                    match textbook_items(c, argument, turtle) {
                        Ok(items) => out.extend(items),
                        Err(why) => reasons.push(format!("{}: {why}", place(call.span))),
                    }
                } else if let Some(k) = names.iter().position(|n| n == name) {
                    let args = call.args.iter().map(|a| arg(a, reasons)).collect();
                    out.push(Item::Call(k, args));
                    calls.push((k, read.take().map(|(slot, _)| slot), call.span));
                } else if lang::is_builtin_command(name) {
                    reasons.push(format!(
                        "{}: '{name}' is not a command the genome uses ({LSYSTEM_NOT_USED})",
                        place(call.span)
                    ));
                }
                // else: a control symbol without a rule, which builds nothing.
            }
        }
    }
    if let Some((_, span)) = read {
        reasons.push(format!(
            "{}: a read ?E(1, SLOT, 0) ends the successor; it stands right before a call of a production",
            place(span)
        ));
    }
    if !super::is_balanced(&out)
        && let Some(first) = modules.first()
    {
        reasons.push(format!(
            "{}: the successor's brackets are not balanced",
            place(first.span)
        ));
    }
    out
}

/// The limits widened to fit `genome` (each the larger of the limit and the seed's size),
/// with a note naming each widened limit.
fn widened(
    genome: &LSystemGenome,
    limits: &LSystemLimits,
    grown: Option<(usize, usize)>,
) -> (LSystemLimits, Option<String>) {
    let mut out = limits.clone();
    let most_pairs = genome.productions.iter().map(|p| p.pairs.len()).max();
    let longest = genome
        .productions
        .iter()
        .flat_map(|p| p.pairs.iter().map(|q| q.successor.len()))
        .max();
    out.max_productions = out.max_productions.max(genome.productions.len());
    out.max_pairs = out.max_pairs.max(most_pairs.unwrap_or(1));
    out.params = out.params.max(genome.start.len());
    out.max_successor = out.max_successor.max(longest.unwrap_or(0));
    out.derivation_length = out.derivation_length.max(genome.derivation_length);
    let most_count = genome
        .successors()
        .flatten()
        .filter_map(|item| match item {
            Item::RepeatClose(n) => Some(*n),
            _ => None,
        })
        .max();
    out.max_repeat = out.max_repeat.max(most_count.unwrap_or(0));
    if let Some((modules, parts)) = grown {
        out.max_modules = out.max_modules.max(modules);
        // A creature of more parts than any run may hold is invalid whatever the limits.
        let parts = parts.min(crate::encoding::limits::MOST_PARTS);
        out.max_parts = out.max_parts.max(parts);
    }
    let changes: Vec<String> = [
        (
            "max_productions",
            limits.max_productions,
            out.max_productions,
        ),
        ("max_pairs", limits.max_pairs, out.max_pairs),
        ("params", limits.params, out.params),
        ("max_successor", limits.max_successor, out.max_successor),
        (
            "derivation_length",
            limits.derivation_length as usize,
            out.derivation_length as usize,
        ),
        ("max_modules", limits.max_modules, out.max_modules),
        ("max_parts", limits.max_parts, out.max_parts),
        ("max_repeat", limits.max_repeat, out.max_repeat),
    ]
    .iter()
    .filter(|(_, was, now)| was != now)
    .map(|(key, was, now)| format!("{key} {was} → {now}"))
    .collect();
    let note = (!changes.is_empty()).then(|| {
        format!(
            "the run's limits are widened to fit the seed ({}); its mutants keep within them",
            changes.join(", ")
        )
    });
    (out, note)
}

/// The genome `text` seeds a run with under `limits`: see the module's comment.
/// A genome file read as the genome writes it ([`LSystemGenome::text`]): refused when it
/// would need rewriting (another encoding's file, or a hand-written grammar), or does not fit
/// `limits`.
pub(super) fn genome_as_written(
    text: &str,
    limits: &LSystemLimits,
) -> Result<LSystemGenome, DevelopError> {
    let lsys = LSystem::from_text("file.lsys", text).map_err(|d| DevelopError(without_flags(d)))?;
    match structural("file.lsys", text, &lsys) {
        Ok((mut genome, notes)) if notes.is_empty() => {
            genome.projectile = crate::encoding::projectile::read_line(text)?;
            genome.check(limits).map_err(refuse)?;
            Ok(genome)
        }
        Ok((_, notes)) => Err(refuse(format!(
            "not as the genome writes it: {}",
            notes.join("; ")
        ))),
        Err(reasons) => Err(refuse(reasons.join("; "))),
    }
}

/// `grow`: grow the seed and widen the limits on modules and parts to fit it (a run's seed),
/// else only check it (a genome read back).
pub(super) fn seed_from_lsys(
    name: &str,
    text: &str,
    limits: &LSystemLimits,
    grow: bool,
) -> Result<Seed<LSystemGenome>, DevelopError> {
    // The language's own checks first: a file that does not compile gets its located error.
    let lsys = LSystem::from_text(name, text).map_err(|d| DevelopError(without_flags(d)))?;
    let (mut genome, mut notes) = match structural(name, text, &lsys) {
        Ok((mut genome, notes)) => {
            // Every production takes at least the limits' parameters, as random genomes do.
            let params = genome.start.len().max(limits.param_count());
            genome.start.resize(params, 0.0);
            for pair in genome
                .productions
                .iter_mut()
                .flat_map(|p| p.pairs.iter_mut())
            {
                for item in &mut pair.successor {
                    if let Item::Call(_, args) = item {
                        args.resize(params, Arg::Const(0.0));
                    }
                }
            }
            (genome, notes)
        }
        Err(reasons) => match derived_items(name, text, MOST_MODULES) {
            Ok(items) if items.len() <= MOST_SUCCESSOR => {
                let shown = match reasons.as_slice() {
                    [a, b, c, _, ..] => format!("{a}; {b}; {c}; and {} more", reasons.len() - 3),
                    _ => reasons.join("; "),
                };
                let note = format!(
                    "its rules cannot be the genome's ({shown}): the run starts from the string it derives, as production P0's one successor (the same creature)"
                );
                let genome = LSystemGenome {
                    start: vec![0.0; limits.param_count()],
                    derivation_length: 1,
                    productions: vec![Production {
                        pairs: vec![Pair {
                            condition: None,
                            successor: items,
                        }],
                        read: None,
                    }],
                    environment: Vec::new(),
                    projectile: None,
                };
                (genome, vec![note])
            }
            Ok(items) => {
                return Err(refuse(format!(
                    "its rules cannot be the genome's ({}), and the string it derives has {} building modules, more than a successor may hold ({MOST_SUCCESSOR})",
                    reasons.join("; "),
                    items.len()
                )));
            }
            Err(problems) => {
                return Err(refuse(format!(
                    "its rules cannot be the genome's:\n  {}\nnor can the string it derives:\n  {}",
                    reasons.join("\n  "),
                    problems.join("\n  ")
                )));
            }
        },
    };
    genome.projectile = crate::encoding::projectile::read_line(text)?;
    // A run's seed is grown, and the limits on modules and parts widened to fit it; a
    // genome read back is only checked.
    let grown = match grow.then(|| grown_size(&genome.to_text())) {
        Some(Err(why)) => {
            return Err(refuse(format!(
                "it does not grow within the most any run may hold ({MOST_MODULES} modules, {} parts): {why}",
                crate::encoding::limits::MOST_PARTS
            )));
        }
        Some(Ok(size)) => Some(size),
        None => None,
    };
    let (limits, widening) = widened(&genome, limits, grown);
    if grow && let Err(e) = limits.check_ranges() {
        return Err(refuse(format!(
            "its seed needs more than any run may hold: {}",
            e.to_string().trim_start_matches("[limits] ")
        )));
    }
    notes.extend(widening);
    genome.check(&limits).map_err(refuse)?;
    Ok(Seed {
        genome,
        limits,
        notes,
    })
}
