//! Habitats and trials: a grammar that reads its environment grows a body per habitat,
//! `eval` prints every habitat-trial and their aggregate (or one habitat's), identical
//! creatures get identical trials, a tiny evolution is the same on one thread and two and
//! when stopped and resumed, the store keeps every unit, each habitat draws from its own
//! noise ranges, budgets of walks count the elite walked again on fresh trials, and bad
//! tables are refused.

use std::path::{Path, PathBuf};

use crate::util::{
    assert_the_same_on_any_thread_count_and_resumed, evolve, ontogeny, ontogeny_command,
    ontogeny_ok, refused, scratch_dir, stdout, succeeded,
};

/// Two flat habitats that differ in chemical 0 (`poor` 0, `rich` 1), `trials` trials each
/// with `noise` (lines of `[task.trials]`), short walks.
fn config(dir: &Path, trials: u32, noise: &str) -> PathBuf {
    let path = dir.join("habitats.toml");
    std::fs::write(
        &path,
        format!(
            "encoding = \"lsystem\"\nseed = 3\n\n[ga]\npopulation = 6\ngenerations = 3\n\n\
             [task]\ntask = \"walker\"\n\n[task.walker]\nseconds = 0.5\n\n\
             [task.trials]\ncount = {trials}\naggregate = \"median\"\n{noise}\n\n\
             [[task.habitats]]\nname = \"poor\"\nenvironment = [0]\n\n\
             [[task.habitats]]\nname = \"rich\"\nenvironment = [1]\n"
        ),
    )
    .unwrap();
    path
}

fn eval_json(args: &[&str]) -> serde_json::Value {
    serde_json::from_str(&stdout(&ontogeny_ok(args))).unwrap()
}

#[test]
fn a_grammar_that_reads_its_environment_grows_a_body_per_habitat() {
    let dir = scratch_dir("habitats-plastic");
    let config = config(&dir, 1, "");
    let config = config.to_str().unwrap();
    let e = eval_json(&[
        "eval",
        "examples/plastic.lsys",
        "--config",
        config,
        "--json",
    ]);
    let units = e["habitats"].as_array().unwrap();
    let morph = |i: usize| {
        (
            units[i]["name"].as_str().unwrap().to_string(),
            units[i]["parts"].as_u64().unwrap(),
        )
    };
    // The limb grows straight (4 segments) where chemical 0 is poor, branches where rich:
    // what `ontogeny derive examples/plastic.lsys --env 0=0` and `--env 0=1` grow.
    assert_eq!(morph(0), ("poor".to_string(), 4));
    assert_eq!(morph(1), ("rich".to_string(), 15));
}

#[test]
fn eval_prints_each_habitat_trial_and_their_aggregate() {
    let dir = scratch_dir("habitats-eval");
    let config = config(&dir, 2, "heading = 20\nstrength = 10");
    let config = config.to_str().unwrap();
    let walker = "examples/hornby-walker.lsys";
    let e = eval_json(&["eval", walker, "--config", config, "--json"]);
    let units = e["habitats"].as_array().unwrap();
    let places: Vec<(&str, u64)> = units
        .iter()
        .map(|u| (u["name"].as_str().unwrap(), u["trial"].as_u64().unwrap()))
        .collect();
    assert_eq!(places, [("poor", 0), ("poor", 1), ("rich", 0), ("rich", 1)]);
    let mut fitness: Vec<f64> = units
        .iter()
        .map(|u| u["fitness"].as_f64().unwrap())
        .collect();
    assert!(units.iter().all(|u| u["status"] == "ok"), "{e}");
    // Noise is drawn per trial: the two trials of a habitat walk differently.
    assert_ne!(fitness[0], fitness[1]);
    // The median of four: the mean of the two middle values.
    fitness.sort_by(f64::total_cmp);
    assert_eq!(
        e["fitness"].as_f64().unwrap(),
        (fitness[1] + fitness[2]) / 2.0
    );
    let text = stdout(&ontogeny_ok(&["eval", walker, "--config", config]));
    let lines: Vec<&str> = text.lines().collect();
    assert!(
        lines[0].starts_with(&format!("{walker}: walker fitness ")),
        "{text}"
    );
    let unit_lines: Vec<String> = units
        .iter()
        .map(|u| {
            format!(
                "  habitat {}, trial {}: fitness {:.6} (ok)",
                u["name"].as_str().unwrap(),
                u["trial"].as_u64().unwrap() + 1,
                u["fitness"].as_f64().unwrap()
            )
        })
        .collect();
    let n = lines.len();
    assert_eq!(lines[n - 5..n - 1], unit_lines[..], "{text}");
    assert_eq!(lines[n - 1], "  fitness: the median of 4 walks");
}

