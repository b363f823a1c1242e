//! The evaluator's fidelity diagnostics, on a real exploit: `tests/fixtures/exploit-walker.json`
//! is the best graph walker of a 3,940-evaluation comparison replicate (a 10 kg rod on a
//! 146 kg cube, one spherical joint), evolved at the fast setting that was the default then.
//! With that setting the solver lets its joint come apart by about 20 cm and it walks about
//! 200 m; with today's default and with the fine reference setting the joint holds to a few
//! millimetres and it walks about a metre.

/// The fine reference setting as `eval` flags (`SimOptions::fine_reference`).
const FINE: [&str; 10] = [
    "--substeps",
    "4",
    "--solver-iterations",
    "8",
    "--pgs-iterations",
    "1",
    "--rest-substeps",
    "4",
    "--rest-solver-iterations",
    "8",
];

/// `ontogeny eval` of the fixture on the walker task, scored by distance, with `extra` flags.
fn eval_fixture(extra: &[&str]) -> std::process::Output {
    crate::util::ontogeny_command()
        .args([
            "eval",
            "tests/fixtures/exploit-walker.json",
            "--task",
            "walker",
        ])
        .args(["--fitness", "distance", "--json"])
        .args(extra)
        .output()
        .expect("run ontogeny")
}

/// The fixture's evaluation with `extra` flags: (fitness, joint gap, stderr).
fn walk(extra: &[&str]) -> (f64, f64, String) {
    let out = eval_fixture(extra);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert_eq!(json["status"], "ok");
    (
        json["fitness"].as_f64().unwrap(),
        json["terms"]["joint_gap"]
            .as_f64()
            .expect("a joint_gap term"),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn an_exploit_of_the_fast_setting_shows_in_its_joint_gap_and_fails_at_the_default() {
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
    let (distance, gap, stderr) = walk(&["--setting", "fast"]);
    assert!(
        distance > 50.0,
        "the exploit walks {distance} m at the fast setting"
    );
    // `--setting fast` is those five flags.
    assert_eq!(walk(&fast).0, distance);
    assert!(gap > ontogeny::sim::JOINT_GAP_WARNING, "gap {gap} m");
    assert!(
        stderr.contains("warning: the solver let a joint come") && stderr.contains("cm apart"),
        "{stderr}"
    );

    for (setting, flags) in [("the default", &[][..]), ("the fine reference", &FINE[..])] {
        let (distance, gap, stderr) = walk(flags);
        assert!(distance < 5.0, "{setting} walks it {distance} m");
        assert!(gap < 0.01, "gap {gap} m at {setting}");
        assert!(!stderr.contains("warning: the solver"), "{stderr}");
    }
}

#[test]
fn a_resting_creature_keeps_its_joints_together() {
    // The snake at the fine reference: its joints hold to well under a centimetre.
    let out = crate::util::ontogeny_command()
        .args([
            "eval",
            "examples/snake.lsys",
            "--task",
            "walker",
            "--seconds",
            "2",
            "--json",
        ])
        .args(FINE)
        .output()
        .expect("run ontogeny");
    assert!(out.status.success());
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let gap = json["terms"]["joint_gap"].as_f64().unwrap();
    assert!((0.0..0.01).contains(&gap), "gap {gap} m");
}
