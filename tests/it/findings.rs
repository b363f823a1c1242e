//! What a grammar's reader is told about its mistakes in every verb: a word read as modules
//! that are not known names (a typo) warned about with its place, a caret and the name meant;
//! the same word an error where the grammar declares its modules; a built-in command given
//! more parameters than it takes refused at the call; a problem the builder meets many times
//! said once with a count.

use std::path::{Path, PathBuf};

use crate::util::{lsystem, ontogeny, refused, scratch_dir, stderr, stdout};

/// Writes `text` to `name` in a fresh scratch directory of this module's.
fn grammar(name: &str, text: &str) -> PathBuf {
    let dir = scratch_dir(&format!("findings-{name}"));
    let path = dir.join(format!("{name}.lsys"));
    std::fs::write(&path, text).unwrap();
    path
}

/// A creature whose tail and one leg are misspelt.
const TYPOS: &str = "\
# a creature with two typos
derivation length: 2
axiom: Torso
Torso --> forward(0.5) Legs Tial
Legs --> [ left(1) revolute1 forward(0.3) ] [ right(1) revolute1 foward(0.3) ]
Tail --> forward(0.2)
";

/// The two warnings every verb prints for [`TYPOS`] read from `file`.
fn typo_warnings(file: &Path) -> String {
    let file = file.display();
    format!(
        "\
warning: 'Tial' is read as the modules T i a l (did you mean `Tail`?)
 --> {file}:4:29
  |
4 | Torso --> forward(0.5) Legs Tial
  |                             ^^^^
warning: 'foward' is read as the modules f o w a r d (did you mean `forward`?)
 --> {file}:5:66
  |
5 | Legs --> [ left(1) revolute1 forward(0.3) ] [ right(1) revolute1 foward(0.3) ]
  |                                                                  ^^^^^^
"
    )
}

/// `ontogeny VERB FILE EXTRA...`.
fn run(verb: &str, file: &Path, extra: &[&str]) -> std::process::Output {
    let mut args = vec![verb, file.to_str().unwrap()];
    args.extend_from_slice(extra);
    ontogeny(&args)
}

/// The verbs that read a grammar, each with the flags that keep it short.
const VERBS: [(&str, &[&str]); 4] = [
    ("grow", &[]),
    ("derive", &[]),
    ("eval", &["--task", "walker", "--seconds", "0.1"]),
    ("check", &[]),
];

