//! Growing while acting: a creature whose development goes on during the walk
//! (`develop = "during"`).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use ontogeny::develop::BuildOptions;
use ontogeny::lsystem::{DeriveOptions, LSystem};
use ontogeny::task::{Growing, Phase, Status, TaskKind, TaskSpec, Watch};

use crate::util::{
    assert_bad_input, assert_the_same_on_any_thread_count_and_resumed, evolve, ontogeny,
    scratch_dir, succeeded,
};

const EXAMPLE: &str = "examples/grow-while-walking.lsys";

fn example() -> Arc<LSystem> {
    let text = std::fs::read_to_string(EXAMPLE).unwrap();
    Arc::new(LSystem::from_text(EXAMPLE, &text).unwrap())
}

/// A 2 s walk.
fn short_walk() -> TaskSpec {
    let mut spec = TaskSpec::new(TaskKind::Walker);
    *spec.seconds_mut() = 2.0;
    spec
}

/// The example evaluated by `spec` growing from its first valid frame at one unit of
/// developmental time per second, recorded or not, and its development after the walk.
fn walk_growing(spec: &TaskSpec, record: bool) -> (ontogeny::task::Evaluation, Growing) {
    let mut growing = Growing::start(
        example(),
        &DeriveOptions::default(),
        &BuildOptions::default(),
        1.0,
        None,
    )
    .unwrap();
    let creature = growing.creature().clone();
    let evaluation = spec
        .evaluate_growing(
            &creature,
            Watch::uncancelled(record, &mut |_| {}),
            Some(&mut growing),
        )
        .unwrap();
    (evaluation, growing)
}

/// The example's 2 s walk growing ([`walk_growing`]), recorded.
fn grown_walk() -> ontogeny::task::Evaluation {
    walk_growing(&short_walk(), true).0
}

#[test]
fn a_creature_growing_during_the_walk_gains_parts_as_it_walks() {
    let evaluation = grown_walk();
    assert_eq!(evaluation.status, Status::Ok, "{evaluation:?}");
    // Dropped as three segments, it has them at the start of the walk; a pair of legs
    // appears half a second into the walk, another a second in: first each leg's shoulder
    // (two parts), at the next control step its hip and lower leg, buds one step long (four
    // parts).
    let counts: Vec<(Option<Phase>, usize)> = evaluation
        .recording
        .iter()
        .map(|s| (s.phase, s.parts.len()))
        .collect();
    assert!(
        counts
            .iter()
            .all(|&(phase, n)| phase == Some(Phase::Measuring) || n == 3)
    );
    let walking: Vec<usize> = counts
        .iter()
        .filter(|(phase, _)| *phase == Some(Phase::Measuring))
        .map(|&(_, n)| n)
        .collect();
    assert_eq!(walking.first(), Some(&3));
    for n in [5, 9, 11] {
        assert!(walking.contains(&n), "{n} parts: {walking:?}");
    }
    assert_eq!(walking.last(), Some(&15));
    assert!(walking.windows(2).all(|w| w[0] <= w[1]));
    assert_eq!(evaluation.terms["grown_parts"], 12.0);
    // Each hip and lower leg brings its output neuron and the link that feeds it.
    assert_eq!(evaluation.terms["grown_neurons"], 8.0);
    assert_eq!(evaluation.terms["grown_links"], 8.0);
    // The size terms are the body's at the start of the walk: three parts.
    assert_eq!(evaluation.terms["N"], 3.0);
}

#[test]
fn a_creature_growing_during_the_walk_walks_the_same_twice() {
    assert_eq!(grown_walk(), grown_walk());
}

/// `ontogeny eval` of the example for a 3 s walk, with `extra` flags, as JSON.
fn eval_json(extra: &[&str]) -> serde_json::Value {
    let mut args = vec!["eval", EXAMPLE, "--seconds", "3", "--json"];
    args.extend_from_slice(extra);
    serde_json::from_str(&succeeded(&ontogeny(&args))).unwrap()
}

