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
        s.push_str(&crate::encoding::projectile::text_line(self.projectile));
        s.push_str(&format!("time: {}\n", self.time));
        s.push_str(&format!("dt: {}\n", self.dt));
        s.push_str("timing: exact\n");
        if !self.environment.is_empty() {
            let values: Vec<String> = self.environment.iter().map(f64::to_string).collect();
            s.push_str(&format!("environment: {}\n", values.join(" ")));
        }
        s.push_str(&format!("axiom: {}\n", self.sequence_text(&self.axiom)));
        for rule in &self.rules {
            let name = rule.grower.name();
            let t = rule.threshold;
            s.push('\n');
            s.push_str(&format!(
                "{name}(x) : x < {t} --> solve dx/dt = {}\n",
                rule.rate
            ));
            let successor = |seq: &[Token]| match rule.grower {
                Grower::Control(_) => self.sequence_text(seq),
                _ => self.matured_text(rule, seq),
            };
            if let Some(branch) = &rule.plastic {
                let line = format!(
                    "?E(1, {}, c) < {name}(x) : x >= {t} && c > {} --> {}",
                    branch.slot,
                    branch.above,
                    successor(&branch.successor)
                );
                s.push_str(line.trim_end());
                s.push('\n');
            }
            let line = format!("{name}(x) : x >= {t} --> {}", successor(&rule.successor));
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
        "'{name}' is not a token of the genome (the commands but target, release, increase \
         and decrease; the maturing twins of forward, the turns and the \
         joints; {controls})"
    ))
}

/// A sequence read from a file: its tokens, and the reads `?E(1, slot, 0)` written in it as
/// (index of the token after the read, slot).
type ReadSequence = (Vec<Token>, Vec<(usize, usize)>);

/// A constant formal parameter of a pattern (`1` in `?E(1, 0, c)`).
fn constant_formal(param: &str) -> Option<f64> {
    param.parse::<f64>().ok()
}

/// The calls of an axiom or successor as tokens and reads.
fn sequence_of(calls: &[ModuleCall], limits: &ContinuousLimits) -> Result<ReadSequence, String> {
    let mut tokens = Vec::with_capacity(calls.len());
    let mut reads = Vec::new();
    for call in calls {
        if call.name == "?E" {
            let args: Vec<Option<f64>> = call.args.iter().map(|a| number(a, true)).collect();
            match args.as_slice() {
                [Some(mode), Some(slot), Some(value)]
                    if *mode == 1.0 && *slot >= 0.0 && slot.fract() == 0.0 && *value == 0.0 =>
                {
                    reads.push((tokens.len(), *slot as usize));
                }
                _ => {
                    return Err("a genome's environment read is written ?E(1, SLOT, 0), \
                                right before a maturing token"
                        .into());
                }
            }
            continue;
        }
        tokens.push(token_of(call, limits)?);
    }
    Ok((tokens, reads))
}