#[test]
fn identical_creatures_get_identical_trials() {
    let dir = scratch_dir("habitats-identical");
    let config = config(&dir, 2, "heading = 30\noffset = 0.3\nfriction = 20");
    let config = config.to_str().unwrap();
    let args = [
        "eval",
        "examples/hornby-walker.lsys",
        "--config",
        config,
        "--json",
    ];
    let once = stdout(&ontogeny_ok(&args));
    let twice = stdout(&ontogeny_ok(&args));
    assert_eq!(once, twice);
    // On one thread, too.
    let mut one = ontogeny_command();
    one.env("RAYON_NUM_THREADS", "1").args(args);
    assert_eq!(stdout(&one.output().unwrap()), once);
}

#[test]
fn eval_habitat_walks_that_habitat_alone_and_refuses_an_unknown_name() {
    let dir = scratch_dir("habitats-one");
    let config = config(&dir, 2, "heading = 20");
    let config = config.to_str().unwrap();
    let walker = "examples/hornby-walker.lsys";
    let all = eval_json(&["eval", walker, "--config", config, "--json"]);
    let rich = eval_json(&[
        "eval",
        walker,
        "--config",
        config,
        "--habitat",
        "rich",
        "--json",
    ]);
    // The same draws as in the whole evaluation, of that habitat's trials only.
    assert_eq!(
        rich["habitats"].as_array().unwrap()[..],
        all["habitats"].as_array().unwrap()[2..]
    );
    let out = ontogeny(&["eval", walker, "--config", config, "--habitat", "wet"]);
    refused(&out, "no habitat 'wet'; the habitats are poor, rich");
    let out = ontogeny(&["eval", walker, "--config", config, "--seconds", "2"]);
    refused(&out, "--seconds cannot be given with it");
}

#[test]
fn a_bad_habitats_table_is_refused_with_exit_code_2_at_its_line_and_column() {
    let dir = scratch_dir("habitats-bad");
    let config = config(&dir, 2, "");
    let text = std::fs::read_to_string(&config).unwrap();
    // The second habitat's table starts at line 23: `name = "rich"` is line 24.
    for (from, to, message, at) in [
        (
            "name = \"rich\"",
            "name = \"poor\"",
            "[[task.habitats]] name must be unique among the habitats, not 'poor' a second time",
            "habitats.toml:24:8",
        ),
        (
            "count = 2",
            "count = 0",
            "[task.trials] count must be 1 to 64, not 0",
            "habitats.toml:15:9",
        ),
        (
            "count = 2",
            "count = 2\nroughness = 120",
            "[task.trials] roughness must be in [0, 99], not 120",
            "habitats.toml:16:13",
        ),
        (
            "environment = [1]",
            "environment = [1]\n[task.habitats.world]\nslope = { degrees = 95 }",
            "[task.habitats.world.slope] degrees must be at least 0 and below 80, not 95 \
             (habitat 'rich')",
            "habitats.toml:27:21",
        ),
        (
            "environment = [1]",
            "environment = [1, nan]",
            "[[task.habitats]] environment must be finite numbers (habitat 'rich'), not NaN",
            "habitats.toml:25:15",
        ),
        (
            "environment = [1]",
            "environment = [1]\n[task.habitats.trials]\nheading = 200",
            "[task.habitats.trials] heading must be in [0, 180], not 200 (habitat 'rich')",
            "habitats.toml:27:11",
        ),
        (
            "environment = [1]",
            "environment = [1]\n[task.habitats.trials]\ncount = 3",
            "unknown key count in [task.habitats.trials]",
            "habitats.toml:27:1",
        ),
        (
            "environment = [1]",
            "environment = [1]\ncolour = 3",
            "unknown key colour in [[task.habitats]]",
            "habitats.toml:26:1",
        ),
        (
            "environment = [1]",
            "environment = [1]\n\n[[task.habitats]]\nname = \"\"",
            "[[task.habitats]] name must be a word of printable characters, not ''",
            "habitats.toml:28:8",
        ),
    ] {
        std::fs::write(&config, text.replace(from, to)).unwrap();
        let out = ontogeny_command()
            .args(["evolve", "--config"])
            .arg(&config)
            .arg("--out")
            .arg(dir.join("run"))
            .output()
            .unwrap();
        let said = refused(&out, message);
        assert!(said.contains(&format!("{at}\n")), "{at} not in {said}");
        assert!(!dir.join("run").exists());
    }
}