#[test]
fn eval_with_develop_during_adds_parts_during_the_walk_and_gives_the_same_twice() {
    let grown = eval_json(&["--develop", "during"]);
    assert_eq!(grown["status"], "ok");
    assert_eq!(grown["terms"]["N"], 3.0);
    assert_eq!(grown["terms"]["grown_parts"], 12.0);
    assert_eq!(grown["terms"]["grown_neurons"], 8.0);
    assert_eq!(eval_json(&["--develop", "during"]), grown);
    // From the config's [task] table (a 4 s walk), the same growth, and the legs walk it
    // forward as they grow: 2.02 m at the commit that set this example's gait, against
    // 0.3 mm for a body whose outputs were constant.
    let args = [
        "eval",
        EXAMPLE,
        "--config",
        "examples/grow-while-walking.toml",
        "--json",
    ];
    let config: serde_json::Value = serde_json::from_str(&succeeded(&ontogeny(&args))).unwrap();
    assert_eq!(config["terms"]["grown_parts"], 12.0);
    assert_eq!(config["terms"]["N"], 3.0);
    let walked = config["terms"]["D_w"].as_f64().unwrap();
    assert!(walked > 1.0, "walked {walked} m");
}

#[test]
fn eval_with_develop_before_is_today_s_evaluation() {
    let today = eval_json(&[]);
    assert_eq!(eval_json(&["--develop", "before"]), today);
    // The finished creature: fifteen parts from the start, nothing grown.
    assert_eq!(today["terms"]["N"], 15.0);
    assert!(today["terms"].get("grown_parts").is_none());
}

#[test]
fn a_grammar_in_discrete_steps_cannot_grow_during_a_walk() {
    assert_bad_input(
        &["eval", "examples/quadruped.lsys", "--develop", "during"],
        "error: develop = \"during\": examples/quadruped.lsys develops in discrete steps; only \
         continuous development (a `time:` line, or --time) goes on during a walk",
    );
    assert_bad_input(
        &[
            "eval",
            EXAMPLE,
            "--develop",
            "during",
            "--develop-rate",
            "-1",
        ],
        "--develop-rate must be finite and positive, not -1",
    );
}

/// A config of a tiny run of `encoding` whose walkers grow during their 0.5 s walks, with
/// `extra` lines in its `[task]` table.
fn growing_config(dir: &Path, encoding: &str, extra: &str) -> PathBuf {
    let config = dir.join("config.toml");
    std::fs::write(
        &config,
        format!(
            "encoding = \"{encoding}\"\nseed = 5\n[ga]\npopulation = 6\ngenerations = 2\n\
             [task]\ntask = \"walker\"\ndevelop = \"during\"\n{extra}\n\
             [task.walker]\nseconds = 0.5\n"
        ),
    )
    .unwrap();
    config
}

#[test]
fn a_run_of_a_genome_that_cannot_grow_during_the_walk_is_refused() {
    let out = scratch_dir("grow_while_walking_refused");
    let config = growing_config(&out, "lsystem", "");
    let said = assert_bad_input(
        &[
            "evolve",
            "--config",
            config.to_str().unwrap(),
            "--out",
            out.join("run").to_str().unwrap(),
        ],
        "develop must be \"before\" with the lsystem genome (only lsystem-continuous grows \
         during its evaluation), not \"during\"",
    );
    assert!(said.contains("config.toml:8:11"), "{said}");
    assert!(!out.join("run").exists());
    // So is a task other than the walker.
    let config = growing_config(&out, "lsystem-continuous", "");
    let text = std::fs::read_to_string(&config).unwrap();
    std::fs::write(
        &config,
        text.replace("task = \"walker\"", "task = \"jump\""),
    )
    .unwrap();
    assert_bad_input(
        &[
            "evolve",
            "--config",
            config.to_str().unwrap(),
            "--out",
            out.join("run").to_str().unwrap(),
        ],
        "develop must be \"before\" on the jump task (only the walker grows its creature \
         during its evaluation), not \"during\"",
    );
    assert!(!out.join("run").exists());
}

