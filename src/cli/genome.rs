//! `ontogeny genome`: inspect genome files.

use std::path::PathBuf;

use anyhow::Context;
use clap::{Args, Subcommand};
use ontogeny::encoding::{ShowError, read_genome_file};

/// Subcommands of `ontogeny genome`.
#[derive(Subcommand)]
pub enum GenomeVerb {
    /// Print a genome file readably (a run's `best.lsys` or `best.json`, any encoding's):
    /// its encoding, the genome (an L-system genome's grammar with its symbols and rules; a
    /// graph genome's nodes, connections and neurons) and the creature it develops into.
    Show {
        /// The genome file (`.lsys` of the L-system and direct genomes, `.json` of the graph).
        file: PathBuf,
        /// Print it as one JSON object: the file, its encoding, the genome as text, and the
        /// creature it develops into summarised as `grow --json` does (null, with the error,
        /// when it does not develop).
        #[arg(long)]
        json: bool,
    },
}

/// Inspect genome files (`genome show FILE`: any encoding's genome, readably).
#[derive(Args)]
pub struct GenomeArgs {
    #[command(subcommand)]
    verb: GenomeVerb,
}

/// Runs `ontogeny genome`.
pub fn run(args: &GenomeArgs) -> anyhow::Result<()> {
    match &args.verb {
        GenomeVerb::Show { file, json } => {
            let text = ontogeny::input::read_to_string(file)
                .with_context(|| format!("cannot read {}", file.display()))?;
            let shown = read_genome_file(file, &text).map_err(|e| match e {
                ShowError::Grammar(d) => anyhow::Error::new(d),
                ShowError::NotAGenome(m) => super::bad(m),
            })?;
            if *json {
                say!("{}", serde_json::to_string_pretty(&shown.json())?);
            } else {
                say!("{}", shown.text());
            }
            Ok(())
        }
    }
}
