//! Every kind of bad input gets one clear, located diagnostic, never a panic.

use ontogeny::lang::DiagnosticKind;
use ontogeny::lsystem::{DeriveOptions, LSystem};

/// Compiles `text` and expects an error; returns it rendered, after checking its kind and
/// that it points at `line`.
fn compile_error(text: &str, kind: DiagnosticKind, line: usize) -> String {
    let err = LSystem::from_text("bad.lsys", text).expect_err("should not compile");
    assert_eq!(err.kind, kind, "{err}");
    let loc = err.location.as_ref().expect("a location");
    assert_eq!(loc.line, line, "{err}");
    let shown = err.to_string();
    assert!(
        shown.contains(&format!("bad.lsys:{line}:{}", loc.column)),
        "{shown}"
    );
    assert!(shown.contains('^'), "a caret: {shown}");
    shown
}

/// Derives `steps` steps and expects a run-time error.
fn derive_error(text: &str, steps: usize, max_modules: usize) -> String {
    let lsys = LSystem::from_text("bad.lsys", text).unwrap_or_else(|e| panic!("{e}"));
    let mut d = lsys
        .derivation(&DeriveOptions {
            max_modules,
            ..DeriveOptions::default()
        })
        .unwrap_or_else(|e| panic!("{e}"));
    for _ in 0..steps {
        if let Err(e) = d.step() {
            assert_eq!(e.kind, DiagnosticKind::Runtime);
            assert!(e.location.is_some(), "{e}");
            return e.to_string();
        }
    }
    panic!("derivation should have failed");
}

#[test]
fn syntax_error_names_what_was_expected() {
    let shown = compile_error("axiom: A\nA --> B(1,\n", DiagnosticKind::Syntax, 2);
    assert!(shown.contains("expected an expression"), "{shown}");
    let shown = compile_error("axiom: A\nA B --> C\n", DiagnosticKind::Syntax, 2);
    assert!(shown.contains("expected"), "{shown}");
    let shown = compile_error("axiom: A\nA -> B\n", DiagnosticKind::Syntax, 2);
    assert!(shown.contains("'-->'"), "{shown}");
}

#[test]
fn syntax_error_column_is_exact() {
    let err = LSystem::from_text("bad.lsys", "axiom: A\nA(x) --> A(x +)\n").unwrap_err();
    let loc = err.location.unwrap();
    assert_eq!((loc.line, loc.column), (2, 15));
}

#[test]
fn unknown_constant() {
    let shown = compile_error(
        "define GROWTH = 2\naxiom: A(1)\nA(x) --> A(x * GROWHT)\n",
        DiagnosticKind::Semantic,
        3,
    );
    assert!(shown.contains("unknown name 'GROWHT'"), "{shown}");
    assert!(shown.contains("bad.lsys:3:16"), "{shown}");
}

#[test]
fn wrong_number_of_parameters_against_a_predecessor() {
    let shown = compile_error(
        "axiom: A(1)\nA(x, y) --> A(x, y)\n",
        DiagnosticKind::Semantic,
        1,
    );
    assert!(shown.contains("takes 2"), "{shown}");
    compile_error(
        "axiom: A(1, 2)\nA(x, y) --> A(x)\n",
        DiagnosticKind::Semantic,
        2,
    );
    compile_error(
        "axiom: A(1)\nA(x) --> A(x)\nA(x, y) --> A(x)\n",
        DiagnosticKind::Semantic,
        3,
    );
    compile_error(
        "axiom: A(1)\nA(x) --> A(x)\nB < A(x) > A --> A(x)\n",
        DiagnosticKind::Semantic,
        3,
    );
}

#[test]
fn probability_outside_zero_to_one() {
    let shown = compile_error("axiom: F\nF --> F : 1.5\n", DiagnosticKind::Semantic, 2);
    assert!(shown.contains("not in (0, 1]"), "{shown}");
    compile_error("axiom: F\nF --> F : 0\n", DiagnosticKind::Semantic, 2);
    compile_error("axiom: F\nF --> F : -0.5\n", DiagnosticKind::Semantic, 2);
    compile_error(
        "axiom: F(1)\nF(x) --> F(x) : x\n",
        DiagnosticKind::Semantic,
        2,
    );
}

