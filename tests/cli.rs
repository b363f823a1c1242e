//! The `ontogeny` command as a user runs it: output formats and exit codes.

use std::process::{Command, Output};

fn ontogeny(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_ontogeny"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Runs `ontogeny` with `input` on its standard input.
fn ontogeny_reading(args: &[&str], input: &[u8]) -> Output {
    use std::io::Write;
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_ontogeny"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    child.stdin.take().unwrap().write_all(input).unwrap();
    child.wait_with_output().unwrap()
}

/// Grows the snake example into a fresh directory and returns it.
fn grown_snake(tag: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("ontogeny-{tag}-{}", std::process::id()));
    let out = ontogeny(&[
        "grow",
        "examples/snake.lsys",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    dir
}

fn temp_file(name: &str, text: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("ontogeny-cli-{}", std::process::id()));
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
            "--seed",
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
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(err.contains(&format!("{}:2:15", path.display())), "{err}");
    assert!(err.contains('^') && err.contains("expected"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(stdout(&out).is_empty());
}

#[test]
fn runaway_growth_exits_2() {
    let out = ontogeny(&[
        "derive",
        "examples/algae.lsys",
        "--steps",
        "40",
        "--max-modules",
        "1000",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("grew past 1000 modules"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn missing_file_exits_2() {
    let out = ontogeny(&["derive", "no-such-file.lsys"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("cannot read no-such-file.lsys"));
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
    let dir = std::env::temp_dir().join(format!("ontogeny-grow-{}", std::process::id()));
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
fn grow_reports_an_invalid_creature() {
    let path = temp_file(
        "crossing.lsys",
        "axiom: forward(1) left(1) forward(1) left(1) forward(1) left(1) forward(2)\n",
    );
    let out = ontogeny(&["grow", path.to_str().unwrap()]);
    assert!(out.status.success());
    let text = stdout(&out);
    assert!(text.contains("valid: no"), "{text}");
    assert!(
        text.contains("error: parts 0 and 3 interpenetrate"),
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
    let dir = std::env::temp_dir().join(format!("ontogeny-eval-{}", std::process::id()));
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
    let out = ontogeny(&["eval", path.to_str().unwrap(), "--task", "walker"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("not a creature"), "{}", stderr(&out));
    // Well-formed JSON, but a joint to a part that does not exist, and a negative size.
    let grown = grown_snake("bad");
    let text = std::fs::read_to_string(grown.join("creature.json")).unwrap();
    let mut value: serde_json::Value = serde_json::from_str(&text).unwrap();
    value["joints"][0]["child"] = serde_json::json!(99);
    let bad = temp_file("bad-joint.json", &value.to_string());
    let out = ontogeny(&["eval", bad.to_str().unwrap(), "--task", "walker"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("joint 0 does not join two of the 9 parts"),
        "{}",
        stderr(&out)
    );
    let mut value: serde_json::Value = serde_json::from_str(&text).unwrap();
    value["parts"][0]["size"] = serde_json::json!([-1.0, 1.0, 1.0]);
    let bad = temp_file("bad-size.json", &value.to_string());
    let out = ontogeny(&["eval", bad.to_str().unwrap(), "--task", "jump"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(!stderr(&out).contains("panicked"));

    let out = ontogeny(&["replay", "/no/such/dir"]);
    assert_eq!(
        out.status.code(),
        Some(2),
        "a missing file is bad input: {}",
        stderr(&out)
    );
    assert!(stderr(&out).contains("cannot read /no/such/dir/recording.json"));
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
    let o = ontogeny(&[
        "eval",
        "examples/snake.lsys",
        "--task",
        "walker",
        "--seconds",
        "-1",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("--seconds must be in (0, 3600], not -1"),
        "{}",
        stderr(&o)
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
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("<stdin>:2:"), "{}", stderr(&o));
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
    let dir = std::env::temp_dir().join(format!("ontogeny-fps-{}", std::process::id()));
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
        // One frame per 1/fps s of the recording, the first at its start.
        assert_eq!(
            delays.len(),
            (span * fps + 1e-9).floor() as usize + 1,
            "fps {fps}"
        );
        // Played back, frame k starts at round(100 k / fps) cs: real time.
        let mut start = 0u64;
        for (k, d) in delays.iter().enumerate() {
            assert_eq!(start, (100.0 * k as f64 / fps).round() as u64, "fps {fps}");
            start += *d as u64;
        }
        assert!(stdout(&o).contains(&format!("{} frames at {fps} frames/s", delays.len())));
    }
    // Beyond what GIF timing can show.
    let o = ontogeny(&["replay", dir.to_str().unwrap(), "--fps", "60"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("--fps must be in (0, 50]"),
        "{}",
        stderr(&o)
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
    let snapshot =
        std::env::temp_dir().join(format!("ontogeny-refused-{}.png", std::process::id()));
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
        stdout(&o).contains("grown to t = 2 in 3 frame(s)"),
        "{}",
        stdout(&o)
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
    let dir = std::env::temp_dir().join(format!("ontogeny-seconds-{}", std::process::id()));
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
            "error: --record {}: a file is there; give a directory",
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
    let dir = std::env::temp_dir().join(format!("ontogeny-steps-{}", std::process::id()));
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
    let o = ontogeny(&[
        "eval",
        "examples/continuous-walker.lsys",
        "--task",
        "walker",
        "--steps",
        "3",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--steps counts discrete steps"));
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
        err.contains("warning: --target is for the aim task only"),
        "{err}"
    );
    assert!(err.contains("warning: --projectile-size is for the catapult and aim tasks only"));
    let o = ontogeny(&[
        "eval",
        "examples/thrower.lsys",
        "--task",
        "catapult",
        "--fitness",
        "distance",
    ]);
    assert!(stderr(&o).contains("warning: --fitness is for the walker task only"));
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
        "--seed",
        "4",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("warning: --steps, --seed grow a creature from a grammar;"),
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
fn bench_fidelity_ranks_settings_and_counts_walks_and_creatures_at_rest() {
    // Four creatures (the shipped walkers), one short walk each: the fast setting beside the
    // default. Every row names its setting and gives rest as counts of the fine reference's.
    let o = ontogeny(&[
        "bench",
        "--evaluations",
        "1",
        "--seconds",
        "0.5",
        "--fidelity",
        "4",
        "--runs",
        "1",
        "--fidelity-also",
        "fast,1x4x1/4x8",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    let floor = out
        .lines()
        .find(|l| l.starts_with("noise floor"))
        .unwrap_or_else(|| panic!("{out}"));
    assert!(floor.contains("of 4 walks"), "{floor}");
    assert!(
        floor.contains("of 4 creatures (most of their walks)"),
        "{floor}"
    );
    // The fidelity table: a named setting's row is named after it, another by its numbers.
    let table = out
        .split_once("Spearman")
        .unwrap_or_else(|| panic!("no fidelity table: {out}"))
        .1;
    for setting in ["default", "fast", "1x4x1/4x8"] {
        let row = table
            .lines()
            .find(|l| l.starts_with(setting))
            .unwrap_or_else(|| panic!("no {setting} row: {out}"));
        let fields: Vec<&str> = row.split_whitespace().collect();
        assert_eq!(fields.len(), 6, "{row}");
        for rest in &fields[3..5] {
            let (rested, of) = rest.split_once('/').unwrap_or_else(|| panic!("{row}"));
            let (rested, of): (usize, usize) = (rested.parse().unwrap(), of.parse().unwrap());
            assert!(rested <= of && of <= 4, "{row}");
        }
    }
    // The speed rows: the default, 2 substeps of 4 iterations and the fast setting, each
    // named by its setting.
    assert!(out.contains("\nmeasured: default "), "{out}");
    assert!(
        out.contains("\n2x4x1/2x4 (2 substeps, 4 iterations) "),
        "{out}"
    );
    assert!(!out.contains("issue"), "{out}");
    assert!(out.contains("\nfast "), "{out}");
}

/// A fresh scratch directory under the target's, named after `tag`.
fn scratch(tag: &str) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("cli-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn evolve_refuses_a_step_setting_out_of_range_at_once_naming_the_key_and_writes_no_run() {
    let dir = scratch("evolve-bad-sim");
    let cases = [
        ("substeps = 0", "[task.sim] substeps must be 1 to 64, not 0"),
        (
            "substeps = 4000000000",
            "[task.sim] substeps must be 1 to 64, not 4000000000",
        ),
        (
            "solver_iterations = 1000000000",
            "[task.sim] solver_iterations must be 1 to 256, not 1000000000",
        ),
        (
            "dt = 1e-9",
            "[task.sim] control_step must be in [0.001, 0.1] seconds, not 0.000000001",
        ),
        (
            "friction = -1",
            "[task.sim] friction must be finite and not negative, not -1",
        ),
    ];
    for (line, message) in cases {
        let config = dir.join("bad.toml");
        std::fs::write(&config, format!("[task.sim]\n{line}\n")).unwrap();
        let out = dir.join("run");
        let o = ontogeny(&[
            "evolve",
            "--config",
            config.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(2), "{line}: {}", stderr(&o));
        assert_eq!(
            stderr(&o),
            format!("error: {}: {message}\n", config.display()),
            "{line}"
        );
        assert!(!out.exists(), "{line}: a run directory was written");
    }
    // A task's settings too, by their table.
    let config = dir.join("bad.toml");
    std::fs::write(&config, "[task.walker.rest]\nlimit = 1e12\n").unwrap();
    let out = dir.join("run");
    let o = ontogeny(&[
        "evolve",
        "--config",
        config.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("[task.walker.rest] limit must be in (0, 3600]"),
        "{}",
        stderr(&o)
    );
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn bench_refuses_a_stepping_flag_out_of_range_instead_of_clamping_it() {
    for (flag, value, message) in [
        ("--substeps", "0", "--substeps must be 1 to 64, not 0"),
        (
            "--rest-solver-iterations",
            "300",
            "--rest-solver-iterations must be 1 to 256, not 300",
        ),
    ] {
        let o = ontogeny(&[
            "bench",
            "--evaluations",
            "1",
            "--seconds",
            "0.1",
            flag,
            value,
        ]);
        assert_eq!(o.status.code(), Some(2), "{flag}: {}", stderr(&o));
        assert_eq!(stderr(&o), format!("error: {message}\n"));
        assert!(stdout(&o).is_empty(), "{flag} measured something");
    }
}

/// The snake's fitness on a one-second walk with `flags`.
fn snake_walk(flags: &[&str]) -> f64 {
    let mut args = vec![
        "eval",
        "examples/snake.lsys",
        "--task",
        "walker",
        "--seconds",
        "1",
        "--json",
    ];
    args.extend(flags);
    let o = ontogeny(&args);
    assert!(o.status.success(), "{flags:?}: {}", stderr(&o));
    let json: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    json["fitness"].as_f64().unwrap()
}

#[test]
fn eval_setting_names_the_stepping_flags_and_an_explicit_flag_overrides_it() {
    let fast = [
        "--substeps",
        "1",
        "--solver-iterations",
        "2",
        "--pgs-iterations",
        "3",
        "--rest-substeps",
        "2",
        "--rest-solver-iterations",
        "4",
    ];
    let named = snake_walk(&["--setting", "fast"]);
    assert_eq!(named, snake_walk(&fast));
    assert_eq!(snake_walk(&["--setting", "default"]), snake_walk(&[]));
    // An explicit flag beside the name replaces that one value of the setting.
    let mut overridden = fast.to_vec();
    overridden[1] = "3";
    let over = snake_walk(&["--setting", "fast", "--substeps", "3"]);
    assert_eq!(over, snake_walk(&overridden));
    assert_ne!(over, named, "--substeps 3 changed nothing");
    // An unknown name is refused, with the names that exist.
    let o = ontogeny(&[
        "eval",
        "examples/snake.lsys",
        "--task",
        "walker",
        "--setting",
        "quick",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("[possible values: fast, default, fine]"),
        "{}",
        stderr(&o)
    );
    // --fast is gone: --setting fast says it.
    let o = ontogeny(&["eval", "examples/snake.lsys", "--task", "walker", "--fast"]);
    assert_eq!(o.status.code(), Some(2));
}

/// The `[task.sim]` table of a run's or a comparison's settings file.
fn sim_table(path: &std::path::Path) -> toml::Table {
    let text = std::fs::read_to_string(path).unwrap();
    let table: toml::Table = toml::from_str(&text).unwrap();
    table["task"]["sim"].as_table().unwrap().clone()
}

/// The five stepping values of a `[task.sim]` table.
fn stepping(sim: &toml::Table) -> [i64; 5] {
    [
        "substeps",
        "solver_iterations",
        "pgs_iterations",
        "rest_substeps",
        "rest_solver_iterations",
    ]
    .map(|key| sim[key].as_integer().unwrap_or_else(|| panic!("no {key}")))
}

#[test]
fn a_config_names_its_step_setting_and_the_run_writes_every_value_back() {
    let dir = scratch("evolve-setting");
    let config = dir.join("fast.toml");
    std::fs::write(&config, "[task.sim]\nsetting = \"fast\"\nsubsteps = 2\n").unwrap();
    let out = dir.join("run");
    let o = ontogeny(&[
        "evolve",
        "--config",
        config.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--pop",
        "4",
        "--gens",
        "1",
        "--seconds",
        "0.2",
        "--no-verify-best",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // The fast setting with its substeps overridden, written out in full, without the name.
    let sim = sim_table(&out.join("config.toml"));
    assert_eq!(stepping(&sim), [2, 2, 3, 2, 4]);
    assert!(!sim.contains_key("setting"), "{sim:?}");
    // --setting on the command line replaces the config's stepping: here in a comparison's
    // settings, which `--plan` writes without running anything.
    let plan = dir.join("plan");
    let o = ontogeny(&[
        "compare",
        "--encodings",
        "direct",
        "--evaluations",
        "100",
        "--pop",
        "10",
        "--config",
        config.to_str().unwrap(),
        "--setting",
        "fine",
        "--out",
        plan.to_str().unwrap(),
        "--plan",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        stepping(&sim_table(&plan.join("evolve.toml"))),
        [4, 8, 1, 4, 8]
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn compare_refuses_a_step_setting_out_of_range_and_writes_nothing() {
    let dir = scratch("compare-bad-sim");
    let config = dir.join("bad.toml");
    std::fs::write(&config, "[task.sim]\nrest_substeps = 0\n").unwrap();
    let out = dir.join("cmp");
    let o = ontogeny(&[
        "compare",
        "--encodings",
        "direct",
        "--evaluations",
        "100",
        "--config",
        config.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(
        stderr(&o),
        format!(
            "error: {}: [task.sim] rest_substeps must be 1 to 64, not 0\n",
            config.display()
        )
    );
    assert!(!out.exists());
    // A comparison's settings edited by hand afterwards are refused when it resumes.
    let o = ontogeny(&[
        "compare",
        "--encodings",
        "direct",
        "--evaluations",
        "100",
        "--pop",
        "10",
        "--out",
        out.to_str().unwrap(),
        "--plan",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let settings = out.join("evolve.toml");
    let text = std::fs::read_to_string(&settings)
        .unwrap()
        .replace("substeps = 4\n", "substeps = 0\n");
    std::fs::write(&settings, text).unwrap();
    let o = ontogeny(&["compare", "--resume", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("[task.sim] substeps must be 1 to 64, not 0"),
        "{}",
        stderr(&o)
    );
    let _ = std::fs::remove_dir_all(dir);
}

/// A scratch directory of this test binary's own, made afresh.
fn scratch_dir(name: &str) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn a_growth_of_a_billion_frames_is_refused_at_once_when_its_frames_are_written() {
    let dir = scratch_dir("billion-frames");
    let file = dir.join("long.lsys");
    std::fs::write(
        &file,
        "axiom: forward(1)\nderivation length: 1000000000\nforward(x) --> forward(x)\n",
    )
    .unwrap();
    let out = dir.join("out");
    let o = ontogeny(&[
        "grow",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let said = stderr(&o);
    assert!(
        said.contains("1000000001 frames") && said.contains("--steps"),
        "{said}"
    );
    assert!(!out.exists(), "nothing is written");
    // --steps brings it within the limit; without --out only the last frame is kept.
    let o = ontogeny(&["grow", file.to_str().unwrap(), "--steps", "20000"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("in 20001 frame(s)"), "{}", stdout(&o));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_creature_file_with_more_parts_than_max_parts_is_refused_by_eval_and_export() {
    let dir = scratch_dir("too-many-parts");
    let file = dir.join("chain.lsys");
    std::fs::write(
        &file,
        "axiom: { forward(0.5) }(100) { forward(0.5) }(100) forward(0.5)\n",
    )
    .unwrap();
    let out = dir.join("grown");
    let o = ontogeny(&[
        "grow",
        file.to_str().unwrap(),
        "--max-parts",
        "201",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let creature = out.join("creature.json");
    let creature = creature.to_str().unwrap();
    for args in [
        &["eval", creature, "--task", "walker"][..],
        &["export", creature],
    ] {
        let o = ontogeny(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("201 parts, more than the 200 allowed (--max-parts)"),
            "{args:?}: {}",
            stderr(&o)
        );
    }
    // --max-parts lifts the limit.
    let o = ontogeny(&["export", creature, "--max-parts", "201"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let _ = std::fs::remove_dir_all(&dir);
}

/// A fresh scratch directory under the test target's own temporary directory.
fn target_scratch(name: &str) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn export_refuses_an_out_that_is_a_directory_and_leaves_it_intact() {
    let dir = target_scratch("export-out-directory");
    let taken = dir.join("model.xml");
    std::fs::create_dir(&taken).unwrap();
    std::fs::write(taken.join("kept"), "kept").unwrap();
    let out = ontogeny(&[
        "export",
        "examples/snake.lsys",
        "--out",
        taken.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains(&format!(
            "{} exists and is not a regular file; refusing to replace it",
            taken.display()
        )),
        "{}",
        stderr(&out)
    );
    assert_eq!(std::fs::read_to_string(taken.join("kept")).unwrap(), "kept");
    // A regular file is replaced whole, and nothing is left beside it.
    let file = dir.join("model-file.xml");
    std::fs::write(&file, "old").unwrap();
    let out = ontogeny(&[
        "export",
        "examples/snake.lsys",
        "--out",
        file.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(std::fs::read_to_string(&file).unwrap().contains("<mujoco"));
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 2);
}

#[cfg(unix)]
#[test]
fn eval_record_refuses_a_socket_before_evaluating_and_leaves_it_in_place() {
    use std::os::unix::fs::FileTypeExt;
    let dir = target_scratch("record-socket");
    let socket = dir.join("behaviour.gif");
    let _listener = std::os::unix::net::UnixListener::bind(&socket).unwrap();
    let out = ontogeny(&[
        "eval",
        "examples/snake.lsys",
        "--task",
        "walker",
        "--seconds",
        "1",
        "--record",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("behaviour.gif exists and is not a regular file"),
        "{}",
        stderr(&out)
    );
    assert!(
        std::fs::symlink_metadata(&socket)
            .unwrap()
            .file_type()
            .is_socket()
    );
    // Refused before anything was evaluated or written.
    assert!(!dir.join("recording.json").exists());
    assert!(stdout(&out).is_empty(), "{}", stdout(&out));
}

#[test]
fn grow_out_refuses_a_picture_that_is_a_directory_and_writes_nothing() {
    let dir = target_scratch("grow-out-directory");
    std::fs::create_dir(dir.join("creature.png")).unwrap();
    let out = ontogeny(&[
        "grow",
        "examples/snake.lsys",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("creature.png exists and is not a regular file"),
        "{}",
        stderr(&out)
    );
    assert!(dir.join("creature.png").is_dir());
    assert!(!dir.join("creature.json").exists());
}

#[test]
fn eval_activation_sets_the_walker_s_first_activation_and_is_checked() {
    let file = "tests/fixtures/late-toppler.lsys";
    let fitness = |extra: &[&str]| -> f64 {
        let mut args = vec!["eval", file, "--task", "walker", "--fitness", "distance"];
        args.extend_from_slice(extra);
        let o = ontogeny(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let out = stdout(&o);
        let line = out.lines().next().unwrap();
        line.split("fitness ")
            .nth(1)
            .unwrap()
            .split(' ')
            .next()
            .unwrap()
            .parse()
            .unwrap()
    };
    // The default (1 s): toppled before the walk; 9 steps: toppled during it.
    assert!(fitness(&[]) < 0.01);
    assert!(fitness(&["--activation", "0.15"]) > 0.5);
    let o = ontogeny(&["eval", file, "--task", "walker", "--activation", "-1"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--activation"), "{}", stderr(&o));
}
