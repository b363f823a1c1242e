//! `ontogeny derive`

use std::io::{BufWriter, IsTerminal, Write};
use std::path::PathBuf;

use anyhow::bail;
use clap::{Args, ValueEnum};
use ontogeny::environment::Environment;
use ontogeny::lang::{Diagnostic, DiagnosticKind};
use ontogeny::lsystem::{
    DEFAULT_MAX_MODULES, DeriveOptions, Event, LSystem, ModuleString, NamedModule, Timing,
};
use serde::Serialize;

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
    #[arg(long = "env", value_name = "INDEX=VALUE", value_parser = parse_env)]
    env: Vec<(usize, f64)>,
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
        out
    }
}

/// The derivation options the flags ask for.
pub fn derive_options(
    args: &DevelopmentArgs,
    seed: Option<u64>,
    max_modules: usize,
) -> DeriveOptions {
    DeriveOptions {
        seed,
        max_modules,
        env: args.env.clone(),
        time: args.time,
        dt: args.dt,
        timing: args.timing.map(|t| match t {
            TimingArg::Exact => Timing::Exact,
            TimingArg::Iterative => Timing::Iterative,
        }),
    }
}

/// Flags of `ontogeny derive`.
#[derive(Args)]
pub struct DeriveArgs {
    /// The L-system file (`.lsys`); `-` reads it from standard input.
    file: PathBuf,
    #[command(flatten)]
    development: DevelopmentArgs,
    /// Also print a line for every event (time, module, rule line) in continuous mode.
    #[arg(long)]
    events: bool,
    /// Seed for stochastic rules and random functions (default: the file's `seed:`, else 0).
    #[arg(long)]
    seed: Option<u64>,
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

fn parse_env(text: &str) -> Result<(usize, f64), String> {
    let (index, value) = text
        .split_once('=')
        .ok_or_else(|| format!("'{text}' is not INDEX=VALUE"))?;
    let index = index
        .trim()
        .parse()
        .map_err(|_| format!("'{index}' is not an index (0, 1, 2, ...)"))?;
    let value: f64 = value
        .trim()
        .parse()
        .map_err(|_| format!("'{value}' is not a number"))?;
    if !value.is_finite() {
        return Err(format!("'{value}' is not a finite number"));
    }
    Ok((index, value))
}

#[derive(Serialize)]
struct Frame<'a> {
    step: u64,
    t: f64,
    modules: Vec<NamedModule<'a>>,
    env: &'a [f64],
}

#[derive(Serialize)]
struct EventLine<'a> {
    event: &'a Event,
}

/// Derives the file and prints the steps.
pub fn run(args: &DeriveArgs) -> anyhow::Result<()> {
    let lsys = LSystem::from_path(&args.file)?;
    let options = derive_options(&args.development, args.seed, args.max_modules);
    let stdout = std::io::stdout();
    let mut out = Printer {
        out: BufWriter::new(stdout.lock()),
        lsys: &lsys,
        args,
        options: &options,
    };
    if options.time.is_some() || lsys.is_continuous() {
        discrete_steps(&lsys, &options, args.development.steps, "printing")?;
        frames(&lsys, &options, &mut out)?;
    } else {
        derive(&lsys, &options, &mut out)?;
    }
    out.out.flush()?;
    Ok(())
}

fn derive(lsys: &LSystem, options: &DeriveOptions, out: &mut Printer<'_>) -> anyhow::Result<()> {
    discrete_steps(lsys, options, out.args.development.steps, "printing")?;
    frames(lsys, options, out)
}