#[test]
fn division_by_zero_during_derivation() {
    // A(3) -> A(2)B(0.5) -> A(1)B(1) -> A(0)B(1/0): the third step fails.
    let shown = derive_error("axiom: A(3)\nA(x) --> A(x - 1) B(1 / (x - 1))\n", 5, 1000);
    assert!(shown.contains("division by zero"), "{shown}");
    assert!(shown.contains("step 3"), "{shown}");
    assert!(shown.contains("bad.lsys:2:"), "{shown}");
}

#[test]
fn nan_during_derivation() {
    let shown = derive_error("axiom: A(-1)\nA(x) --> A(sqrt(x))\n", 1, 1000);
    assert!(shown.contains("NaN"), "{shown}");
    let shown = derive_error("axiom: A(2)\nA(x) --> A(x ^ 1000)\n", 5, 1000);
    assert!(shown.contains("infinity"), "{shown}");
}

#[test]
fn runaway_growth_past_max_modules() {
    let shown = derive_error("axiom: a\na --> ab\nb --> a\n", 30, 100);
    assert!(shown.contains("grew past 100 modules"), "{shown}");
    assert!(shown.contains("--max-modules"), "{shown}");
}

#[test]
fn constant_division_by_zero_is_found_before_deriving() {
    compile_error("axiom: A\nA --> B(1 / 0)\n", DiagnosticKind::Semantic, 2);
    compile_error(
        "define Z = 0\ndefine W = 1 % Z\naxiom: A\n",
        DiagnosticKind::Semantic,
        2,
    );
}

#[test]
fn unknown_function_and_wrong_argument_count() {
    let shown = compile_error("axiom: A(sinh(1))\n", DiagnosticKind::Semantic, 1);
    assert!(shown.contains("unknown function 'sinh'"), "{shown}");
    let shown = compile_error("axiom: A(atan2(1))\n", DiagnosticKind::Semantic, 1);
    assert!(shown.contains("takes 2 arguments"), "{shown}");
}

#[test]
fn other_semantic_errors() {
    compile_error(
        "axiom: A(1)\nA(x) < A(x) --> A\n",
        DiagnosticKind::Semantic,
        2,
    );
    compile_error("axiom: A\nA [ < B --> C\n", DiagnosticKind::Semantic, 2);
    compile_error(
        "define X = 1\ndefine X = 2\naxiom: A\n",
        DiagnosticKind::Semantic,
        2,
    );
    compile_error("axiom: A\naxiom: B\n", DiagnosticKind::Semantic, 2);
    compile_error("axiom: A\nseed: 1\nseed: 2\n", DiagnosticKind::Semantic, 3);
    compile_error(
        "axiom: A\nderivation length: 2.5\n",
        DiagnosticKind::Semantic,
        2,
    );
    compile_error(
        "axiom: A\nderivation length: -1\n",
        DiagnosticKind::Semantic,
        2,
    );
    compile_error("axiom: [(1)\n", DiagnosticKind::Semantic, 1);
    compile_error("axiom: A\nignore: [\n", DiagnosticKind::Semantic, 2);
    compile_error(
        "axiom: A\nseed: 99999999999999999999999\n",
        DiagnosticKind::Semantic,
        2,
    );
}

#[test]
fn missing_axiom_is_reported_with_the_file_name() {
    let err = LSystem::from_text("bad.lsys", "A --> B\n").unwrap_err();
    assert!(
        err.to_string().contains("bad.lsys: no 'axiom:' line"),
        "{err}"
    );
}

#[test]
fn deep_nesting_is_an_error_not_a_stack_overflow() {
    let deep = format!("axiom: A({}1{})\n", "(".repeat(500), ")".repeat(500));
    assert!(LSystem::from_text("bad.lsys", &deep).is_err());
    let long = format!("axiom: A({})\n", vec!["1"; 5000].join("^"));
    assert!(LSystem::from_text("bad.lsys", &long).is_err());
    let negs = format!("axiom: A({}1)\n", "-".repeat(5000));
    assert!(LSystem::from_text("bad.lsys", &negs).is_err());
}

