//! Helpers shared by the integration tests: running the command, scratch directories, and
//! small creatures and genomes.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use ontogeny::creature::Creature;
use ontogeny::develop::{BuildOptions, grow};
use ontogeny::lsystem::{DeriveOptions, LSystem};

/// Compiles `text`, panicking with the rendered diagnostic on failure.
pub fn lsystem(text: &str) -> LSystem {
    LSystem::from_text("test.lsys", text).unwrap_or_else(|e| panic!("{e}"))
}

/// The readable strings of steps 0..=steps, with spaces removed.
pub fn derive(text: &str, steps: usize) -> Vec<String> {
    derive_with(text, steps, &DeriveOptions::default())
}

/// As [`derive`], with options.
pub fn derive_with(text: &str, steps: usize, options: &DeriveOptions) -> Vec<String> {
    let lsys = lsystem(text);
    let mut d = lsys.derivation(options).unwrap_or_else(|e| panic!("{e}"));
    let mut out = vec![squash(&lsys.display(d.current()))];
    for _ in 0..steps {
        let s = d.step().unwrap_or_else(|e| panic!("{e}"));
        out.push(squash(&lsys.display(s)));
    }
    out
}

/// Removes white space, so that expected strings can be written either way.
pub fn squash(s: &str) -> String {
    s.chars().filter(|c| !c.is_whitespace()).collect()
}

/// The creature a shipped example grows into (its last frame).
pub fn grown(path: &str) -> Creature {
    let lsys = LSystem::from_path(std::path::Path::new(path)).unwrap();
    let frames = grow(
        &lsys,
        &DeriveOptions::default(),
        None,
        &BuildOptions::default(),
    )
    .unwrap();
    frames.into_iter().last().unwrap().creature
}

/// The last creature `develop::grow` makes from `text` with a module and a part cap (what
/// `ontogeny grow --max-modules --max-parts` does).
pub fn grown_with_caps(text: &str, max_modules: usize, max_parts: usize) -> Creature {
    let lsys = lsystem(text);
    let options = DeriveOptions {
        max_modules,
        ..DeriveOptions::default()
    };
    let build = BuildOptions {
        max_parts,
        ..BuildOptions::default()
    };
    grow(&lsys, &options, None, &build)
        .unwrap_or_else(|e| panic!("{e}"))
        .pop()
        .expect("a frame")
        .creature
}

/// Asserts that a genome type's operators are functions of their random source: the same
/// seed gives the same random genome, mutant, child and creature, another seed another
/// genome.
pub fn assert_determined_by_the_random_source<G: ontogeny::encoding::Genome + PartialEq>(
    limits: &G::Limits,
) {
    use rand::SeedableRng;
    let rng = ontogeny::encoding::Rng::seed_from_u64;
    let a = G::random(limits, &mut rng(42));
    assert_eq!(a, G::random(limits, &mut rng(42)));
    assert_ne!(a, G::random(limits, &mut rng(43)));
    let other = G::random(limits, &mut rng(1));
    assert_eq!(
        a.mutate(limits, 0.2, &mut rng(5)),
        a.mutate(limits, 0.2, &mut rng(5))
    );
    assert_eq!(
        a.crossover(&other, limits, &mut rng(5)),
        a.crossover(&other, limits, &mut rng(5))
    );
    assert_eq!(
        a.graft(&other, limits, &mut rng(5)),
        a.graft(&other, limits, &mut rng(5))
    );
    assert_eq!(a.develop(limits, 3), a.develop(limits, 3));
}

/// The `ontogeny` binary as a command, for a test to add arguments, input or environment to.
pub fn ontogeny_command() -> Command {
    Command::new(env!("CARGO_BIN_EXE_ontogeny"))
}

/// Runs `ontogeny ARGS` and returns what it did, whatever its exit code.
pub fn ontogeny(args: &[&str]) -> Output {
    ontogeny_command()
        .args(args)
        .output()
        .expect("the binary runs")
}

/// Runs `ontogeny ARGS` with `input` on its standard input.
pub fn ontogeny_reading(args: &[&str], input: &[u8]) -> Output {
    use std::io::Write;
    use std::process::Stdio;
    let mut child = ontogeny_command()
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    child.stdin.take().unwrap().write_all(input).unwrap();
    child.wait_with_output().unwrap()
}

