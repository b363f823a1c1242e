//! Turning a grammar's knobs without editing it: `--define NAME=VALUE` on every verb that
//! reads a grammar, and `--grammar-seed` (with the old spelling `--seed`).

use std::path::PathBuf;

use ontogeny::lsystem::{DefineOverride, LSystem, Overrides};

use crate::util::{assert_bad_input, ontogeny, ontogeny_ok, scratch_dir, stderr, stdout};

/// A grammar of a row of `PARTS` parts, each `LENGTH` long, `LENGTH` following `PARTS`.
const ROW: &str = "\
define PARTS = 2
define LENGTH = PARTS * 0.25
axiom: S(PARTS)
derivation length: 4
S(n) : n > 0 --> forward(LENGTH) S(n - 1)
";

/// `text` written to a file of the scratch directory `name`.
fn grammar(name: &str, text: &str) -> PathBuf {
    let path = scratch_dir(&format!("defines-{name}")).join("row.lsys");
    std::fs::write(&path, text).unwrap();
    path
}

fn set(name: &str, value: f64) -> DefineOverride {
    DefineOverride {
        name: name.into(),
        value,
    }
}

#[test]
fn a_define_set_on_the_command_line_changes_the_derived_string_and_its_dependents_follow() {
    let file = grammar("derive", ROW);
    let file = file.to_str().unwrap();
    let plain = ontogeny_ok(&["derive", file, "--last"]);
    assert_eq!(stdout(&plain), "4: forward(0.5) forward(0.5) S(0)\n");
    let set = ontogeny_ok(&["derive", file, "--last", "--define", "PARTS=3"]);
    assert_eq!(
        stdout(&set),
        "4: forward(0.75) forward(0.75) forward(0.75) S(0)\n"
    );
    // The last of two values for one name wins; a dependent set itself no longer follows.
    let both = ontogeny_ok(&[
        "derive", file, "--last", "--define", "PARTS=1", "--define", "PARTS=3", "--define",
        "LENGTH=2",
    ]);
    assert_eq!(stdout(&both), "4: forward(2) forward(2) forward(2) S(0)\n");
}

#[test]
fn check_grow_export_and_eval_grow_the_grammar_with_the_defines_given() {
    let file = grammar("verbs", ROW);
    let file = file.to_str().unwrap();
    let check = ontogeny_ok(&["check", file, "--define", "PARTS=5"]);
    assert!(
        stdout(&check).contains("\naxiom: S(5)\n"),
        "{}",
        stdout(&check)
    );

    let grow = ontogeny_ok(&["grow", file, "--json", "--define", "PARTS=3"]);
    let summary: serde_json::Value = serde_json::from_str(&stdout(&grow)).unwrap();
    assert_eq!(summary["parts"], 3);
    assert_eq!(summary["bounding_box"][1][0], 2.25);

    let export = |extra: &[&str]| {
        let mut args = vec!["export", file];
        args.extend(extra);
        stdout(&ontogeny_ok(&args)).matches("<body").count()
    };
    assert_eq!(export(&[]), 2);
    assert_eq!(export(&["--define", "PARTS=4"]), 4);

    let eval = |extra: &[&str]| {
        let mut args = vec!["eval", file, "--task", "jump", "--seconds", "0.5", "--json"];
        args.extend(extra);
        let out: serde_json::Value = serde_json::from_str(&stdout(&ontogeny_ok(&args))).unwrap();
        (out["status"].clone(), out["message"].clone())
    };
    assert_eq!(eval(&[]), ("ok".into(), serde_json::Value::Null));
    assert_eq!(
        eval(&["--define", "PARTS=0"]),
        ("invalid".into(), "the creature has no parts".into())
    );
}

