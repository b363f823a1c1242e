//! The step settings on the command line: `bench fidelity`, `--setting` and the stepping flags
//! of `eval`, a config's `[task.sim]` table for `evolve` and `compare`, each value checked and
//! written back.

use super::*;

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
        // The key is pointed at where the file sets it (`dt` too, the old name of
        // `control_step`).
        let key = line.split(" = ").next().unwrap();
        let expected = format!(
            "error: {message}\n --> {}:2:{}\n",
            config.display(),
            key.len() + 4
        );
        assert!(stderr(&o).starts_with(&expected), "{line}: {}", stderr(&o));
        assert!(!out.exists(), "{line}: a run directory was written");
    }
    // A task's settings too, by their table.
    let config = dir.join("bad.toml");
    std::fs::write(&config, "[task.walker.rest]\nlimit = 1e12\n").unwrap();
    let out = dir.join("run");
    assert_bad_input(
        &[
            "evolve",
            "--config",
            config.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        "[task.walker.rest] limit must be in (0, 3600]",
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
    assert_bad_input(
        &[
            "eval",
            "examples/snake.lsys",
            "--task",
            "walker",
            "--setting",
            "quick",
        ],
        "[possible values: fast, default, fine]",
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
    assert!(
        stderr(&o).starts_with(&format!(
            "error: [task.sim] rest_substeps must be 1 to 64, not 0\n --> {}:2:17\n",
            config.display()
        )),
        "{}",
        stderr(&o)
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
    assert_bad_input(
        &["compare", "--resume", out.to_str().unwrap()],
        "[task.sim] substeps must be 1 to 64, not 0",
    );
    let _ = std::fs::remove_dir_all(dir);
}
