//! `ontogeny check`

use std::path::PathBuf;

use clap::Args;

/// Parse and validate an L-system; summarise its symbols and rules, and point out rules
/// that can never fire and parameters never used.
#[derive(Args)]
pub struct CheckArgs {
    /// The L-system file (`.lsys`); `-` reads it from standard input.
    file: PathBuf,
    /// Print the report as one JSON object.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    defines: super::grammar::DefineArgs,
    #[command(flatten)]
    seed: super::grammar::SeedArgs,
}

/// Checks the file and prints the report.
pub fn run(args: &CheckArgs) -> anyhow::Result<()> {
    let lsys = args.defines.load(&args.file, args.seed.seed())?;
    let report = lsys.check();
    if args.json {
        say!("{}", serde_json::to_string_pretty(&report)?);
        return Ok(());
    }
    say!("{}", report.text());
    Ok(())
}
