//! Expressions compiled against a rule's parameters, and their evaluation.

use rand::RngExt;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};

use crate::lang::Span;
use crate::lang::ast::{BinaryOp, Expr, UnaryOp};

/// A function callable in expressions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Func {
    /// `sin(x)`
    Sin,
    /// `cos(x)`
    Cos,
    /// `tan(x)`
    Tan,
    /// `asin(x)`
    Asin,
    /// `acos(x)`
    Acos,
    /// `atan(x)`
    Atan,
    /// `atan2(y, x)`
    Atan2,
    /// `sqrt(x)`
    Sqrt,
    /// `exp(x)`
    Exp,
    /// `ln(x)`: natural logarithm
    Ln,
    /// `log(x)`: base-10 logarithm
    Log,
    /// `abs(x)`
    Abs,
    /// `floor(x)`
    Floor,
    /// `ceil(x)`
    Ceil,
    /// `round(x)`: halves away from zero
    Round,
    /// `min(a, b, ...)`
    Min,
    /// `max(a, b, ...)`
    Max,
    /// `clamp(x, lo, hi)`
    Clamp,
    /// `pow(x, y)`
    Pow,
    /// `uniform(a, b)`: a seeded uniform draw in [a, b)
    Uniform,
    /// `normal(mean, sd)`: a seeded normal draw
    Normal,
}

/// Every function: name, the function, least and most arguments.
pub const FUNCTIONS: &[(&str, Func, usize, usize)] = &[
    ("sin", Func::Sin, 1, 1),
    ("cos", Func::Cos, 1, 1),
    ("tan", Func::Tan, 1, 1),
    ("asin", Func::Asin, 1, 1),
    ("acos", Func::Acos, 1, 1),
    ("atan", Func::Atan, 1, 1),
    ("atan2", Func::Atan2, 2, 2),
    ("sqrt", Func::Sqrt, 1, 1),
    ("exp", Func::Exp, 1, 1),
    ("ln", Func::Ln, 1, 1),
    ("log", Func::Log, 1, 1),
    ("abs", Func::Abs, 1, 1),
    ("floor", Func::Floor, 1, 1),
    ("ceil", Func::Ceil, 1, 1),
    ("round", Func::Round, 1, 1),
    ("min", Func::Min, 2, usize::MAX),
    ("max", Func::Max, 2, usize::MAX),
    ("clamp", Func::Clamp, 3, 3),
    ("pow", Func::Pow, 2, 2),
    ("uniform", Func::Uniform, 2, 2),
    ("normal", Func::Normal, 2, 2),
];

impl Func {
    fn is_random(self) -> bool {
        matches!(self, Func::Uniform | Func::Normal)
    }
}

/// An expression with names resolved: parameters are argument slots, constants are numbers.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum CExpr {
    Const(f64),
    Arg(usize),
    Time,
    Unary(UnaryOp, Box<CExpr>, Span),
    Binary(BinaryOp, Box<CExpr>, Box<CExpr>, Span),
    Call(Func, Vec<CExpr>, Span),
}

/// What a name in an expression stands for.
pub(crate) enum Resolved {
    Arg(usize),
    Const(f64),
    Time,
}

/// Why an expression could not be compiled or evaluated, and where.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ExprError {
    pub span: Span,
    pub message: String,
}

/// What evaluation reads: the bound arguments, the time and the random stream.
pub(crate) struct EvalEnv<'a> {
    pub args: &'a [f64],
    pub t: f64,
    pub rng: &'a mut ChaCha8Rng,
}

/// Compiles `expr`, resolving names with `resolve`; folds constant parts.
pub(crate) fn compile(
    expr: &Expr,
    resolve: &dyn Fn(&str) -> Option<Resolved>,
) -> Result<CExpr, ExprError> {
    compile_folding(expr, resolve, true)
}

