//! Command-line verbs. Exit codes: 0 success, 2 bad input, 1 internal failure.

/// Like `println!`, but a closed standard output (`ontogeny ... | head`) is an error the
/// caller returns (and `main` treats as success), never a panic.
macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        writeln!(std::io::stdout().lock(), $($arg)*)?;
    }};
}

/// Writes a line to standard error, as `eprintln!` does, but never fails: a reader that has
/// closed the pipe (`ontogeny check bad.lsys 2>&1 | head -1`) loses the message, and the
/// command goes on to its exit code instead of panicking.
macro_rules! tell {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr().lock(), $($arg)*);
    }};
}

/// Runs `$body` with `$G` standing for the genome type of the encoding named `$name`, or
/// `$unknown(name)` when no encoding has that name: the library's registry of encodings
/// ([`ontogeny::encoding::ENCODINGS`]), under the name every verb uses.
macro_rules! with_genome {
    ($($dispatch:tt)*) => {
        ontogeny::with_genome!($($dispatch)*)
    };
}

mod bench;
mod check;
mod compare;
mod derive;
mod eval;
mod evolve;
mod export;
mod genome;
mod grammar;
mod grow;
mod input;
mod physics;
mod progress;
mod replay;
mod runs;
mod view;

use std::io::Write;
use std::process::ExitCode;

use clap::{Command, CommandFactory, FromArgMatches, Parser, Subcommand};
use ontogeny::lang::{Diagnostic, DiagnosticKind};

/// Grow virtual creatures from L-systems and evolve them in physics.
#[derive(Parser)]
#[command(name = "ontogeny", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    verb: Verb,
}

/// Declares [`Verb`], one variant per verb holding its flags (`derive::DeriveArgs`, whose
/// doc comment is the verb's `--help`), and [`Verb::run`], which runs the verb's module's
/// `run`.
macro_rules! verbs {
    ($($variant:ident: $module:ident::$args:ident),* $(,)?) => {
        /// The verbs.
        #[derive(Subcommand)]
        enum Verb {
            $($variant($module::$args),)*
        }

        impl Verb {
            /// Runs the verb.
            fn run(self) -> anyhow::Result<()> {
                match self {
                    $(Verb::$variant(args) => $module::run(&args),)*
                }
            }
        }
    };
}

verbs! {
    Derive: derive::DeriveArgs, Check: check::CheckArgs, Grow: grow::GrowArgs,
    Eval: eval::EvalArgs, Export: export::ExportArgs, Replay: replay::ReplayArgs,
    Evolve: evolve::EvolveArgs, Compare: compare::CompareArgs, Runs: runs::RunsArgs,
    Genome: genome::GenomeArgs, Bench: bench::BenchArgs, View: view::ViewArgs,
}

/// Lets every verb take negative numbers as option values (`--strength -1`), not only
/// `--strength=-1`.
/// What `--fitness` sets the fitness of.
enum FitnessOf {
    /// An evaluation (`eval`, `replay`).
    Evaluation,
    /// A run (`evolve`, `compare`).
    Run,
}

/// The help of `--fitness` in `eval`, `replay`, `evolve` and `compare`: the walker's formulas
/// by name ([`ontogeny::task::WalkerFitness::name`]), or an expression of the task's terms,
/// which the task's check reads once the task is known; and the default where it sets the
/// fitness `of`.
fn fitness_help(of: FitnessOf) -> String {
    use ontogeny::task::WalkerFitness;
    let (what, default) = match of {
        FitnessOf::Evaluation => (
            "The fitness",
            "a run's or a champion file's own, else the task's (the walker's normalised)",
        ),
        FitnessOf::Run => (
            "The fitness, as `eval --fitness`",
            "the config's [task.NAME] fitness, else the task's (the walker's normalised)",
        ),
    };
    let names: Vec<&str> = WalkerFitness::ALL.map(WalkerFitness::name).to_vec();
    format!(
        "{what}: one of the walker's formulas ({}), or an expression of the task's terms, \
         as \"D_w - 0.5 * drag\" (docs/reference/tasks.md lists each task's terms) [default: \
         {default}]",
        names.join(", ")
    )
}

/// Reads a count of parts (`--max-parts`): a whole number of at least 1.
fn parse_part_count(text: &str) -> Result<usize, String> {
    match text.parse::<usize>() {
        Ok(0) => Err("a creature has at least one part: give 1 or more".to_string()),
        Ok(n) => Ok(n),
        Err(e) => Err(e.to_string()),
    }
}

