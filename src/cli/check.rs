//! `ontogeny check`

use std::path::PathBuf;

use clap::Args;
use ontogeny::lsystem::LSystem;

/// Flags of `ontogeny check`.
#[derive(Args)]
pub struct CheckArgs {
    /// The L-system file (`.lsys`); `-` reads it from standard input.
    file: PathBuf,
    /// Print the report as one JSON object.
    #[arg(long)]
    json: bool,
}

/// Checks the file and prints the report.
pub fn run(args: &CheckArgs) -> anyhow::Result<()> {
    let lsys = LSystem::from_path(&args.file)?;
    let report = lsys.check();
    if args.json {
        say!("{}", serde_json::to_string_pretty(&report)?);
        return Ok(());
    }
    say!("{}: ok", report.file);
    say!("axiom: {}", report.axiom);
    match (report.time, report.derivation_length) {
        (Some(time), _) => say!(
            "continuous time: 0 to {time}, dt = {}, timing {}, {} differential rule{}",
            report.dt,
            report.timing,
            report.differential_rules,
            if report.differential_rules == 1 {
                ""
            } else {
                "s"
            }
        ),
        (None, Some(n)) => say!("derivation length: {n}"),
        (None, None) => {
            say!("derivation length: not given (derive prints the axiom only unless --steps)")
        }
    }
    if report.time.is_none() && report.differential_rules > 0 {
        say!(
            "note: {} differential rule(s) but no 'time:': derive them with --time T",
            report.differential_rules
        );
    }
    if !report.environment.is_empty() {
        let values: Vec<String> = report.environment.iter().map(|v| v.to_string()).collect();
        say!("environment: {}", values.join(" "));
    }
    let symbols: Vec<String> = report
        .symbols
        .iter()
        .map(|s| {
            let arity = match s.arities.as_slice() {
                [0] => String::new(),
                [n] => format!("({n})"),
                many => format!(
                    "({})",
                    many.iter()
                        .map(usize::to_string)
                        .collect::<Vec<_>>()
                        .join("|")
                ),
            };
            let mark = if s.rewritten { "*" } else { "" };
            format!("{}{arity}{mark}", s.name)
        })
        .collect();
    say!(
        "symbols ({}, * = rewritten by a production): {}",
        symbols.len(),
        symbols.join(" ")
    );
    say!(
        "rules: {} production{}, {} interpretation rule{}",
        report.productions,
        if report.productions == 1 { "" } else { "s" },
        report.interpretation_rules,
        if report.interpretation_rules == 1 {
            ""
        } else {
            "s"
        }
    );
    if !report.constants.is_empty() {
        let constants: Vec<String> = report
            .constants
            .iter()
            .map(|(n, v)| format!("{n} = {v}"))
            .collect();
        say!("constants: {}", constants.join(", "));
    }
    if report.findings.is_empty() {
        say!("findings: none");
    } else {
        say!("findings ({}):", report.findings.len());
        for f in &report.findings {
            say!("  {}:{}:{}: {}", report.file, f.line, f.column, f.message);
        }
    }
    Ok(())
}