#[test]
fn missing_file_is_a_clear_error() {
    let err = LSystem::from_path(std::path::Path::new("no/such/file.lsys")).unwrap_err();
    assert!(
        err.to_string().contains("cannot read no/such/file.lsys"),
        "{err}"
    );
}

#[test]
fn constant_query_indices_are_checked_before_deriving_and_runtime_errors_name_the_rule() {
    let text = "environment: 0 0\naxiom: S\nderivation length: 2\nS --> ?E(0, 1+4, 0.8) S\n";
    let shown = compile_error(text, DiagnosticKind::Semantic, 4);
    assert!(shown.contains("outside the environment"), "{shown}");
    let text = "define IDX = 7\nenvironment: 0\naxiom: ?E(0, IDX, 1)\n";
    compile_error(text, DiagnosticKind::Semantic, 3);
    // Made by a constant rule, found while deriving: the message points at that rule.
    let text = "environment: 0 0\naxiom: S(5)\nS(i) --> ?E(0, i, 0.8)\n";
    let shown = derive_error(text, 2, 1000);
    assert!(shown.contains("bad.lsys:3:1"), "{shown}");
}

#[test]
fn and_or_with_a_constant_side_short_circuit_when_compiled() {
    let text = "define K = 0\naxiom: A(2)\nA(x) : K != 0 && x > 1/K --> B\n";
    let lsys = LSystem::from_text("ok.lsys", text).unwrap_or_else(|e| panic!("{e}"));
    let mut d = lsys.derivation(&DeriveOptions::default()).unwrap();
    assert_eq!(lsys.display(d.step().unwrap()), "A(2)");
    assert!(LSystem::from_text("ok.lsys", "axiom: A(1 || 1/0)\n").is_ok());
    // The dead side's names must still exist.
    compile_error("axiom: A(0 && NOPE)\n", DiagnosticKind::Semantic, 1);
}

#[test]
fn lone_carriage_returns_end_lines_in_error_positions() {
    let err = LSystem::from_text("cr.lsys", "axiom: A\rA --> B(1/0)\rderivation length: 1\r")
        .unwrap_err();
    let loc = err.location.unwrap();
    assert_eq!((loc.line, loc.column), (2, 9));
    assert_eq!(loc.line_text, "A --> B(1/0)");
}