/// Compiles `expr`; with `folding` off, constant parts are left unevaluated (for the side of
/// `&&` or `||` that a constant left side makes dead: its names must still resolve, but its
/// value — say a division by zero — never matters).
fn compile_folding(
    expr: &Expr,
    resolve: &dyn Fn(&str) -> Option<Resolved>,
    folding: bool,
) -> Result<CExpr, ExprError> {
    let compile = |e: &Expr| compile_folding(e, resolve, folding);
    let compiled = match expr {
        Expr::Number(v, _) => CExpr::Const(*v),
        Expr::Name(name, span) => match resolve(name) {
            Some(Resolved::Arg(i)) => CExpr::Arg(i),
            Some(Resolved::Const(v)) => CExpr::Const(v),
            Some(Resolved::Time) => CExpr::Time,
            None => match name.as_str() {
                "pi" => CExpr::Const(std::f64::consts::PI),
                "e" => CExpr::Const(std::f64::consts::E),
                _ => {
                    return Err(ExprError {
                        span: *span,
                        message: format!("unknown name '{name}'"),
                    });
                }
            },
        },
        Expr::Unary { op, operand, span } => CExpr::Unary(*op, Box::new(compile(operand)?), *span),
        Expr::Binary {
            op: op @ (BinaryOp::And | BinaryOp::Or),
            lhs,
            rhs,
            span,
        } => {
            let left = compile(lhs)?;
            let decided = match (op, left.as_const()) {
                (BinaryOp::And, Some(v)) => (v == 0.0).then_some(0.0),
                (BinaryOp::Or, Some(v)) => (v != 0.0).then_some(1.0),
                _ => None,
            };
            if let Some(value) = decided {
                compile_folding(rhs, resolve, false)?;
                return Ok(CExpr::Const(value));
            }
            CExpr::Binary(*op, Box::new(left), Box::new(compile(rhs)?), *span)
        }
        Expr::Binary { op, lhs, rhs, span } => {
            CExpr::Binary(*op, Box::new(compile(lhs)?), Box::new(compile(rhs)?), *span)
        }
        Expr::Call { name, args, span } => {
            let Some(&(_, func, least, most)) = FUNCTIONS.iter().find(|(n, ..)| n == name) else {
                let known: Vec<&str> = FUNCTIONS.iter().map(|(n, ..)| *n).collect();
                return Err(ExprError {
                    span: *span,
                    message: format!("unknown function '{name}' (known: {})", known.join(", ")),
                });
            };
            if args.len() < least || args.len() > most {
                let wanted = if least == most {
                    format!("{least}")
                } else {
                    format!("at least {least}")
                };
                return Err(ExprError {
                    span: *span,
                    message: format!(
                        "'{name}' takes {wanted} argument{}, not {}",
                        if least == 1 && most == 1 { "" } else { "s" },
                        args.len()
                    ),
                });
            }
            let args = args.iter().map(compile).collect::<Result<Vec<_>, _>>()?;
            CExpr::Call(func, args, *span)
        }
    };
    if folding {
        fold(compiled)
    } else {
        Ok(compiled)
    }
}

/// Evaluates a node now if it is constant and not random.
fn fold(expr: CExpr) -> Result<CExpr, ExprError> {
    let foldable = match &expr {
        CExpr::Unary(_, a, _) => matches!(**a, CExpr::Const(_)),
        CExpr::Binary(_, a, b, _) => {
            matches!(**a, CExpr::Const(_)) && matches!(**b, CExpr::Const(_))
        }
        CExpr::Call(f, args, _) => {
            !f.is_random() && args.iter().all(|a| matches!(a, CExpr::Const(_)))
        }
        _ => false,
    };
    if !foldable {
        return Ok(expr);
    }
    // A constant expression reads no arguments, time or randomness.
    let mut rng = <ChaCha8Rng as rand::SeedableRng>::seed_from_u64(0);
    let mut env = EvalEnv {
        args: &[],
        t: 0.0,
        rng: &mut rng,
    };
    Ok(CExpr::Const(expr.eval(&mut env)?))
}

fn truth(v: f64) -> f64 {
    if v != 0.0 { 1.0 } else { 0.0 }
}

impl CExpr {
    /// Whether the expression is a constant, and which.
    pub fn as_const(&self) -> Option<f64> {
        match self {
            CExpr::Const(v) => Some(*v),
            _ => None,
        }
    }

    /// Whether the expression reads the time `t`.
    pub fn uses_time(&self) -> bool {
        match self {
            CExpr::Time => true,
            CExpr::Const(_) | CExpr::Arg(_) => false,
            CExpr::Unary(_, a, _) => a.uses_time(),
            CExpr::Binary(_, a, b, _) => a.uses_time() || b.uses_time(),
            CExpr::Call(_, args, _) => args.iter().any(CExpr::uses_time),
        }
    }

    /// Whether evaluating the expression draws random numbers.
    pub fn uses_random(&self) -> bool {
        match self {
            CExpr::Const(_) | CExpr::Arg(_) | CExpr::Time => false,
            CExpr::Unary(_, a, _) => a.uses_random(),
            CExpr::Binary(_, a, b, _) => a.uses_random() || b.uses_random(),
            CExpr::Call(f, args, _) => f.is_random() || args.iter().any(CExpr::uses_random),
        }
    }

