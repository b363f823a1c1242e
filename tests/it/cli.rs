//! The `ontogeny` command as a user runs it: output formats and exit codes.

mod limits;
mod stepping;

use std::path::PathBuf;

use crate::util::{
    assert_bad_input, ontogeny, ontogeny_reading, refused, scratch_dir, stderr, stdout,
};

/// A fresh scratch directory of this module's, named after `tag`.
fn scratch(tag: &str) -> PathBuf {
    scratch_dir(&format!("cli-{tag}"))
}

/// Grows the snake example into a fresh directory and returns it.
fn grown_snake(tag: &str) -> PathBuf {
    let dir = scratch(&format!("snake-{tag}"));
    let out = ontogeny(&[
        "grow",
        "examples/snake.lsys",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    dir
}

/// Writes `text` to the file `name` in a directory the module's tests share.
fn temp_file(name: &str, text: &str) -> PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli-files");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn derive_json_lines_have_exactly_the_documented_fields() {
    let out = ontogeny(&["derive", "examples/parametric.lsys", "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let lines: Vec<serde_json::Value> = stdout(&out)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 5, "axiom and four steps");
    let first = &lines[0];
    assert_eq!(
        first,
        &serde_json::json!({
            "step": 0, "t": 0.0,
            "modules": [{"sym": "B", "params": [2.0]}, {"sym": "A", "params": [4.0, 4.0]}],
            "env": []
        })
    );
    assert_eq!(lines[4]["step"], 4);
    assert_eq!(lines[4]["t"], 4.0);
    assert_eq!(
        lines[4]["modules"],
        serde_json::json!([
            {"sym": "C", "params": []},
            {"sym": "B", "params": [1.0]},
            {"sym": "A", "params": [8.0, 7.0]}
        ])
    );
}

#[test]
fn derive_text_prints_a_line_per_step_and_steps_override_the_file() {
    let out = ontogeny(&["derive", "examples/algae.lsys", "--steps", "3"]);
    assert!(out.status.success());
    assert_eq!(stdout(&out), "0: a\n1: ab\n2: aba\n3: abaab\n");
    let out = ontogeny(&["derive", "examples/algae.lsys", "--steps", "3", "--last"]);
    assert_eq!(stdout(&out), "3: abaab\n");
}

#[test]
fn derive_seed_flag_changes_stochastic_results_reproducibly() {
    let run = |seed: &str| {
        stdout(&ontogeny(&[
            "derive",
            "examples/stochastic-plant.lsys",
            "--grammar-seed",
            seed,
            "--last",
        ]))
    };
    assert_eq!(run("3"), run("3"));
    assert_ne!(run("3"), run("4"));
}

#[test]
fn bad_grammar_exits_2_with_a_located_message_and_no_panic() {
    let path = temp_file("bad.lsys", "axiom: A\nA(x) --> A(x +)\n");
    let out = ontogeny(&["derive", path.to_str().unwrap()]);
    let err = refused(&out, &format!("{}:2:15", path.display()));
    assert!(err.contains('^') && err.contains("expected"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(stdout(&out).is_empty());
}

#[test]
fn runaway_growth_exits_2() {
    assert_bad_input(
        &[
            "derive",
            "examples/algae.lsys",
            "--steps",
            "40",
            "--max-modules",
            "1000",
        ],
        "grew past 1000 modules",
    );
}

#[test]
fn missing_file_exits_2() {
    assert_bad_input(
        &["derive", "no-such-file.lsys"],
        "cannot read no-such-file.lsys",
    );
}

#[test]
fn check_reports_rules_that_never_fire_and_unused_parameters() {
    let path = temp_file(
        "check.lsys",
        "define UNUSED = 3\naxiom: A(1)\nA(x) --> A(1)\nA(x) : x > 2 --> B\nZ --> A(2)\n",
    );
    let out = ontogeny(&["check", path.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(
        text.contains(":4:1: rule never fires: the rule on line 3"),
        "{text}"
    );
    assert!(
        text.contains(":5:1: rule never fires: 'Z' never appears"),
        "{text}"
    );
    assert!(text.contains(":3:3: parameter 'x' is never used"), "{text}");
    assert!(
        text.contains(":1:8: constant 'UNUSED' is never used"),
        "{text}"
    );
    assert!(
        text.contains("rules: 3 productions, 0 interpretation rules"),
        "{text}"
    );

    let out = ontogeny(&["check", path.to_str().unwrap(), "--json"]);
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let kinds: Vec<&str> = report["findings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["kind"].as_str().unwrap())
        .collect();
    assert_eq!(
        kinds,
        [
            "unused-constant",
            "unused-parameter",
            "never-fires",
            "never-fires"
        ]
    );
}

#[test]
fn check_reports_brackets_a_successor_or_the_axiom_leaves_unpaired() {
    let path = temp_file(
        "brackets.lsys",
        "axiom: A ]\nA --> [ B\nB --> C ] ]\nC --> [ D ] [ E ]\n",
    );
    let out = ontogeny(&["check", path.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(text.contains("findings (4):"), "{text}");
    assert!(
        text.contains(":1:10: ']' closes a branch the axiom did not open"),
        "{text}"
    );
    assert!(
        text.contains(":2:7: '[' is not closed in this successor"),
        "{text}"
    );
    assert!(
        text.contains(":3:9: ']' closes a branch this successor did not open"),
        "{text}"
    );
    assert!(text.contains(":3:11: ']' closes a branch"), "{text}");
    let out = ontogeny(&["check", path.to_str().unwrap(), "--json"]);
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(
        report["findings"]
            .as_array()
            .unwrap()
            .iter()
            .all(|f| f["kind"] == "unbalanced-brackets"),
        "{report}"
    );
}

#[test]
fn help_describes_every_verb() {
    let out = ontogeny(&["--help"]);
    let text = stdout(&out);
    assert!(text.contains("derive") && text.contains("check"), "{text}");
    let out = ontogeny(&["derive", "--help"]);
    assert!(stdout(&out).contains("--max-modules"));
}

#[test]
fn derive_in_continuous_time_prints_frames_events_and_environment() {
    let out = ontogeny(&["derive", "examples/dl-figure1.lsys", "--json", "--events"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let lines: Vec<serde_json::Value> = stdout(&out)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let frames: Vec<&serde_json::Value> =
        lines.iter().filter(|l| l.get("step").is_some()).collect();
    let events: Vec<&serde_json::Value> =
        lines.iter().filter(|l| l.get("event").is_some()).collect();
    assert_eq!(frames.len(), 4, "t = 0, 1, 2, 3");
    assert_eq!(frames[2]["t"], 2.0);
    assert_eq!(
        frames[2]["modules"].as_array().unwrap().len(),
        3,
        "B(3)B(4)C(2)"
    );
    assert_eq!(events.len(), 2);
    assert!((events[0]["event"]["t"].as_f64().unwrap() - 2.0).abs() < 1e-9);
    assert_eq!(events[0]["event"]["rule_line"], 11);
    assert_eq!(events[0]["event"]["module"], "A(4,2)");

    let out = ontogeny(&[
        "derive",
        "examples/dl-figure1.lsys",
        "--dt",
        "0.5",
        "--timing",
        "exact",
        "--last",
    ]);
    assert!(out.status.success());
    assert_eq!(stdout(&out), "t=3: B(2)C(2)B(1)B(3)C(2)B(2)C(2)\n");
}

#[test]
fn env_flag_grows_the_plastic_example_two_ways() {
    let grow = |value: &str| {
        let out = ontogeny(&[
            "derive",
            "examples/plastic.lsys",
            "--env",
            value,
            "--last",
            "--json",
        ]);
        assert!(out.status.success(), "{}", stderr(&out));
        let frame: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        frame
    };
    let poor = grow("0=0");
    let rich = grow("0=1");
    assert_eq!(poor["env"], serde_json::json!([0.0]));
    assert_eq!(rich["env"], serde_json::json!([1.0]));
    assert_ne!(poor["modules"], rich["modules"]);
}

#[test]
fn bad_continuous_flags_exit_2() {
    for args in [
        &["derive", "examples/dl-figure1.lsys", "--dt", "0"][..],
        &["derive", "examples/dl-figure1.lsys", "--steps", "3"][..],
        &["derive", "examples/plastic.lsys", "--env", "5=1"][..],
        &["derive", "examples/algae.lsys", "--dt", "0.5"][..],
    ] {
        let out = ontogeny(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
        assert!(stderr(&out).starts_with("error: "), "{}", stderr(&out));
    }
    let out = ontogeny(&["derive", "examples/plastic.lsys", "--env", "x"]);
    assert_eq!(
        out.status.code(),
        Some(2),
        "clap's own errors exit 2 as well"
    );
}

#[test]
fn grow_writes_the_creature_its_frames_and_pictures() {
    let dir = scratch("grow");
    let out = ontogeny(&[
        "grow",
        "examples/quadruped.lsys",
        "--out",
        dir.to_str().unwrap(),
        "--json",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let summary: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(summary["parts"], 11);
    assert_eq!(summary["joints"]["revolute"], 8);
    assert_eq!(summary["joints"]["rigid"], 2);
    assert_eq!(summary["actuators"], 8);
    assert_eq!(summary["sensors"], 0);
    assert_eq!(summary["valid"], true);
    let creature: ontogeny::creature::Creature =
        serde_json::from_str(&std::fs::read_to_string(dir.join("creature.json")).unwrap()).unwrap();
    assert_eq!(creature.parts.len(), 11);
    let frames = std::fs::read_to_string(dir.join("frames.jsonl")).unwrap();
    assert_eq!(frames.lines().count(), 4, "axiom and three steps");
    let png = std::fs::read(dir.join("creature.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    let gif = std::fs::read(dir.join("growth.gif")).unwrap();
    assert_eq!(&gif[..3], b"GIF");
}

#[test]
fn grow_reports_interpenetrating_parts_as_an_error_for_eval_and_evolve() {
    let path = temp_file(
        "crossing.lsys",
        "axiom: forward(1) left(1) forward(1) left(1) forward(1) left(1) forward(2)\n",
    );
    // `grow` makes a picture: the overlap is a warning that says what physics makes of it.
    let out = ontogeny(&["grow", path.to_str().unwrap()]);
    assert!(out.status.success());
    let text = stdout(&out);
    assert!(
        text.contains(
            "warning: parts 0 and 3 interpenetrate (fine for a picture; an error for eval and \
             evolve)"
        ),
        "{text}"
    );
    assert!(
        text.contains("valid: as a picture only (eval and evolve refuse it)\n"),
        "{text}"
    );
    // `eval` needs a valid creature: it is refused there.
    let out = ontogeny(&["eval", path.to_str().unwrap(), "--task", "walker"]);
    let text = stdout(&out);
    assert!(
        text.contains(
            "walker fitness -999999.000000 (self-intersecting)\n  parts 0 and 3 interpenetrate\n"
        ),
        "{text}"
    );
}

#[test]
fn check_counts_names_used_in_odes_and_time_headers() {
    let path = temp_file(
        "ode.lsys",
        "define RATE = 2\ndefine T = 3\ndefine STEP = 0.5\ntime: T\ndt: STEP\naxiom: A(1) B(0)\nA(x) --> solve dx/dt = RATE * x\nA(a) < B(y) : y < 100 --> solve dy/dt = a\n",
    );
    let out = ontogeny(&["check", path.to_str().unwrap()]);
    let text = stdout(&out);
    assert!(text.contains("findings: none"), "{text}");
}

#[test]
fn eval_prints_fitness_terms_and_records() {
    let dir = scratch("eval");
    let out = ontogeny(&[
        "eval",
        "examples/thrower.lsys",
        "--task",
        "catapult",
        "--json",
        "--record",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let e: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(e["status"], "ok");
    assert_eq!(e["task"], "catapult");
    assert!(e["terms"]["D_p"].as_f64().unwrap() > 3.0);
    assert!(dir.join("recording.json").exists() && dir.join("behaviour.gif").exists());
    let recording: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("recording.json")).unwrap())
            .unwrap();
    let frames = recording["frames"].as_array().unwrap();
    assert!(frames.len() > 30);
    assert_eq!(frames[0]["parts"].as_array().unwrap().len(), 2);
    assert!(
        frames[0]["projectile"].is_array(),
        "the projectile is recorded"
    );
    assert!(recording["target"].is_null(), "the catapult has no target");
    std::fs::remove_file(dir.join("behaviour.gif")).unwrap();
    let out = ontogeny(&["replay", dir.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(dir.join("behaviour.gif").exists());

    // A creature.json works as well as an L-system.
    let grown = grown_snake("eval-grown");
    let out = ontogeny(&[
        "eval",
        grown.join("creature.json").to_str().unwrap(),
        "--task",
        "walker",
        "--seconds",
        "2",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(stdout(&out).contains("walker fitness"), "{}", stdout(&out));
    assert!(stdout(&out).contains("D_w = "), "{}", stdout(&out));
}

#[test]
fn eval_rejects_bad_input_with_exit_2() {
    let path = temp_file("not-a-creature.json", "{\"parts\": 3}");
    assert_bad_input(
        &["eval", path.to_str().unwrap(), "--task", "walker"],
        "not a creature",
    );
    // Well-formed JSON, but a joint to a part that does not exist, and a negative size.
    let grown = grown_snake("bad");
    let text = std::fs::read_to_string(grown.join("creature.json")).unwrap();
    let mut value: serde_json::Value = serde_json::from_str(&text).unwrap();
    value["joints"][0]["child"] = serde_json::json!(99);
    let bad = temp_file("bad-joint.json", &value.to_string());
    assert_bad_input(
        &["eval", bad.to_str().unwrap(), "--task", "walker"],
        "joint 0 does not join two of the 9 parts",
    );
    let mut value: serde_json::Value = serde_json::from_str(&text).unwrap();
    value["parts"][0]["size"] = serde_json::json!([-1.0, 1.0, 1.0]);
    let bad = temp_file("bad-size.json", &value.to_string());
    let out = ontogeny(&["eval", bad.to_str().unwrap(), "--task", "jump"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(!stderr(&out).contains("panicked"));

    assert_bad_input(
        &["replay", "/no/such/dir"],
        "cannot read /no/such/dir/recording.json",
    );
}

#[test]
fn negative_option_values_are_values_not_flags() {
    // A target behind the projectile, written as a user would.
    let o = ontogeny(&[
        "eval",
        "examples/thrower.lsys",
        "--task",
        "aim",
        "--target",
        "-3,0,1",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let behind: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let o = ontogeny(&[
        "eval",
        "examples/thrower.lsys",
        "--task",
        "aim",
        "--target",
        "5,0,1",
        "--json",
    ]);
    let ahead: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    // Targets are relative to the projectile's start: -3 and 5 on x are 8 m apart.
    let x = |v: &serde_json::Value| v["terms"]["target_x"].as_f64().unwrap();
    assert!((x(&ahead) - x(&behind) - 8.0).abs() < 1e-5);
    // A negative number reaches the command's own range check (exit 2, its own words),
    // not clap's "unexpected argument".
    assert_bad_input(
        &[
            "eval",
            "examples/snake.lsys",
            "--task",
            "walker",
            "--seconds",
            "-1",
        ],
        "--seconds must be in (0, 3600], not -1",
    );
}

#[test]
fn a_dash_reads_the_grammar_from_standard_input() {
    for verb in ["derive", "check", "grow"] {
        let o = ontogeny_reading(
            &[verb, "-"],
            b"derivation length: 2\naxiom: a\na --> ab\nb --> a\n",
        );
        assert!(o.status.success(), "{verb}: {}", stderr(&o));
    }
    // Errors name the source <stdin>, with line and column.
    let o = ontogeny_reading(&["derive", "-"], b"axiom: a\na --> (\n");
    refused(&o, "<stdin>:2:");
}

/// Each frame's delay (centiseconds) of a GIF.
fn gif_delays(path: &std::path::Path) -> Vec<u16> {
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::Indexed);
    let mut decoder = options
        .read_info(std::fs::File::open(path).unwrap())
        .unwrap();
    let mut delays = Vec::new();
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        delays.push(frame.delay);
    }
    delays
}

#[test]
fn replay_writes_the_frames_per_second_it_says() {
    let dir = scratch("fps");
    let o = ontogeny(&[
        "eval",
        "examples/snake.lsys",
        "--task",
        "walker",
        "--seconds",
        "1",
        "--record",
        dir.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(dir.join("recording.json")).unwrap();
    let recording: serde_json::Value = serde_json::from_str(&text).unwrap();
    let times: Vec<f64> = recording["frames"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["t"].as_f64().unwrap())
        .collect();
    let span = times.last().unwrap() - times[0];
    for fps in [30.0, 7.0] {
        let o = ontogeny(&["replay", dir.to_str().unwrap(), "--fps", &fps.to_string()]);
        assert!(o.status.success(), "{}", stderr(&o));
        let delays = gif_delays(&dir.join("behaviour.gif"));
        // One frame per 1/fps s of the recording, the first at its start, and the last
        // sample at the end: one frame more when the last of those is nearer another sample.
        let regular = (span * fps + 1e-9).floor() as usize + 1;
        let t = times[0] + (regular - 1) as f64 / fps;
        let nearest = (0..times.len())
            .min_by(|&a, &b| {
                (times[a] - t)
                    .abs()
                    .total_cmp(&(times[b] - t).abs())
                    .then(b.cmp(&a))
            })
            .unwrap();
        let extra = usize::from(nearest != times.len() - 1);
        assert_eq!(delays.len(), regular + extra, "fps {fps}");
        // Played back, frame k starts at round(100 k / fps) cs: real time.
        let mut start = 0u64;
        for (k, d) in delays.iter().enumerate() {
            assert_eq!(start, (100.0 * k as f64 / fps).round() as u64, "fps {fps}");
            start += *d as u64;
        }
        // What was written is a message, on standard error.
        let said = stderr(&o);
        assert!(said.contains(&format!("{} frames at {fps} frames/s", delays.len())));
    }
    // Beyond what GIF timing can show.
    assert_bad_input(
        &["replay", dir.to_str().unwrap(), "--fps", "60"],
        "--fps must be in (0, 50]",
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn growing_nothing_says_so() {
    let o = ontogeny_reading(&["grow", "-"], b"axiom: a b c\n");
    let out = stdout(&o);
    assert!(out.starts_with("<stdin>: grown to t = 0"), "{out}");
    assert!(out.contains("mass: 0.0000"), "{out}");
    assert!(
        out.contains("valid: no\n  error: no part: the string builds nothing"),
        "{out}"
    );
    // `backward` moves the turtle and builds nothing: the message names only what builds.
    let o = ontogeny_reading(&["grow", "-"], b"axiom: backward\n");
    let out = stdout(&o);
    assert!(out.contains("parts: 0"), "{out}");
    assert!(
        out.contains("(a part comes from forward or its maturing twin mforward;"),
        "{out}"
    );
    assert!(!out.contains("backward or"), "{out}");
}

#[test]
fn continuous_time_flags_for_a_discrete_file_are_refused_by_every_verb_that_grows_it() {
    let snapshot = scratch("refused").join("refused.png");
    let snapshot = snapshot.to_str().unwrap();
    for verb in ["derive", "grow", "eval", "export", "view"] {
        for flag in [&["--dt", "0.3"][..], &["--timing", "exact"][..]] {
            let mut args = vec![verb, "examples/thrower.lsys"];
            if verb == "eval" {
                args.extend(["--task", "catapult"]);
            }
            if verb == "view" {
                // Refused before any server or browser starts.
                args.extend(["--snapshot", snapshot]);
            }
            args.extend(flag);
            let o = ontogeny(&args);
            assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
            assert!(
                stderr(&o).starts_with(
                    "error: --dt and --timing are for continuous time: give --time T (or 'time:' in examples/thrower.lsys)"
                ),
                "{args:?}: {}",
                stderr(&o)
            );
            assert!(stdout(&o).is_empty(), "{args:?}: {}", stdout(&o));
        }
    }
    // With --time the file develops in continuous time, and --dt applies.
    let o = ontogeny(&["grow", "examples/thrower.lsys", "--time", "2", "--dt", "1"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("grown to t = 2 in 3 frames"),
        "{}",
        stdout(&o)
    );
}

#[test]
fn grow_counts_one_neuron_in_the_singular() {
    let o = ontogeny_reading(&["grow", "-"], b"axiom: forward(1) revolute2 forward(1)\n");
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(out.contains(" in 1 frame\n"), "{out}");
    assert!(
        out.contains("brain: 1 neuron (0 sensors, 0 actuators), 1 link\n"),
        "{out}"
    );
}

#[test]
fn eval_names_standard_input_and_prints_the_builders_warnings() {
    let o = ontogeny_reading(
        &["eval", "-", "--task", "walker", "--seconds", "0.5"],
        b"axiom: [ forward(1)\n",
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stdout(&o).starts_with("<stdin>: walker fitness"),
        "{}",
        stdout(&o)
    );
    assert!(
        stderr(&o).contains(
            "warning: 1 '[' without a matching ']': each branch runs to the end of the string"
        ),
        "{}",
        stderr(&o)
    );
    let o = ontogeny_reading(
        &["eval", "-", "--task", "walker", "--seconds", "0.5"],
        b"axiom: forward(1) ] forward(1)\n",
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("warning: ']' with nothing to pop: ignored []]"),
        "{}",
        stderr(&o)
    );
    // A creature without warnings gets none.
    let o = ontogeny(&["eval", "examples/thrower.lsys", "--task", "catapult"]);
    assert!(!stderr(&o).contains("warning"), "{}", stderr(&o));
}

#[test]
fn range_errors_name_only_the_flag_at_fault_and_its_value() {
    let cases: [(&[&str], &str); 10] = [
        (
            &["--strength", "-1"],
            "--strength must be finite and not negative, not -1",
        ),
        (
            &["--muscle-speed", "-2"],
            "--muscle-speed must be finite and positive, not -2",
        ),
        (&["--substeps", "0"], "--substeps must be 1 to 64, not 0"),
        (
            &["--rest-substeps", "65"],
            "--rest-substeps must be 1 to 64, not 65",
        ),
        (
            &["--solver-iterations", "0"],
            "--solver-iterations must be 1 to 256, not 0",
        ),
        (
            &["--rest-solver-iterations", "257"],
            "--rest-solver-iterations must be 1 to 256, not 257",
        ),
        (
            &["--pgs-iterations", "0"],
            "--pgs-iterations must be 1 to 256, not 0",
        ),
        (
            &["--energy-tolerance", "-1"],
            "--energy-tolerance must be finite and not negative (0 turns the audit off), not -1",
        ),
        (
            &["--projectile-size", "0"],
            "--projectile-size must be finite and positive, not 0",
        ),
        (
            &["--projectile-density", "-5"],
            "--projectile-density must be finite and positive, not -5",
        ),
    ];
    for (flag, message) in cases {
        let mut args = vec!["eval", "examples/thrower.lsys", "--task", "catapult"];
        args.extend(flag);
        let o = ontogeny(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        // The whole of standard error: one line, no blank line after it.
        assert_eq!(stderr(&o), format!("error: {message}\n"), "{args:?}");
    }
    // evolve and compare say the same of --seconds, with no "the command line:" before it.
    let dir = scratch("seconds");
    let out = dir.join("run");
    let out = out.to_str().unwrap();
    for args in [
        &["evolve", "--out", out, "--seconds", "5000"][..],
        &[
            "compare",
            "--encodings",
            "lsystem",
            "--evaluations",
            "100",
            "--out",
            out,
            "--seconds",
            "0",
        ][..],
    ] {
        let o = ontogeny(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        let value = args.last().unwrap();
        assert!(
            stderr(&o).starts_with(&format!(
                "error: --seconds must be in (0, 3600], not {value}"
            )),
            "{args:?}: {}",
            stderr(&o)
        );
        assert!(!std::path::Path::new(out).exists(), "{args:?} made {out}");
    }
    // ... and their --help gives the range, as bench's does.
    for verb in ["evolve", "compare", "bench"] {
        let o = ontogeny(&[verb, "--help"]);
        let help = stdout(&o);
        let seconds = help
            .split("--seconds <SECONDS>")
            .nth(1)
            .unwrap_or_default()
            .split("\n      --")
            .next()
            .unwrap_or_default()
            .to_string();
        assert!(seconds.contains("in (0, 3600]"), "{verb}: {seconds}");
    }
}

#[test]
fn eval_refuses_a_record_path_that_is_a_file_before_evaluating() {
    let file = temp_file("a-file-not-a-dir", "taken\n");
    let o = ontogeny(&[
        "eval",
        "examples/thrower.lsys",
        "--task",
        "catapult",
        "--record",
        file.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).starts_with(&format!(
            "error: {} exists and is not a folder; refusing to write into it",
            file.display()
        )),
        "{}",
        stderr(&o)
    );
    // Refused before the evaluation: nothing was printed, and the file is untouched.
    assert!(stdout(&o).is_empty(), "{}", stdout(&o));
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "taken\n");
}

#[test]
fn grow_and_eval_take_steps_and_note_a_missing_derivation_length() {
    let dir = scratch("steps");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("no-length.lsys");
    std::fs::write(&file, "axiom: A\nA --> forward(1) revolute2 A\n").unwrap();
    let file = file.to_str().unwrap();
    // Without a length: the axiom alone, and a note saying so, as `derive` does.
    for verb in [
        &["grow", file][..],
        &["eval", file, "--task", "walker", "--seconds", "0.5"][..],
    ] {
        let o = ontogeny(verb);
        assert!(
            stderr(&o).contains("has no 'derivation length:' and no --steps was given"),
            "{verb:?}: {}",
            stderr(&o)
        );
    }
    // --steps 3: A → forward revolute2 A, three times: 3 parts joined by 2 joints.
    let o = ontogeny(&["grow", file, "--steps", "3"]);
    assert!(
        stdout(&o).contains("parts: 3   joints: 2 revolute"),
        "{}",
        stdout(&o)
    );
    assert!(!stderr(&o).contains("note:"));
    let o = ontogeny(&[
        "eval",
        file,
        "--task",
        "walker",
        "--seconds",
        "0.5",
        "--steps",
        "3",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let value: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(value["terms"]["N"].as_f64(), Some(3.0));
    // In continuous time, steps mean nothing: an error.
    assert_bad_input(
        &[
            "eval",
            "examples/continuous-walker.lsys",
            "--task",
            "walker",
            "--steps",
            "3",
        ],
        "--steps counts discrete steps",
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn flags_the_task_does_not_use_are_warned_about() {
    let o = ontogeny(&[
        "eval",
        "examples/snake.lsys",
        "--task",
        "walker",
        "--seconds",
        "0.5",
        "--target",
        "1,2,3",
        "--projectile-size",
        "0.3",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains("warning: --target is for the aim task only; ignored"),
        "{err}"
    );
    assert!(err.contains("warning: --projectile-size is for the catapult and aim tasks only"));
    let o = ontogeny(&[
        "eval",
        "examples/thrower.lsys",
        "--task",
        "jump",
        "--seconds",
        "0.2",
        "--activation",
        "0.5",
    ]);
    assert!(
        stderr(&o).contains("warning: --activation is for the walker task only; ignored"),
        "{}",
        stderr(&o)
    );
    let o = ontogeny(&[
        "eval",
        "examples/thrower.lsys",
        "--task",
        "catapult",
        "--fitness",
        "distance",
    ]);
    // A walker formula is no expression of the catapult's terms.
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains(
            "error: --fitness \"distance\" is a formula of the walker task, not of the catapult \
             task, whose fitness may be an expression of its terms: D_p, release_step, \
             release_time, seconds, projectile_x, projectile_y, projectile_z, \
             projectile_mass, joint_gap"
        ),
        "{}",
        stderr(&o)
    );
    // Development flags on a creature that is not grown from a grammar.
    let dir = grown_snake("inapplicable");
    let creature = dir.join("creature.json");
    let o = ontogeny(&[
        "eval",
        creature.to_str().unwrap(),
        "--task",
        "walker",
        "--seconds",
        "0.5",
        "--steps",
        "3",
        "--grammar-seed",
        "4",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("warning: --steps, --grammar-seed grow a creature from a grammar;"),
        "{}",
        stderr(&o)
    );
    let _ = std::fs::remove_dir_all(dir);
    // Flags that apply give no warning.
    let o = ontogeny(&[
        "eval",
        "examples/thrower.lsys",
        "--task",
        "aim",
        "--target",
        "4,0,0",
    ]);
    assert!(!stderr(&o).contains("warning"), "{}", stderr(&o));
}

#[test]
fn a_closed_standard_error_loses_the_message_and_keeps_the_exit_code() {
    // `ontogeny check bad.lsys 2>&1 | head -0`: the reader is gone before the message is
    // written, so writing it fails; the command must still exit 2, not panic (101).
    let dir = crate::util::scratch_dir("closed-stderr");
    let file = dir.join("bad.lsys");
    std::fs::write(&file, "axiom: A(\n").unwrap();
    let mut child = crate::util::ontogeny_command()
        .args(["check", file.to_str().unwrap()])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stderr.take());
    drop(child.stdout.take());
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(2));
}
