//! The L-system genome as text: the printed `.lsys` file, and a genome read from a
//! hand-written one.

use super::*;
use crate::encoding::number;

impl LSystemGenome {
    /// The genome as a valid `.lsys` file.
    pub(super) fn text(&self) -> String {
        let params: Vec<String> = (0..self.start.len()).map(|i| format!("n{i}")).collect();
        let formal = if params.is_empty() {
            String::new()
        } else {
            format!("({})", params.join(", "))
        };
        let mut out = String::new();
        out.push_str(&format!(
            "# An L-system genome (Hornby & Pollack 2001): {} production(s) of {} parameter(s).\n",
            self.productions.len(),
            self.start.len()
        ));
        out.push_str(&format!("derivation length: {}\n", self.derivation_length));
        let start: Vec<String> = self.start.iter().map(|v| format!("{v}")).collect();
        if start.is_empty() {
            out.push_str("axiom: P0\n\n");
        } else {
            out.push_str(&format!("axiom: P0({})\n\n", start.join(", ")));
        }
        for (i, p) in self.productions.iter().enumerate() {
            for pair in &p.pairs {
                out.push_str(&format!("P{i}{formal}"));
                if let Some(c) = pair.condition {
                    out.push_str(&format!(
                        " : n{} {} {}",
                        c.param,
                        c.compare.symbol(),
                        c.value
                    ));
                }
                out.push_str(" -->");
                for item in &pair.successor {
                    out.push(' ');
                    push_item_text(item, &mut out);
                }
                out.push('\n');
            }
        }
        out
    }
}

/// Appends an item as the language writes it (`[`, `forward(0.5)`, `P1(n0 - 1, 2)`).
pub(crate) fn push_item_text(item: &Item, out: &mut String) {
    match item {
        Item::Push => out.push('['),
        Item::Pop => out.push(']'),
        Item::Command(c, None) => out.push_str(c.name()),
        Item::Command(c, Some(a)) => out.push_str(&format!("{}({})", c.name(), a.text())),
        Item::Call(t, args) if args.is_empty() => out.push_str(&format!("P{t}")),
        Item::Call(t, args) => {
            let args: Vec<String> = args.iter().map(Arg::text).collect();
            out.push_str(&format!("P{t}({})", args.join(", ")));
        }
    }
}

// ---- reading hand-written files ------------------------------------------------------

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
        let formals: Vec<String> = rule
            .predecessor
            .params
            .iter()
            .map(|(f, _)| f.clone())
            .collect();
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