#[test]
fn a_tiny_evolution_in_habitats_is_the_same_on_any_thread_count_and_resumed() {
    let dir = scratch_dir("habitats-evolve");
    let config = config(&dir, 2, "heading = 20\nstrength = 10");
    // Stopped after two generations, then resumed to three: the same run.
    assert_the_same_on_any_thread_count_and_resumed(&config, &dir, "2", "3");
    // The store keeps each habitat's and trial's result in the individual's evaluation.
    let store = ontogeny::run::store::RunStore::open_read_only(&dir.join("one").join("run.sqlite"))
        .unwrap();
    let first = &store.individuals(0).unwrap()[0];
    let json: serde_json::Value = serde_json::from_str(&first.genome_json).unwrap();
    let units = json["evaluation"]["habitats"].as_array().unwrap();
    assert_eq!(units.len(), 4, "{json}");
    let ok: Vec<f64> = units
        .iter()
        .map(|u| u["fitness"].as_f64().unwrap())
        .collect();
    if units.iter().all(|u| u["status"] == "ok") {
        let mut sorted = ok.clone();
        sorted.sort_by(f64::total_cmp);
        assert_eq!(first.fitness, (sorted[1] + sorted[2]) / 2.0);
    } else {
        assert_eq!(first.fitness, ontogeny::task::FAILURE_FITNESS);
    }
}

#[test]
fn the_habitats_example_runs() {
    let dir = scratch_dir("habitats-example");
    evolve(
        Path::new("examples/habitats.toml"),
        &dir.join("run"),
        &["--pop", "4", "--gens", "1", "--seconds", "0.5"],
    );
    let config = std::fs::read_to_string(dir.join("run").join("config.toml")).unwrap();
    assert!(
        config.contains("[[task.habitats]]") && config.contains("count = 2"),
        "{config}"
    );
}

#[test]
fn fresh_trials_walk_the_elite_again_on_new_draws() {
    let dir = scratch_dir("habitats-fresh");
    let config = config(&dir, 2, "heading = 30\nfresh = true");
    let run = dir.join("run");
    evolve(&config, &run, &["--gens", "2"]);
    let store = ontogeny::run::store::RunStore::open_read_only(&run.join("run.sqlite")).unwrap();
    // Every individual of generation 1 was walked, the elite (one of six) included.
    assert_eq!(store.generations().unwrap()[1].evaluations, 6);
    let elite = &store.individuals(1).unwrap()[0];
    assert_eq!(elite.operator, "elite");
    let parent = &store.individuals(0).unwrap()[elite.parents[0] as usize];
    let units = |genome_json: &str| {
        let json: serde_json::Value = serde_json::from_str(genome_json).unwrap();
        json["evaluation"]["habitats"].clone()
    };
    assert_eq!(elite.genome_text, parent.genome_text);
    // The same creature on the generation's own draws walks differently.
    assert_ne!(units(&elite.genome_json), units(&parent.genome_json));
}

