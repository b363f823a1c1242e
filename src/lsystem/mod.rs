//! L-systems: compiling a parsed file, and deriving module strings from it.
//!
//! ```
//! use ontogeny::lsystem::{DeriveOptions, LSystem};
//!
//! let lsys = LSystem::from_text("algae", "axiom: a\na --> ab\nb --> a\n").unwrap();
//! let mut derivation = lsys.derivation(&DeriveOptions::default());
//! for _ in 0..4 {
//!     derivation.step().unwrap();
//! }
//! assert_eq!(lsys.display(derivation.current()), "abaab");
//! ```

pub mod check;
mod compile;
mod derive;
pub mod expr;
mod string;

use std::sync::Arc;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

pub use string::{Module, ModuleString, NamedModule, POP, PUSH, SymbolId, SymbolTable};

use crate::lang::{self, Diagnostic, DiagnosticKind, LsysFile, Source, Span};
use compile::RuleSet;
use derive::{Failure, Pass, Workspace};

/// The default limit on the length of a derived string.
pub const DEFAULT_MAX_MODULES: usize = 1_000_000;

/// A compiled L-system, ready to derive.
#[derive(Debug)]
pub struct LSystem {
    source: Arc<Source>,
    file: LsysFile,
    symbols: SymbolTable,
    constants: Vec<(String, f64, Span)>,
    axiom: ModuleString,
    axiom_span: Span,
    seed: u64,
    derivation_length: Option<u64>,
    productions: RuleSet,
    interpretation: RuleSet,
    ignored: Vec<bool>,
}

/// Settings of one derivation.
#[derive(Clone, Debug)]
pub struct DeriveOptions {
    /// Overrides the file's `seed:`.
    pub seed: Option<u64>,
    /// A string longer than this is an error.
    pub max_modules: usize,
}

impl Default for DeriveOptions {
    fn default() -> Self {
        DeriveOptions {
            seed: None,
            max_modules: DEFAULT_MAX_MODULES,
        }
    }
}

impl LSystem {
    /// Parses and compiles an L-system.
    pub fn parse(source: Arc<Source>) -> Result<LSystem, Diagnostic> {
        let file = lang::parse(&source)?;
        compile::compile(source, file)
    }

    /// Parses and compiles `text`, reported under `name`.
    pub fn from_text(name: &str, text: &str) -> Result<LSystem, Diagnostic> {
        LSystem::parse(Source::new(name, text))
    }

    /// Reads, parses and compiles a file.
    pub fn from_path(path: &std::path::Path) -> Result<LSystem, Diagnostic> {
        let source = Source::read(path).map_err(|e| {
            Diagnostic::without_location(
                DiagnosticKind::Semantic,
                format!("cannot read {}: {e}", path.display()),
            )
        })?;
        LSystem::parse(source)
    }

    /// The source the system was read from.
    pub fn source(&self) -> &Source {
        &self.source
    }

    /// The syntax tree it was compiled from.
    pub fn file(&self) -> &LsysFile {
        &self.file
    }

    /// The module names.
    pub fn symbols(&self) -> &SymbolTable {
        &self.symbols
    }

    /// The starting string.
    pub fn axiom(&self) -> &ModuleString {
        &self.axiom
    }

    /// The file's `seed:` (0 if absent).
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// The file's `derivation length:`, if given.
    pub fn derivation_length(&self) -> Option<u64> {
        self.derivation_length
    }

    /// Named constants with their values.
    pub fn constants(&self) -> impl Iterator<Item = (&str, f64)> {
        self.constants.iter().map(|(n, v, _)| (n.as_str(), *v))
    }

    /// Whether the file has an `interpretation:` section.
    pub fn has_interpretation(&self) -> bool {
        !self.interpretation.rules.is_empty()
    }

    /// A string written readably (see [`ModuleString::display`]).
    pub fn display(&self, s: &ModuleString) -> String {
        s.display(&self.symbols)
    }

    /// Starts a derivation at the axiom.
    pub fn derivation(&self, options: &DeriveOptions) -> Derivation<'_> {
        self.derivation_from(self.axiom.clone(), 0, options)
    }

    /// Starts a derivation at `start`, taken to be the string after `step` steps (its
    /// symbols must come from this system's [`symbols`](Self::symbols)). The random stream
    /// starts afresh from the seed.
    pub fn derivation_from(
        &self,
        start: ModuleString,
        step: u64,
        options: &DeriveOptions,
    ) -> Derivation<'_> {
        let mut rng = ChaCha8Rng::seed_from_u64(options.seed.unwrap_or(self.seed));
        rng.set_stream(0);
        Derivation {
            lsys: self,
            current: start,
            next: ModuleString::new(),
            step,
            rng,
            workspace: Workspace::default(),
            max_modules: options.max_modules,
        }
    }

    /// Applies the interpretation rules once (L-Py's homomorphism) for the builder and
    /// renderer; derivation never sees the result. Without an `interpretation:` section the
    /// string comes back unchanged. `t` is the time the string belongs to.
    pub fn interpret(
        &self,
        s: &ModuleString,
        t: f64,
        options: &DeriveOptions,
    ) -> Result<ModuleString, Diagnostic> {
        if self.interpretation.rules.is_empty() {
            return Ok(s.clone());
        }
        let mut rng = ChaCha8Rng::seed_from_u64(options.seed.unwrap_or(self.seed));
        rng.set_stream(1);
        let mut out = ModuleString::with_capacity(s.len(), s.params.len());
        let pass = Pass {
            rules: &self.interpretation,
            ignored: &self.ignored,
            t,
            max_modules: options.max_modules,
        };
        pass.rewrite(s, &mut out, &mut Workspace::default(), &mut rng)
            .map_err(|f| self.failure(f, &format!("interpreting the string at t = {t}")))?;
        Ok(out)
    }

    fn failure(&self, failure: Failure, when: &str) -> Diagnostic {
        match failure {
            Failure::Expr(e) => Diagnostic::at(
                DiagnosticKind::Runtime,
                &self.source,
                e.span,
                format!("{} while {when}", e.message),
            ),
            Failure::TooLong { span, limit } => Diagnostic::at(
                DiagnosticKind::Runtime,
                &self.source,
                span.unwrap_or(self.axiom_span),
                format!("the string grew past {limit} modules while {when}"),
            )
            .with_note("raise the limit with --max-modules, or check for a runaway rule"),
        }
    }
}

/// A derivation in progress: the current string and the means to rewrite it.
pub struct Derivation<'l> {
    lsys: &'l LSystem,
    current: ModuleString,
    next: ModuleString,
    step: u64,
    rng: ChaCha8Rng,
    workspace: Workspace,
    max_modules: usize,
}

impl Derivation<'_> {
    /// The string after [`step_number`](Self::step_number) steps.
    pub fn current(&self) -> &ModuleString {
        &self.current
    }

    /// How many steps have been taken.
    pub fn step_number(&self) -> u64 {
        self.step
    }

    /// Rewrites the current string once, in parallel.
    pub fn step(&mut self) -> Result<&ModuleString, Diagnostic> {
        let pass = Pass {
            rules: &self.lsys.productions,
            ignored: &self.lsys.ignored,
            t: self.step as f64,
            max_modules: self.max_modules,
        };
        if let Err(f) = pass.rewrite(
            &self.current,
            &mut self.next,
            &mut self.workspace,
            &mut self.rng,
        ) {
            let when = format!("deriving step {}", self.step + 1);
            return Err(self.lsys.failure(f, &when));
        }
        std::mem::swap(&mut self.current, &mut self.next);
        self.step += 1;
        Ok(&self.current)
    }
}