pub(super) fn from_lsys(text: &str, limits: &LSystemLimits) -> Result<LSystemGenome, DevelopError> {
    // The language's own checks first: a file that does not compile gets its located error.
    let lsys = LSystem::from_text("file.lsys", text).map_err(|d| DevelopError(d.to_string()))?;
    let source = Source::new("file.lsys", text);
    let mut file = lang::parse(&source).map_err(|d| DevelopError(d.to_string()))?;
    inline_constants(&mut file, &lsys.constants().collect::<Vec<_>>());
    let snippet = |span: lang::Span| text.get(span.start..span.end).unwrap_or("?").to_string();
    let line = |span: lang::Span| source.line_col(span.start).0;

    if lsys.is_continuous() || file.environment.is_some() {
        return Err(refuse(
            "it develops in continuous time or has an environment; the genome derives discrete steps",
        ));
    }
    let derivation_length = lsys.derivation_length().unwrap_or(0);
    if derivation_length > limits.derivation_length {
        return Err(refuse(format!(
            "its derivation length {derivation_length} is more than the limit, {}",
            limits.derivation_length
        )));
    }
    let Some((axiom, axiom_span)) = &file.axiom else {
        return Err(refuse("it has no axiom"));
    };
    let [start] = axiom.as_slice() else {
        return Err(refuse(format!(
            "its axiom must be one production with constant parameters, not '{}'",
            snippet(*axiom_span)
        )));
    };

    // Productions, the axiom's first, then in order of first appearance.
    let mut names: Vec<String> = vec![start.name.clone()];
    for rule in &file.rules {
        if !names.contains(&rule.predecessor.name) {
            names.push(rule.predecessor.name.clone());
        }
    }
    let params = limits.param_count();
    if names.len() > limits.productions() {
        return Err(refuse(format!(
            "it has {} productions, more than the limit, {}",
            names.len(),
            limits.productions()
        )));
    }
    let mut arity = vec![None; names.len()];
    let mut productions: Vec<Production> = vec![Production { pairs: Vec::new() }; names.len()];
    for rule in &file.rules {
        let at = line(rule.span);
        if rule.section == Section::Interpretation {
            return Err(refuse(format!(
                "line {at}: interpretation rules are not part of the genome"
            )));
        }
        if !rule.left.is_empty() || !rule.right.is_empty() {
            return Err(refuse(format!(
                "line {at}: context-sensitive rules are not part of the genome"
            )));
        }
        if rule.probability.is_some() || rule.solve.is_some() {
            return Err(refuse(format!(
                "line {at}: stochastic and differential rules are not part of the genome"
            )));
        }
        let name = &rule.predecessor.name;
        if Command::building_from_name(name).is_some() || lang::is_builtin_command(name) {
            return Err(refuse(format!(
                "line {at}: a rule rewrites the building command '{name}'; productions must be control symbols"
            )));
        }
        let k = names.iter().position(|n| n == name).expect("collected");
        let formals = &rule.predecessor.params;
        if formals.len() > params {
            return Err(refuse(format!(
                "line {at}: {name} has {} parameters, more than the limit, {params}",
                formals.len()
            )));
        }
        if let Some((f, _)) = formals
            .iter()
            .find(|(f, _)| lang::ast::is_constant_formal(f))
        {
            return Err(refuse(format!(
                "line {at}: the predecessor matches the number {f}; write a condition instead"
            )));
        }
        arity[k] = Some(formals.len());
        let param_of = |n: &str| formals.iter().position(|(f, _)| f == n);
        let arg = |e: &Expr| -> Result<Arg, DevelopError> {
            if let Some(v) = number(e, false) {
                return Ok(Arg::Const(v));
            }
            let bad = || {
                refuse(format!(
                    "line {at}: the argument '{}' is not a number, a parameter, or a parameter plus, minus or times a number",
                    snippet(e.span())
                ))
            };
            match e {
                Expr::Name(n, _) => param_of(n).map(|i| Arg::Plus(i, 0.0)).ok_or_else(bad),
                Expr::Binary { op, lhs, rhs, .. } => {
                    let (n, c, swapped) =
                        match (lhs.as_ref(), number(rhs, false), number(lhs, false)) {
                            (Expr::Name(n, _), Some(c), _) => (n, c, false),
                            (_, _, Some(c)) => match rhs.as_ref() {
                                Expr::Name(n, _) => (n, c, true),
                                _ => return Err(bad()),
                            },
                            _ => return Err(bad()),
                        };
                    let i = param_of(n).ok_or_else(bad)?;
                    match op {
                        BinaryOp::Add => Ok(Arg::Plus(i, c)),
                        BinaryOp::Sub if !swapped => Ok(Arg::Plus(i, -c)),
                        BinaryOp::Mul => Ok(Arg::Times(i, c)),
                        _ => Err(bad()),
                    }
                }
                _ => Err(bad()),
            }
        };
        let condition = match &rule.guard {
            None => None,
            Some(g) => {
                let bad = || {
                    refuse(format!(
                        "line {at}: the condition '{}' is not a parameter compared with a number",
                        snippet(g.span())
                    ))
                };
                let Expr::Binary { op, lhs, rhs, .. } = g else {
                    return Err(bad());
                };
                let compare = match op {
                    BinaryOp::Lt => Compare::Less,
                    BinaryOp::Le => Compare::LessEqual,
                    BinaryOp::Gt => Compare::Greater,
                    BinaryOp::Ge => Compare::GreaterEqual,
                    _ => return Err(bad()),
                };
                let (n, value, compare) =
                    match (lhs.as_ref(), number(rhs, false), number(lhs, false)) {
                        (Expr::Name(n, _), Some(c), _) => (n, c, compare),
                        (_, _, Some(c)) => match rhs.as_ref() {
                            Expr::Name(n, _) => (n, c, compare.flipped()),
                            _ => return Err(bad()),
                        },
                        _ => return Err(bad()),
                    };
                let param = param_of(n).ok_or_else(bad)?;
                Some(Condition {
                    param,
                    compare,
                    value,
                })
            }
        };
        let mut successor = Vec::new();
        for call in &rule.successor {
            successor.push(item(call, &names, params, at, &arg)?);
        }
        if successor.len() > limits.max_successor {
            return Err(refuse(format!(
                "line {at}: the successor has {} items, more than the limit, {}",
                successor.len(),
                limits.max_successor
            )));
        }
        if !is_balanced(&successor) {
            return Err(refuse(format!(
                "line {at}: the successor's brackets are not balanced"
            )));
        }
        productions[k].pairs.push(Pair {
            condition,
            successor,
        });
        if productions[k].pairs.len() > limits.pairs() {
            return Err(refuse(format!(
                "{name} has more than {} condition-successor pairs",
                limits.pairs()
            )));
        }
    }
    if productions[0].pairs.is_empty() {
        return Err(refuse(format!(
            "the axiom's module {} has no rule",
            names[0]
        )));
    }
    let mut start_values = Vec::new();
    for a in &start.args {
        start_values.push(number(a, false).ok_or_else(|| {
            refuse(format!(
                "the axiom's parameter '{}' is not a number",
                snippet(a.span())
            ))
        })?);
    }
    if arity[0].is_some_and(|a| a != start_values.len()) {
        return Err(refuse(
            "the axiom's parameter count differs from its rule's",
        ));
    }
    start_values.resize(params, 0.0);
    let genome = LSystemGenome {
        start: start_values,
        derivation_length,
        productions,
    };
    genome.check(limits).map_err(refuse)?;
    Ok(genome)
}

