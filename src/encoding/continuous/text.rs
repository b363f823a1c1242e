//! The continuous genome as text: the printed `.lsys` file, and a genome read from a
//! hand-written one.

use super::*;
use crate::encoding::number;

impl ContinuousGenome {
    /// The genome as a valid `.lsys` file.
    pub(super) fn text(&self) -> String {
        let mut s = String::new();
        s.push_str("# An lsystem-continuous genome (Matos & Arita, section 3.2): every rule\n");
        s.push_str("# grows a maturing token linearly until its threshold, then matures it.\n");
        s.push_str(&format!("time: {}\n", self.time));
        s.push_str(&format!("dt: {}\n", self.dt));
        s.push_str("timing: exact\n");
        s.push_str(&format!("axiom: {}\n", sequence_text(&self.axiom)));
        for rule in &self.rules {
            let name = rule.grower.name();
            let t = rule.threshold;
            s.push('\n');
            s.push_str(&format!(
                "{name}(x) : x < {t} --> solve dx/dt = {}\n",
                rule.rate
            ));
            let twin = match rule.grower {
                Grower::Control(_) => None,
                Grower::Maturing(c) if c.has_argument() => Some(format!("{}(x)", c.name())),
                Grower::Maturing(c) => Some(c.name().to_string()),
            };
            let tail = sequence_text(&rule.successor);
            let successor = match (twin, tail.is_empty()) {
                (Some(twin), true) => twin,
                (Some(twin), false) => format!("{twin} {tail}"),
                (None, _) => tail,
            };
            let line = format!("{name}(x) : x >= {t} --> {successor}");
            s.push_str(line.trim_end());
            s.push('\n');
        }
        s
    }
}

// ---- reading a hand-written file -----------------------------------------------------

/// `name OP number`.
pub(super) fn comparison(e: &Expr, want: BinaryOp, param: &str) -> Option<f64> {
    match e {
        Expr::Binary { op, lhs, rhs, .. } if *op == want => match lhs.as_ref() {
            Expr::Name(n, _) if n == param => number(rhs, true),
            _ => None,
        },
        _ => None,
    }
}

pub(super) fn token_of(call: &ModuleCall, limits: &ContinuousLimits) -> Result<Token, String> {
    let name = call.name.as_str();
    match name {
        "[" | "]" if call.args.is_empty() => {
            return Ok(if name == "[" { Token::Push } else { Token::Pop });
        }
        _ => {}
    }
    if let Some(c) = command_named(name) {
        return match (c.has_argument(), call.args.as_slice()) {
            (false, []) => Ok(Token::Command(c, None)),
            (true, [arg]) => number(arg, true)
                .map(|v| Token::Command(c, Some(v)))
                .ok_or_else(|| format!("{name}'s parameter must be a number")),
            (true, _) => Err(format!("write {name} with one number, as {name}(1)")),
            (false, _) => Err(format!("{name} takes no parameter here")),
        };
    }
    if let Some(g) = Grower::from_name(name, limits) {
        return match call.args.as_slice() {
            [arg] if number(arg, true) == Some(0.0) => Ok(Token::Grower(g)),
            _ => Err(format!(
                "the maturing token {name} must be written {name}(0)"
            )),
        };
    }
    let controls = match limits.control_tokens.min(26) {
        0 => "no control tokens".to_string(),
        n => format!(
            "control tokens A to {}",
            Grower::Control(n as u8 - 1).name()
        ),
    };
    Err(format!(
        "'{name}' is not a token of the genome (the commands but chem, target, secrete, \
         release, increase and decrease; the maturing twins of forward, the turns and the \
         joints; {controls})"
    ))
}