/// The development flags checked against the mode (every verb that develops a grammar calls
/// this): `--steps` is an error in continuous time, `--dt` and `--timing` in discrete time; in
/// discrete time, a note on standard error when the file has productions but neither it nor
/// `--steps` gives a derivation length (`doing` says what happens to the axiom alone, e.g.
/// "growing").
pub fn discrete_steps(
    lsys: &LSystem,
    options: &DeriveOptions,
    steps: Option<u64>,
    doing: &str,
) -> anyhow::Result<Option<u64>> {
    check_continuous_flags(lsys, options)?;
    if options.time.is_some() || lsys.is_continuous() {
        if steps.is_some() {
            bail!(Diagnostic::without_location(
                DiagnosticKind::Semantic,
                "--steps counts discrete steps; in continuous time use --time and --dt",
            ));
        }
    } else if steps.is_none() && lsys.derivation_length().is_none() && lsys.has_productions() {
        eprintln!(
            "note: {} has no 'derivation length:' and no --steps was given: {doing} the axiom only",
            lsys.source().name()
        );
    }
    Ok(steps)
}

/// `--dt` and `--timing` for a discrete file (no differential rules, no `time:`) and no
/// `--time`: an error, since they would change nothing.
pub fn check_continuous_flags(lsys: &LSystem, options: &DeriveOptions) -> anyhow::Result<()> {
    let continuous = options.time.is_some() || lsys.is_continuous();
    if !continuous && (options.dt.is_some() || options.timing.is_some()) {
        bail!(Diagnostic::without_location(
            DiagnosticKind::Semantic,
            format!(
                "--dt and --timing are for continuous time: give --time T (or 'time:' in {})",
                lsys.source().name()
            ),
        ));
    }
    Ok(())
}

fn frames(lsys: &LSystem, options: &DeriveOptions, out: &mut Printer<'_>) -> anyhow::Result<()> {
    // A bar only when the frames are not printing to the terminal themselves.
    let quiet = out.args.last || !std::io::stdout().is_terminal();
    let mut progress =
        super::progress::Progress::on("deriving", quiet && std::io::stderr().is_terminal());
    let derived = lsys.for_each_frame(options, out.args.development.steps, |frame| {
        progress.set(frame.fraction());
        if out.args.events {
            for event in &frame.events {
                out.event(event)?;
            }
        }
        if !out.args.last || frame.last {
            out.frame(frame.step, frame.t, frame.string, frame.env)?;
        }
        Ok::<(), anyhow::Error>(())
    });
    progress.finish();
    derived
}

struct Printer<'a> {
    out: BufWriter<std::io::StdoutLock<'a>>,
    lsys: &'a LSystem,
    args: &'a DeriveArgs,
    options: &'a DeriveOptions,
}

impl Printer<'_> {
    fn frame(
        &mut self,
        step: u64,
        t: f64,
        string: &ModuleString,
        env: &Environment,
    ) -> anyhow::Result<()> {
        let interpreted;
        let string = if self.args.interpret {
            interpreted = self.lsys.interpret(string, t, self.options)?;
            &interpreted
        } else {
            string
        };
        if self.args.json {
            let frame = Frame {
                step,
                t,
                modules: string.to_modules(self.lsys.symbols()),
                env: env.values(),
            };
            serde_json::to_writer(&mut self.out, &frame)?;
            writeln!(self.out)?;
        } else {
            let env_text = if env.is_empty() {
                String::new()
            } else {
                let values: Vec<String> = env.values().iter().map(|v| format!("{v}")).collect();
                format!("  env [{}]", values.join(" "))
            };
            if self.lsys.is_continuous() || self.options.time.is_some() {
                writeln!(
                    self.out,
                    "t={}: {}{env_text}",
                    ontogeny::lsystem::format_number(t),
                    self.lsys.display(string)
                )?;
            } else {
                writeln!(self.out, "{step}: {}{env_text}", self.lsys.display(string))?;
            }
        }
        Ok(())
    }

    fn event(&mut self, event: &Event) -> anyhow::Result<()> {
        if self.args.json {
            serde_json::to_writer(&mut self.out, &EventLine { event })?;
            writeln!(self.out)?;
        } else {
            let rule = match event.rule_line {
                Some(line) => format!("the rule on line {line} applies"),
                None => "no rule applies".to_string(),
            };
            writeln!(
                self.out,
                "  event t={}: {}: {rule}",
                ontogeny::lsystem::format_number(event.t),
                event.module
            )?;
        }
        Ok(())
    }
}