fn allow_negative_numbers(command: Command) -> Command {
    let verbs: Vec<String> = command
        .get_subcommands()
        .map(|verb| verb.get_name().to_string())
        .collect();
    verbs
        .into_iter()
        .fold(command.allow_negative_numbers(true), |command, verb| {
            command.mut_subcommand(verb, allow_negative_numbers)
        })
}

/// `command` with its flag `id` refusing every other of its flags but those in `keep`: the
/// lists of conflicts computed from the flags themselves, so that a flag added later is
/// refused beside `id` unless it is named here.
fn conflicts_with_all_but(command: Command, id: &str, keep: &[&str]) -> Command {
    let others: Vec<clap::Id> = command
        .get_arguments()
        .map(|a| a.get_id().clone())
        .filter(|other| other != id && !keep.contains(&other.as_str()))
        .collect();
    command.mut_arg(id, |arg| arg.conflicts_with_all(others))
}

/// The command line: the verbs' flags, negative numbers allowed where a number is wanted, and
/// the flags that continue or merge earlier work refusing those that would start new work
/// ([`conflicts_with_all_but`]).
fn command() -> Command {
    allow_negative_numbers(Cli::command())
        .mut_subcommand("evolve", |c| {
            conflicts_with_all_but(c, "resume", evolve::WITH_RESUME)
        })
        .mut_subcommand("compare", |c| {
            let c = conflicts_with_all_but(c, "resume", compare::WITH_RESUME);
            conflicts_with_all_but(c, "merge", compare::WITH_MERGE)
        })
}

/// Runs the command line and turns the outcome into an exit code.
pub fn main() -> ExitCode {
    let matches = command().get_matches();
    if let Some(("eval", eval)) = matches.subcommand() {
        eval::set_given(eval);
    }
    let cli = Cli::from_arg_matches(&matches).unwrap_or_else(|e| e.exit());
    let result = cli.verb.run();
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => report(error),
    }
}

/// Prints `lines`: results on standard output, messages on standard error.
fn print(lines: Vec<ontogeny::front::text::Line>) -> anyhow::Result<()> {
    for line in lines {
        match line {
            ontogeny::front::text::Line::Result(l) => say!("{l}"),
            ontogeny::front::text::Line::Message(l) => tell!("{l}"),
        }
    }
    Ok(())
}

/// Prints the grammar's findings ([`LSystem::findings`]) on standard error, as warnings
/// located with a caret: what every verb that reads a grammar shows.
///
/// [`LSystem::findings`]: ontogeny::lsystem::LSystem::findings
fn tell_findings(lsys: &ontogeny::lsystem::LSystem) {
    for finding in lsys.findings() {
        tell!("{}", finding.warning());
    }
}

/// A bad-input error (exit code 2) with `message`.
pub fn bad(message: impl Into<String>) -> anyhow::Error {
    anyhow::Error::new(Diagnostic::without_location(
        DiagnosticKind::Semantic,
        message.into(),
    ))
}

/// Refuses, before any work is done, output files that could not be written: each must be
/// missing or a regular file (see [`ontogeny::output`]).
fn check_outputs<P: AsRef<std::path::Path>>(
    paths: impl IntoIterator<Item = P>,
) -> anyhow::Result<()> {
    for path in paths {
        ontogeny::output::check_target(path.as_ref())?;
    }
    Ok(())
}

/// A failure to draw `path` as the command line reports it: a refused output as it is (its
/// message names the file; exit code 2), anything else after the file it was writing.
fn render_error(
    path: &std::path::Path,
) -> impl FnOnce(ontogeny::render::RenderError) -> anyhow::Error + '_ {
    move |error| match error {
        ontogeny::render::RenderError::Output(e) => anyhow::Error::new(e),
        other => anyhow::Error::new(other).context(format!("cannot write {}", path.display())),
    }
}

fn report(error: anyhow::Error) -> ExitCode {
    if let Some(diagnostic) = error.downcast_ref::<Diagnostic>() {
        tell!("{diagnostic}");
        return ExitCode::from(2);
    }
    let io = error
        .chain()
        .find_map(|cause| cause.downcast_ref::<std::io::Error>());
    if io.is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe) {
        // The reader (e.g. `head`) has had enough: not a failure.
        return ExitCode::SUCCESS;
    }
    let _ = writeln!(std::io::stderr(), "error: {error:#}");
    ExitCode::from(exit_code(&error))
}