#[test]
fn an_evolution_growing_during_the_walk_is_the_same_on_any_thread_count_and_resumed() {
    let dir = scratch_dir("grow_while_walking_evolve");
    let config = growing_config(&dir, "lsystem-continuous", "develop_rate = 2");
    // Stopped after one generation, then resumed to two: the same run.
    assert_the_same_on_any_thread_count_and_resumed(&config, &dir, "1", "2");
    // Its walkers grew during their walks: every evaluation that succeeded tallies it.
    let store = ontogeny::run::store::RunStore::open_read_only(&dir.join("one").join("run.sqlite"))
        .unwrap();
    let individuals = store.individuals(0).unwrap();
    let walked: Vec<serde_json::Value> = individuals
        .iter()
        .map(|i| serde_json::from_str::<serde_json::Value>(&i.genome_json).unwrap())
        .filter(|json| json["evaluation"]["status"] == "ok")
        .collect();
    assert!(!walked.is_empty());
    for json in &walked {
        assert!(
            json["evaluation"]["terms"]["grown_parts"].is_number(),
            "{json}"
        );
    }
}

/// The events of the example's development during a 2 s walk at control step `step`, as
/// (developmental time, module).
fn events_at_control_step(step: f64) -> Vec<(f64, String)> {
    let mut spec = short_walk();
    spec.sim.control_step = step;
    let (evaluation, growing) = walk_growing(&spec, false);
    assert_eq!(evaluation.status, Status::Ok, "{evaluation:?}");
    growing
        .events()
        .iter()
        .map(|e| (e.t, e.module.clone()))
        .collect()
}

#[test]
fn events_during_the_walk_are_located_at_the_same_times_whatever_the_control_step() {
    let coarse = events_at_control_step(1.0 / 60.0);
    let fine = events_at_control_step(1.0 / 120.0);
    assert!(!coarse.is_empty());
    assert_eq!(coarse.len(), fine.len(), "{coarse:?}\n{fine:?}");
    for ((t1, m1), (t2, m2)) in coarse.iter().zip(&fine) {
        assert_eq!(m1, m2);
        assert!((t1 - t2).abs() < 1e-9, "{t1} against {t2}");
    }
}

/// Two segments whose token A, once 1.5 time units old, sprouts a pair of legs that lengthen
/// to 0.4 m, but only where slot 0 of the array holds more than 0.5.
const CUE: &str = "time: 3\ntiming: exact\nenvironment: 0\n\
    axiom: width(0.6) thickness(0.2) forward(0.8) forward(0.8) ?E(1, 0, 0) A(0)\n\
    A(x) : x < 1.5 --> solve dx/dt = 1\n\
    ?E(1, 0, c) < A(x) : x >= 1.5 && c > 0.5 --> [ left(1) mforward(0) ] [ right(1) mforward(0) ]\n\
    mforward(x) : x < 0.4 --> solve dx/dt = 0.4\n\
    mforward(x) : x >= 0.4 --> forward(x)\n";

/// The parts `CUE` grows during a 2 s walk from an array whose slot 0 starts at `value`, as
/// a habitat's array starts it.
fn parts_grown_in(value: f64) -> f64 {
    let seedling = ontogeny::develop::Seedling {
        lsys: Arc::new(LSystem::from_text("cue.lsys", CUE).unwrap()),
        derive: DeriveOptions {
            env: vec![(0, value)],
            ..DeriveOptions::default()
        },
        build: BuildOptions::default(),
    };
    let evaluation = short_walk()
        .evaluate_grown_job(&seedling, None, Watch::uncancelled(false, &mut |_| {}))
        .unwrap();
    assert_eq!(evaluation.status, Status::Ok, "{evaluation:?}");
    assert_eq!(evaluation.terms["N"], 2.0);
    evaluation.terms["grown_parts"]
}