#[test]
fn a_typo_is_warned_about_with_its_place_and_the_name_meant_by_grow_derive_and_eval() {
    let file = grammar("typos", TYPOS);
    for (verb, extra) in &VERBS[..3] {
        let o = run(verb, &file, extra);
        assert_eq!(o.status.code(), Some(0), "{verb}: {}", stderr(&o));
        assert!(
            stderr(&o).starts_with(&typo_warnings(&file)),
            "{verb}: {}",
            stderr(&o)
        );
    }
    // check lists them with its other findings, on standard output.
    let o = run("check", &file, &[]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let file = file.display();
    assert!(stdout(&o).contains(&format!(
        "findings (3):\n  \
         {file}:4:29: 'Tial' is read as the modules T i a l (did you mean `Tail`?)\n  \
         {file}:5:66: 'foward' is read as the modules f o w a r d (did you mean `forward`?)\n  \
         {file}:6:1: rule never fires: 'Tail' never appears in the axiom or in a successor that can be produced"
    )));
}

#[test]
fn a_word_of_known_names_is_no_typo_and_only_check_notes_one_of_longer_names() {
    // `ab` is the predecessors `a` and `b`; `FF` is two textbook `F`s: the one-letter notation,
    // about which nothing is said. `TailTail` is two `Tail`s: not a typo, a note of check's.
    let file = grammar(
        "known",
        "module Tail\nderivation length: 1\naxiom: a FF TailTail\na --> ab\nb --> a\nTail --> forward(1)\n",
    );
    let o = run("grow", &file, &[]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(!stderr(&o).contains("warning"), "{}", stderr(&o));
    let o = run("check", &file, &[]);
    let out = stdout(&o);
    assert!(
        out.contains(&format!(
            "findings (1):\n  {}:3:13: 'TailTail' is read as the modules Tail Tail\n",
            file.display()
        )),
        "{out}"
    );
}

#[test]
fn a_word_not_made_of_declared_modules_is_an_error_in_every_verb() {
    let text = format!("module Torso, Legs, Tail\n{TYPOS}");
    let file = grammar("declared", &text);
    let shown = file.display();
    for (verb, extra) in VERBS {
        let said = refused(&run(verb, &file, extra), "");
        assert_eq!(
            said,
            format!(
                "\
error: 'Tial' is not a declared module: it would be read as the modules T i a l (did you mean `Tail`?)
 --> {shown}:5:29
  |
5 | Torso --> forward(0.5) Legs Tial
  |                             ^^^^
  = this file declares its modules (line 1): a word must be a declared module, a rule's predecessor or a built-in command, or be written of them ('FF' is 'F F')
"
            ),
            "{verb}"
        );
    }
}

#[test]
fn declared_modules_still_read_ff_as_two_fs_and_a_lone_letter_as_one_module() {
    let lsys = lsystem("module Torso\naxiom: Torso FF X\n");
    let names: Vec<&str> = lsys
        .axiom()
        .symbols()
        .iter()
        .map(|&s| lsys.symbols().name(s))
        .collect();
    assert_eq!(names, ["Torso", "F", "F", "X"]);
}

#[test]
fn a_built_in_command_given_too_many_parameters_is_refused_at_the_call_by_every_verb() {
    let cases = [
        (
            "define s = 1\naxiom: forward(1, 2)\n",
            "error: 'forward' is given 2 parameters, but the built-in command takes 1 (a part's length in metres)\n \
             --> FILE:2:8\n  |\n2 | axiom: forward(1, 2)\n  |        ^^^^^^^^^^^^^\n",
        ),
        (
            "axiom: forward(1) revolute1(5) forward(1)\n",
            "error: 'revolute1' is given 1 parameter, but the built-in command takes none\n \
             --> FILE:1:19\n  |\n1 | axiom: forward(1) revolute1(5) forward(1)\n  |                   ^^^^^^^^^^^^\n",
        ),
        (
            "define s = 1\nderivation length: 1\naxiom: A\nA --> forward(1) output(s, 2)\n",
            "error: 'output' is given 2 parameters, but the built-in command takes 1 (a link weight)\n \
             --> FILE:4:18\n  |\n4 | A --> forward(1) output(s, 2)\n  |                  ^^^^^^^^^^^^\n",
        ),
        (
            "axiom: forward(1) mrevolute1(0, 1) mforward(0)\n",
            "error: 'mrevolute1' is given 2 parameters, but the built-in command takes 1 (its age)\n \
             --> FILE:1:19\n  |\n1 | axiom: forward(1) mrevolute1(0, 1) mforward(0)\n  |                   ^^^^^^^^^^^^^^^^\n",
        ),
    ];
    for (i, (text, message)) in cases.iter().enumerate() {
        let file = grammar(&format!("arity{i}"), text);
        let message = message.replace("FILE", &file.display().to_string());
        for (verb, extra) in VERBS {
            let said = refused(&run(verb, &file, extra), "");
            assert_eq!(said, message, "{verb} {text}");
        }
    }
}

#[test]
fn a_built_in_command_a_rule_rewrites_takes_the_parameters_of_its_rule() {
    // The plastic example's limb: mforward(x, l) grows x up to l; the builder reads x.
    let o = ontogeny(&["check", "examples/plastic.lsys"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    // A maturing twin takes one parameter (its age), and its command's own count is kept.
    let lsys = lsystem("axiom: forward(1) mrevolute1(0) mforward(0) revolute1 forward(1)\n");
    assert_eq!(lsys.axiom().len(), 5);
}

#[test]
fn a_problem_the_builder_meets_many_times_is_said_once_with_its_count() {
    let file = grammar(
        "repeats",
        "derivation length: 5\naxiom: forward(1) A\nA --> ] backward A\n",
    );
    let o = run("grow", &file, &[]);
    assert!(
        stdout(&o).ends_with(
            "valid: yes\n  \
             warning: ']' with nothing to pop: ignored []] at t = 5 (5 times)\n  \
             warning: backward on the root part: ignored [backward] at t = 5 (5 times)\n"
        ),
        "{}",
        stdout(&o)
    );
    let o = run("eval", &file, &["--task", "walker", "--seconds", "0.1"]);
    assert_eq!(
        stderr(&o),
        "warning: ']' with nothing to pop: ignored []] at t = 5 (5 times)\n\
         warning: backward on the root part: ignored [backward] at t = 5 (5 times)\n"
    );
}