    /// Evaluates the expression. Division by zero and any NaN or infinite result are errors.
    pub fn eval(&self, env: &mut EvalEnv<'_>) -> Result<f64, ExprError> {
        let (value, span) = match self {
            CExpr::Const(v) => return Ok(*v),
            CExpr::Arg(i) => return Ok(env.args[*i]),
            CExpr::Time => return Ok(env.t),
            CExpr::Unary(op, a, span) => {
                let a = a.eval(env)?;
                let v = match op {
                    UnaryOp::Neg => -a,
                    UnaryOp::Not => 1.0 - truth(a),
                };
                (v, *span)
            }
            CExpr::Binary(op, a, b, span) => (self.binary(*op, a, b, *span, env)?, *span),
            CExpr::Call(func, args, span) => (call(*func, args, *span, env)?, *span),
        };
        if value.is_finite() {
            Ok(value)
        } else {
            Err(ExprError {
                span,
                message: format!(
                    "expression gives {}",
                    if value.is_nan() {
                        "NaN (not a number)"
                    } else {
                        "infinity"
                    }
                ),
            })
        }
    }

    fn binary(
        &self,
        op: BinaryOp,
        a: &CExpr,
        b: &CExpr,
        span: Span,
        env: &mut EvalEnv<'_>,
    ) -> Result<f64, ExprError> {
        let x = a.eval(env)?;
        // && and || do not evaluate their right side when the left decides.
        match op {
            BinaryOp::And if x == 0.0 => return Ok(0.0),
            BinaryOp::Or if x != 0.0 => return Ok(1.0),
            _ => {}
        }
        let y = b.eval(env)?;
        let bool_of = |c: bool| if c { 1.0 } else { 0.0 };
        Ok(match op {
            BinaryOp::Add => x + y,
            BinaryOp::Sub => x - y,
            BinaryOp::Mul => x * y,
            BinaryOp::Div | BinaryOp::Rem if y == 0.0 => {
                return Err(ExprError {
                    span,
                    message: "division by zero".to_string(),
                });
            }
            BinaryOp::Div => x / y,
            BinaryOp::Rem => x % y,
            BinaryOp::Pow => x.powf(y),
            BinaryOp::Lt => bool_of(x < y),
            BinaryOp::Le => bool_of(x <= y),
            BinaryOp::Gt => bool_of(x > y),
            BinaryOp::Ge => bool_of(x >= y),
            BinaryOp::Eq => bool_of(x == y),
            BinaryOp::Ne => bool_of(x != y),
            BinaryOp::And | BinaryOp::Or => truth(y),
        })
    }
}

fn call(func: Func, args: &[CExpr], span: Span, env: &mut EvalEnv<'_>) -> Result<f64, ExprError> {
    let mut arg = |i: usize| args[i].eval(env);
    Ok(match func {
        Func::Atan2 => {
            let y = arg(0)?;
            y.atan2(arg(1)?)
        }
        Func::Min | Func::Max => {
            let mut best = args[0].eval(env)?;
            for a in &args[1..] {
                let v = a.eval(env)?;
                best = if func == Func::Min {
                    best.min(v)
                } else {
                    best.max(v)
                };
            }
            best
        }
        Func::Clamp => {
            let (x, lo, hi) = (arg(0)?, arg(1)?, arg(2)?);
            if lo > hi {
                return Err(ExprError {
                    span,
                    message: format!("clamp's lower bound {lo} is above its upper bound {hi}"),
                });
            }
            x.clamp(lo, hi)
        }
        Func::Pow => {
            let x = arg(0)?;
            x.powf(arg(1)?)
        }
        Func::Uniform => {
            let (lo, hi) = (arg(0)?, arg(1)?);
            let u: f64 = env.rng.random();
            lo + (hi - lo) * u
        }
        Func::Normal => {
            let (mean, sd) = (arg(0)?, arg(1)?);
            if sd < 0.0 {
                return Err(ExprError {
                    span,
                    message: format!("normal's standard deviation {sd} is negative"),
                });
            }
            let z: f64 = StandardNormal.sample(env.rng);
            mean + sd * z
        }
        // Every other function takes one number.
        _ => match unary(func) {
            Some(f) => f(arg(0)?),
            None => f64::NAN,
        },
    })
}

/// The function of one number that `func` computes, if it is one (`None` for the others,
/// which [`call`] computes itself).
fn unary(func: Func) -> Option<fn(f64) -> f64> {
    Some(match func {
        Func::Sin => f64::sin,
        Func::Cos => f64::cos,
        Func::Tan => f64::tan,
        Func::Asin => f64::asin,
        Func::Acos => f64::acos,
        Func::Atan => f64::atan,
        Func::Sqrt => f64::sqrt,
        Func::Exp => f64::exp,
        Func::Ln => f64::ln,
        Func::Log => f64::log10,
        Func::Abs => f64::abs,
        Func::Floor => f64::floor,
        Func::Ceil => f64::ceil,
        Func::Round => f64::round,
        _ => return None,
    })
}