pub(super) fn from_file(
    lsys: &LSystem,
    limits: &ContinuousLimits,
) -> Result<ContinuousGenome, String> {
    let file = lsys.file();
    let Some(time) = lsys.time() else {
        return Err("it has no 'time:' (the genome develops in continuous time)".into());
    };
    if lsys.timing() != Timing::Exact {
        return Err("it uses 'timing: iterative'; the genome uses exact timing".into());
    }
    if file.environment.is_some() {
        return Err("it has an environment ('environment:'); the genome has none".into());
    }
    if !file.defines.is_empty() {
        return Err("it defines constants; write numbers instead".into());
    }
    if !file.ignore.is_empty() {
        return Err("it has an 'ignore:' line; the genome's rules use no context".into());
    }
    let axiom = file
        .axiom
        .as_ref()
        .map(|(calls, _)| calls.iter().map(|c| token_of(c, limits)).collect())
        .transpose()
        .map_err(|e| format!("in the axiom: {e}"))?
        .unwrap_or_default();
    let mut rules: Vec<Rule> = Vec::new();
    let mut done: Vec<String> = Vec::new();
    for rule in &file.rules {
        let name = rule.predecessor.name.clone();
        if done.contains(&name) {
            continue;
        }
        let line = format!("the rules for {name}");
        if rule.section != crate::lang::ast::Section::Productions {
            return Err("it has interpretation rules".into());
        }
        let Some(grower) = Grower::from_name(&name, limits) else {
            return Err(format!(
                "{name} is not a maturing symbol (the maturing twins of forward, the turns \
                 and the joints, and the control tokens A, B, ... that the limits allow)"
            ));
        };
        let pair: Vec<_> = file
            .rules
            .iter()
            .filter(|r| r.predecessor.name == name)
            .collect();
        let template = "they must be the template's two rules, \
                        'P(x) : x < T --> solve dx/dt = R' and 'P(x) : x >= T --> ...'";
        if pair.len() != 2 {
            return Err(format!("{line}: {template}"));
        }
        let mut grow = None;
        let mut mature = None;
        for r in pair {
            if !r.left.is_empty() || !r.right.is_empty() || r.probability.is_some() {
                return Err(format!("{line}: no context and no probabilities, please"));
            }
            let [(param, _)] = r.predecessor.params.as_slice() else {
                return Err(format!("{line}: {name} must have one parameter"));
            };
            let guard = r
                .guard
                .as_ref()
                .ok_or_else(|| format!("{line}: {template}"))?;
            match &r.solve {
                Some(ode) => {
                    let threshold = comparison(guard, BinaryOp::Lt, param)
                        .ok_or_else(|| format!("{line}: {template}"))?;
                    let rate = match ode.as_slice() {
                        [d] if d.param == *param => number(&d.rhs, true),
                        _ => None,
                    }
                    .ok_or_else(|| {
                        format!(
                            "{line}: the growth must be 'solve d{param}/dt = R' with a number R"
                        )
                    })?;
                    grow = Some((threshold, rate));
                }
                None => {
                    let threshold = comparison(guard, BinaryOp::Ge, param)
                        .ok_or_else(|| format!("{line}: {template}"))?;
                    let mut calls = r.successor.as_slice();
                    if let Grower::Maturing(c) = grower {
                        let twin_ok = calls.first().is_some_and(|first| {
                            first.name == c.name()
                                && match first.args.as_slice() {
                                    [] => !c.has_argument(),
                                    [Expr::Name(n, _)] => c.has_argument() && n == param,
                                    _ => false,
                                }
                        });
                        if !twin_ok {
                            let twin = if c.has_argument() {
                                format!("{}({param})", c.name())
                            } else {
                                c.name().to_string()
                            };
                            return Err(format!(
                                "{line}: the matured successor must start with the twin, {twin}"
                            ));
                        }
                        calls = &calls[1..];
                    }
                    let successor = calls
                        .iter()
                        .map(|c| token_of(c, limits))
                        .collect::<Result<Vec<_>, _>>()
                        .map_err(|e| format!("{line}: {e}"))?;
                    mature = Some((threshold, successor));
                }
            }
        }
        let (Some((t1, rate)), Some((t2, successor))) = (grow, mature) else {
            return Err(format!("{line}: {template}"));
        };
        if t1 != t2 {
            return Err(format!(
                "{line}: the two guards must use the same threshold ({t1} and {t2})"
            ));
        }
        rules.push(Rule {
            grower,
            threshold: t1,
            rate,
            successor,
        });
        done.push(name);
    }
    let mut genome = ContinuousGenome {
        time,
        dt: lsys.dt(),
        axiom,
        rules: Vec::new(),
    };
    for rule in rules {
        genome.insert_rule(rule);
    }
    genome.check_limits(limits)?;
    Ok(genome)
}
#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_printed_rule_is_the_papers_template() {
        let g = ContinuousGenome {
            time: 4.0,
            dt: 0.5,
            axiom: vec![Token::Grower(Grower::Maturing(Command::Forward))],
            rules: vec![Rule {
                grower: Grower::Maturing(Command::Forward),
                threshold: 2.0,
                rate: 1.0,
                successor: vec![
                    Token::Push,
                    Token::Command(Command::Right, Some(-1.0)),
                    Token::Grower(Grower::Maturing(Command::Forward)),
                ],
            }],
        };
        let text = g.to_text();
        assert!(text.contains("time: 4\ndt: 0.5\ntiming: exact\naxiom: mforward(0)\n"));
        assert!(text.contains("mforward(x) : x < 2 --> solve dx/dt = 1\n"));
        // Figure 2, with its unclosed push (allowed in a hand-written rule, not by the genome).
        assert!(text.contains("mforward(x) : x >= 2 --> forward(x) [ right(-1) mforward(0)\n"));
        assert!(g.check_limits(&ContinuousLimits::default()).is_err());
    }
}