/// One successor module as an item.
pub(super) fn item(
    call: &ModuleCall,
    names: &[String],
    params: usize,
    at: usize,
    arg: &dyn Fn(&Expr) -> Result<Arg, DevelopError>,
) -> Result<Item, DevelopError> {
    match call.name.as_str() {
        "[" => return Ok(Item::Push),
        "]" => return Ok(Item::Pop),
        _ => {}
    }
    if let Some(c) = Command::building_from_name(&call.name) {
        return match call.args.as_slice() {
            [] => Ok(Item::Command(c, None)),
            [a] if c.argument() != Argument::None => Ok(Item::Command(c, Some(arg(a)?))),
            _ => Err(refuse(format!(
                "line {at}: '{}' takes {} argument",
                c.name(),
                if c.argument() == Argument::None {
                    "no"
                } else {
                    "at most one"
                }
            ))),
        };
    }
    if let Some(k) = names.iter().position(|n| *n == call.name) {
        let mut args = call.args.iter().map(arg).collect::<Result<Vec<_>, _>>()?;
        args.resize(params, Arg::Const(0.0));
        return Ok(Item::Call(k, args));
    }
    Err(refuse(format!(
        "line {at}: '{}' is neither a production nor a building command the genome uses \
         (not used: repeat blocks, maturing m-commands, chem, secrete, target, release)",
        call.name
    )))
}
#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arguments_print_as_the_language_reads_them() {
        assert_eq!(Arg::Const(-1.5).text(), "-1.5");
        assert_eq!(Arg::Plus(0, 0.0).text(), "n0");
        assert_eq!(Arg::Plus(1, -2.0).text(), "n1 - 2");
        assert_eq!(Arg::Plus(1, 0.25).text(), "n1 + 0.25");
        assert_eq!(Arg::Times(0, -1.0).text(), "n0 * -1");
    }
}