#[test]
fn an_unknown_define_exits_2_naming_the_closest_and_listing_the_grammars_defines() {
    let file = grammar("unknown", ROW);
    let file = file.to_str().unwrap();
    let message = format!(
        "error: {file}: cannot set PART: the grammar has no define by that name (did you mean \
         PARTS?); its defines are PARTS, LENGTH\n"
    );
    for verb in ["derive", "check", "grow", "export", "view"] {
        let said = assert_bad_input(&[verb, file, "--define", "PART=3"], &message);
        assert_eq!(said, message, "{verb}");
    }
    let said = assert_bad_input(
        &["eval", file, "--task", "jump", "--define", "PART=3"],
        &message,
    );
    assert_eq!(said, message);
    let none = grammar("none", "axiom: A\n");
    let none = none.to_str().unwrap();
    assert_bad_input(
        &["derive", none, "--define", "PARTS=3"],
        &format!(
            "error: {none}: cannot set PARTS: the grammar has no define by that name; it has no \
             defines\n"
        ),
    );
}

#[test]
fn a_define_that_is_not_name_equals_number_exits_2_saying_why() {
    let file = grammar("malformed", ROW);
    let file = file.to_str().unwrap();
    for (given, why) in [
        ("PARTS", "'PARTS' is not NAME=VALUE (e.g. GROWTH=1.5)"),
        ("PARTS=many", "the value of PARTS, 'many', is not a number"),
        ("PARTS=NaN", "the value of PARTS, 'NaN', is not a number"),
        (
            "3D=1",
            "'3D' is not a define's name (a letter or _, then letters, digits or _)",
        ),
    ] {
        assert_bad_input(
            &["derive", file, "--define", given],
            &format!("invalid value '{given}' for '--define <NAME=VALUE>': {why}"),
        );
    }
}

#[test]
fn a_value_the_grammar_cannot_take_is_reported_where_the_grammar_uses_it() {
    let file = grammar("located", "define N = 2\naxiom: A\nderivation length: N\n");
    let file = file.to_str().unwrap();
    let said = assert_bad_input(
        &["derive", file, "--define", "N=2.5"],
        "derivation length must be a whole number from 0 to 10^9, not 2.5",
    );
    assert!(said.contains(&format!("{file}:3:20")), "{said}");
}

#[test]
fn an_overridden_define_leaves_the_random_draws_of_the_defines_after_it_unchanged() {
    let text = "define A = uniform(0, 1)\ndefine B = uniform(0, 1)\naxiom: X(A) Y(B)\n";
    let value = |lsys: &LSystem, name: &str| {
        lsys.constants()
            .find(|(n, _)| *n == name)
            .map(|(_, v)| v)
            .unwrap()
    };
    let plain = LSystem::from_text("r.lsys", text).unwrap();
    let set = LSystem::parse_with(
        ontogeny::lang::Source::new("r.lsys", text),
        &Overrides {
            defines: vec![set("A", 7.0)],
            seed: None,
        },
    )
    .unwrap();
    assert_eq!(value(&set, "A"), 7.0);
    assert_ne!(value(&plain, "A"), 7.0);
    assert_eq!(value(&set, "B"), value(&plain, "B"));
}

