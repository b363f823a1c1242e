//! `ontogeny derive`

use std::io::{BufWriter, Write};
use std::path::PathBuf;

use clap::Args;
use ontogeny::lsystem::{DEFAULT_MAX_MODULES, DeriveOptions, LSystem, ModuleString};
use serde::Serialize;

/// Flags of `ontogeny derive`.
#[derive(Args)]
pub struct DeriveArgs {
    /// The L-system file (`.lsys`).
    file: PathBuf,
    /// Number of derivation steps (default: the file's `derivation length:`).
    #[arg(long)]
    steps: Option<u64>,
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

#[derive(Serialize)]
struct Frame<'a> {
    step: u64,
    t: f64,
    modules: Vec<ontogeny::lsystem::NamedModule<'a>>,
    env: [f64; 0],
}

/// Derives the file and prints the steps.
pub fn run(args: &DeriveArgs) -> anyhow::Result<()> {
    let lsys = LSystem::from_path(&args.file)?;
    let steps = match (args.steps, lsys.derivation_length()) {
        (Some(n), _) | (None, Some(n)) => n,
        (None, None) => {
            eprintln!(
                "note: {} has no 'derivation length:' and no --steps was given: printing the axiom only",
                args.file.display()
            );
            0
        }
    };
    let options = DeriveOptions {
        seed: args.seed,
        max_modules: args.max_modules,
    };
    let stdout = std::io::stdout();
    let mut out = BufWriter::new(stdout.lock());
    let mut derivation = lsys.derivation(&options);
    for step in 0..=steps {
        if step > 0 {
            derivation.step()?;
        }
        if !args.last || step == steps {
            let t = step as f64;
            let interpreted;
            let string = if args.interpret {
                interpreted = lsys.interpret(derivation.current(), t, &options)?;
                &interpreted
            } else {
                derivation.current()
            };
            print_step(&mut out, &lsys, step, t, string, args.json)?;
        }
    }
    out.flush()?;
    Ok(())
}

fn print_step(
    out: &mut impl Write,
    lsys: &LSystem,
    step: u64,
    t: f64,
    string: &ModuleString,
    json: bool,
) -> std::io::Result<()> {
    if json {
        let frame = Frame {
            step,
            t,
            modules: string.to_modules(lsys.symbols()),
            env: [],
        };
        serde_json::to_writer(&mut *out, &frame)?;
        writeln!(out)
    } else {
        writeln!(out, "{step}: {}", lsys.display(string))
    }
}
