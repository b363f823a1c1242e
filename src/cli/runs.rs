//! `ontogeny runs`: inspecting run directories.

use std::path::PathBuf;

use clap::{Args, Subcommand};

/// Subcommands of `ontogeny runs`.
#[derive(Subcommand)]
pub enum RunsVerb {
    /// Print a run's generation table.
    Show {
        /// The run directory.
        dir: PathBuf,
    },
}

/// Flags of `ontogeny runs`.
#[derive(Args)]
pub struct RunsArgs {
    #[command(subcommand)]
    verb: RunsVerb,
}

/// Runs `ontogeny runs`.
pub fn run(args: &RunsArgs) -> anyhow::Result<()> {
    match &args.verb {
        RunsVerb::Show { dir } => {
            let table = ontogeny::evolve::text::generation_table(dir)
                .map_err(|e| super::bad(e.to_string()))?;
            say!("{table}");
            Ok(())
        }
    }
}