#[test]
fn a_grammar_that_reads_its_array_grows_differently_during_the_walk_in_two_habitats() {
    assert_eq!(parts_grown_in(0.0), 0.0);
    assert_eq!(parts_grown_in(1.0), 2.0);
}

#[test]
fn runs_growth_gives_each_generation_s_best_and_mean_growth_from_the_store() {
    let dir = scratch_dir("grow_while_walking_runs_growth");
    let config = growing_config(&dir, "lsystem-continuous", "develop_rate = 2");
    let run = dir.join("run");
    evolve(&config, &run, &[]);
    let shown: serde_json::Value = serde_json::from_str(&crate::util::stdout(&ontogeny(&[
        "runs",
        "growth",
        run.to_str().unwrap(),
        "--json",
    ])))
    .unwrap();
    let generations = shown["runs"][0]["generations"].as_array().unwrap();
    assert_eq!(generations.len(), 2);
    let store = ontogeny::run::store::RunStore::open_read_only(&run.join("run.sqlite")).unwrap();
    let terms = [
        "grown_parts",
        "grown_length",
        "grown_neurons",
        "grown_links",
    ];
    let figures = ["parts", "length", "neurons", "links"];
    for (g, shown) in generations.iter().enumerate() {
        let individuals = store.individuals(g as u32).unwrap();
        let evaluations: Vec<serde_json::Value> = individuals
            .iter()
            .map(|i| serde_json::from_str::<serde_json::Value>(&i.genome_json).unwrap())
            .map(|json| json["evaluation"].clone())
            .collect();
        // The best: the highest fitness, the lowest index among equals.
        let best = (0..individuals.len())
            .rev()
            .max_by(|&a, &b| individuals[a].fitness.total_cmp(&individuals[b].fitness))
            .unwrap();
        assert_eq!(shown["best"].as_f64(), Some(individuals[best].fitness));
        let grew: Vec<&serde_json::Value> = evaluations
            .iter()
            .filter(|e| e["terms"]["grown_parts"].is_number())
            .collect();
        assert!(!grew.is_empty());
        assert_eq!(shown["growers"]["measured"], grew.len());
        assert_eq!(shown["growers"]["population"], individuals.len());
        for (term, figure) in terms.iter().zip(figures) {
            let mean = grew
                .iter()
                .map(|e| e["terms"][term].as_f64().unwrap())
                .sum::<f64>()
                / grew.len() as f64;
            let got = shown["mean"][figure].as_f64().unwrap();
            assert!((got - mean).abs() < 1e-12, "{term}: {got} against {mean}");
            assert_eq!(
                shown["champion"][figure], evaluations[best]["terms"][term],
                "{term}"
            );
        }
    }
    // The CSV: a row per generation; the table: one per condition.
    let csv = crate::util::stdout(&ontogeny(&[
        "runs",
        "growth",
        run.to_str().unwrap(),
        "--csv",
    ]));
    assert_eq!(
        csv.lines().next().unwrap(),
        ontogeny::study::lifetime::CSV_COLUMNS
    );
    assert_eq!(csv.lines().count(), 3);
    let table = crate::util::stdout(&ontogeny(&["runs", "growth", run.to_str().unwrap()]));
    assert!(
        table.contains(": 1 run(s); medians over the runs"),
        "{table}"
    );
    assert_eq!(table.lines().count(), 2 + 2, "{table}");
    // A run whose creatures develop before their walks has nothing to show: bad input.
    let before = dir.join("before");
    let text = std::fs::read_to_string(&config).unwrap();
    let config = dir.join("before.toml");
    std::fs::write(&config, text.replace("develop = \"during\"", "")).unwrap();
    evolve(&config, &before, &["--gens", "1"]);
    assert_bad_input(
        &["runs", "growth", before.to_str().unwrap()],
        &format!(
            "{}: its creatures do not grow during their walks (develop = \"before\")",
            before.display()
        ),
    );
}

