//! `ontogeny runs`: inspecting run directories.

use std::path::PathBuf;

use anyhow::Context;
use clap::{Args, Subcommand};
use ontogeny::front::text;
use ontogeny::study::listing;

/// Subcommands of `ontogeny runs`.
#[derive(Subcommand)]
pub enum RunsVerb {
    /// Print a run's generation table (or, with --csv or --json, every generation's record).
    Show {
        /// The run directory.
        dir: PathBuf,
        /// Print the generations as CSV: a header, then a row per generation, every number in
        /// full (empty where there is none).
        #[arg(long, conflicts_with = "json")]
        csv: bool,
        /// Print the run as one JSON object: its settings and an array of its generations.
        #[arg(long)]
        json: bool,
    },
    /// List the runs and comparisons in a directory and under it, one line each: path, kind,
    /// encoding(s), task, progress and best (or why it cannot be read).
    List {
        /// The directory to search.
        dir: PathBuf,
    },
}

/// Inspect runs: a run's generations (`runs show DIR`), the runs and comparisons under a
/// directory (`runs list DIR`).
#[derive(Args)]
pub struct RunsArgs {
    #[command(subcommand)]
    verb: RunsVerb,
}

/// Runs `ontogeny runs`.
pub fn run(args: &RunsArgs) -> anyhow::Result<()> {
    match &args.verb {
        RunsVerb::Show { dir, csv, json } => {
            let shown = match (csv, json) {
                (true, _) => text::generation_csv(dir),
                (_, true) => text::generation_json(dir),
                _ => text::generation_table(dir),
            };
            say!("{}", shown.map_err(|e| super::bad(e.to_string()))?);
        }
        RunsVerb::List { dir } => {
            let found =
                listing::list(dir).with_context(|| format!("cannot read {}", dir.display()))?;
            if found.is_empty() {
                tell!("{}: no run or comparison here", dir.display());
            }
            for listed in found {
                say!("{}", listed.line());
            }
        }
    }
    Ok(())
}