#[test]
fn a_habitat_is_walked_in_its_own_world() {
    let dir = scratch_dir("habitats-world");
    let walker = "examples/hornby-walker.lsys";
    let head = "[task]\ntask = \"walker\"\n\n[task.walker]\nseconds = 0.5\n\n";
    let slope = "slope = { degrees = 10, direction = 90 }\n";
    let habitats = dir.join("habitats.toml");
    std::fs::write(
        &habitats,
        format!(
            "{head}[[task.habitats]]\nname = \"level\"\n\n\
             [[task.habitats]]\nname = \"hill\"\n[task.habitats.world]\n{slope}"
        ),
    )
    .unwrap();
    let hill = dir.join("hill.toml");
    std::fs::write(&hill, format!("{head}[task.world]\n{slope}")).unwrap();
    let level = dir.join("level.toml");
    std::fs::write(&level, head).unwrap();
    let fitness = |config: &Path| -> f64 {
        eval_json(&[
            "eval",
            walker,
            "--config",
            config.to_str().unwrap(),
            "--json",
        ])["fitness"]
            .as_f64()
            .unwrap()
    };
    let e = eval_json(&[
        "eval",
        walker,
        "--config",
        habitats.to_str().unwrap(),
        "--json",
    ]);
    let units = e["habitats"].as_array().unwrap();
    let walked: Vec<f64> = units
        .iter()
        .map(|u| u["fitness"].as_f64().unwrap())
        .collect();
    // Each habitat walks as a plain task in its world does: level ground, then the slope.
    assert_eq!(walked, [fitness(&level), fitness(&hill)]);
    assert_ne!(walked[0], walked[1]);
}

#[test]
fn each_habitat_draws_its_trials_from_its_own_ranges() {
    use ontogeny::task::{Habitat, Noise, TaskKind, TaskSpec};
    let habitat = |name: &str, trials: Option<Noise>| Habitat {
        name: name.into(),
        world: Default::default(),
        environment: None,
        trials,
    };
    let mut spec = TaskSpec::new(TaskKind::Walker);
    spec.trials.count = 8;
    spec.trials.strength = 10.0;
    let slippery = Noise {
        strength: Some(0.0),
        friction: Some(50.0),
        ..Noise::default()
    };
    spec.habitats = vec![habitat("calm", None), habitat("slippery", Some(slippery))];
    assert!(spec.check().is_ok());
    assert_eq!(spec.trials_in(1).friction, 50.0);
    assert_eq!(spec.trials_in(1).count, 8);
    let units = spec.units([5; 32], 0);
    let (calm, slippery) = units.split_at(8);
    // The calm habitat draws from [task.trials]: strength ±10%, friction as written.
    assert!(
        calm.iter()
            .all(|u| (0.9..=1.1).contains(&u.perturbation.strength)
                && u.perturbation.friction == 1.0)
    );
    assert!(calm.iter().any(|u| u.perturbation.strength != 1.0));
    // The slippery one from its own: strength as written, friction ±50%.
    assert!(
        slippery
            .iter()
            .all(|u| u.perturbation.strength == 1.0
                && (0.5..=1.5).contains(&u.perturbation.friction))
    );
    assert!(
        slippery
            .iter()
            .any(|u| (u.perturbation.friction - 1.0).abs() > 0.1)
    );
}

