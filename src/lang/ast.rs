//! The syntax tree of an L-system file, after words have been split into modules.

use super::source::Span;

/// A unary operator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnaryOp {
    /// `-x`
    Neg,
    /// `!x` (1 if x is 0, else 0)
    Not,
}

/// A binary operator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinaryOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `%` (remainder with the sign of the dividend)
    Rem,
    /// `^` (power, right-associative)
    Pow,
    /// `<`
    Lt,
    /// `<=`
    Le,
    /// `>`
    Gt,
    /// `>=`
    Ge,
    /// `==`
    Eq,
    /// `!=`
    Ne,
    /// `&&` (short-circuit)
    And,
    /// `||` (short-circuit)
    Or,
}

/// An expression over parameters, constants and functions.
#[derive(Clone, Debug, PartialEq)]
pub enum Expr {
    /// A number literal.
    Number(f64, Span),
    /// A parameter, constant, `pi` or `e`.
    Name(String, Span),
    /// A unary operation.
    Unary {
        /// The operator.
        op: UnaryOp,
        /// Its operand.
        operand: Box<Expr>,
        /// The whole expression.
        span: Span,
    },
    /// A binary operation.
    Binary {
        /// The operator.
        op: BinaryOp,
        /// Left operand.
        lhs: Box<Expr>,
        /// Right operand.
        rhs: Box<Expr>,
        /// The whole expression.
        span: Span,
    },
    /// A function call such as `sin(x)` or `uniform(0, 1)`.
    Call {
        /// The function's name.
        name: String,
        /// The arguments.
        args: Vec<Expr>,
        /// The whole call.
        span: Span,
    },
}

impl Expr {
    /// Where the expression stands in the source.
    pub fn span(&self) -> Span {
        match self {
            Expr::Number(_, span) | Expr::Name(_, span) => *span,
            Expr::Unary { span, .. } | Expr::Binary { span, .. } | Expr::Call { span, .. } => *span,
        }
    }

    /// Calls `f` on every name this expression refers to (not function names).
    pub fn visit_names(&self, f: &mut impl FnMut(&str, Span)) {
        match self {
            Expr::Number(..) => {}
            Expr::Name(name, span) => f(name, *span),
            Expr::Unary { operand, .. } => operand.visit_names(f),
            Expr::Binary { lhs, rhs, .. } => {
                lhs.visit_names(f);
                rhs.visit_names(f);
            }
            Expr::Call { args, .. } => args.iter().for_each(|a| a.visit_names(f)),
        }
    }
}

/// A module in a predecessor or context: a name and formal parameter names.
#[derive(Clone, Debug, PartialEq)]
pub struct PatternModule {
    /// The module's name (`A`, `forward`, `[`, ...).
    pub name: String,
    /// Formal parameters with their places: a name binds the value; a number (written as
    /// such, e.g. `1` or `-0.5`) is a value the module's parameter must equal.
    pub params: Vec<(String, Span)>,
    /// The module as written (for a split word: the part of the word it came from).
    pub span: Span,
}

impl PatternModule {
    /// The formal parameters' names, in order.
    pub fn formals(&self) -> Vec<String> {
        self.params.iter().map(|(f, _)| f.clone()).collect()
    }
}

/// Whether a formal parameter is a number to match rather than a name to bind.
pub fn is_constant_formal(param: &str) -> bool {
    param
        .chars()
        .next()
        .is_some_and(|c| c.is_ascii_digit() || c == '-' || c == '+' || c == '.')
}

/// A module in an axiom or successor: a name and parameter expressions.
#[derive(Clone, Debug, PartialEq)]
pub struct ModuleCall {
    /// The module's name.
    pub name: String,
    /// Parameter expressions.
    pub args: Vec<Expr>,
    /// The module as written.
    pub span: Span,
}

/// Which part of the file a rule sits in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Section {
    /// Productions rewrite the string at every derivation step.
    Productions,
    /// Interpretation rules (a homomorphism) rewrite the string only for the builder and
    /// renderer, never feeding back into derivation.
    Interpretation,
}

/// One ODE of a `solve` successor: `d<param>/dt = rhs`.
#[derive(Clone, Debug, PartialEq)]
pub struct Derivative {
    /// The parameter that changes.
    pub param: String,
    /// Where `d<param>` stands.
    pub span: Span,
    /// Its rate of change.
    pub rhs: Expr,
}

