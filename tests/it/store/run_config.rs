//! A run's settings as its directory keeps them: every seed the command line accepts
//! round-trips through `config.toml` and the store (TOML's integers are signed, so a seed of
//! 2^63 or more is written as a string of digits), and extending a run changes only the
//! count in `config.toml`, keeping the comments and layout a person gave it.

use std::process::Output;

use super::*;
use crate::evolve::contents;
use crate::util::{ontogeny_command, refused, succeeded, tiny_run};

/// `ontogeny evolve --resume DIR --gens GENS`.
fn extend(dir: &Path, gens: &str) -> Output {
    ontogeny_command()
        .args(["evolve", "--gens", gens, "--resume"])
        .arg(dir)
        .output()
        .unwrap()
}

/// The tiny run of [`tiny_run`] with three generations instead of two.
fn three_generations(out: &Path, extra: &[&str]) {
    let output = crate::util::evolve_walkers("direct", "6")
        .args(["--gens", "3", "--seconds", "1"])
        .args(extra)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    succeeded(&output);
}

/// The `seed = ...` line of the run's `config.toml`.
fn seed_line(dir: &Path) -> String {
    fs::read_to_string(dir.join("config.toml"))
        .unwrap()
        .lines()
        .find(|l| l.starts_with("seed"))
        .unwrap()
        .to_string()
}

#[test]
fn every_seed_from_0_to_2_pow_64_minus_1_resumes_and_extends_as_a_run_started_with_it() {
    let dir = scratch("seeds");
    for (seed, written) in [
        ("0", "seed = 0"),
        ("9223372036854775807", "seed = 9223372036854775807"),
        ("9223372036854775808", "seed = \"9223372036854775808\""),
        ("18446744073709551615", "seed = \"18446744073709551615\""),
    ] {
        let run = dir.join(seed);
        tiny_run("direct", &run, &["--seed", seed]);
        assert_eq!(seed_line(&run), written);
        let store = RunStore::open_read_only(&run.join("run.sqlite")).unwrap();
        assert_eq!(store.run().unwrap().seed.to_string(), seed);
        drop(store);
        succeeded(&extend(&run, "3"));
        assert_eq!(seed_line(&run), written);
        // The extended run is the run started with three generations.
        let whole = dir.join(format!("{seed}-whole"));
        three_generations(&whole, &["--seed", seed]);
        assert_eq!(contents(&run), contents(&whole), "seed {seed}");
    }
    let _ = fs::remove_dir_all(dir);
}

#[test]
fn a_config_file_may_give_a_seed_above_2_pow_63_in_quotes_or_bare() {
    let dir = scratch("seed-config");
    for (name, line) in [
        ("quoted", "seed = \"18446744073709551615\"\n"),
        ("bare", "seed = 18446744073709551615\n"),
    ] {
        let config = dir.join(format!("{name}.toml"));
        fs::write(&config, line).unwrap();
        let run = dir.join(name);
        tiny_run("direct", &run, &["--config", config.to_str().unwrap()]);
        assert_eq!(seed_line(&run), "seed = \"18446744073709551615\"");
        succeeded(&extend(&run, "3"));
    }
    // A seed below 0, or a string that is no number, is refused at its place in the file.
    for (line, shown) in [
        ("seed = -1\n", "not -1"),
        ("seed = \"12x\"\n", "not \"12x\""),
    ] {
        let config = dir.join("bad.toml");
        fs::write(&config, line).unwrap();
        let output = crate::util::evolve_walkers("direct", "6")
            .args(["--gens", "1", "--config", config.to_str().unwrap(), "--out"])
            .arg(dir.join("refused"))
            .output()
            .unwrap();
        let said = refused(
            &output,
            "seed must be a whole number from 0 to 18446744073709551615",
        );
        assert!(said.contains(shown), "{said}");
        assert!(said.contains("bad.toml:1:8"), "{said}");
        assert!(!dir.join("refused").exists());
    }
    let _ = fs::remove_dir_all(dir);
}

#[test]
fn a_run_whose_config_toml_holds_a_bare_seed_above_2_pow_63_resumes() {
    // As an older ontogeny wrote it: a bare integer that TOML's signed integers cannot hold.
    let dir = scratch("seed-bare");
    let run = dir.join("run");
    tiny_run("direct", &run, &["--seed", "9223372036854775808"]);
    let path = run.join("config.toml");
    let text = fs::read_to_string(&path).unwrap();
    fs::write(
        &path,
        text.replace(
            "seed = \"9223372036854775808\"",
            "seed = 9223372036854775808",
        ),
    )
    .unwrap();
    succeeded(&extend(&run, "3"));
    // Extending it put the seed in quotes, the one change besides the count.
    assert_eq!(seed_line(&run), "seed = \"9223372036854775808\"");
    let whole = dir.join("whole");
    three_generations(&whole, &["--seed", "9223372036854775808"]);
    assert_eq!(contents(&run), contents(&whole));
    let _ = fs::remove_dir_all(dir);
}

#[test]
fn extending_a_run_changes_only_the_count_in_config_toml() {
    let dir = scratch("extend-keeps-layout");
    let run = dir.join("run");
    tiny_run("direct", &run, &[]);
    let path = run.join("config.toml");
    let text = fs::read_to_string(&path).unwrap();
    assert!(
        text.contains("\n[ga]\n") && text.contains("\ngenerations = 2\n"),
        "{text}"
    );
    // A person's comments, blank lines, spacing and a comment after the count itself.
    let edited = format!(
        "# my walkers, second try\n\n{}",
        text.replace("\n[ga]\n", "\n\n[ga]   # the schedule\n")
            .replace(
                "\ngenerations = 2\n",
                "\ngenerations    =   2   # more later\n"
            )
            .replace("\npopulation = 6\n", "\n  population = 6\n")
    );
    fs::write(&path, &edited).unwrap();
    succeeded(&extend(&run, "3"));
    assert_eq!(
        fs::read_to_string(&path).unwrap(),
        edited.replace(
            "generations    =   2   # more later",
            "generations    =   3   # more later"
        )
    );
    // The store's copy of the settings records the new count too.
    let store = RunStore::open_read_only(&run.join("run.sqlite")).unwrap();
    assert_eq!(store.run().unwrap().planned_generations(), Some(3));
    assert_eq!(store.last_generation().unwrap(), Some(2));
    let _ = fs::remove_dir_all(dir);
}