#[test]
fn syntax_errors_in_plain_words() {
    // (grammar, the line the error is on, what the message says)
    let cases = [
        // The ways to start a value (a sign, a name, a number, ...) are "a value", once.
        ("axiom: a\na --> b(1 +)\n", 2, "expected a value, found ')'"),
        // An arrow where a value should be is named whole.
        (
            "axiom: A(1)\nA(x) : x > --> B\n",
            2,
            "expected a value, found '-->'",
        ),
        // The binary operators are "an operator"; in an argument list ',' and ')' are named.
        (
            "axiom: A\nA --> B(1 2)\n",
            2,
            "expected an operator, ',', or ')', found '2'",
        ),
        (
            "axiom: A\nA --> B(1, f(2 33))\n",
            2,
            "expected an operator, ',', or ')', found '33'",
        ),
        // A bracketing parenthesis closes with ')' alone.
        (
            "axiom: A\nA : (1 2) --> B\n",
            2,
            "expected an operator or ')', found '2'",
        ),
        // Outside parentheses, the line may end instead.
        (
            "axiom: A\nA --> B : 0.5 : 2\n",
            2,
            "expected end of line or an operator, found ':'",
        ),
        // A header line with an error is reported as that header, not as a rule.
        (
            "seed: x\naxiom: A\n",
            1,
            "expected a whole number, found 'x'\n --> bad.lsys:1:7",
        ),
        (
            "axiom: A\ntiming: fast\n",
            2,
            "expected 'exact' or 'iterative', found 'fast'",
        ),
        // A header without its colon.
        ("axiom a\n", 1, "a header ends with a colon: 'axiom: ...'"),
        (
            "derivation length 3\naxiom: a\n",
            1,
            "'derivation length: ...'",
        ),
        // A header in capitals reads as a module: the note says headers are lower case.
        (
            "Axiom: A\nA --> A B\n",
            1,
            "headers are written in lower case: 'axiom:'",
        ),
        (
            "axiom: a\nDerivation Length: 3\n",
            2,
            "'derivation length:'",
        ),
        // A space between a module's name and its parameters.
        (
            "axiom: a\na --> forward (1)\n",
            2,
            "parameters follow a module's name with no space between: 'forward(...)'",
        ),
    ];
    for (text, line, expected) in cases {
        let shown = compile_error(text, DiagnosticKind::Syntax, line);
        assert!(shown.contains(expected), "{text:?}: {shown}");
    }
    // An argument list names its own closers, not every operator.
    let shown = compile_error("axiom: A\nA --> B(1 2)\n", DiagnosticKind::Syntax, 2);
    assert!(!shown.contains("'||'"), "{shown}");
    // ... also when the module ends an axiom line (the line is read as the header it is).
    for (text, word, column) in [
        ("axiom: forward (1)\n", "forward", 16),
        ("axiom: A (2)\nA --> B\n", "A", 10),
        ("axiom: A (2)", "A", 10),
    ] {
        let shown = compile_error(text, DiagnosticKind::Syntax, 1);
        assert!(
            shown.contains(&format!(
                "parameters follow a module's name with no space between: '{word}(...)'"
            )),
            "{shown}"
        );
        assert!(shown.contains(&format!("bad.lsys:1:{column}")), "{shown}");
        assert!(!shown.contains("'-->'"), "{shown}");
    }
    // A module whose name merely starts like a header gets no header hint.
    let shown = compile_error("axiom: a\ntimer --> (\n", DiagnosticKind::Syntax, 2);
    assert!(!shown.contains("header"), "{shown}");
}