/// How continuous development rewrites modules at events (see docs/reference/language.md).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Timing {
    /// Settle at every event and at t = 0: development does not depend on `dt`.
    #[default]
    Exact,
    /// One rewriting pass at the start of every observation step and at every event, as in
    /// Matos & Arita's listing for their Figure 1.
    Iterative,
}

/// How the turtle starts (`heading:`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Heading {
    /// Along +x, lying on the ground, its up along +y (Ontogeny's creatures).
    #[default]
    Ground,
    /// Heading up (+y), as the textbook's plants grow; its up along +z (towards the camera of
    /// pictures, so that a plant drawn in a plane faces it), its left along −x.
    Up,
}

/// A production or interpretation rule, its modules of type `Pattern` (contexts) and `Call`
/// (successor): [`Rule`] once the modules' words are split, the parser's raw words before.
#[derive(Clone, Debug, PartialEq)]
pub struct RuleOf<Pattern, Call> {
    /// Left context, in string order (`B C` in `BC < S`).
    pub left: Vec<Pattern>,
    /// The module the rule rewrites.
    pub predecessor: PatternModule,
    /// Right context, in string order; may contain `[` and `]`.
    pub right: Vec<Pattern>,
    /// The condition after `:`.
    pub guard: Option<Expr>,
    /// What the predecessor becomes (empty for a `solve` rule).
    pub successor: Vec<Call>,
    /// For a differential rule, its ODEs: the module stays and its parameters grow.
    pub solve: Option<Vec<Derivative>>,
    /// The weight after the successor (stochastic rules).
    pub probability: Option<Expr>,
    /// The section the rule is in.
    pub section: Section,
    /// The whole rule.
    pub span: Span,
}

/// A production or interpretation rule.
pub type Rule = RuleOf<PatternModule, ModuleCall>;

/// `define NAME = expr`
#[derive(Clone, Debug, PartialEq)]
pub struct Define {
    /// The constant's name.
    pub name: String,
    /// Where the name stands.
    pub name_span: Span,
    /// Its value.
    pub value: Expr,
}

/// A whole L-system file.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LsysFile {
    /// Named constants, in file order.
    pub defines: Vec<Define>,
    /// Names declared with `module`.
    pub declared_modules: Vec<(String, Span)>,
    /// `seed: N`
    pub seed: Option<(u64, Span)>,
    /// `axiom: ...`
    pub axiom: Option<(Vec<ModuleCall>, Span)>,
    /// `derivation length: expr`
    pub derivation_length: Option<Expr>,
    /// `time: expr`: develop in continuous time from 0 to this.
    pub time: Option<Expr>,
    /// `dt: expr`: the observation step.
    pub dt: Option<Expr>,
    /// `timing: exact | iterative`
    pub timing: Option<(Timing, Span)>,
    /// `environment: v0 v1 ...`: the chemical array's initial values.
    pub environment: Option<(Vec<f64>, Span)>,
    /// `angle: expr`: the textbook turns' default angle, in degrees.
    pub angle: Option<Expr>,
    /// `step: expr`: the textbook `F` and `f`'s default length.
    pub step: Option<Expr>,
    /// `heading: up | ground`
    pub heading: Option<(Heading, Span)>,
    /// `ignore: ...` (all such lines together)
    pub ignore: Vec<(String, Span)>,
    /// Rules in file order, productions and interpretation rules together.
    pub rules: Vec<Rule>,
    /// Words that were split into several modules, in file order.
    pub split_words: Vec<SplitWord>,
}

/// A word of a module list read as several modules (`FF` as `F F`, `Tial` as `T i a l`).
#[derive(Clone, Debug, PartialEq)]
pub struct SplitWord {
    /// The word as written.
    pub word: String,
    /// The modules it is read as, in order.
    pub pieces: Vec<String>,
    /// Whether each piece is a known name (declared, a rule's predecessor or a built-in
    /// command); a piece that is not is a single character taken because nothing known
    /// starts there.
    pub known: Vec<bool>,
    /// When some piece is not known: the known name closest to the word, which it was
    /// probably meant to be (`forward` for `foward`).
    pub suggestion: Option<String>,
    /// Where the word stands.
    pub span: Span,
}

impl SplitWord {
    /// Whether every piece is a known name (`FF` with a rule for `F`): the classic
    /// one-letter notation, not a mistake.
    pub fn all_known(&self) -> bool {
        self.known.iter().all(|&k| k)
    }
}