#[test]
fn a_habitat_without_noise_walks_as_a_plain_task_beside_a_noisy_one() {
    let dir = scratch_dir("habitats-own-noise");
    let head = "[task]\ntask = \"walker\"\n\n[task.walker]\nseconds = 0.5\n\n";
    let config = dir.join("noise.toml");
    std::fs::write(
        &config,
        format!(
            "{head}[task.trials]\ncount = 2\nheading = 40\noffset = 0.2\n\n\
             [[task.habitats]]\nname = \"noisy\"\n\n\
             [[task.habitats]]\nname = \"quiet\"\n\
             [task.habitats.trials]\nheading = 0\noffset = 0\n"
        ),
    )
    .unwrap();
    let plain = dir.join("plain.toml");
    std::fs::write(&plain, head).unwrap();
    let walker = "examples/hornby-walker.lsys";
    let eval = |config: &Path| {
        eval_json(&[
            "eval",
            walker,
            "--config",
            config.to_str().unwrap(),
            "--json",
        ])
    };
    let level = eval(&plain)["fitness"].as_f64().unwrap();
    let e = eval(&config);
    let walked: Vec<f64> = e["habitats"]
        .as_array()
        .unwrap()
        .iter()
        .map(|u| u["fitness"].as_f64().unwrap())
        .collect();
    assert_eq!(walked.len(), 4, "{e}");
    // The quiet habitat's two trials are the plain walk; the noisy one's differ from it.
    assert_eq!(walked[2..], [level, level]);
    assert!(
        walked[..2].iter().all(|&w| w != level),
        "{walked:?} {level}"
    );
}

/// The generations `compare --plan` gives each replicate of `lsystem` under a walker config
/// with `trials` trials (drawn afresh each generation when `fresh`), at a budget of `walks`
/// walks.
fn planned_generations(dir: &Path, trials: u32, fresh: bool, walks: &str) -> u64 {
    let name = if fresh { "fresh-" } else { "" };
    let config = dir.join(format!("{name}trials-{trials}.toml"));
    std::fs::write(
        &config,
        format!(
            "[ga]\npopulation = 10\n\n[task]\ntask = \"walker\"\n\n[task.walker]\nseconds = 0.5\n\n\
             [task.trials]\ncount = {trials}\nstrength = 10\nfresh = {fresh}\n"
        ),
    )
    .unwrap();
    let out = dir.join(format!("plan-{name}{trials}-{walks}"));
    succeeded(
        &ontogeny_command()
            .args([
                "compare",
                "--plan",
                "--encodings",
                "lsystem",
                "--replicates",
                "1",
            ])
            .args(["--evaluations", walks, "--config"])
            .arg(&config)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap(),
    );
    let planned = std::fs::read_to_string(out.join("evolve.toml")).unwrap();
    planned
        .lines()
        .find_map(|l| l.strip_prefix("generations = "))
        .unwrap()
        .parse()
        .unwrap()
}

#[test]
fn an_encoding_comparison_counts_its_budget_in_walks() {
    let dir = scratch_dir("habitats-budget");
    // The first generation evaluates all 10, each later one the 8 that are not elite: 12
    // generations make 10 + 8·11 = 98 evaluations, 13 would make 106. At 4 trials, a budget
    // of 400 walks is 100 evaluations, as a budget of 100 is at one.
    assert_eq!(planned_generations(&dir, 4, false, "400"), 12);
    assert_eq!(planned_generations(&dir, 1, false, "100"), 12);
    // Run, the report and the progress count walks: 40 walks are one generation of 10.
    let out = dir.join("run-4");
    let ran = ontogeny_command()
        .args(["compare", "--encodings", "lsystem", "--replicates", "1"])
        .args(["--evaluations", "40", "--config"])
        .arg(dir.join("trials-4.toml"))
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    succeeded(&ran);
    let progress = String::from_utf8_lossy(&ran.stderr);
    assert!(
        progress.contains("comparison 40/40 walks (100.0%)"),
        "{progress}"
    );
    let report = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        report.contains(
            "every replicate made exactly 40 walks, 10 evaluations of 4 walks each \
             (budget 40 walks: population 10, 1 generations"
        ),
        "{report}"
    );
}

