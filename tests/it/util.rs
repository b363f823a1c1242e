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
/// seed gives the same random genome, mutant, child (of each crossover) and creature, another seed another
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
    assert_eq!(
        a.mirroring_crossover(&other, limits, &mut rng(5)),
        a.mirroring_crossover(&other, limits, &mut rng(5))
    );
    assert_eq!(a.develop(limits, 3), a.develop(limits, 3));
}

/// The SHA-256, in hex, of the texts and JSON of genomes of `G` drawn, mutated and crossed
/// over from seeds 0 to 19 under `limits`: a fingerprint of what the operators draw.
pub fn operators_fingerprint<G: ontogeny::encoding::Genome>(limits: &G::Limits) -> String {
    use rand::SeedableRng;
    use sha2::{Digest, Sha256};
    let mut hasher = Sha256::new();
    for seed in 0..20 {
        let mut r = ontogeny::encoding::Rng::seed_from_u64(seed);
        let mut a = G::random(limits, &mut r);
        let b = G::random(limits, &mut r);
        for _ in 0..20 {
            a = a.mutate(limits, 0.3, &mut r);
            a = a.crossover(&b, limits, &mut r).unwrap();
            hasher.update(a.to_text().as_bytes());
            hasher.update(serde_json::to_string(&a).unwrap().as_bytes());
        }
    }
    hasher
        .finalize()
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// The genome of `G` in the file `path`, read with the default limits.
pub fn genome_file<G: ontogeny::encoding::Genome>(path: &str) -> G
where
    G::Limits: Default,
{
    let text = std::fs::read_to_string(path).unwrap();
    G::read_text(&text, &G::Limits::default()).unwrap()
}

/// The creatures a plastic genome of one slot, 0 in its own array, grows where its cue is
/// low (0) and where it is high (1): both valid, each holding the array it grew in, the low
/// one what `develop` grows; an array of another size is refused.
pub fn grown_low_and_high<G: ontogeny::encoding::Genome>(
    g: &G,
    limits: &G::Limits,
) -> (Creature, Creature) {
    use ontogeny::environment::Environment;
    assert_eq!(g.environment(), Environment::new(vec![0.0]));
    let low = g
        .develop_in(limits, 0, &Environment::new(vec![0.0]))
        .unwrap();
    let high = g
        .develop_in(limits, 0, &Environment::new(vec![1.0]))
        .unwrap();
    assert!(low.is_valid() && high.is_valid());
    assert_eq!(low.environment, vec![0.0]);
    assert_eq!(high.environment, vec![1.0]);
    // Its own environment is the low one, and develop() grows in it.
    assert_eq!(g.develop(limits, 0).unwrap(), low);
    // An array of another size is refused, not developed.
    let e = g
        .develop_in(limits, 0, &Environment::new(vec![1.0, 0.0]))
        .unwrap_err();
    assert_eq!(
        e.0,
        "the genome develops in an environment of 1 slot(s), not 2"
    );
    (low, high)
}

/// The offspring of genomes of `G` drawn under `limits` from each seed of `seeds`: a pair
/// of random genomes, then eight rounds, mutation and crossover in turn, each offspring
/// read back equal from its text and given to `each` with its seed and text. Returns how
/// many whether the offspring's body depends on its cue (0 or 1), for those that develop:
/// development never panics, and refuses only a creature of too many modules.
pub fn offspring_whose_body_depends_on_the_cue<G>(
    limits: &G::Limits,
    seeds: std::ops::Range<u64>,
    mut each: impl FnMut(u64, &G, &str),
) -> usize
where
    G: ontogeny::encoding::Genome + PartialEq,
{
    use ontogeny::creature::phenotype_differences;
    use ontogeny::environment::Environment;
    use rand::SeedableRng;
    let mut differ = 0;
    for seed in seeds {
        let mut r = ontogeny::encoding::Rng::seed_from_u64(seed);
        let mut a = G::random(limits, &mut r);
        let b = G::random(limits, &mut r);
        for round in 0..8 {
            a = if round % 2 == 0 {
                a.mutate(limits, 0.3, &mut r)
            } else {
                a.crossover(&b, limits, &mut r).unwrap()
            };
            let text = a.to_text();
            let back =
                G::read_text(&text, limits).unwrap_or_else(|e| panic!("seed {seed}: {e}\n{text}"));
            assert_eq!(back, a, "seed {seed}");
            each(seed, &a, &text);
            let low = a.develop_in(limits, 0, &Environment::new(vec![0.0]));
            let high = a.develop_in(limits, 0, &Environment::new(vec![1.0]));
            match (low, high) {
                (Ok(low), Ok(high)) => {
                    differ += usize::from(!phenotype_differences(&low, &high).is_same());
                }
                (low, high) => {
                    for e in [low.err(), high.err()].into_iter().flatten() {
                        assert!(e.0.contains("modules"), "seed {seed}: {e}\n{text}");
                    }
                }
            }
        }
    }
    differ
}

/// `ontogeny evolve --config CONFIG --out OUT`, run to its end.
pub fn evolve_config(config: &Path, out: &Path) -> Output {
    ontogeny_command()
        .args(["evolve", "--config"])
        .arg(config)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap()
}

/// `ontogeny evolve --config CONFIG --out OUT EXTRA...`, which must succeed.
pub fn evolve(config: &Path, out: &Path, extra: &[&str]) {
    let output = ontogeny_command()
        .args(["evolve", "--config"])
        .arg(config)
        .arg("--out")
        .arg(out)
        .args(extra)
        .output()
        .unwrap();
    succeeded(&output);
}

/// Evolves `config` into `dir`'s `one` on one thread and `two` on two, and into `stopped`
/// stopped after `stop` generations, then resumed to `end`; asserts that the three runs are
/// the same ([`crate::evolve::contents`]).
pub fn assert_the_same_on_any_thread_count_and_resumed(
    config: &Path,
    dir: &Path,
    stop: &str,
    end: &str,
) {
    evolve(config, &dir.join("one"), &["--threads", "1"]);
    evolve(config, &dir.join("two"), &["--threads", "2"]);
    let one = crate::evolve::contents(&dir.join("one"));
    assert_eq!(one, crate::evolve::contents(&dir.join("two")));
    let stopped = dir.join("stopped");
    evolve(config, &stopped, &["--gens", stop]);
    let resumed = ontogeny_command()
        .args(["evolve", "--gens", end, "--resume"])
        .arg(&stopped)
        .output()
        .unwrap();
    succeeded(&resumed);
    assert_eq!(crate::evolve::contents(&stopped), one);
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

/// The SQL that takes a run store of the current schema back to version 3: the parents'
/// generations, the checksums, the evaluator versions and the counts of individuals
/// dropped. A test that edits a store's records by hand runs it after, and sets
/// `user_version` to 3: the resume migrates the store again, checksumming the records as
/// they are, as it does a store an older ontogeny wrote.
pub const DROP_VERSION_4: &str = "
    ALTER TABLE individual DROP COLUMN parents_generation;
    ALTER TABLE run DROP COLUMN checksum;
    ALTER TABLE generation DROP COLUMN checksum;
    ALTER TABLE generation DROP COLUMN individuals;
    ALTER TABLE generation DROP COLUMN evaluator;
    ALTER TABLE individual DROP COLUMN checksum;
";

/// A row's checksum as the run store reference documents it, computed here on its own: the
/// first 8 bytes, in hexadecimal, of a SHA-256 over the table's name, a 0 byte, and each
/// value with its type (0 for NULL; 1 and 8 big-endian bytes for an INTEGER; 2 and the 8
/// bytes of a REAL; 3, the length as 8 bytes and the bytes of a TEXT).
pub fn documented_checksum(table: &str, values: &[rusqlite::types::Value]) -> String {
    use rusqlite::types::Value;
    use sha2::{Digest, Sha256};
    let mut hasher = Sha256::new();
    hasher.update(table.as_bytes());
    hasher.update([0]);
    for value in values {
        match value {
            Value::Null => hasher.update([0]),
            Value::Integer(i) => {
                hasher.update([1]);
                hasher.update(i.to_be_bytes());
            }
            Value::Real(x) => {
                hasher.update([2]);
                hasher.update(x.to_bits().to_be_bytes());
            }
            Value::Text(t) => {
                hasher.update([3]);
                hasher.update((t.len() as u64).to_be_bytes());
                hasher.update(t.as_bytes());
            }
            Value::Blob(_) => unreachable!("the run store holds no BLOB"),
        }
    }
    hasher.finalize()[..8]
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// The columns of a version-4 store's `individual` table a checksum covers.
pub const INDIVIDUAL_COLUMNS_V4: &str = "generation, individual, parents, operator, genome_text, \
    genome_json, fitness, status, terms_json, parts, joints, neurons, reused, evaluation_key";

/// Turns the run store at `path` (of a steady-state run) back into schema version 4, as an
/// ontogeny that knew version 4 only wrote it: a member kept through a block carries its
/// row of the generation before (its birth's parents, operator and genome JSON), no
/// `parents_generation` column, every individual checksummed over version 4's columns
/// ([`documented_checksum`]), the log folded in.
pub fn make_steady_version_4(path: &Path) {
    use rusqlite::types::Value;
    let conn = rusqlite::Connection::open(path).unwrap();
    let rows = |sql: &str| -> Vec<Vec<Value>> {
        let mut stmt = conn.prepare(sql).unwrap();
        let n = stmt.column_count();
        stmt.query_map([], |r| (0..n).map(|i| r.get::<_, Value>(i)).collect())
            .unwrap()
            .collect::<Result<_, _>>()
            .unwrap()
    };
    // In generation order, so that a member kept through several blocks takes its birth's.
    let elites = rows(
        "SELECT generation, individual FROM individual WHERE operator = 'elite' \
         AND generation > 0 ORDER BY generation, individual",
    );
    for elite in elites {
        conn.execute(
            "UPDATE individual SET (parents, operator, genome_json) = \
             (SELECT parents, operator, genome_json FROM individual AS before \
              WHERE before.generation = ?1 - 1 AND before.individual = ?2) \
             WHERE generation = ?1 AND individual = ?2",
            rusqlite::params_from_iter(&elite),
        )
        .unwrap();
    }
    conn.execute_batch("ALTER TABLE individual DROP COLUMN parents_generation;")
        .unwrap();
    for row in rows(&format!(
        "SELECT rowid, {INDIVIDUAL_COLUMNS_V4} FROM individual"
    )) {
        let checksum = documented_checksum("individual", &row[1..]);
        conn.execute(
            "UPDATE individual SET checksum = ?1 WHERE rowid = ?2",
            rusqlite::params![checksum, row[0]],
        )
        .unwrap();
    }
    conn.execute_batch("PRAGMA user_version = 4; PRAGMA wal_checkpoint(TRUNCATE);")
        .unwrap();
}

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