/// Runs `ontogeny ARGS` in a scratch directory holding `files` (name, text); expects exit code
/// 2 and `message` on standard error, which it returns.
fn refused(args: &[&str], files: &[(&str, &str)], message: &str) -> String {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!(
        "errors-refused-{}",
        args.join("-").replace(['/', ' ', '='], "_")
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_ontogeny"))
        .args(args)
        .current_dir(&dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains(message), "{stderr}");
    let _ = std::fs::remove_dir_all(&dir);
    stderr.into_owned()
}

/// A walker config whose `[task.sim]` table holds `sim` (one line).
fn config_with_sim(sim: &str) -> String {
    format!(
        "encoding = \"lsystem\"\n[ga]\npopulation = 4\ngenerations = 1\n[task]\ntask = \"walker\"\n[task.sim]\n{sim}\n"
    )
}

const NO_SUBSTEPS: &str = "substeps must be 1 to 64, not 0";

#[test]
fn zero_substeps_are_refused_by_the_world_itself() {
    let creature = ontogeny::develop::creature_from_commands("forward(1)").unwrap();
    let options = ontogeny::sim::SimOptions {
        substeps: 0,
        ..Default::default()
    };
    let e = ontogeny::sim::World::new(&creature, &options)
        .err()
        .expect("refused");
    assert_eq!(e.to_string(), NO_SUBSTEPS);
}

#[test]
fn an_evaluation_with_zero_substeps_is_invalid_and_says_why() {
    let creature = ontogeny::develop::creature_from_commands("forward(1)").unwrap();
    let mut spec = ontogeny::task::TaskSpec::new(ontogeny::task::TaskKind::Walker);
    spec.sim.rest_substeps = 0;
    let e = spec.evaluate(&creature, false);
    assert_eq!(e.status, ontogeny::task::Status::Invalid);
    assert!(
        e.message
            .unwrap()
            .contains("rest_substeps must be 1 to 64, not 0")
    );
}

#[test]
fn zero_substeps_in_a_config_file_are_refused() {
    refused(
        &["evolve", "--config", "z.toml", "--out", "run"],
        &[("z.toml", &config_with_sim("substeps = 0"))],
        &format!("[task.sim] {NO_SUBSTEPS}\n --> z.toml:8:12"),
    );
}

#[test]
fn zero_substeps_on_eval_are_refused() {
    refused(
        &["eval", "a.lsys", "--task", "walker", "--substeps", "0"],
        &[("a.lsys", "axiom: forward(1)\n")],
        &format!("--{NO_SUBSTEPS}"),
    );
}

#[test]
fn zero_substeps_on_bench_are_refused() {
    refused(
        &[
            "bench",
            "--evaluations",
            "1",
            "--seconds",
            "1",
            "--substeps",
            "0",
        ],
        &[],
        &format!("--{NO_SUBSTEPS}"),
    );
}

#[test]
fn a_control_step_out_of_range_is_named_as_the_config_file_names_it() {
    refused(
        &["evolve", "--config", "z.toml", "--out", "run"],
        &[("z.toml", &config_with_sim("control_step = 0.5"))],
        "[task.sim] control_step must be in [0.001, 0.1] seconds, not 0.5\n --> z.toml:8:16",
    );
    // The name older files use is read as the same key, and pointed at where the file sets it.
    let said = refused(
        &["evolve", "--config", "z.toml", "--out", "run"],
        &[("z.toml", &config_with_sim("dt = 0.5"))],
        "[task.sim] control_step must be in [0.001, 0.1] seconds, not 0.5\n --> z.toml:8:6",
    );
    assert!(
        said.contains("`dt` is the older name of `control_step`"),
        "{said}"
    );
}

#[test]
fn a_config_value_of_the_wrong_type_is_said_in_words_at_its_key() {
    refused(
        &["evolve", "--config", "words.toml", "--out", "run"],
        &[(
            "words.toml",
            "encoding = \"lsystem\"\n[ga]\npopulation = \"twenty\"\n",
        )],
        "error: [ga] population must be a whole number, not \"twenty\"\n --> words.toml:3:14",
    );
    refused(
        &["evolve", "--config", "words-bool.toml", "--out", "run"],
        &[("words-bool.toml", "verify_best = \"yes\"\n")],
        "verify_best must be true or false, not \"yes\"",
    );
    refused(
        &[
            "compare",
            "--config",
            "words-real.toml",
            "--encodings",
            "direct",
            "--evaluations",
            "8",
            "--out",
            "c",
        ],
        &[("words-real.toml", "[task.walker]\nseconds = \"long\"\n")],
        "[task.walker] seconds must be a number, not \"long\"\n --> words-real.toml:2:11",
    );
}

#[test]
fn a_misspelt_name_in_a_config_lists_the_names_and_suggests_the_closest() {
    refused(
        &["evolve", "--config", "enc.toml", "--out", "run"],
        &[("enc.toml", "encoding = \"lsytem\"\n")],
        "encoding must be one of lsystem, lsystem-continuous, direct, graph, not \"lsytem\" \
         (did you mean lsystem?)\n --> enc.toml:1:12",
    );
    refused(
        &["evolve", "--config", "task.toml", "--out", "run"],
        &[("task.toml", "[task]\ntask = \"walkr\"\n")],
        "[task] task must be one of walker, jump, catapult, aim, stand, swim, not \"walkr\" \
         (did you mean walker?)\n --> task.toml:2:8",
    );
    refused(
        &["evolve", "--config", "actuator.toml", "--out", "run"],
        &[("actuator.toml", "[task.sim]\nactuator = \"muscl\"\n")],
        "(did you mean muscle?)",
    );
    refused(
        &["evolve", "--config", "key.toml", "--out", "run"],
        &[("key.toml", "[ga]\npopulaton = 10\n")],
        "unknown key populaton in [ga] (did you mean population?)\n --> key.toml:2:1",
    );
}

#[test]
fn a_value_out_of_range_names_the_flag_that_gave_it() {
    let dir = crate::util::scratch_dir("errors-flag-out-of-range");
    let run = dir.join("run");
    let run = run.to_str().unwrap();
    crate::util::assert_bad_input(
        &["evolve", "--pop", "1", "--out", run],
        "error: --pop must be 2 to 100000, not 1",
    );
    crate::util::assert_bad_input(
        &["evolve", "--gens", "0", "--out", run],
        "error: --gens must be 1 to 100000, not 0",
    );
    crate::util::assert_bad_input(
        &[
            "compare",
            "--pop",
            "1",
            "--encodings",
            "direct",
            "--evaluations",
            "8",
            "--out",
            run,
        ],
        "error: --pop must be 2 to 100000, not 1",
    );
    assert!(!std::path::Path::new(run).exists());
}

#[test]
fn a_value_out_of_range_in_a_config_is_pointed_at_in_the_file() {
    refused(
        &["evolve", "--config", "range.toml", "--out", "run"],
        &[("range.toml", "seed = 3\n[ga]\npopulation = 1\n")],
        "error: [ga] population must be 2 to 100000, not 1\n --> range.toml:3:14",
    );
}

#[test]
fn a_file_that_is_not_a_grammar_is_told_what_it_is_and_which_command_takes_it() {
    let frame = r#"{"step":0,"t":0.0,"creature":{"parts":[],"joints":[]}}"#;
    let files = [
        (
            "quadruped.xml",
            "<?xml version=\"1.0\"?>\n<mujoco model=\"q\">\n</mujoco>\n",
        ),
        ("frames.jsonl", &format!("{frame}\n{frame}\n")),
        ("creature.json", r#"{"parts": [], "joints": []}"#),
        ("recording.json", r#"{"creature": {}, "frames": []}"#),
        ("run.sqlite", "SQLite format 3\0"),
    ];
    refused(
        &["grow", "quadruped.xml"],
        &files,
        "error: quadruped.xml is a MuJoCo model (MJCF), not a grammar: Ontogeny writes MJCF \
         (`ontogeny export`) but does not read it",
    );
    refused(
        &["eval", "frames.jsonl", "--task", "walker"],
        &files,
        "error: frames.jsonl is the frames of a growth (written by `ontogeny grow --out DIR`), \
         not a grammar: show the growth with `ontogeny view .`",
    );
    refused(
        &["derive", "creature.json"],
        &files,
        "creature.json is a creature, not a grammar: `ontogeny eval creature.json --task walker`",
    );
    refused(
        &["check", "run.sqlite"],
        &files,
        "run.sqlite is a run's store (SQLite, written by `ontogeny evolve`), not a grammar",
    );
    refused(
        &["eval", "recording.json", "--task", "walker"],
        &files,
        "recording.json is a recording (written by `ontogeny eval --record DIR`), not a \
         creature: play it with `ontogeny view .`",
    );
    refused(
        &["evolve", "--init", "frames.jsonl", "--out", "run"],
        &files,
        "frames.jsonl is the frames of a growth",
    );
    refused(
        &["view", "frames.jsonl"],
        &files,
        "frames.jsonl is the frames of a growth (written by `ontogeny grow --out DIR`), not an \
         .lsys file: show the growth with `ontogeny view .`",
    );
}

#[test]
fn a_grammar_given_as_a_config_points_to_init() {
    let grammar = [("walker.lsys", "axiom: A\nA --> forward(1) A\n")];
    let advice = "walker.lsys is a grammar, not a configuration: to start a run from its \
                  mutants: `ontogeny evolve --init walker.lsys --out DIR`";
    refused(
        &["evolve", "--config", "walker.lsys", "--out", "run"],
        &grammar,
        advice,
    );
    refused(
        &[
            "compare",
            "--config",
            "walker.lsys",
            "--encodings",
            "direct",
            "--evaluations",
            "8",
            "--out",
            "c",
        ],
        &grammar,
        advice,
    );
}