#[test]
fn a_budget_counts_the_elite_walked_again_on_fresh_trials() {
    let dir = scratch_dir("habitats-fresh-budget");
    // Population 10, elite 2, 4 trials: 40 walks a generation, fresh or not, at first; then
    // 8 × 4 = 32 walks a generation, or 10 × 4 = 40 when the elite are walked again. 400 walks
    // are 12 generations (40 + 11 · 32 = 392), or 10 fresh ones (40 + 9 · 40 = 400).
    assert_eq!(planned_generations(&dir, 4, false, "400"), 12);
    assert_eq!(planned_generations(&dir, 4, true, "400"), 10);
    assert_eq!(planned_generations(&dir, 4, true, "399"), 9);
    // Population 6, elite 1, 2 trials in 2 habitats: 24 walks in generation 0, then 5 × 4 = 20
    // a generation, or 6 × 4 = 24 fresh. 64 walks are 2 fresh generations (48 walks), not 3.
    let config = config(&dir, 2, "heading = 30\nfresh = true");
    let run = dir.join("run");
    let _ = std::fs::remove_dir_all(&run);
    evolve(&config, &run, &["--walks", "64"]);
    let stored = std::fs::read_to_string(run.join("config.toml")).unwrap();
    assert!(stored.contains("generations = 2\n"), "{stored}");
    let store = ontogeny::run::store::RunStore::open_read_only(&run.join("run.sqlite")).unwrap();
    let made: Vec<u64> = store
        .generations()
        .unwrap()
        .iter()
        .map(|g| g.evaluations)
        .collect();
    assert_eq!(made, [6, 6]);
}

#[test]
fn evolve_walks_sets_the_generations_from_a_budget_of_walks() {
    let dir = scratch_dir("habitats-evolve-walks");
    planned_generations(&dir, 4, false, "400");
    let config = dir.join("trials-4.toml");
    let out = dir.join("run");
    let _ = std::fs::remove_dir_all(&out);
    // 10 individuals of 4 trials: 40 walks are one generation, 39 not even that.
    let short = ontogeny_command()
        .args([
            "evolve",
            "--encoding",
            "lsystem",
            "--walks",
            "39",
            "--config",
        ])
        .arg(&config)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    refused(
        &short,
        "--walks 39 (4 per individual): a budget of 9 evaluations",
    );
    assert!(!out.exists());
    succeeded(
        &ontogeny_command()
            .args([
                "evolve",
                "--encoding",
                "lsystem",
                "--walks",
                "40",
                "--config",
            ])
            .arg(&config)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap(),
    );
    let stored = std::fs::read_to_string(out.join("config.toml")).unwrap();
    assert!(stored.contains("generations = 1\n"), "{stored}");
    refused(
        &ontogeny_command()
            .args(["evolve", "--walks", "40", "--gens", "2", "--out"])
            .arg(dir.join("both"))
            .output()
            .unwrap(),
        "--walks",
    );
}

#[test]
fn replay_habitat_writes_each_habitat_s_replay_beside_the_others() {
    let dir = scratch_dir("habitats-replay");
    let config = config(&dir, 1, "");
    let run = dir.join("run");
    evolve(&config, &run, &["--gens", "1"]);
    for habitat in ["poor", "rich"] {
        let output = ontogeny_command()
            .arg("replay")
            .arg(&run)
            .args(["--habitat", habitat])
            .output()
            .unwrap();
        succeeded(&output);
    }
    succeeded(&ontogeny_command().arg("replay").arg(&run).output().unwrap());
    let mut folders: Vec<String> = std::fs::read_dir(run.join("replay"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    folders.sort();
    assert_eq!(
        folders,
        ["gen-0-rank-1", "gen-0-rank-1-poor", "gen-0-rank-1-rich"]
    );
    for folder in &folders {
        assert!(
            run.join("replay")
                .join(folder)
                .join("behaviour.gif")
                .is_file()
        );
    }
}
