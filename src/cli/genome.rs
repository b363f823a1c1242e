//! `ontogeny genome`: inspect genome files.

use std::path::{Path, PathBuf};

use anyhow::Context;
use clap::{Args, Subcommand};
use ontogeny::encoding::{ShowError, read_genome_file};
use ontogeny::front::habitats::{GenomeHabitatsError, genome_in_habitats};

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
        /// Develop the genome in each habitat of this configuration's `[[task.habitats]]`
        /// (with each habitat's chemical array) and print, per pair of habitats, how the
        /// creatures differ (parts, joints, sizes, neurons), then whether the body depends on
        /// the habitat.
        #[arg(long, value_name = "CONFIG")]
        habitats: Option<PathBuf>,
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
        GenomeVerb::Show {
            file,
            json,
            habitats: Some(config),
        } => show_habitats(file, config, *json),
        GenomeVerb::Show {
            file,
            json,
            habitats: None,
        } => {
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

/// `genome show --habitats CONFIG FILE`: the genome developed in each habitat of CONFIG, and
/// how the creatures differ.
fn show_habitats(file: &Path, config: &Path, json: bool) -> anyhow::Result<()> {
    let shown = genome_in_habitats(config, file).map_err(|e| match e {
        GenomeHabitatsError::Diagnostic(d) => anyhow::Error::new(d),
        GenomeHabitatsError::Input(m) => super::bad(m),
        GenomeHabitatsError::Read { path, source } => {
            anyhow::Error::new(source).context(format!("cannot read {}", path.display()))
        }
    })?;
    if json {
        say!("{}", serde_json::to_string_pretty(&shown.json())?);
    } else {
        say!("{}", shown.text());
    }
    Ok(())
}