/// Runs `ontogeny ARGS`, asserting that it succeeds.
pub fn ontogeny_ok(args: &[&str]) -> Output {
    let o = ontogeny(args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    o
}

/// A command's standard output, as text.
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// A command's standard error, as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Asserts that a command succeeded (showing what it printed if not); returns its standard
/// output.
pub fn succeeded(output: &Output) -> String {
    assert!(
        output.status.success(),
        "{}\n{}",
        stdout(output),
        stderr(output)
    );
    stdout(output)
}

/// Asserts that a command refused bad input: exit code 2 and `message` in its standard error.
/// Returns the standard error, for a test to check more of it.
pub fn refused(output: &Output, message: &str) -> String {
    let said = stderr(output);
    assert_eq!(output.status.code(), Some(2), "{said}");
    assert!(said.contains(message), "expected {message:?} in: {said}");
    said
}

/// Runs `ontogeny ARGS` and asserts that it refuses them as bad input: exit code 2 and
/// `message` in its standard error. Returns the standard error.
pub fn assert_bad_input(args: &[&str], message: &str) -> String {
    let output = ontogeny(args);
    let said = stderr(&output);
    assert_eq!(output.status.code(), Some(2), "{args:?}: {said}");
    assert!(
        said.contains(message),
        "{args:?}: expected {message:?} in: {said}"
    );
    said
}

/// A fresh, empty directory for a test's scratch files, under the target directory's
/// `CARGO_TARGET_TMPDIR`. Tests share one process: give each its own `name` (a module
/// prefix keeps them apart).
pub fn scratch_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `ontogeny grow FILE --out OUT EXTRA...`, and the `creature.json` it writes.
pub fn grow_creature_json(file: &Path, out: &Path, extra: &[&str]) -> serde_json::Value {
    let mut args = vec![
        "grow",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    ontogeny_ok(&args);
    serde_json::from_str(&std::fs::read_to_string(out.join("creature.json")).unwrap()).unwrap()
}

/// The SQL that takes a run store of the current schema back to version 3: the checksums,
/// the evaluator versions and the counts of individuals dropped. A test that edits a store's
/// records by hand runs it after, and sets `user_version` to 3: the resume migrates the
/// store again, checksumming the records as they are, as it does a store an older ontogeny
/// wrote.
pub const DROP_VERSION_4: &str = "
    ALTER TABLE run DROP COLUMN checksum;
    ALTER TABLE generation DROP COLUMN checksum;
    ALTER TABLE generation DROP COLUMN individuals;
    ALTER TABLE generation DROP COLUMN evaluator;
    ALTER TABLE individual DROP COLUMN checksum;
";

/// Turns the run store at `path` back into schema version 1, as an older ontogeny wrote it:
/// the checksums, evaluator versions and counts of individuals, the cache's columns and the
/// fine reference columns dropped, the version set to 1, the log folded in.
pub fn make_version_1(path: &Path) {
    let conn = rusqlite::Connection::open(path).unwrap();
    conn.execute_batch(DROP_VERSION_4).unwrap();
    conn.execute_batch(
        "ALTER TABLE generation DROP COLUMN best_fine;
         ALTER TABLE generation DROP COLUMN best_fine_status;
         ALTER TABLE individual DROP COLUMN reused;
         ALTER TABLE individual DROP COLUMN evaluation_key;
         PRAGMA user_version = 1;
         PRAGMA wal_checkpoint(TRUNCATE);",
    )
    .unwrap();
}

/// `ontogeny evolve --encoding ENCODING --task walker --pop POP`, for a test to add the run's
/// size, seed and directory to.
pub fn evolve_walkers(encoding: &str, pop: &str) -> Command {
    let mut command = ontogeny_command();
    command.args([
        "evolve",
        "--encoding",
        encoding,
        "--task",
        "walker",
        "--pop",
        pop,
    ]);
    command
}

/// A tiny run of `encoding` into `out`: walkers, a population of 6, 2 generations of 1 s walks
/// (and `extra` flags); asserts that it succeeded.
pub fn tiny_run(encoding: &str, out: &Path, extra: &[&str]) -> Output {
    let output = evolve_walkers(encoding, "6")
        .args(["--gens", "2", "--seconds", "1"])
        .args(extra)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    succeeded(&output);
    output
}