/// A grammar that answers its environment: at developmental time 1 it writes 0.75 into slot
/// 0, and once slot 1 holds more than 0.5 it writes that value plus 1 into slot 2.
const ANSWERS: &str = "time: 3\n\
    dt: 0.25\n\
    timing: exact\n\
    environment: 0 0 0\n\
    axiom: forward(0.8) revolute1 forward(0.8) A(0) B ?E(1, 1, 0)\n\
    A(x) : x < 1 --> solve dx/dt = 1\n\
    A(x) : x >= 1 --> ?E(0, 0, 0.75)\n\
    B > ?E(1, 1, c) : c > 0.5 --> ?E(0, 2, c + 1)\n";

#[test]
fn the_development_during_the_walk_shares_the_array_the_controller_reads_and_writes() {
    use ontogeny::sim::{SimOptions, World};
    let lsys = Arc::new(LSystem::from_text("answers.lsys", ANSWERS).unwrap());
    let mut growing = Growing::start(
        lsys,
        &DeriveOptions::default(),
        &BuildOptions::default(),
        1.0,
        Some(0.0),
    )
    .unwrap();
    let mut world = World::new(growing.creature(), &SimOptions::default()).unwrap();
    assert_eq!(world.environment(), &[0.0, 0.0, 0.0]);
    // Steps of 0.25 s: the grammar's write at t = 1 reaches the array the controller's
    // chemical sensors read at the end of the fourth step, not before.
    for _ in 0..3 {
        growing.step(&mut world, 0.25).unwrap();
        assert_eq!(world.environment(), &[0.0, 0.0, 0.0]);
    }
    growing.step(&mut world, 0.25).unwrap();
    assert_eq!(world.environment(), &[0.75, 0.0, 0.0]);
    // The controller writes slot 1 (as a secreting neuron does): the grammar reads it at the
    // start of the next step and answers within it.
    world.set_environment(&[0.75, 0.9, 0.0]);
    growing.step(&mut world, 0.25).unwrap();
    assert_eq!(world.environment(), &[0.75, 0.9, 1.9]);
    assert_eq!(growing.creature().environment, vec![0.75, 0.9, 1.9]);
    // The grammar's `?E(0, 0, 0.75)` stays in its string and writes slot 0 at every
    // exchange: a controller's write there lasts until the next one.
    world.set_environment(&[0.5, 0.9, 1.9]);
    growing.step(&mut world, 0.25).unwrap();
    assert_eq!(world.environment(), &[0.75, 0.9, 1.9]);
}

/// A walker whose controller secretes its oscillator's output into slot 0 (with `secrete`),
/// and whose grammar sprouts a pair of legs once it reads less than −0.5 there after
/// developmental time 1 (the oscillator, fed back on itself, settles near −0.65 by then);
/// without `secrete` nothing writes the slot, and it stays 0.
fn secreting(secrete: &str) -> String {
    format!(
        "time: 3\n\
         dt: 0.25\n\
         timing: exact\n\
         environment: 0\n\
         axiom: width(0.6) thickness(0.2) forward(0.8) {secrete} forward(0.8) ?E(1, 0, 0) A(0)\n\
         A(x) : x < 1 --> solve dx/dt = 1\n\
         ?E(1, 0, c) < A(x) : x >= 1 && c < -0.5 --> [ left(1) mforward(0) ] [ right(1) mforward(0) ]\n\
         mforward(x) : x < 0.4 --> solve dx/dt = 0.4\n\
         mforward(x) : x >= 0.4 --> forward(x)\n"
    )
}

fn secreting_walk(secrete: &str) -> ontogeny::task::Evaluation {
    let seedling = ontogeny::develop::Seedling {
        lsys: Arc::new(LSystem::from_text("secreting.lsys", &secreting(secrete)).unwrap()),
        derive: DeriveOptions::default(),
        build: BuildOptions::default(),
    };
    let evaluation = short_walk()
        .evaluate_grown_job(&seedling, None, Watch::uncancelled(false, &mut |_| {}))
        .unwrap();
    assert_eq!(evaluation.status, Status::Ok, "{evaluation:?}");
    evaluation
}

