//! Helpers shared by the integration tests.
#![allow(dead_code)]

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

/// Runs `ontogeny ARGS`, asserting that it succeeds.
pub fn ontogeny_ok(args: &[&str]) -> std::process::Output {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_ontogeny"))
        .args(args)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    o
}

/// `ontogeny grow FILE --out OUT EXTRA...`, and the `creature.json` it writes.
pub fn grow_creature_json(
    file: &std::path::Path,
    out: &std::path::Path,
    extra: &[&str],
) -> serde_json::Value {
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

/// Turns the run store at `path` back into schema version 1, as an older ontogeny wrote it:
/// the fine reference columns dropped, the version set to 1, the log folded in.
pub fn make_version_1(path: &std::path::Path) {
    let conn = rusqlite::Connection::open(path).unwrap();
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
