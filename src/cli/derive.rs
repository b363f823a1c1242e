//! `ontogeny derive`, and the development flags every verb that grows a grammar shares.

use std::io::{BufWriter, IsTerminal, Write};
use std::path::{Path, PathBuf};

use clap::{Args, ValueEnum};
use ontogeny::lsystem::{
    DEFAULT_MAX_MODULES, DEFAULT_MAX_WORK, DeriveOptions, LSystem, Timing, print,
};

/// Flags shared by the verbs that develop an L-system (the default: the file's own settings).
#[derive(Args, Default)]
pub struct DevelopmentArgs {
    /// Number of discrete derivation steps (default: the file's `derivation length:`).
    #[arg(long)]
    pub steps: Option<u64>,
    /// Develop in continuous time from 0 to T (default: the file's `time:`; giving either
    /// switches to continuous mode).
    #[arg(long, value_name = "T")]
    time: Option<f64>,
    /// Observation step in continuous mode: a frame every D time units, the last one at the
    /// final time (default: the file's `dt:`, else 1).
    #[arg(long, value_name = "D")]
    dt: Option<f64>,
    /// How continuous development rewrites at events (default: the file's `timing:`, else
    /// exact).
    #[arg(long, value_enum)]
    timing: Option<TimingArg>,
    /// Override an initial environment value, e.g. `--env 0=1` (repeatable).
    #[arg(long = "env", value_name = "INDEX=VALUE", value_parser = print::parse_env_assignment)]
    env: Vec<(usize, f64)>,
    /// The work budget: the most modules all rewriting passes may read together (about
    /// modules × steps; default 20000000). A derivation that would pass it stops with an
    /// error.
    #[arg(long, value_name = "N")]
    max_work: Option<u64>,
    #[command(flatten)]
    pub defines: super::grammar::DefineArgs,
    #[command(flatten)]
    pub seed: super::grammar::SeedArgs,
}

impl DevelopmentArgs {
    /// The development flags given on the command line, by name (for a warning when the
    /// input is not grown from a grammar).
    pub fn given(&self) -> Vec<&'static str> {
        let mut out = Vec::new();
        if self.steps.is_some() {
            out.push("--steps");
        }
        if self.time.is_some() {
            out.push("--time");
        }
        if self.dt.is_some() {
            out.push("--dt");
        }
        if self.timing.is_some() {
            out.push("--timing");
        }
        if !self.env.is_empty() {
            out.push("--env");
        }
        if self.max_work.is_some() {
            out.push("--max-work");
        }
        if !self.defines.defines.is_empty() {
            out.push("--define");
        }
        out.extend(self.seed.given());
        out
    }
}

impl DevelopmentArgs {
    /// The grammar in `file` with the defines and seed the flags give, its findings told, and
    /// the derivation options the flags ask for.
    pub fn load(
        &self,
        file: &Path,
        max_modules: usize,
    ) -> anyhow::Result<(LSystem, DeriveOptions)> {
        let lsys = self.defines.load(file, self.seed.seed())?;
        super::tell_findings(&lsys);
        Ok((lsys, derive_options(self, max_modules)))
    }
}

/// The derivation options the flags ask for.
pub fn derive_options(args: &DevelopmentArgs, max_modules: usize) -> DeriveOptions {
    DeriveOptions {
        seed: args.seed.seed(),
        max_modules,
        env: args.env.clone(),
        time: args.time,
        dt: args.dt,
        timing: args.timing.map(|t| match t {
            TimingArg::Exact => Timing::Exact,
            TimingArg::Iterative => Timing::Iterative,
        }),
        max_work: args.max_work.unwrap_or(DEFAULT_MAX_WORK),
    }
}

/// Derive an L-system and print every step, axiom first.
#[derive(Args)]
pub struct DeriveArgs {
    /// The L-system file (`.lsys`); `-` reads it from standard input.
    file: PathBuf,
    #[command(flatten)]
    development: DevelopmentArgs,
    /// Also print a line for every event (time, module, rule line) in continuous mode.
    #[arg(long)]
    events: bool,
    /// Stop with an error when the string grows longer than this.
    #[arg(long, default_value_t = DEFAULT_MAX_MODULES)]
    max_modules: usize,
    /// Print JSON Lines: one object per step with `step`, `t`, `modules` and `env`.
    #[arg(long)]
    json: bool,
    /// Print each string after the `interpretation:` rules, as the builder sees it.
    #[arg(long)]
    interpret: bool,
    /// Print only the last step.
    #[arg(long)]
    last: bool,
}

/// `--timing` values.
#[derive(Clone, Copy, ValueEnum)]
enum TimingArg {
    /// Settle at every event: development does not depend on dt.
    Exact,
    /// One rewriting pass per observation step and per event (Matos & Arita's listing).
    Iterative,
}

/// Derives the file and prints the steps.
pub fn run(args: &DeriveArgs) -> anyhow::Result<()> {
    let (lsys, options) = args.development.load(&args.file, args.max_modules)?;
    discrete_steps(&lsys, &options, args.development.steps, "printing")?;
    let mut out = BufWriter::new(std::io::stdout().lock());
    // A bar only when the frames are not printing to the terminal themselves.
    let quiet = args.last || !std::io::stdout().is_terminal();
    let mut progress =
        super::progress::Progress::on("deriving", quiet && std::io::stderr().is_terminal());
    lsys.for_each_frame_until(&options, args.development.steps, |frame| {
        progress.set(frame.fraction());
        if args.events {
            for event in &frame.events {
                writeln!(out, "{}", print::event_line(event, args.json)?)?;
            }
        }
        if let Some(step) = frame.fixed_since {
            tell!(
                "note: fixed point at step {step}: steps {} to {} give the same string, so \
                 they were not derived",
                step + 1,
                frame.step
            );
        }
        if !args.last || frame.last {
            let interpreted;
            let string = if args.interpret {
                interpreted = lsys.interpret(frame.string, frame.t, &options)?;
                &interpreted
            } else {
                frame.string
            };
            let step = (frame.step, frame.t);
            let line = print::frame_line(&lsys, &options, step, string, frame.env, args.json)?;
            writeln!(out, "{line}")?;
        }
        Ok::<bool, anyhow::Error>(true)
    })?;
    progress.finish();
    out.flush()?;
    Ok(())
}

/// The development flags checked against the mode ([`print::check_mode`]), with its note on
/// standard error.
pub fn discrete_steps(
    lsys: &LSystem,
    options: &DeriveOptions,
    steps: Option<u64>,
    doing: &str,
) -> anyhow::Result<Option<u64>> {
    if let Some(note) = print::check_mode(lsys, options, steps, doing)? {
        tell!("{note}");
    }
    Ok(steps)
}