#[test]
fn a_grammar_grows_legs_during_the_walk_when_its_controller_secretes_what_it_reads() {
    let quiet = secreting_walk("");
    assert_eq!(quiet.terms["grown_parts"], 0.0);
    let secreted = secreting_walk("secrete(0)");
    assert_eq!(secreted.terms["grown_parts"], 2.0);
    // The same walk again, exchanges and all, to the bit.
    let again = secreting_walk("secrete(0)");
    assert_eq!(again.fitness.to_bits(), secreted.fitness.to_bits());
    assert_eq!(again.terms, secreted.terms);
}

/// A config of a tiny run of the lsystem-continuous genome whose walkers grow during their
/// 0.5 s walks in two habitats that differ in chemical 0, two noisy trials in each.
pub(crate) fn growing_habitats_config(dir: &Path) -> PathBuf {
    let config = dir.join("config.toml");
    std::fs::write(
        &config,
        "encoding = \"lsystem-continuous\"\nseed = 5\n\
         [ga]\npopulation = 6\ngenerations = 2\nenvironment_reads = 0.5\n\
         [task]\ntask = \"walker\"\ndevelop = \"during\"\ndevelop_rate = 2\n\
         [task.walker]\nseconds = 0.5\n\
         [task.trials]\ncount = 2\naggregate = \"mean\"\nheading = 20\nstrength = 10\n\
         [[task.habitats]]\nname = \"poor\"\nenvironment = [0]\n\
         [[task.habitats]]\nname = \"rich\"\nenvironment = [1]\n",
    )
    .unwrap();
    config
}

#[test]
fn eval_and_replay_of_a_champion_growing_in_habitats_give_its_stored_fitness() {
    let dir = scratch_dir("grow_while_walking_habitats");
    let config = growing_habitats_config(&dir);
    let run = dir.join("run");
    evolve(&config, &run, &[]);
    let store = ontogeny::run::store::RunStore::open_read_only(&run.join("run.sqlite")).unwrap();
    let stored = store.generations().unwrap()[1].best;
    let best = run.join("best.lsys");
    let text = std::fs::read_to_string(&best).unwrap();
    let record = ontogeny::run::champion::ChampionRecord::of_text(&text)
        .unwrap()
        .unwrap();
    assert_eq!(record.fitness, stored);
    assert_eq!(record.task.habitat_count(), 2);
    let best = best.to_str().unwrap();
    let eval = |extra: &[&str]| -> serde_json::Value {
        let mut args = vec!["eval", best, "--json"];
        args.extend_from_slice(extra);
        serde_json::from_str(&succeeded(&ontogeny(&args))).unwrap()
    };
    // The file's record gives the task, habitats and trials: its fitness to the digit, the
    // mean of its four walks, each of which grew.
    let all = eval(&[]);
    assert_eq!(all["status"], "ok", "{all}");
    assert_eq!(all["fitness"].as_f64().unwrap(), stored, "{all}");
    let units = all["habitats"].as_array().unwrap();
    let places: Vec<(&str, u64)> = units
        .iter()
        .map(|u| (u["name"].as_str().unwrap(), u["trial"].as_u64().unwrap()))
        .collect();
    assert_eq!(places, [("poor", 0), ("poor", 1), ("rich", 0), ("rich", 1)]);
    let fitness: Vec<f64> = units
        .iter()
        .map(|u| u["fitness"].as_f64().unwrap())
        .collect();
    // The trials' noise is drawn per trial: the two walks of a habitat differ.
    assert_ne!(fitness[0], fitness[1]);
    assert_eq!(
        all["fitness"].as_f64().unwrap(),
        fitness.iter().sum::<f64>() / 4.0
    );
    assert!(all["terms"]["grown_parts"].is_number(), "{all}");
    // The config gives the same evaluation.
    let config = config.to_str().unwrap();
    assert_eq!(eval(&["--config", config]), all);
    // One habitat alone: the same walks as in the whole evaluation.
    let rich = eval(&["--habitat", "rich"]);
    assert_eq!(rich["habitats"].as_array().unwrap()[..], units[2..]);
    // Recorded: the first unit's walk, growing as it walked.
    let recorded = dir.join("recorded");
    let output = ontogeny(&["eval", best, "--record", recorded.to_str().unwrap()]);
    let said = succeeded(&output);
    assert!(
        crate::util::stderr(&output).contains("note: recording habitat poor, trial 1"),
        "{}",
        crate::util::stderr(&output)
    );
    assert!(said.contains("  habitat poor, trial 1: fitness "), "{said}");
    let recording: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(recorded.join("recording.json")).unwrap())
            .unwrap();
    let frames = recording["frames"].as_array().unwrap();
    assert!(
        frames.iter().any(|f| f.get("growth").is_some()),
        "no frame records growth"
    );
    assert!(recorded.join("behaviour.gif").is_file());
    // `replay` re-evaluates the stored champion, growing, to the same fitness.
    let output = crate::util::ontogeny_command()
        .arg("replay")
        .arg(&run)
        .output()
        .unwrap();
    let said = succeeded(&output);
    assert!(
        said.contains(&format!(
            "walker fitness {stored:.6} (ok; stored {stored:.6})"
        )),
        "{said}"
    );
    assert!(
        !crate::util::stderr(&output).contains("differs"),
        "{}",
        crate::util::stderr(&output)
    );
}