/// The plastic branch's left context and guard: `?E(1, SLOT, c) < P(x) : x >= T && c > V`
/// gives (T, SLOT, V).
fn plastic_guard(rule: &crate::lang::ast::Rule, param: &str) -> Option<(f64, usize, f64)> {
    let [read] = rule.left.as_slice() else {
        return None;
    };
    let [(mode, _), (slot, _), (value, _)] = read.params.as_slice() else {
        return None;
    };
    if read.name != "?E" || constant_formal(mode) != Some(1.0) || value == param {
        return None;
    }
    let slot = constant_formal(slot).filter(|s| *s >= 0.0 && s.fract() == 0.0)?;
    match rule.guard.as_ref()? {
        Expr::Binary {
            op: BinaryOp::And,
            lhs,
            rhs,
            ..
        } => Some((
            comparison(lhs, BinaryOp::Ge, param)?,
            slot as usize,
            comparison(rhs, BinaryOp::Gt, value)?,
        )),
        _ => None,
    }
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
    if !file.defines.is_empty() {
        return Err("it defines constants; write numbers instead".into());
    }
    if !file.ignore.is_empty() {
        return Err("it has an 'ignore:' line; the genome's rules use no context".into());
    }
    let environment = lsys.environment().values().to_vec();
    let (axiom, axiom_reads) = file
        .axiom
        .as_ref()
        .map(|(calls, _)| sequence_of(calls, limits))
        .transpose()
        .map_err(|e| format!("in the axiom: {e}"))?
        .unwrap_or_default();
    let mut rules: Vec<Rule> = Vec::new();
    // The reads written in each sequence: (which sequence, as messages name it, reads).
    let mut written: Vec<(String, Vec<(usize, usize)>)> =
        vec![("the axiom".to_string(), axiom_reads)];
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
        let group: Vec<_> = file
            .rules
            .iter()
            .filter(|r| r.predecessor.name == name)
            .collect();
        let template = "they must be the template's two rules, \
                        'P(x) : x < T --> solve dx/dt = R' and 'P(x) : x >= T --> ...', \
                        and for a plastic rule, before the second, \
                        '?E(1, SLOT, c) < P(x) : x >= T && c > V --> ...'";
        if !(2..=3).contains(&group.len()) {
            return Err(format!("{line}: {template}"));
        }
        let mut grow = None;
        let mut mature = None;
        let mut branch = None;
        for r in group {
            if !r.right.is_empty() || r.probability.is_some() {
                return Err(format!(
                    "{line}: no right context and no probabilities, please"
                ));
            }
            let [(param, _)] = r.predecessor.params.as_slice() else {
                return Err(format!("{line}: {name} must have one parameter"));
            };
            let guard = r
                .guard
                .as_ref()
                .ok_or_else(|| format!("{line}: {template}"))?;
            let plastic = if r.left.is_empty() {
                None
            } else if mature.is_some() || r.solve.is_some() {
                return Err(format!("{line}: {template}"));
            } else {
                Some(plastic_guard(r, param).ok_or_else(|| format!("{line}: {template}"))?)
            };
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
                    let threshold = match plastic {
                        Some((t, _, _)) => Some(t),
                        None => comparison(guard, BinaryOp::Ge, param),
                    }
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
                    let (successor, reads) =
                        sequence_of(calls, limits).map_err(|e| format!("{line}: {e}"))?;
                    match plastic {
                        Some((_, slot, above)) => {
                            if branch.is_some() {
                                return Err(format!("{line}: {template}"));
                            }
                            written.push((format!("the plastic successor of {name}"), reads));
                            branch = Some((threshold, slot, above, successor));
                        }
                        None => {
                            if mature.is_some() {
                                return Err(format!("{line}: {template}"));
                            }
                            written.push((format!("the successor of {name}"), reads));
                            mature = Some((threshold, successor));
                        }
                    }
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
        let plastic = match branch {
            Some((t3, _, _, _)) if t3 != t1 => {
                return Err(format!(
                    "{line}: the plastic rule must use the same threshold ({t1} and {t3})"
                ));
            }
            Some((_, slot, above, successor)) => Some(Plastic {
                slot,
                above,
                successor,
            }),
            None => None,
        };
        rules.push(Rule {
            grower,
            threshold: t1,
            rate,
            successor,
            plastic,
        });
        done.push(name);
    }
    let mut genome = ContinuousGenome {
        time,
        dt: lsys.dt(),
        axiom,
        rules: Vec::new(),
        environment,
        projectile: None,
    };
    for rule in rules {
        genome.insert_rule(rule);
    }
    // The reads must be where the genome writes them: right before each maturing token of a
    // plastic rule, reading its slot, and nowhere else.
    for (what, reads) in &written {
        let seq = if what == "the axiom" {
            &genome.axiom
        } else {
            genome
                .rules
                .iter()
                .find_map(|r| {
                    let name = r.grower.name();
                    if *what == format!("the successor of {name}") {
                        Some(&r.successor)
                    } else if *what == format!("the plastic successor of {name}") {
                        r.plastic.as_ref().map(|b| &b.successor)
                    } else {
                        None
                    }
                })
                .expect("every sequence read belongs to a rule kept")
        };
        if *reads != genome.reads_in(seq) {
            return Err(format!(
                "in {what}: a plastic rule's read ?E(1, SLOT, 0) stands right before each of \
                 its maturing tokens, and no read stands anywhere else"
            ));
        }
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
            environment: Vec::new(),
            projectile: None,
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
                plastic: None,
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