#[test]
fn the_grammar_seed_flag_seeds_stochastic_rules_and_the_old_spelling_still_does_with_a_note() {
    let run = |flag: &str, seed: &str| {
        let o = ontogeny(&[
            "derive",
            "examples/stochastic-plant.lsys",
            flag,
            seed,
            "--last",
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        (stdout(&o), stderr(&o))
    };
    let (three, quiet) = run("--grammar-seed", "3");
    assert_eq!(quiet, "");
    assert_eq!(three, run("--grammar-seed", "3").0);
    assert_ne!(three, run("--grammar-seed", "4").0);
    let (old, note) = run("--seed", "3");
    assert_eq!(old, three);
    assert_eq!(
        note,
        "note: --seed 3 is read as --grammar-seed 3, the seed of the grammar's stochastic rules \
         (--seed is the genetic algorithm's seed, in evolve and compare)\n"
    );
    assert_bad_input(
        &[
            "derive",
            "examples/stochastic-plant.lsys",
            "--seed",
            "3",
            "--grammar-seed",
            "3",
        ],
        "cannot be used with",
    );
}

/// A stochastic grammar whose define `R` is drawn from its seed when it is compiled: `R` is
/// the axiom's parameter and the length of the parts of one of the two rules.
const SEEDED: &str = "\
seed: 1
define R = uniform(0.1, 0.9)
axiom: A(R)
derivation length: 4
A(x) --> forward(x) A(x) : 0.5
A(x) --> forward(0.3) revolute1 A(x) : 0.5
";

/// `SEEDED` with its `seed:` line edited to `seed`, as `seeded.lsys` in the scratch
/// directory `name` (both copies have one file name, so that their outputs are comparable
/// once the directory is replaced).
fn seeded_copy(name: &str, seed: u64) -> (String, String) {
    let dir = scratch_dir(&format!("defines-{name}"));
    let path = dir.join("seeded.lsys");
    std::fs::write(&path, SEEDED.replace("seed: 1", &format!("seed: {seed}"))).unwrap();
    (
        path.to_str().unwrap().to_string(),
        dir.to_str().unwrap().to_string(),
    )
}

#[test]
fn the_grammar_seed_flag_is_the_files_seed_line_edited_on_every_grammar_verb() {
    let (file, dir) = seeded_copy("seed-flag", 1);
    let (edited, edited_dir) = seeded_copy("seed-edited", 7);
    // What a verb prints on the file with `--grammar-seed 7` and on the edited copy alone
    // (the copy's directory named as the file's).
    let both = |verb: &[&str]| {
        let mut flagged = verb.to_vec();
        flagged.splice(1..1, [file.as_str(), "--grammar-seed", "7"]);
        let mut plain = verb.to_vec();
        plain.insert(1, edited.as_str());
        (
            stdout(&ontogeny_ok(&flagged)),
            stdout(&ontogeny_ok(&plain)).replace(&edited_dir, &dir),
        )
    };

    // The define drawn at compile time follows the seed: the axiom's parameter is the seed 7
    // copy's, not the file's.
    let r = |lsys: &LSystem| lsys.constants().find(|(n, _)| *n == "R").unwrap().1;
    let of_file = LSystem::from_path(file.as_ref()).unwrap();
    let reseeded = LSystem::from_path_with(
        file.as_ref(),
        &Overrides {
            defines: Vec::new(),
            seed: Some(7),
        },
    )
    .unwrap();
    let of_edited = LSystem::from_path(edited.as_ref()).unwrap();
    assert_eq!(r(&reseeded), r(&of_edited));
    assert_ne!(r(&reseeded), r(&of_file));
    assert_eq!(reseeded.seed(), 7);

    let (flagged, plain) = both(&["derive"]);
    assert_eq!(flagged, plain);
    let axiom = format!("0: A({})\n", ontogeny::number::format_number(r(&of_edited)));
    assert!(flagged.starts_with(&axiom), "{flagged}");
    assert_ne!(flagged, stdout(&ontogeny_ok(&["derive", &file])));

    let (flagged, plain) = both(&["check", "--json"]);
    assert_eq!(flagged, plain);
    assert!(
        flagged.contains(&format!(
            "A({})",
            ontogeny::number::format_number(r(&of_edited))
        )),
        "{flagged}"
    );
    // `check` reads the old spelling too.
    let old = stdout(&ontogeny_ok(&["check", &file, "--seed", "7", "--json"]));
    assert_eq!(old, flagged);

    let (flagged, plain) = both(&["grow", "--json"]);
    assert_eq!(flagged, plain);
    let (flagged, plain) = both(&["export"]);
    assert_eq!(flagged, plain);
    let (flagged, plain) = both(&["eval", "--task", "jump", "--seconds", "0.5", "--json"]);
    assert_eq!(flagged, plain);

    // The viewer's page grows the file as `view FILE --grammar-seed 7` asks.
    let options = ontogeny::lsystem::DeriveOptions {
        seed: Some(7),
        ..Default::default()
    };
    let page = |path: &str, options: &ontogeny::lsystem::DeriveOptions| {
        ontogeny::view::lsys_data_with(path.as_ref(), options, None, 200, &[])
            .unwrap()
            .to_string()
    };
    let shown = page(&file, &options);
    assert_eq!(
        shown,
        page(&edited, &Default::default()).replace(&edited_dir, &dir)
    );
    assert_ne!(shown, page(&file, &Default::default()));
}