#[test]
fn a_grammar_growing_during_the_walk_grows_legs_in_the_rich_habitat_alone() {
    let args = [
        "eval",
        "examples/grow-where-rich.lsys",
        "--config",
        "examples/grow-while-walking-habitats.toml",
        "--json",
    ];
    let e: serde_json::Value = serde_json::from_str(&succeeded(&ontogeny(&args))).unwrap();
    let units = e["habitats"].as_array().unwrap();
    let grown: Vec<(&str, f64, f64)> = units
        .iter()
        .map(|u| {
            (
                u["name"].as_str().unwrap(),
                u["terms"]["N"].as_f64().unwrap(),
                u["terms"]["grown_parts"].as_f64().unwrap(),
            )
        })
        .collect();
    // Dropped as two segments everywhere; where chemical 0 starts at 1 a pair of legs
    // sprouts 1.5 s into development, where it starts at 0 none.
    assert_eq!(
        grown,
        [
            ("poor", 2.0, 0.0),
            ("poor", 2.0, 0.0),
            ("rich", 2.0, 2.0),
            ("rich", 2.0, 2.0)
        ]
    );
    // The aggregate's terms are the means of the walks'.
    assert_eq!(e["terms"]["grown_parts"], 1.0);
}

#[test]
fn eval_growing_in_habitats_refuses_an_unknown_habitat_and_a_grammar_in_discrete_steps() {
    assert_bad_input(
        &[
            "eval",
            "examples/grow-where-rich.lsys",
            "--config",
            "examples/grow-while-walking-habitats.toml",
            "--habitat",
            "wet",
        ],
        "no habitat 'wet'; the habitats are poor, rich",
    );
    assert_bad_input(
        &[
            "eval",
            "examples/quadruped.lsys",
            "--config",
            "examples/grow-while-walking-habitats.toml",
        ],
        "error: develop = \"during\": examples/quadruped.lsys develops in discrete steps",
    );
    assert_bad_input(
        &[
            "eval",
            "examples/grow-where-rich.lsys",
            "--develop",
            "during",
            "--habitat",
            "rich",
        ],
        "no habitat 'rich': the task has no [[task.habitats]]",
    );
}