/// The exit code of an error that is not a diagnostic: a file that cannot be read or
/// written, or an output refused (a target that is not a regular file), is the user's to fix
/// (2); anything else is ours (1).
fn exit_code(error: &anyhow::Error) -> u8 {
    if error.downcast_ref::<Diagnostic>().is_some() {
        return 2;
    }
    let io = error
        .chain()
        .any(|cause| cause.downcast_ref::<std::io::Error>().is_some());
    let refused = error.chain().any(|cause| {
        cause
            .downcast_ref::<ontogeny::output::OutputError>()
            .is_some()
    });
    if io || refused { 2 } else { 1 }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// clap's own checks of every verb's flags (unique names, valid defaults), which
    /// otherwise only fire when that verb is run.
    #[test]
    fn the_command_line_is_well_formed() {
        command().debug_assert();
    }

    /// The flags of a new run or comparison are refused beside `--resume` and `--merge`, as
    /// the lists written out by hand before the lists were computed said.
    #[test]
    fn resume_and_merge_refuse_the_flags_of_new_work() {
        let conflicts = |verb: &str, id: &str| {
            let mut command = command();
            command.build();
            let sub = command.find_subcommand(verb).unwrap();
            let arg = sub.get_arguments().find(|a| a.get_id() == id).unwrap();
            let mut names: Vec<String> = sub
                .get_arg_conflicts_with(arg)
                .iter()
                .map(|a| a.get_id().to_string())
                .collect();
            names.sort();
            names
        };
        let sorted = |names: &[&str]| {
            let mut names: Vec<String> = names.iter().map(|n| n.to_string()).collect();
            names.sort();
            names
        };
        assert_eq!(
            conflicts("evolve", "resume"),
            sorted(&[
                "out",
                "encoding",
                "task",
                "fitness",
                "preset",
                "pop",
                "walks",
                "seed",
                "config",
                "init",
                "seconds",
                "setting",
                "target",
                "no_verify_best",
                "no_cache",
                "algorithm",
                "in_flight"
            ])
        );
        // A comparison's own flags, refused beside both.
        let comparison = [
            "encodings",
            "condition",
            "task",
            "fitness",
            "replicates",
            "evaluations",
            "seed",
            "out",
            "preset",
            "pop",
            "seconds",
            "setting",
            "config",
            "plan",
            "primary",
            "power_for",
        ];
        let with = |extra: &[&str]| sorted(&[&comparison[..], extra].concat());
        assert_eq!(conflicts("compare", "resume"), with(&["merge"]));
        assert_eq!(
            conflicts("compare", "merge"),
            with(&["threads", "no_cache", "resume"])
        );
    }

    /// A store or a plot ontogeny cannot write is its own failure; a damaged or foreign
    /// store is the input's.
    #[test]
    fn a_store_or_plot_that_cannot_be_written_exits_1_and_a_damaged_store_exits_2() {
        use ontogeny::run::RunError;
        use ontogeny::run::store::StoreError;
        let path = std::path::PathBuf::from("runs/a/run.sqlite");
        let code = |e: RunError| exit_code(&evolve::run_error(e));
        let full = StoreError::Sqlite {
            path: path.clone(),
            action: "cannot write generation 3 (nothing of it was stored): the commit".into(),
            source: rusqlite::Error::SqliteFailure(
                rusqlite::ffi::Error::new(rusqlite::ffi::SQLITE_FULL),
                None,
            ),
        };
        assert_eq!(code(RunError::Store(full)), 1);
        let cannot_move = StoreError::Io {
            path: path.clone(),
            action: "cannot move the new store into place",
            source: std::io::Error::from(std::io::ErrorKind::StorageFull),
        };
        assert_eq!(code(RunError::Store(cannot_move)), 1);
        assert_eq!(code(RunError::Plot("cannot draw".into())), 1);
        assert_eq!(code(RunError::Panicked("a fault".into())), 1);
        let damaged = StoreError::Corrupt {
            path: path.clone(),
            detail: "the file is truncated".into(),
        };
        assert_eq!(code(RunError::Store(damaged)), 2);
        assert_eq!(code(RunError::Store(StoreError::Missing { path })), 2);
        assert_eq!(code(RunError::Extend("--gens must be 1 or more".into())), 2);
    }
}
